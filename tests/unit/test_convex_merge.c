/*
 * test_convex_merge.c: the convex merge (convex_merge.h) on the star of
 * star_fixture.h.  Its true parts (a sphere and six arms) stay apart: an
 * arm stands above the sphere's tangent planes.  The sphere cut in two
 * halves is two convex pieces of a convex part, and they merge back,
 * recorded as one merge with the leaf renamed; the same on a rotated and
 * scaled copy.  A flat input is left alone.
 */
#include "convex_merge.h"
#include "star_fixture.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define HALF PS_STAR_PARTS /* the sphere's other half */
#define N_GROUPS (PS_STAR_PARTS + 1)

/* The true parts, with the sphere's points on the far side of the plane
 * x + 2y + 3z = 0 in HALF. */
static void cut_pieces(const ps_star *s, int *group) {
    for (size_t p = 0; p < s->n; p++) {
        const double *x = s->points + 3 * p;
        int far_side = s->part[p] == 0 && x[0] + 2 * x[1] + 3 * x[2] > 0;
        group[p] = far_side ? HALF : s->part[p];
    }
}

static ps_status run_merge(const ps_star *s, const double *points, const double *normals,
                           double mean_angular, int *group, int *leaf, ps_merge **merges,
                           int *n_merges) {
    double *f = calloc(s->n, sizeof *f);
    if (!f) return PS_ERR_NOMEM;
    ps_merge_input in = {.graph = &s->graph, .points = points, .normals = normals, .f = f,
                         .mean_angular = mean_angular, .n_groups = N_GROUPS};
    for (int t = 0; t < N_GROUPS; t++) leaf[t] = t;
    *merges = NULL, *n_merges = 0;
    ps_error err = {0};
    ps_status st = ps_convex_merge(&in, group, leaf, merges, n_merges, &err);
    free(f);
    return st;
}

static void test_true_parts_stay_apart(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    int *group = malloc(s.n * sizeof *group), leaf[N_GROUPS], n_merges;
    REQUIRE(group);
    memcpy(group, s.part, s.n * sizeof *group);
    ps_merge *merges;
    CHECK(run_merge(&s, s.points, s.normals, 1.0, group, leaf, &merges, &n_merges) == PS_OK);
    CHECK_MSG(n_merges == 0, "%d merges", n_merges);
    CHECK(memcmp(group, s.part, s.n * sizeof *group) == 0);
    free(merges);
    free(group);
    ps_star_free(&s);
}

/* After the merge the true parts are back (under the pieces' surviving
 * ids): every point of a part in one segment, no two parts in one. */
static void check_true_parts(const ps_star *s, const int *group) {
    int id_of[PS_STAR_PARTS];
    for (int t = 0; t < PS_STAR_PARTS; t++) id_of[t] = -1;
    size_t wrong = 0;
    for (size_t p = 0; p < s->n; p++) {
        int t = s->part[p];
        if (id_of[t] < 0) id_of[t] = group[p];
        wrong += group[p] != id_of[t];
    }
    CHECK_MSG(wrong == 0, "%zu points away from their part's segment", wrong);
    for (int t = 0; t < PS_STAR_PARTS; t++)
        for (int u = t + 1; u < PS_STAR_PARTS; u++) CHECK(id_of[t] != id_of[u]);
}

/* Rotates and scales s's points and normals into copies. */
static int transformed(const ps_star *s, double scale, double **points, double **normals) {
    *points = malloc(3 * s->n * sizeof **points);
    *normals = malloc(3 * s->n * sizeof **normals);
    if (!*points || !*normals) return 0;
    double c = cos(0.9), t = sin(0.9);
    for (size_t p = 0; p < s->n; p++) {
        const double *x = s->points + 3 * p, *nx = s->normals + 3 * p;
        double *y = *points + 3 * p, *ny = *normals + 3 * p;
        y[0] = scale * (c * x[0] - t * x[1]), y[1] = scale * (t * x[0] + c * x[1]);
        y[2] = scale * x[2];
        ny[0] = c * nx[0] - t * nx[1], ny[1] = t * nx[0] + c * nx[1], ny[2] = nx[2];
    }
    return 1;
}

static void test_convex_pieces_merge_back(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    int *group = malloc(s.n * sizeof *group), *moved = malloc(s.n * sizeof *moved);
    int leaf[N_GROUPS], n_merges;
    double *points = NULL, *normals = NULL;
    REQUIRE(group && moved && transformed(&s, 250.0, &points, &normals));
    ps_merge *merges;
    cut_pieces(&s, group);
    CHECK(run_merge(&s, s.points, s.normals, 1.0, group, leaf, &merges, &n_merges) == PS_OK);
    CHECK_MSG(n_merges == 1, "%d merges", n_merges);
    check_true_parts(&s, group);
    CHECK(leaf[0] == leaf[HALF] && group[0] == leaf[0]);
    free(merges);
    cut_pieces(&s, moved);
    CHECK(run_merge(&s, points, normals, 1.0, moved, leaf, &merges, &n_merges) == PS_OK);
    CHECK_MSG(memcmp(group, moved, s.n * sizeof *group) == 0,
              "a rotated, scaled copy merges otherwise");
    free(merges);
    free(group), free(moved), free(points), free(normals);
    ps_star_free(&s);
}

static void test_flat_input_left_alone(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    int *group = malloc(s.n * sizeof *group), *want = malloc(s.n * sizeof *want);
    int leaf[N_GROUPS], n_merges;
    REQUIRE(group && want);
    cut_pieces(&s, group);
    memcpy(want, group, s.n * sizeof *group);
    ps_merge *merges;
    CHECK(run_merge(&s, s.points, s.normals, 0.0, group, leaf, &merges, &n_merges) == PS_OK);
    CHECK(n_merges == 0 && memcmp(group, want, s.n * sizeof *group) == 0);
    free(merges);
    free(group), free(want);
    ps_star_free(&s);
}

PS_TEST_MAIN(TEST(test_true_parts_stay_apart), TEST(test_convex_pieces_merge_back),
             TEST(test_flat_input_left_alone))
