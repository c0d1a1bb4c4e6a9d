/* test_shapes.c: the synthetic shapes are deterministic, sized as promised,
 * lie on the surface of their union, and ps_shape_transform is s R x + t. */
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef double *(*shape_fn)(double, size_t *, int **);

static double norm3(double x, double y, double z) { return sqrt(x * x + y * y + z * z); }

static void check_deterministic(shape_fn make) {
    size_t n1, n2;
    int *p1, *p2;
    double *a = make(0.0, &n1, &p1), *b = make(0.0, &n2, &p2);
    REQUIRE(a && b && n1 == n2);
    CHECK(memcmp(a, b, n1 * 3 * sizeof *a) == 0);
    CHECK(memcmp(p1, p2, n1 * sizeof *p1) == 0);
    free(a), free(b), free(p1), free(p2);
}

static void test_deterministic(void) {
    check_deterministic(ps_shape_dumbbell);
    check_deterministic(ps_shape_hand);
    check_deterministic(ps_shape_star);
    check_deterministic(ps_shape_sphere);
}

static void check_count(shape_fn make, size_t lo, size_t hi, int parts) {
    size_t n;
    int *part;
    double *pts = make(0.0, &n, &part);
    REQUIRE(pts && part);
    CHECK_MSG(n >= lo && n <= hi, "n = %zu, want %zu..%zu", n, lo, hi);
    int *seen = calloc((size_t)parts, sizeof *seen);
    REQUIRE(seen);
    for (size_t i = 0; i < n; i++) {
        CHECK(part[i] >= 0 && part[i] < parts);
        if (part[i] >= 0 && part[i] < parts) seen[part[i]]++;
    }
    for (int q = 0; q < parts; q++) CHECK_MSG(seen[q] > 20, "part %d has %d points", q, seen[q]);
    free(seen), free(pts), free(part);
}

static void test_default_sizes(void) {
    check_count(ps_shape_dumbbell, 2600, 3400, 3);
    check_count(ps_shape_hand, 3500, 4500, 6);
    check_count(ps_shape_star, 3500, 4500, 7);
    check_count(ps_shape_sphere, 1000, 5000, 1);
}

static void test_density_scales_count(void) {
    size_t n1, n2;
    double *a = ps_shape_star(50.0, &n1, NULL), *b = ps_shape_star(200.0, &n2, NULL);
    REQUIRE(a && b);
    CHECK_NEAR((double)n2 / (double)n1, 4.0, 0.1);
    free(a), free(b);
}

/* Unit sphere: on the surface, centred, balanced between hemispheres and
 * octants (a uniformity check with a generous tolerance). */
static void test_sphere_uniform(void) {
    size_t n;
    int *part;
    double *p = ps_shape_sphere(0.0, &n, &part);
    REQUIRE(p && n > 0);
    double mean[3] = {0, 0, 0};
    size_t octant[8] = {0};
    for (size_t i = 0; i < n; i++) {
        const double *x = &p[3 * i];
        CHECK_NEAR(norm3(x[0], x[1], x[2]), 1.0, 1e-12);
        CHECK(part[i] == 0);
        for (int d = 0; d < 3; d++) mean[d] += x[d] / (double)n;
        octant[(x[0] > 0) + 2 * (x[1] > 0) + 4 * (x[2] > 0)]++;
    }
    for (int d = 0; d < 3; d++) CHECK_NEAR(mean[d], 0.0, 0.05);
    for (int o = 0; o < 8; o++) CHECK_NEAR((double)octant[o] / (double)n, 0.125, 0.025);
    free(p), free(part);
}

/* Dumbbell: sphere points at radius 1 from their centre and outside the
 * tube (or on the far side of the centre, beyond the tube's end); tube
 * points at radius 0.25 from the axis and outside both spheres;
 * the two spheres get about the same number of points. */
