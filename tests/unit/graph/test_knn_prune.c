/* test_knn_prune.c: ps_knn_graph_prune gives, edge for edge and weight
 * for weight, the graph a new build gives on the kept points: for the
 * stray points the outlier search finds (one and two threads), over two
 * rounds of removals, on a grid full of ties, and when most points go; it
 * declines (graph unchanged) when too few points would remain. */
#include "graph/knn_graph.h"
#include "graph/outliers.h"
#include "random_bits.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

static double *random_points(size_t n, unsigned seed) {
    double *p = malloc(n * 3 * sizeof *p);
    uint64_t s = 88172645463325252ULL ^ seed;
    for (size_t i = 0; p && i < n * 3; i++) {
        p[i] = ps_uniform_next(&s);
    }
    return p;
}

/* The kept points (keep_for[p] == p) in order, as a new array. */
static double *kept_points(const double *pts, size_t n, const uint32_t *keep_for, size_t *kept) {
    double *out = malloc(n * 3 * sizeof *out);
    *kept = 0;
    for (size_t p = 0; out && p < n; p++)
        if (keep_for[p] == p) memcpy(out + 3 * (*kept)++, pts + 3 * p, 3 * sizeof *out);
    return out;
}

static void check_same_graph(const ps_graph *a, const ps_graph *b) {
    REQUIRE(a->n == b->n);
    REQUIRE(a->offsets[a->n] == b->offsets[b->n]);
    size_t rows = 0, cols = 0;
    for (size_t p = 0; p <= a->n; p++) rows += a->offsets[p] != b->offsets[p];
    for (size_t e = 0; e < a->offsets[a->n]; e++)
        cols += a->neighbors[e] != b->neighbors[e] || a->weights[e] != b->weights[e];
    CHECK_MSG(rows == 0 && cols == 0, "%zu offsets and %zu entries differ", rows, cols);
}

/* Removes the points with keep_for[p] != p from g and memo (of *pts, *n
 * points) and checks the result against a new build; *pts and *n become
 * the kept points, *removed how many went. */
static void prune_and_check(ps_graph *g, ps_knn_memo *memo, double **pts, size_t *n, int k,
                            int threads, const uint32_t *keep_for, size_t *removed) {
    ps_progress_span span = {NULL, PS_PHASE_KNN, 0.0, 1.0};
    int pruned = 0;
    ps_error err;
    REQUIRE(ps_knn_graph_prune(g, memo, *pts, keep_for, threads, &span, &pruned, &err) == PS_OK);
    CHECK(pruned);
    size_t kept = 0;
    double *rest = kept_points(*pts, *n, keep_for, &kept);
    ps_graph fresh;
    REQUIRE(rest && ps_knn_graph_build(rest, kept, 3, k, threads, &fresh, &err) == PS_OK);
    check_same_graph(g, &fresh);
    ps_graph_free(&fresh);
    free(*pts);
    *removed = *n - kept;
    *pts = rest, *n = kept;
}

static void strays_like_the_pipeline(int threads) {
    size_t n = 4000, strays = 20;
    double *pts = random_points(n + strays, 7);
    REQUIRE(pts);
    for (size_t p = 0; p < n + strays; p++) /* a thin slab, strays well above it */
        pts[3 * p + 2] = p < n ? 0.02 * pts[3 * p + 2] : 0.1 + 0.3 * pts[3 * p + 2];
    n += strays;
    ps_graph g;
    ps_knn_memo *memo = NULL;
    ps_progress_span span = {NULL, PS_PHASE_KNN, 0.0, 1.0};
    ps_knn_graph_input in = {.points = pts, .n = n, .dim = 3, .k = 7, .threads = threads,
                             .span = &span};
    REQUIRE(ps_knn_graph_build_memo(&in, &g, &memo, NULL) == PS_OK);
    uint32_t *keep_for = malloc(n * sizeof *keep_for);
    size_t count = 0;
    REQUIRE(keep_for && ps_outliers_find(&g, threads, keep_for, &count, NULL) == PS_OK);
    CHECK(count > strays / 2);
    size_t removed = 0;
    prune_and_check(&g, memo, &pts, &n, 7, threads, keep_for, &removed);
    CHECK(removed == count);
    free(keep_for);
    free(pts);
    ps_knn_memo_free(memo);
    ps_graph_free(&g);
}

