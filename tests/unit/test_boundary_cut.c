/*
 * test_boundary_cut.c: the boundary cut (boundary_cut.h) on the star of
 * shapes.h, whose arms meet the central sphere along concave creases.
 * Segments start as the true parts with each boundary moved off the crease
 * (out along odd arms, into the sphere for even ones); after the cut more
 * points agree with their part, the boundaries lie on the creases, every
 * supernode's points share its sink's segment, and the answer is the same
 * on every run.  Starting from the true parts, the cut keeps them.
 */
#include "boundary_cut.h"
#include "normals.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N_PARTS 7               /* sphere 0, arms 1..6 */
#define CREASE 1.1475           /* sqrt(1.2^2 - 0.35^2): where an arm meets the sphere */

typedef struct star {
    double *points, *normals;
    int *part;
    size_t n;
    ps_graph graph;
    uint32_t sinks[N_PARTS];    /* a point of each part, far from any crease */
} star;

/* Coordinate along the axis of arm k (1..6). */
static double along_arm(const double *x, int k) {
    int axis = (k - 1) / 2;
    return (k - 1) % 2 ? -x[axis] : x[axis];
}

/* The sphere's sink: its point nearest +x+y+z; an arm's: its tip. */
static double sink_score(const double *x, int k) {
    return k == 0 ? x[0] + x[1] + x[2] : along_arm(x, k);
}

static int star_build(star *s) {
    memset(s, 0, sizeof *s);
    s->points = ps_shape_star(0, &s->n, &s->part);
    s->normals = malloc(s->n * 3 * sizeof *s->normals);
    int *component = malloc(s->n * sizeof *component);
    ps_error err = {0};
    int ok = s->normals && component &&
             ps_knn_graph_build(s->points, s->n, 3, 7, 1, &s->graph, &err) == PS_OK;
    int nc = ok ? ps_graph_components(&s->graph, component) : 0;
    ok = ok && ps_normals_build(&s->graph, s->points, NULL, component, nc, s->normals, &err) ==
                   PS_OK;
    free(component);
    double best[N_PARTS];
    for (int k = 0; k < N_PARTS; k++) best[k] = -INFINITY;
    for (uint32_t p = 0; ok && p < s->n; p++) {
        double score = sink_score(s->points + 3 * p, s->part[p]);
        if (score > best[s->part[p]]) best[s->part[p]] = score, s->sinks[s->part[p]] = p;
    }
    return ok;
}

static void star_free(star *s) {
    free(s->points);
    free(s->normals);
    free(s->part);
    ps_graph_free(&s->graph);
}

/* Parts with boundaries off the crease: odd arms lose their base up to
 * 1.6 along the arm to the sphere, even arms take the sphere's points
 * beyond 0.95 along their axis. */
static void shifted_groups(const star *s, int *group) {
    for (size_t p = 0; p < s->n; p++) {
        const double *x = s->points + 3 * p;
        group[p] = s->part[p];
        if (s->part[p] > 0 && s->part[p] % 2 && along_arm(x, s->part[p]) < 1.6) group[p] = 0;
        for (int k = 2; k < N_PARTS && s->part[p] == 0; k += 2)
            if (along_arm(x, k) > 0.95) group[p] = k;
    }
}

static double agreement(const star *s, const int *group) {
    size_t same = 0;
    for (size_t p = 0; p < s->n; p++) same += group[p] == s->part[p];
    return (double)same / (double)s->n;
}

/* Fraction of the edges between two segments whose ends are both within
 * `tolerance` of the crease of the arm involved. */
static double boundary_on_crease(const star *s, const int *group, double tolerance) {
    size_t crossing = 0, on_crease = 0;
    for (size_t p = 0; p < s->n; p++)
        for (size_t e = s->graph.offsets[p]; e < s->graph.offsets[p + 1]; e++) {
            size_t q = s->graph.neighbors[e];
            if (q <= p || group[p] == group[q]) continue;
            int arm = group[p] > group[q] ? group[p] : group[q];
            double dp = along_arm(s->points + 3 * p, arm) - CREASE;
            double dq = along_arm(s->points + 3 * q, arm) - CREASE;
            crossing++;
            on_crease += fabs(dp) <= tolerance && fabs(dq) <= tolerance;
        }
    return crossing ? (double)on_crease / (double)crossing : 0;
}

static ps_status run_cut(const star *s, int *group, int *supernode_of) {
    ps_boundary_cut_input in = {.graph = &s->graph, .points = s->points,
                                .normals = s->normals, .n_groups = N_PARTS,
                                .n_supernodes = N_PARTS, .sinks = s->sinks};
    for (size_t p = 0; p < s->n; p++) supernode_of[p] = group[p];
    ps_error err = {0};
    ps_status st = ps_boundary_cut(&in, group, supernode_of, &err);
    CHECK_MSG(st == PS_OK, "ps_boundary_cut: %s", err.message);
    return st;
}

static void test_star_boundaries_move_to_creases(void) {
    star s;
    REQUIRE(star_build(&s));
    int *group = malloc(s.n * sizeof *group), *supernode_of = malloc(s.n * sizeof *supernode_of);
    REQUIRE(group && supernode_of);
    shifted_groups(&s, group);
    double before = agreement(&s, group), crease_before = boundary_on_crease(&s, group, 0.2);
    REQUIRE(run_cut(&s, group, supernode_of) == PS_OK);
    double after = agreement(&s, group), crease_after = boundary_on_crease(&s, group, 0.2);
    CHECK_MSG(after > before && after >= 0.97, "agreement %.3f before, %.3f after", before,
              after);
    CHECK_MSG(crease_before < 0.1 && crease_after >= 0.9,
              "boundary edges on the crease: %.3f before, %.3f after", crease_before,
              crease_after);
    for (size_t p = 0; p < s.n; p++)
        CHECK(group[p] == group[s.sinks[supernode_of[p]]]);
    free(group);
    free(supernode_of);
    star_free(&s);
}

static void test_true_parts_stay(void) {
    star s;
    REQUIRE(star_build(&s));
    int *group = malloc(s.n * sizeof *group), *supernode_of = malloc(s.n * sizeof *supernode_of);
    REQUIRE(group && supernode_of);
    memcpy(group, s.part, s.n * sizeof *group);
    REQUIRE(run_cut(&s, group, supernode_of) == PS_OK);
    double kept = agreement(&s, group);
    CHECK_MSG(kept >= 0.98, "only %.3f of the points kept their part", kept);
    free(group);
    free(supernode_of);
    star_free(&s);
}

static void test_deterministic(void) {
    star s;
    REQUIRE(star_build(&s));
    int *a = malloc(s.n * sizeof *a), *b = malloc(s.n * sizeof *b);
    int *sa = malloc(s.n * sizeof *sa), *sb = malloc(s.n * sizeof *sb);
    REQUIRE(a && b && sa && sb);
    shifted_groups(&s, a);
    shifted_groups(&s, b);
    REQUIRE(run_cut(&s, a, sa) == PS_OK && run_cut(&s, b, sb) == PS_OK);
    CHECK(memcmp(a, b, s.n * sizeof *a) == 0);
    CHECK(memcmp(sa, sb, s.n * sizeof *sa) == 0);
    free(a);
    free(b);
    free(sa);
    free(sb);
    star_free(&s);
}

PS_TEST_MAIN(TEST(test_star_boundaries_move_to_creases), TEST(test_true_parts_stay),
             TEST(test_deterministic))
