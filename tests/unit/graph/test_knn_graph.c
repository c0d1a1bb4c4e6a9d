/* test_knn_graph.c: the kNN graph equals a brute-force one (exact neighbour
 * sets, ties by index), is symmetric with sorted rows, does not depend on
 * the thread count, the scale or a rotation of a grid full of ties, and
 * components are numbered by lowest vertex. */
#include "graph/knn_graph.h"
#include "progress_seen.h"
#include "random_bits.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static double *random_points(size_t n, int dim, unsigned seed) {
    double *p = malloc(n * (size_t)dim * sizeof *p);
    uint64_t s = 88172645463325252ULL ^ seed;
    for (size_t i = 0; p && i < n * (size_t)dim; i++) {
        p[i] = ps_uniform_next(&s);
    }
    return p;
}

static double dist(const double *a, const double *b, int dim) {
    double s = 0;
    for (int i = 0; i < dim; i++) s += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(s);
}

/* adj #P by #P: 1 when q is among p's k nearest (distance, then index) or p among q's. */
static unsigned char *brute_adjacency(const double *pts, size_t n, int dim, int k) {
    unsigned char *adj = calloc(n * n, 1);
    unsigned char *taken = malloc(n);
    for (size_t p = 0; adj && taken && p < n; p++) {
        memset(taken, 0, n);
        taken[p] = 1;
        for (int t = 0; t < k; t++) {
            size_t best = n;
            for (size_t q = 0; q < n; q++) {
                if (taken[q]) continue;
                if (best == n || dist(&pts[p * dim], &pts[q * dim], dim) <
                                     dist(&pts[p * dim], &pts[best * dim], dim))
                    best = q;
            }
            taken[best] = 1;
            adj[p * n + best] = adj[best * n + p] = 1;
        }
    }
    free(taken);
    return adj;
}

static void check_against_brute(const double *pts, size_t n, int dim, int k, int threads) {
    ps_graph g;
    ps_error err;
    REQUIRE(ps_knn_graph_build(pts, n, dim, k, threads, &g, &err) == PS_OK);
    unsigned char *adj = brute_adjacency(pts, n, dim, k);
    REQUIRE(adj);
    size_t expected_edges = 0, mismatches = 0;
    for (size_t i = 0; i < n * n; i++) expected_edges += adj[i];
    CHECK(g.offsets[n] == expected_edges);
    for (size_t p = 0; p < n; p++)
        for (size_t e = g.offsets[p]; e < g.offsets[p + 1]; e++) {
            uint32_t q = g.neighbors[e];
            if (e > g.offsets[p]) CHECK(q > g.neighbors[e - 1]);
            mismatches += !adj[p * n + q];
            CHECK(g.weights[e] == dist(&pts[p * dim], &pts[q * dim], dim));
        }
    CHECK_MSG(mismatches == 0, "%zu edges not in the brute-force graph", mismatches);
    free(adj);
    ps_graph_free(&g);
}

static void test_random_3d(void) {
    double *p = random_points(600, 3, 1);
    REQUIRE(p);
    check_against_brute(p, 600, 3, 7, 2);
    check_against_brute(p, 600, 3, 1, 1);
    free(p);
}

static void test_random_high_dim(void) {
    double *p = random_points(300, 6, 2);
    REQUIRE(p);
    check_against_brute(p, 300, 6, 10, 3);
    free(p);
}

/* A square grid is all ties: 4 neighbours at 1, 4 at sqrt 2, 4 at 2. */
static void test_grid_ties(void) {
    double p[2 * 15 * 15];
    for (int i = 0; i < 15; i++)
        for (int j = 0; j < 15; j++) p[2 * (i * 15 + j)] = i, p[2 * (i * 15 + j) + 1] = j;
    check_against_brute(p, 225, 2, 6, 2);
    check_against_brute(p, 225, 2, 5, 1);
}

