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
#include "star_fixture.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N_PARTS PS_STAR_PARTS
#define CREASE PS_STAR_CREASE

typedef struct star {
    ps_star shape;
    uint32_t sinks[N_PARTS];    /* a point of each part, far from any crease */
} star;

/* The sphere's sink: its point nearest +x+y+z; an arm's: its tip. */
static double sink_score(const double *x, int k) {
    return k == 0 ? x[0] + x[1] + x[2] : ps_star_along_arm(x, k);
}

static int star_build(star *s) {
    int ok = ps_star_build(&s->shape);
    double best[N_PARTS];
    for (int k = 0; k < N_PARTS; k++) best[k] = -INFINITY;
    for (uint32_t p = 0; ok && p < s->shape.n; p++) {
        double score = sink_score(s->shape.points + 3 * p, s->shape.part[p]);
        int k = s->shape.part[p];
        if (score > best[k]) best[k] = score, s->sinks[k] = p;
    }
    return ok;
}

static void star_free(star *s) {
    ps_star_free(&s->shape);
}

/* Parts with boundaries off the crease: odd arms lose their base up to
 * 1.6 along the arm to the sphere, even arms take the sphere's points
 * beyond 0.95 along their axis. */
static void shifted_groups(const star *s, int *group) {
    for (size_t p = 0; p < s->shape.n; p++) {
        const double *x = s->shape.points + 3 * p;
        int part = s->shape.part[p];
        group[p] = part;
        if (part > 0 && part % 2 && ps_star_along_arm(x, part) < 1.6) group[p] = 0;
        for (int k = 2; k < N_PARTS && part == 0; k += 2)
            if (ps_star_along_arm(x, k) > 0.95) group[p] = k;
    }
}

static double agreement(const star *s, const int *group) {
    size_t same = 0;
    for (size_t p = 0; p < s->shape.n; p++) same += group[p] == s->shape.part[p];
    return (double)same / (double)s->shape.n;
}

/* Fraction of the edges between two segments whose ends are both within
 * `tolerance` of the crease of the arm involved. */
static double boundary_on_crease(const star *s, const int *group, double tolerance) {
    size_t crossing = 0, on_crease = 0;
    for (size_t p = 0; p < s->shape.n; p++)
        for (size_t e = s->shape.graph.offsets[p]; e < s->shape.graph.offsets[p + 1]; e++) {
            size_t q = s->shape.graph.neighbors[e];
            if (q <= p || group[p] == group[q]) continue;
            int arm = group[p] > group[q] ? group[p] : group[q];
            double dp = ps_star_along_arm(s->shape.points + 3 * p, arm) - CREASE;
            double dq = ps_star_along_arm(s->shape.points + 3 * q, arm) - CREASE;
            crossing++;
            on_crease += fabs(dp) <= tolerance && fabs(dq) <= tolerance;
        }
    return crossing ? (double)on_crease / (double)crossing : 0;
}

static ps_status run_cut(const star *s, int *group, int *supernode_of) {
    ps_boundary_cut_input in = {.graph = &s->shape.graph, .points = s->shape.points,
                                .normals = s->shape.normals, .n_groups = N_PARTS,
                                .n_supernodes = N_PARTS, .sinks = s->sinks};
    for (size_t p = 0; p < s->shape.n; p++) supernode_of[p] = group[p];
    ps_error err = {0};
    ps_status st = ps_boundary_cut(&in, group, supernode_of, &err);
    CHECK_MSG(st == PS_OK, "ps_boundary_cut: %s", err.message);
    return st;
}

static void test_star_boundaries_move_to_creases(void) {
    star s;
    REQUIRE(star_build(&s));
    int *group = malloc(s.shape.n * sizeof *group), *supernode_of = malloc(s.shape.n * sizeof *supernode_of);
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
    for (size_t p = 0; p < s.shape.n; p++)
        CHECK(group[p] == group[s.sinks[supernode_of[p]]]);
    free(group);
    free(supernode_of);
    star_free(&s);
}

static void test_true_parts_stay(void) {
    star s;
    REQUIRE(star_build(&s));
    int *group = malloc(s.shape.n * sizeof *group), *supernode_of = malloc(s.shape.n * sizeof *supernode_of);
    REQUIRE(group && supernode_of);
    memcpy(group, s.shape.part, s.shape.n * sizeof *group);
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
    int *a = malloc(s.shape.n * sizeof *a), *b = malloc(s.shape.n * sizeof *b);
    int *sa = malloc(s.shape.n * sizeof *sa), *sb = malloc(s.shape.n * sizeof *sb);
    REQUIRE(a && b && sa && sb);
    shifted_groups(&s, a);
    shifted_groups(&s, b);
    REQUIRE(run_cut(&s, a, sa) == PS_OK && run_cut(&s, b, sb) == PS_OK);
    CHECK(memcmp(a, b, s.shape.n * sizeof *a) == 0);
    CHECK(memcmp(sa, sb, s.shape.n * sizeof *sa) == 0);
    free(a);
    free(b);
    free(sa);
    free(sb);
    star_free(&s);
}

PS_TEST_MAIN(TEST(test_star_boundaries_move_to_creases), TEST(test_true_parts_stay),
             TEST(test_deterministic))
