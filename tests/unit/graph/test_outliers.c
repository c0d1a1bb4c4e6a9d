/*
 * test_outliers.c: stray points (outliers.h).  A sphere keeps every point;
 * points far off it are found, each mapped to a sphere point; a cluster of
 * its own stays; dropping remaps the distinct points and the duplicates of
 * an outlier to the kept neighbour; the thread count changes nothing; on a
 * grid, whose edge lengths tie, one point far off it is found.
 */
#include "graph/dedup.h"
#include "graph/outliers.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define STRAYS 6

/* The unit sphere, then `extra` more points from `more` (#extra by 3). */
static double *sphere_and(const double *more, size_t extra, size_t *n) {
    size_t m = 0;
    int *part = NULL;
    double *sphere = ps_shape_sphere(0, &m, &part);
    double *p = sphere ? realloc(sphere, (m + extra) * 3 * sizeof *p) : NULL;
    if (!p) free(sphere);
    if (p && extra) memcpy(p + 3 * m, more, extra * 3 * sizeof *p);
    free(part);
    *n = m + extra;
    return p;
}

/* Runs ps_outliers_find on threads on the kNN graph (k = 7) of p #n. */
static size_t find_on(const double *p, size_t n, int threads, uint32_t *keep_for) {
    ps_graph g = {0};
    ps_error err = {0};
    size_t count = 0;
    if (ps_knn_graph_build(p, n, 3, 7, 1, &g, &err) != PS_OK) return SIZE_MAX;
    if (ps_outliers_find(&g, threads, keep_for, &count, &err) != PS_OK) count = SIZE_MAX;
    ps_graph_free(&g);
    return count;
}

static size_t find(const double *p, size_t n, uint32_t *keep_for) {
    return find_on(p, n, 1, keep_for);
}

static void test_sphere_keeps_every_point(void) {
    size_t n;
    double *p = sphere_and(NULL, 0, &n);
    uint32_t *keep_for = malloc(n * sizeof *keep_for);
    REQUIRE(p && keep_for);
    CHECK(find(p, n, keep_for) == 0);
    for (size_t i = 0; i < n; i++) CHECK(keep_for[i] == i);
    free(p), free(keep_for);
}

static void test_strays_are_found(void) {
    const double strays[STRAYS * 3] = {3, 0, 0, 0, -3, 0, 0, 0, 4, 2, 2, 2, -2, 2, -2, 0, 0, -3.5};
    size_t n;
    double *p = sphere_and(strays, STRAYS, &n);
    uint32_t *keep_for = malloc(n * sizeof *keep_for);
    REQUIRE(p && keep_for);
    CHECK(find(p, n, keep_for) == STRAYS);
    size_t m = n - STRAYS;
    for (size_t i = 0; i < m; i++) CHECK(keep_for[i] == i);
    for (size_t i = m; i < n; i++) {
        CHECK(keep_for[i] < m);
        const double *q = p + 3 * keep_for[i];
        CHECK_NEAR(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]), 1.0, 1e-9);
    }
    free(p), free(keep_for);
}

/* 30 points on a small circle far away: a part of its own, not strays. */
static void test_far_cluster_stays(void) {
    double ring[30 * 3];
    for (int i = 0; i < 30; i++) {
        double t = 2 * 3.14159265358979 * i / 30;
        ring[3 * i] = 10 + 0.2 * cos(t), ring[3 * i + 1] = 0.2 * sin(t), ring[3 * i + 2] = 0;
    }
    size_t n;
    double *p = sphere_and(ring, 30, &n);
    uint32_t *keep_for = malloc(n * sizeof *keep_for);
    REQUIRE(p && keep_for);
    CHECK(find(p, n, keep_for) == 0);
    free(p), free(keep_for);
}

/* Input 0..4 with point 3 a duplicate of the stray 1: distinct 0, 1, 2, 4
 * (indices 0..3), stray 1 kept for by distinct 2. */
static void test_drop_remaps(void) {
    const double pts[5 * 3] = {0, 0, 0, 9, 9, 9, 1, 0, 0, 9, 9, 9, 2, 0, 0};
    ps_dedup d;
    REQUIRE(ps_dedup_build(pts, 5, 3, &d, NULL) == PS_OK);
    REQUIRE(d.n_unique == 4);
    const uint32_t keep_for[4] = {0, 2, 2, 3};
    ps_error err = {0};
    REQUIRE(ps_outliers_drop(&d, 5, keep_for, &err) == PS_OK);
    CHECK(d.n_unique == 3);
    const uint32_t unique_of[5] = {0, 1, 1, 1, 2}, first[3] = {0, 2, 4};
    CHECK(memcmp(d.unique_of, unique_of, sizeof unique_of) == 0);
    CHECK(memcmp(d.first, first, sizeof first) == 0);
    ps_dedup_free(&d);
}

/* The same outliers and keep_for on 1 and 3 threads. */
static void test_threads_same_answer(void) {
    const double strays[STRAYS * 3] = {3, 0, 0, 0, -3, 0, 0, 0, 4, 2, 2, 2, -2, 2, -2, 0, 0, -3.5};
    size_t n;
    double *p = sphere_and(strays, STRAYS, &n);
    uint32_t *one = malloc(n * sizeof *one), *three = malloc(n * sizeof *three);
    REQUIRE(p && one && three);
    CHECK(find_on(p, n, 1, one) == STRAYS && find_on(p, n, 3, three) == STRAYS);
    CHECK(memcmp(one, three, n * sizeof *one) == 0);
    free(p), free(one), free(three);
}

/* A square grid, whose rows of edge lengths are full of ties, and one
 * point far above its middle: that point alone is stray. */
static void test_grid_ties(void) {
    enum { SIDE = 20, N = SIDE * SIDE + 1 };
    double p[3 * N];
    for (int i = 0; i < SIDE * SIDE; i++)
        p[3 * i] = i % SIDE, p[3 * i + 1] = i / SIDE, p[3 * i + 2] = 0;
    p[3 * (N - 1)] = 9.5, p[3 * (N - 1) + 1] = 9.5, p[3 * (N - 1) + 2] = 30;
    uint32_t keep_for[N];
    CHECK(find(p, N, keep_for) == 1);
    for (int i = 0; i < N - 1; i++) CHECK(keep_for[i] == (uint32_t)i);
    CHECK(keep_for[N - 1] < N - 1);
}

PS_TEST_MAIN(TEST(test_threads_same_answer), TEST(test_sphere_keeps_every_point), TEST(test_strays_are_found),
             TEST(test_far_cluster_stays), TEST(test_drop_remaps), TEST(test_grid_ties))