/* The origin is the nearest neighbour of 200 random unit vectors in 64-d
 * (pairwise about sqrt 2 apart): a hub whose row holds 200 entries. */
static void test_hub_row(void) {
    size_t n = 201;
    int dim = 64;
    double *p = random_points(n, dim, 4);
    REQUIRE(p);
    for (size_t i = 0; i < (size_t)dim; i++) p[i] = 0.0;
    for (size_t i = 1; i < n; i++) {
        double len = 0.0;
        for (int d = 0; d < dim; d++) p[i * dim + d] -= 0.5, len += p[i * dim + d] * p[i * dim + d];
        for (int d = 0; d < dim; d++) p[i * dim + d] /= sqrt(len);
    }
    ps_graph g;
    REQUIRE(ps_knn_graph_build(p, n, dim, 2, 2, &g, NULL) == PS_OK);
    CHECK(g.offsets[1] - g.offsets[0] == n - 1);
    ps_graph_free(&g);
    check_against_brute(p, n, dim, 2, 2);
    free(p);
}

static int same_graph(const ps_graph *a, const ps_graph *b) {
    size_t e = a->offsets[a->n];
    return a->n == b->n && memcmp(a->offsets, b->offsets, (a->n + 1) * sizeof *a->offsets) == 0 &&
           memcmp(a->neighbors, b->neighbors, e * sizeof *a->neighbors) == 0;
}

static void test_threads_and_scale_invariant(void) {
    size_t n;
    double *p = ps_shape_hand(0.0, &n, NULL);
    REQUIRE(p);
    double *big = malloc(n * 3 * sizeof *big), *tiny = malloc(n * 3 * sizeof *tiny);
    REQUIRE(big && tiny);
    for (size_t i = 0; i < 3 * n; i++) big[i] = p[i] * 1024.0 + 5e6, tiny[i] = p[i] / 1024.0;
    ps_graph g1, g2, g3, gb, gt;
    REQUIRE(ps_knn_graph_build(p, n, 3, 7, 1, &g1, NULL) == PS_OK);
    REQUIRE(ps_knn_graph_build(p, n, 3, 7, 2, &g2, NULL) == PS_OK);
    REQUIRE(ps_knn_graph_build(p, n, 3, 7, 3, &g3, NULL) == PS_OK);
    REQUIRE(ps_knn_graph_build(big, n, 3, 7, 2, &gb, NULL) == PS_OK);
    REQUIRE(ps_knn_graph_build(tiny, n, 3, 7, 2, &gt, NULL) == PS_OK);
    CHECK(same_graph(&g1, &g2));
    CHECK(same_graph(&g1, &g3));
    CHECK(memcmp(g1.weights, g3.weights, g1.offsets[n] * sizeof *g1.weights) == 0);
    CHECK(same_graph(&g1, &gb));
    CHECK(same_graph(&g1, &gt));
    CHECK_NEAR(gt.weights[0] * 1024.0, g1.weights[0], 1e-12);
    ps_graph_free(&g1), ps_graph_free(&g2), ps_graph_free(&g3);
    ps_graph_free(&gb), ps_graph_free(&gt);
    free(p), free(big), free(tiny);
}

/* A square grid in 3-D, rotated and scaled: its equal distances differ in
 * the last bits after the move, and must still be ties broken by index
 * (4 neighbours at 1, 4 at sqrt 2: a tie set within the EXTRA candidates). */
static void test_rotated_grid_same_graph(void) {
    enum { side = 30, count = side * side };
    double *grid = malloc(3 * count * sizeof *grid), *moved = malloc(3 * count * sizeof *moved);
    REQUIRE(grid && moved);
    for (int i = 0; i < count; i++) grid[3 * i] = i % side, grid[3 * i + 1] = i / side, grid[3 * i + 2] = 0;
    memcpy(moved, grid, 3 * count * sizeof *moved);
    const double shift[3] = {3.5, -1.25, 7};
    ps_shape_transform(moved, count, 1, 2, 3, 1.1, 1000, shift);
    ps_graph a, b;
    REQUIRE(ps_knn_graph_build(grid, count, 3, 7, 1, &a, NULL) == PS_OK);
    REQUIRE(ps_knn_graph_build(moved, count, 3, 7, 2, &b, NULL) == PS_OK);
    CHECK(same_graph(&a, &b));
    ps_graph_free(&a), ps_graph_free(&b);
    free(grid), free(moved);
}

