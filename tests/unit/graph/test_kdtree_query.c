/* test_kdtree_query.c: blocked queries on a shared kd-tree (kdtree_query.h):
 * every query answered with its true nearest points, the same for 1 and 3
 * workers and any block size; no queries is no work; a failing take and a
 * raised cancel flag stop the batch with their status. */
#include "graph/kdtree_query.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

#define SIDE 20 /* a SIDE^3 grid of points, spacing 1 */
#define N (SIDE * SIDE * SIDE)
#define NEIGHBOURS 2

typedef struct queries {
    const double *points;  /* #N by 3: the grid, queried at its own points + 0.1 */
    int *found;            /* #N by NEIGHBOURS */
    int fail_from;         /* take fails for a block starting at or after this (-1: never) */
} queries;

static void gather(void *ctx, size_t first, size_t rows, double *out) {
    const queries *q = ctx;
    for (size_t r = 0; r < rows; r++)
        for (int d = 0; d < 3; d++) out[3 * r + d] = q->points[3 * (first + r) + d] + 0.1;
}

static int take(void *ctx, size_t first, size_t rows, const int *found) {
    queries *q = ctx;
    if (q->fail_from >= 0 && first >= (size_t)q->fail_from) return -1;
    memcpy(q->found + first * NEIGHBOURS, found, rows * NEIGHBOURS * sizeof *found);
    return 0;
}

static double *grid(void) {
    double *p = malloc(3 * N * sizeof *p);
    for (int i = 0; p && i < N; i++)
        p[3 * i] = i % SIDE, p[3 * i + 1] = (i / SIDE) % SIDE, p[3 * i + 2] = i / (SIDE * SIDE);
    return p;
}

/* A kd-tree over the grid *p (made here; free both). */
static flann_index_t grid_index(double **p) {
    struct FLANNParameters fp = ps_kd_parameters();
    float speedup = 0;
    *p = grid();
    return *p ? flann_build_index_double(*p, N, 3, &speedup, &fp) : NULL;
}

static void free_index(flann_index_t index) {
    struct FLANNParameters fp = ps_kd_parameters();
    flann_free_index_double(index, &fp);
}

static ps_status run(flann_index_t index, queries *q, size_t count, size_t block, int threads,
                     const ps_control *ctl) {
    ps_kd_batch b = {.index = index, .dim = 3, .neighbours = NEIGHBOURS, .count = count,
                     .block = block, .gather = gather, .take = take, .ctx = q};
    ps_progress_span span = {ctl, PS_PHASE_KNN, 0.0, 1.0};
    return ps_kd_query(&b, threads, &span);
}

static void test_nearest_for_any_workers(void) {
    double *p = NULL;
    flann_index_t index = grid_index(&p);
    REQUIRE(index);
    int *one = malloc(N * NEIGHBOURS * sizeof *one), *three = malloc(N * NEIGHBOURS * sizeof *three);
    REQUIRE(one && three);
    queries q = {p, one, -1};
    CHECK(run(index, &q, N, 100, 1, NULL) == PS_OK);
    int right = 1;
    for (int i = 0; i < N; i++) right &= one[NEIGHBOURS * i] == i; /* its own point, 0.17 away */
    CHECK(right);
    q.found = three;
    CHECK(run(index, &q, N, 7, 3, NULL) == PS_OK);
    CHECK(memcmp(one, three, N * NEIGHBOURS * sizeof *one) == 0);
    CHECK(run(index, &q, 0, 7, 3, NULL) == PS_OK);
    free_index(index);
    free(p), free(one), free(three);
}

static void test_failure_and_cancel(void) {
    double *p = NULL;
    flann_index_t index = grid_index(&p);
    int *found = malloc(N * NEIGHBOURS * sizeof *found);
    REQUIRE(index && found);
    queries q = {p, found, N / 2};
    CHECK(run(index, &q, N, 64, 2, NULL) == PS_ERR_INTERNAL);
    q.fail_from = -1;
    volatile int cancel = 1;
    ps_control ctl = {.cancel = &cancel};
    CHECK(run(index, &q, N, 64, 2, &ctl) == PS_ERR_CANCELLED);
    free_index(index);
    free(p), free(found);
}

PS_TEST_MAIN(TEST(test_nearest_for_any_workers), TEST(test_failure_and_cancel))