static void test_dumbbell_surface(void) {
    size_t n, count[3] = {0};
    int *part;
    double *p = ps_shape_dumbbell(0.0, &n, &part);
    REQUIRE(p && part);
    for (size_t i = 0; i < n; i++) {
        const double *x = &p[3 * i];
        double dl = norm3(x[0] + 2.0, x[1], x[2]), dr = norm3(x[0] - 2.0, x[1], x[2]);
        double axis = norm3(0.0, x[1], x[2]);
        REQUIRE(part[i] >= 0 && part[i] <= 2);
        count[part[i]]++;
        if (part[i] == 1) CHECK(fabs(dl - 1.0) < 1e-12 && (axis >= 0.25 - 1e-9 || x[0] <= -2.0));
        if (part[i] == 2) CHECK(fabs(dr - 1.0) < 1e-12 && (axis >= 0.25 - 1e-9 || x[0] >= 2.0));
        if (part[i] == 0) CHECK(fabs(axis - 0.25) < 1e-12 && dl >= 1.0 - 1e-9 && dr >= 1.0 - 1e-9);
    }
    CHECK_NEAR((double)count[1] / (double)count[2], 1.0, 0.08);
    CHECK(count[0] > 200);
    free(p), free(part);
}

/* Star: the arm parts reach out to 3.85 along their own axis only. */
static void test_star_arms(void) {
    size_t n;
    int *part;
    double *p = ps_shape_star(0.0, &n, &part);
    REQUIRE(p && part);
    double reach[7] = {0};
    for (size_t i = 0; i < n; i++) {
        const double *x = &p[3 * i];
        REQUIRE(part[i] >= 0 && part[i] <= 6);
        if (part[i] == 0) CHECK_NEAR(norm3(x[0], x[1], x[2]), 1.2, 1e-12);
        if (part[i] == 0) continue;
        int axis = (part[i] - 1) / 2;
        double sign = (part[i] - 1) % 2 ? -1.0 : 1.0;
        reach[part[i]] = fmax(reach[part[i]], sign * x[axis]);
    }
    for (int a = 1; a <= 6; a++) CHECK_NEAR(reach[a], 3.85, 0.03);
    free(p), free(part);
}

static void test_transform(void) {
    double pts[6] = {1, 0, 0, 0, 0, 2};
    const double t[3] = {1, 2, 3};
    ps_shape_transform(pts, 2, 0, 0, 1, PI / 2, 2.0, t);
    CHECK_NEAR(pts[0], 1.0, 1e-12);
    CHECK_NEAR(pts[1], 4.0, 1e-12);
    CHECK_NEAR(pts[2], 3.0, 1e-12);
    CHECK_NEAR(pts[3], 1.0, 1e-12);
    CHECK_NEAR(pts[4], 2.0, 1e-12);
    CHECK_NEAR(pts[5], 7.0, 1e-12);
}

/* A rotation about a slanted axis keeps distances, scaled by s, and fixes
 * the axis itself. */
static void test_transform_rigid(void) {
    size_t n;
    double *p = ps_shape_hand(20.0, &n, NULL);
    REQUIRE(p && n > 10);
    double *q = malloc(n * 3 * sizeof *q);
    REQUIRE(q);
    memcpy(q, p, n * 3 * sizeof *q);
    const double zero[3] = {0, 0, 0};
    ps_shape_transform(q, n, 1, 2, 3, 0.7, 3.0, zero);
    for (size_t i = 1; i < n; i++) {
        double d0 = norm3(p[0] - p[3 * i], p[1] - p[3 * i + 1], p[2] - p[3 * i + 2]);
        double d1 = norm3(q[0] - q[3 * i], q[1] - q[3 * i + 1], q[2] - q[3 * i + 2]);
        CHECK_NEAR(d1, 3.0 * d0, 1e-9);
    }
    double axis[3] = {1, 2, 3};
    ps_shape_transform(axis, 1, 1, 2, 3, 0.7, 1.0, NULL);
    CHECK_NEAR(axis[0], 1.0, 1e-12);
    CHECK_NEAR(axis[1], 2.0, 1e-12);
    CHECK_NEAR(axis[2], 3.0, 1e-12);
    free(p), free(q);
}

PS_TEST_MAIN(TEST(test_deterministic), TEST(test_default_sizes),
             TEST(test_density_scales_count), TEST(test_sphere_uniform),
             TEST(test_dumbbell_surface), TEST(test_star_arms), TEST(test_transform),
             TEST(test_transform_rigid))
