/*
 * test_convex_merge.c: the convex merge (convex_merge.h) on the star of
 * star_fixture.h.  Its true parts (a sphere and six arms) stay apart: an
 * arm stands above the sphere's tangent planes.  The sphere cut in two
 * halves is two convex pieces of a convex part, and they merge back,
 * recorded as one merge with the leaf renamed; the same on a rotated and
 * scaled copy.  A flat input is left alone.  Two overlapping spheres cut
 * at their waist merge by the threshold their boundary's creases ask.
 */
#include "graph/knn_graph.h"
#include "refine/convex_merge.h"
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
    ps_star_merge_input in = {.points = points, .normals = normals,
                              .mean_angular = mean_angular, .n_groups = N_GROUPS};
    return ps_star_merge(s, ps_convex_merge, &in, group, leaf, merges, n_merges);
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

/* Two unit spheres with centres 2d apart on the z axis, the points of
 * each outside the other (a peanut with a concave waist), their outward
 * normals, a kNN graph; group: the side of z = 0. */
typedef struct peanut {
    size_t n;
    double *points, *normals;
    int *group;
    ps_graph graph;
} peanut;

static int peanut_build(double d, peanut *pn) {
    enum { RINGS = 60, PER_RING = 120 };
    size_t cap = 2 * RINGS * PER_RING;
    pn->points = malloc(3 * cap * sizeof *pn->points);
    pn->normals = malloc(3 * cap * sizeof *pn->normals);
    pn->group = malloc(cap * sizeof *pn->group);
    if (!pn->points || !pn->normals || !pn->group) return 0;
    pn->n = 0;
    for (int side = 0; side < 2; side++) {
        double cz = side ? d : -d;
        for (int i = 0; i < RINGS; i++) {
            double theta = 3.14159265358979323846 * (i + 0.5) / RINGS;
            for (int j = 0; j < PER_RING; j++) {
                double phi = 2 * 3.14159265358979323846 * (j + 0.5 * (i % 2)) / PER_RING;
                double n[3] = {sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta)};
                double x[3] = {n[0], n[1], cz + n[2]};
                double oz = side ? -d : d; /* inside the other sphere: left out */
                if (x[0] * x[0] + x[1] * x[1] + (x[2] - oz) * (x[2] - oz) < 1) continue;
                memcpy(pn->points + 3 * pn->n, x, sizeof x);
                memcpy(pn->normals + 3 * pn->n, n, sizeof n);
                pn->group[pn->n++] = x[2] > 0;
            }
        }
    }
    ps_error err = {0};
    return ps_knn_graph_build(pn->points, pn->n, 3, 7, 1, &pn->graph, &err) == PS_OK;
}

static void peanut_free(peanut *pn) {
    free(pn->points), free(pn->normals), free(pn->group);
    ps_graph_free(&pn->graph);
}

static int peanut_merges(const peanut *pn, double mean_angular) {
    double *f = calloc(pn->n, sizeof *f);
    int *group = malloc(pn->n * sizeof *group), leaf[2] = {0, 1}, n_merges = 0;
    ps_merge *merges = NULL;
    memcpy(group, pn->group, pn->n * sizeof *group);
    ps_merge_input in = {.graph = &pn->graph, .points = pn->points, .normals = pn->normals,
                         .f = f, .mean_angular = mean_angular, .n_groups = 2};
    ps_error err = {0};
    ps_status st = ps_convex_merge(&in, group, leaf, &merges, &n_merges, &err);
    free(f), free(group), free(merges);
    return st == PS_OK ? n_merges : -1;
}

/* The two thresholds (convex_merge.h): a waist with a convexity of about
 * 0.9 merges when it is no crease (a large crease scale in the input) and
 * stays when it is one (a tiny scale marks every boundary edge); a barely
 * concave waist (about 0.98) merges either way, a deep one (about 0.6)
 * neither way. */
static void test_partly_smooth_boundary(void) {
    static const struct {
        double d;
        int smooth, creased; /* merges expected */
    } cases[] = {{0.3, 1, 1}, {0.55, 1, 0}, {0.9, 0, 0}};
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        peanut pn;
        REQUIRE(peanut_build(cases[i].d, &pn));
        CHECK_MSG(peanut_merges(&pn, 1e3) == cases[i].smooth, "d %.2f, smooth", cases[i].d);
        CHECK_MSG(peanut_merges(&pn, 1e-5) == cases[i].creased, "d %.2f, creased", cases[i].d);
        peanut_free(&pn);
    }
}

PS_TEST_MAIN(TEST(test_true_parts_stay_apart), TEST(test_convex_pieces_merge_back),
             TEST(test_flat_input_left_alone), TEST(test_partly_smooth_boundary))