static void test_strays_one_thread(void) {
    strays_like_the_pipeline(1);
}

static void test_strays_two_threads(void) {
    strays_like_the_pipeline(2);
}

/* keep_for for dropping every step-th point (the others keep themselves). */
static uint32_t *every(size_t n, size_t step, size_t offset) {
    uint32_t *keep_for = malloc(n * sizeof *keep_for);
    for (size_t p = 0; keep_for && p < n; p++)
        keep_for[p] = (uint32_t)(p % step == offset ? (p + 1) % n : p);
    return keep_for;
}

static void rounds(double *pts, size_t n, int k, const size_t *steps, size_t n_steps) {
    ps_graph g;
    ps_knn_memo *memo = NULL;
    ps_progress_span span = {NULL, PS_PHASE_KNN, 0.0, 1.0};
    ps_knn_graph_input in = {.points = pts, .n = n, .dim = 3, .k = k, .threads = 2,
                             .span = &span};
    REQUIRE(ps_knn_graph_build_memo(&in, &g, &memo, NULL) == PS_OK);
    for (size_t r = 0; r < n_steps; r++) {
        uint32_t *keep_for = every(n, steps[r], r % steps[r]);
        REQUIRE(keep_for);
        size_t removed = 0;
        prune_and_check(&g, memo, &pts, &n, k, 2, keep_for, &removed);
        CHECK(removed > 0);
        free(keep_for);
    }
    free(pts);
    ps_knn_memo_free(memo);
    ps_graph_free(&g);
}

static void test_two_rounds(void) {
    const size_t steps[] = {7, 5};
    rounds(random_points(3000, 3), 3000, 7, steps, 2);
}

/* Every other point goes: most rows are searched again and rebuilt. */
static void test_most_rows_change(void) {
    const size_t steps[] = {2, 3};
    rounds(random_points(2000, 5), 2000, 10, steps, 2);
}

/* A 30 x 30 grid: equal distances everywhere, ties broken by index (k = 4
 * keeps every tie set within the candidates, as the build needs to be
 * exact). */
static void test_grid_ties(void) {
    size_t n = 30 * 30;
    double *pts = calloc(n * 3, sizeof *pts);
    REQUIRE(pts);
    for (size_t i = 0; i < n; i++) pts[3 * i] = (double)(i % 30), pts[3 * i + 1] = (double)(i / 30);
    const size_t steps[] = {11, 17};
    rounds(pts, n, 4, steps, 2);
}

/* Fewer than k + 4 points left: it declines and leaves g alone. */
static void test_declines_when_few_remain(void) {
    size_t n = 12;
    double *pts = random_points(n, 9);
    ps_graph g;
    ps_knn_memo *memo = NULL;
    ps_progress_span span = {NULL, PS_PHASE_KNN, 0.0, 1.0};
    ps_knn_graph_input in = {.points = pts, .n = n, .dim = 3, .k = 7, .threads = 1,
                             .span = &span};
    REQUIRE(pts && ps_knn_graph_build_memo(&in, &g, &memo, NULL) == PS_OK);
    size_t edges = g.offsets[n];
    uint32_t *keep_for = every(n, 4, 0);
    int pruned = 1;
    REQUIRE(keep_for &&
            ps_knn_graph_prune(&g, memo, pts, keep_for, 1, &span, &pruned, NULL) == PS_OK);
    CHECK(!pruned && g.n == n && g.offsets[n] == edges);
    free(keep_for), free(pts);
    ps_knn_memo_free(memo);
    ps_graph_free(&g);
}

PS_TEST_MAIN(TEST(test_strays_one_thread), TEST(test_strays_two_threads), TEST(test_two_rounds),
             TEST(test_most_rows_change), TEST(test_grid_ties), TEST(test_declines_when_few_remain))