/* Two clusters far apart, interleaved in index order, and a small third
 * one of k + 2 points at the end. */
static void test_components(void) {
    size_t n = 410;
    double *p = random_points(n, 3, 3);
    REQUIRE(p);
    for (size_t i = 0; i < 400; i++) p[3 * i] += (i % 2) ? 100.0 : 0.0;
    for (size_t i = 400; i < n; i++) p[3 * i] -= 500.0;
    ps_graph g;
    REQUIRE(ps_knn_graph_build(p, n, 3, 8, 2, &g, NULL) == PS_OK);
    int *comp = malloc(n * sizeof *comp);
    REQUIRE(comp);
    CHECK(ps_graph_components(&g, comp) == 3);
    for (size_t i = 0; i < 400; i++) CHECK(comp[i] == (int)(i % 2));
    for (size_t i = 400; i < n; i++) CHECK(comp[i] == 2);
    free(comp), free(p);
    ps_graph_free(&g);
}

static void test_rejects_bad_k(void) {
    double p[6] = {0, 0, 0, 1, 1, 1};
    ps_graph g;
    ps_error err = {0};
    CHECK(ps_knn_graph_build(p, 2, 3, 2, 1, &g, &err) == PS_ERR_INVALID);
    CHECK(err.status == PS_ERR_INVALID && strstr(err.message, "k") != NULL);
    CHECK(g.offsets == NULL);
    CHECK(ps_knn_graph_build(p, 2, 3, 0, 1, &g, NULL) == PS_ERR_INVALID);
}

/* The tracked build gives the same graph, reports rising progress over
 * its span as the query blocks go, and stops when cancelled. */
static void test_tracked_progress_and_cancel(void) {
    size_t n;
    double *pts = ps_shape_star(400.0, &n, NULL);
    ps_graph plain, tracked;
    ps_progress_seen seen = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &seen};
    ps_progress_span span = {&ctl, PS_PHASE_KNN, 0.0, 0.45};
    REQUIRE(pts && n > 4 * 2048);
    REQUIRE(ps_knn_graph_build(pts, n, 3, 7, 2, &plain, NULL) == PS_OK);
    ps_knn_graph_input in = {.points = pts, .n = n, .dim = 3, .k = 7, .threads = 2, .span = &span};
    REQUIRE(ps_knn_graph_build_tracked(&in, &tracked, NULL) == PS_OK);
    CHECK(same_graph(&plain, &tracked));
    CHECK_MSG(seen.calls[PS_PHASE_KNN] > 3 && !seen.went_back && seen.last[PS_PHASE_KNN] == 0.45,
              "%d calls, last %g", seen.calls[PS_PHASE_KNN], seen.last[PS_PHASE_KNN]);
    ps_graph_free(&plain), ps_graph_free(&tracked);
    volatile int cancel = 1;
    ctl.cancel = &cancel;
    ps_error err = {0};
    CHECK(ps_knn_graph_build_tracked(&in, &tracked, &err) == PS_ERR_CANCELLED);
    CHECK(err.status == PS_ERR_CANCELLED && tracked.offsets == NULL);
    free(pts);
}

PS_TEST_MAIN(TEST(test_random_3d), TEST(test_random_high_dim), TEST(test_grid_ties),
             TEST(test_rotated_grid_same_graph),
             TEST(test_hub_row),
             TEST(test_threads_and_scale_invariant), TEST(test_components),
             TEST(test_rejects_bad_k), TEST(test_tracked_progress_and_cancel))
