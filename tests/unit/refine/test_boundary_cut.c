/*
 * test_boundary_cut.c: the boundary cut (boundary_cut.h) on the star of
 * shapes.h, whose arms meet the central sphere along concave creases.
 * Segments start as the true parts with each boundary moved off the crease
 * (out along odd arms, into the sphere for even ones); after the cut more
 * points agree with their part, the boundaries lie on the creases, every
 * supernode's points share its sink's segment, and the answer is the same
 * on every run.  Starting from the true parts, the cut keeps them.  From
 * messy segments (blobs of other segments, two of them split in pieces,
 * and scattered points), sinks keep their segments and every point the cut
 * moves lies within the band's cap of a boundary it started next to.  With
 * a progress span it answers the same, reports rising progress pair by
 * pair up to the span's end, and stops when cancelled.  Pairs run side by
 * side give the same answer on 1, 2 and 3 threads.
 */
#include "progress_seen.h"
#include "refine/boundary_cut.h"
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

/* The edge scales the cut reads, as the pipeline's metric pass gives them. */
static ps_edge_scales scales_of(const ps_star *sh) {
    ps_edge_scales scales = {0, 0};
    ps_error err = {0};
    CHECK(ps_crease_scales(&sh->graph, sh->points, sh->normals, 1, &scales, &err) == PS_OK);
    return scales;
}

static ps_status run_tracked(const star *s, int *group, int *supernode_of,
                             const ps_progress_span *span) {
    ps_boundary_cut_input in = {.graph = &s->shape.graph, .points = s->shape.points,
                                .normals = s->shape.normals, .scales = scales_of(&s->shape),
                                .n_groups = N_PARTS,
                                .n_supernodes = N_PARTS, .sinks = s->sinks, .span = span};
    for (size_t p = 0; p < s->shape.n; p++) supernode_of[p] = group[p];
    ps_error err = {0};
    return ps_boundary_cut(&in, group, supernode_of, &err);
}

static ps_status run_cut(const star *s, int *group, int *supernode_of) {
    ps_status st = run_tracked(s, group, supernode_of, NULL);
    CHECK_MSG(st == PS_OK, "ps_boundary_cut: status %d", (int)st);
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

static void test_progress_and_cancel(void) {
    star s;
    REQUIRE(star_build(&s));
    size_t n = s.shape.n;
    int *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    int *sa = malloc(n * sizeof *sa), *sb = malloc(n * sizeof *sb);
    REQUIRE(a && b && sa && sb);
    ps_progress_seen seen = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &seen};
    ps_progress_span span = {&ctl, PS_PHASE_REFINE, 0.2, 0.7};
    shifted_groups(&s, a);
    shifted_groups(&s, b);
    REQUIRE(run_cut(&s, a, sa) == PS_OK);
    REQUIRE(run_tracked(&s, b, sb, &span) == PS_OK);
    CHECK(memcmp(a, b, n * sizeof *a) == 0 && memcmp(sa, sb, n * sizeof *sa) == 0);
    CHECK_MSG(seen.calls[PS_PHASE_REFINE] >= N_PARTS - 1 && !seen.went_back &&
                  seen.last[PS_PHASE_REFINE] == 0.7,
              "%d calls, last %g", seen.calls[PS_PHASE_REFINE], seen.last[PS_PHASE_REFINE]);
    volatile int cancel = 1;
    ctl.cancel = &cancel;
    shifted_groups(&s, b);
    CHECK(run_tracked(&s, b, sb, &span) == PS_ERR_CANCELLED);
    free(a), free(b), free(sa), free(sb);
    star_free(&s);
}

#define N_MESSY (N_PARTS + 2) /* the parts and two segments made of blobs only */
#define N_BLOBS 24

/* The true parts, then blobs (radius 0.3 around every n/N_BLOBS-th point)
 * of segment j % N_MESSY, then every 29th point takes its first
 * neighbour's segment. */
static void messy_groups(const star *s, int *group) {
    const double *x = s->shape.points;
    memcpy(group, s->shape.part, s->shape.n * sizeof *group);
    for (size_t j = 0; j < N_BLOBS; j++) {
        const double *c = x + 3 * (j * (s->shape.n / N_BLOBS));
        for (size_t p = 0; p < s->shape.n; p++) {
            double dx = x[3 * p] - c[0], dy = x[3 * p + 1] - c[1], dz = x[3 * p + 2] - c[2];
            if (dx * dx + dy * dy + dz * dz < 0.09) group[p] = (int)(j % N_MESSY);
        }
    }
    for (size_t p = 0; p < s->shape.n; p += 29)
        group[p] = group[s->shape.graph.neighbors[s->shape.graph.offsets[p]]];
}

/* One supernode per segment, its sink the segment's lowest point. */
static int messy_supernodes(const star *s, const int *group, int *supernode_of,
                            uint32_t *sinks) {
    int of_group[N_MESSY], m = 0;
    for (int k = 0; k < N_MESSY; k++) of_group[k] = -1;
    for (uint32_t p = 0; p < s->shape.n; p++) {
        if (of_group[group[p]] < 0) of_group[group[p]] = m, sinks[m++] = p;
        supernode_of[p] = of_group[group[p]];
    }
    return m;
}

