/* test_mesh_sample.c: the benchmarks' surface samplers (mesh_sample.h) on
 * a flat rectangle of two triangles: points on the rectangle, uniform by area,
 * the same for the same seed; graded samples whose density falls from the
 * low end of the longest axis to `far` at the high end; bad arguments; the
 * area. */
#include "mesh_sample.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SAMPLES 40000

/* A 2 by 1 rectangle in z = 0: x is its longest axis. */
static ps_pointset strip(double *points, uint32_t *faces) {
    static const double corners[12] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0};
    static const uint32_t triangles[6] = {0, 1, 2, 0, 2, 3};
    memcpy(points, corners, sizeof corners);
    memcpy(faces, triangles, sizeof triangles);
    return (ps_pointset){.points = points, .n = 4, .dim = 3, .faces = faces, .n_faces = 2};
}

/* Samples with x in the first and in the last tenth of [0, 2]. */
static void count_ends(const double *p, size_t n, size_t *low, size_t *high) {
    *low = *high = 0;
    for (size_t i = 0; i < n; i++) {
        *low += p[3 * i] < 0.2;
        *high += p[3 * i] > 1.8;
    }
}

static void test_uniform_on_the_surface(void) {
    double corners[12];
    uint32_t faces[6];
    ps_pointset mesh = strip(corners, faces);
    double *a = NULL, *b = NULL;
    REQUIRE(ps_mesh_sample_surface(&mesh, SAMPLES, 7, &a) == 0);
    REQUIRE(ps_mesh_sample_surface(&mesh, SAMPLES, 7, &b) == 0);
    CHECK(memcmp(a, b, 3 * SAMPLES * sizeof *a) == 0);
    int inside = 1;
    for (size_t i = 0; i < SAMPLES; i++)
        inside &= a[3 * i] >= 0 && a[3 * i] <= 2 && a[3 * i + 1] >= 0 && a[3 * i + 1] <= 1 &&
                  a[3 * i + 2] == 0;
    CHECK(inside);
    size_t low, high;
    count_ends(a, SAMPLES, &low, &high);
    CHECK_MSG(low > 3700 && low < 4300 && high > 3700 && high < 4300, "%zu and %zu of %d", low,
              high, SAMPLES);
    free(a), free(b);
}

/* Density 1 - 0.9 t along x: the first tenth holds about 0.955 / 0.145 =
 * 6.6 times the samples of the last. */
static void test_graded_falls_along_the_longest_axis(void) {
    double corners[12];
    uint32_t faces[6];
    ps_pointset mesh = strip(corners, faces);
    double *a = NULL, *b = NULL;
    REQUIRE(ps_mesh_sample_graded(&mesh, SAMPLES, 0.1, 7, &a) == 0);
    REQUIRE(ps_mesh_sample_graded(&mesh, SAMPLES, 0.1, 7, &b) == 0);
    CHECK(memcmp(a, b, 3 * SAMPLES * sizeof *a) == 0);
    size_t low, high;
    count_ends(a, SAMPLES, &low, &high);
    CHECK_MSG(high > 0 && (double)low / (double)high > 5.5 && (double)low / (double)high < 8,
              "%zu against %zu samples", low, high);
    free(a), free(b);
    REQUIRE(ps_mesh_sample_graded(&mesh, SAMPLES, 1.0, 7, &a) == 0);
    count_ends(a, SAMPLES, &low, &high);
    CHECK_MSG(low > 3700 && low < 4300 && high > 3700 && high < 4300, "far 1: %zu and %zu", low,
              high);
    free(a);
}

static void test_bad_arguments(void) {
    double corners[12];
    uint32_t faces[6];
    ps_pointset mesh = strip(corners, faces);
    double *out = (double *)&mesh;
    CHECK(ps_mesh_sample_graded(&mesh, 10, 0.0, 1, &out) == -1 && out == NULL);
    CHECK(ps_mesh_sample_graded(&mesh, 10, 1.5, 1, &out) == -1 && out == NULL);
    mesh.n_faces = 0;
    CHECK(ps_mesh_sample_surface(&mesh, 10, 1, &out) == -1 && out == NULL);
    CHECK(ps_mesh_sample_graded(&mesh, 10, 0.5, 1, &out) == -1 && out == NULL);
}

/* The 2 by 1 rectangle's area, and none without faces. */
static void test_area(void) {
    double corners[12];
    uint32_t faces[6];
    ps_pointset mesh = strip(corners, faces);
    CHECK(fabs(ps_mesh_area(&mesh) - 2.0) < 1e-12);
    mesh.n_faces = 0;
    CHECK(ps_mesh_area(&mesh) == 0);
}

PS_TEST_MAIN(TEST(test_uniform_on_the_surface), TEST(test_graded_falls_along_the_longest_axis),
             TEST(test_bad_arguments), TEST(test_area))