static double mean_edge(const ps_graph *g) {
    double sum = 0;
    for (size_t e = 0; e < g->offsets[g->n]; e++) sum += g->weights[e];
    return sum / (double)g->offsets[g->n];
}

/* Euclidean distance from p to the nearest point with a neighbour in
 * another segment of group. */
static double to_boundary(const star *s, const int *group, size_t p) {
    const ps_graph *g = &s->shape.graph;
    const double *x = s->shape.points;
    double best = INFINITY;
    for (size_t q = 0; q < g->n; q++)
        for (size_t e = g->offsets[q]; e < g->offsets[q + 1]; e++) {
            if (group[g->neighbors[e]] == group[q]) continue;
            double dx = x[3 * p] - x[3 * q], dy = x[3 * p + 1] - x[3 * q + 1];
            double dz = x[3 * p + 2] - x[3 * q + 2];
            best = fmin(best, sqrt(dx * dx + dy * dy + dz * dz));
            break;
        }
    return best;
}

static void test_messy_segments_move_only_near_boundaries(void) {
    star s;
    REQUIRE(star_build(&s));
    size_t n = s.shape.n;
    int *start = malloc(n * sizeof *start), *group = malloc(n * sizeof *group);
    int *again = malloc(n * sizeof *again), *supernode_of = malloc(n * sizeof *supernode_of);
    uint32_t sinks[N_MESSY];
    REQUIRE(start && group && again && supernode_of);
    messy_groups(&s, start);
    int m = messy_supernodes(&s, start, supernode_of, sinks);
    ps_boundary_cut_input in = {.graph = &s.shape.graph, .points = s.shape.points,
                                .normals = s.shape.normals, .scales = scales_of(&s.shape),
                                .n_groups = N_MESSY,
                                .n_supernodes = m, .sinks = sinks};
    ps_error err = {0};
    memcpy(group, start, n * sizeof *group);
    REQUIRE(ps_boundary_cut(&in, group, supernode_of, &err) == PS_OK);
    double cap = PS_BOUNDARY_CUT_MAX_EDGES * mean_edge(&s.shape.graph) + 1e-9;
    size_t moved = 0;
    for (size_t p = 0; p < n; p++) {
        CHECK(group[p] == group[sinks[supernode_of[p]]]);
        if (group[p] == start[p]) continue;
        moved++;
        CHECK_MSG(to_boundary(&s, start, p) <= cap, "point %zu moved %.3f from a boundary",
                  p, to_boundary(&s, start, p));
    }
    for (int k = 0; k < m; k++) CHECK(group[sinks[k]] == start[sinks[k]]);
    CHECK_MSG(moved > n / 100, "only %zu of %zu points moved", moved, n);
    messy_supernodes(&s, start, supernode_of, sinks);
    memcpy(again, start, n * sizeof *again);
    REQUIRE(ps_boundary_cut(&in, again, supernode_of, &err) == PS_OK);
    CHECK(memcmp(group, again, n * sizeof *group) == 0);
    free(start);
    free(group);
    free(again);
    free(supernode_of);
    star_free(&s);
}

/* From the messy segments (many pairs, some side by side): the same
 * segments and supernodes on 1, 2 and 3 threads. */
static void test_same_for_any_thread_count(void) {
    star s;
    REQUIRE(star_build(&s));
    size_t n = s.shape.n;
    int *start = malloc(n * sizeof *start), *group[3], *supernodes[3];
    uint32_t sinks[N_MESSY];
    REQUIRE(start);
    messy_groups(&s, start);
    for (int t = 0; t < 3; t++) {
        group[t] = malloc(n * sizeof *group[t]);
        supernodes[t] = malloc(n * sizeof *supernodes[t]);
        REQUIRE(group[t] && supernodes[t]);
        int m = messy_supernodes(&s, start, supernodes[t], sinks);
        ps_boundary_cut_input in = {.graph = &s.shape.graph, .points = s.shape.points,
                                    .normals = s.shape.normals, .scales = scales_of(&s.shape),
                                    .n_groups = N_MESSY, .n_supernodes = m, .sinks = sinks,
                                    .threads = t + 1};
        ps_error err = {0};
        memcpy(group[t], start, n * sizeof *group[t]);
        REQUIRE(ps_boundary_cut(&in, group[t], supernodes[t], &err) == PS_OK);
    }
    for (int t = 1; t < 3; t++) {
        CHECK_MSG(memcmp(group[t], group[0], n * sizeof *group[0]) == 0, "%d threads", t + 1);
        CHECK(memcmp(supernodes[t], supernodes[0], n * sizeof *supernodes[0]) == 0);
    }
    CHECK(memcmp(group[0], start, n * sizeof *start) != 0);
    for (int t = 0; t < 3; t++) free(group[t]), free(supernodes[t]);
    free(start);
    star_free(&s);
}

PS_TEST_MAIN(TEST(test_star_boundaries_move_to_creases), TEST(test_true_parts_stay),
             TEST(test_progress_and_cancel),
             TEST(test_deterministic), TEST(test_messy_segments_move_only_near_boundaries),
             TEST(test_same_for_any_thread_count))
