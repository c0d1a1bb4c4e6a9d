/*
 * test_patch_merge.c: the patch merge (patch_merge.h) on the star of
 * star_fixture.h.  Its true parts (a sphere and six arms, none flat) stay
 * apart; a cap of the sphere cut off between the arms is a flat patch and
 * merges back into the sphere, recorded as one merge with its leaf
 * renamed; a flat input is left alone.  On a hand-made graph, a patch
 * larger than its neighbour stays (it is the surface the parts stand on),
 * and so does one that sticks out of its neighbour.
 * A crumb (the tip of an arm, under 0.5% of the points) merges back into
 * its arm, flat input or not.
 */
#include "hand_graph.h"
#include "refine/patch_merge.h"
#include "star_fixture.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CAP PS_STAR_PARTS /* segment id of the cap */
#define N_GROUPS (PS_STAR_PARTS + 1)

/* Angle in degrees between x and the diagonal (1, 1, 1): 55 degrees from
 * every arm's axis, so a cap of 30 degrees around it misses the arms (17
 * degrees wide where they meet the sphere). */
static double degrees_off_diagonal(const double *x) {
    double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    double c = (x[0] + x[1] + x[2]) / (sqrt(3.0) * r);
    return acos(c > 1 ? 1 : c) * 45 / atan(1.0);
}

/* The true parts, with the sphere's points within 30 degrees of the
 * diagonal in CAP. */
static void cut_cap(const ps_star *s, int *group) {
    for (size_t p = 0; p < s->n; p++) {
        int on_cap = s->part[p] == 0 && degrees_off_diagonal(s->points + 3 * p) < 30;
        group[p] = on_cap ? CAP : s->part[p];
    }
}

static ps_status run_merge(const ps_star *s, double mean_angular, int *group, int *leaf,
                           ps_merge **merges, int *n_merges) {
    ps_star_merge_input in = {.mean_angular = mean_angular, .n_groups = N_GROUPS};
    return ps_star_merge(s, ps_patch_merge, &in, group, leaf, merges, n_merges);
}

/* Whether some kNN edge joins segments a and b. */
static int adjacent(const ps_star *s, const int *group, int a, int b) {
    for (size_t p = 0; p < s->n; p++)
        for (size_t e = s->graph.offsets[p]; e < s->graph.offsets[p + 1]; e++)
            if (group[p] == a && group[s->graph.neighbors[e]] == b) return 1;
    return 0;
}

static void test_true_parts_stay_apart(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    int *group = malloc(s.n * sizeof *group), leaf[N_GROUPS], n_merges;
    REQUIRE(group);
    memcpy(group, s.part, s.n * sizeof *group);
    ps_merge *merges;
    CHECK(run_merge(&s, 1.0, group, leaf, &merges, &n_merges) == PS_OK);
    CHECK_MSG(n_merges == 0, "%d merges", n_merges);
    CHECK(memcmp(group, s.part, s.n * sizeof *group) == 0);
    free(merges);
    free(group);
    ps_star_free(&s);
}

static void test_flat_cap_merges_back(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    int *group = malloc(s.n * sizeof *group), leaf[N_GROUPS], n_merges;
    REQUIRE(group);
    cut_cap(&s, group);
    REQUIRE(adjacent(&s, group, CAP, 0));
    ps_merge *merges;
    CHECK(run_merge(&s, 1.0, group, leaf, &merges, &n_merges) == PS_OK);
    REQUIRE(n_merges == 1);
    CHECK(merges[0].segment == CAP && merges[0].into == 0);
    CHECK(leaf[CAP] == 0);
    CHECK(memcmp(group, s.part, s.n * sizeof *group) == 0);
    free(merges);
    free(group);
    ps_star_free(&s);
}

/* Segment 0, four points with normal +z (a flat patch) at x = 0..3 on the
 * x axis, joined to segment 1, n_other points at y = 1 with normals around
 * the x axis (flatness 0), by one edge per point of segment 1 (point i of
 * segment 1 to point i % 4, beside it).  f is 0 but on the patch's last
 * point, where it is reach: how far the patch sticks out.  Returns how
 * many merges. */
static int merges_of_patch_reaching(int n_other, double reach) {
    double normals[3 * 8] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    int group[8] = {0, 0, 0, 0}, leaf[2] = {0, 1}, n_merges = 0;
    int edges[3 + 4 + 3][2] = {{0, 1}, {1, 2}, {2, 3}};
    int n_edges = 3;
    for (int i = 0; i < n_other; i++) {
        int p = 4 + i;
        normals[3 * p + (i % 2 ? 1 : 2)] = i % 4 < 2 ? 1 : -1;
        group[p] = 1;
        edges[n_edges][0] = i % 4, edges[n_edges++][1] = p;
        if (i > 0) edges[n_edges][0] = p - 1, edges[n_edges++][1] = p;
    }
    double points[3 * 8] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
    for (int i = 0; i < n_other; i++) points[3 * (4 + i)] = i % 4, points[3 * (4 + i) + 1] = 1;
    ps_hand_graph h;
    ps_hand_graph_edges(&h, (size_t)(4 + n_other), (const int (*)[2])edges, n_edges, 1.0);
    double f[8] = {0, 0, 0, reach};
    ps_merge_input in = {.graph = &h.g, .points = points, .normals = normals, .f = f,
                         .mean_angular = 1.0, .n_groups = 2};
    ps_merge *merges = NULL;
    ps_error err = {0};
    CHECK(ps_patch_merge(&in, group, leaf, &merges, &n_merges, &err) == PS_OK);
    free(merges);
    return n_merges;
}

static void test_patch_larger_than_its_neighbour_stays(void) {
    CHECK(merges_of_patch_reaching(2, 0) == 0);
    CHECK(merges_of_patch_reaching(4, 0) == 1);
}

/* A flat patch that sticks out of its neighbour, farther (in f) than
 * PS_PATCH_MERGE_PROTRUSION times their boundary's width (the midpoints
 * at x = 0..3: 2 sqrt(1.25) = 2.24), is a part (the arms of a noisy flat
 * star); one that reaches less is not. */
static void test_protruding_patch_stays(void) {
    double width = 2 * sqrt(1.25);
    CHECK(merges_of_patch_reaching(4, 0.95 * PS_PATCH_MERGE_PROTRUSION * width) == 1);
    CHECK(merges_of_patch_reaching(4, 1.05 * PS_PATCH_MERGE_PROTRUSION * width) == 0);
}

static void test_flat_input_left_alone(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    int *group = malloc(s.n * sizeof *group), leaf[N_GROUPS], n_merges;
    REQUIRE(group);
    cut_cap(&s, group);
    ps_merge *merges;
    CHECK(run_merge(&s, 0.0, group, leaf, &merges, &n_merges) == PS_OK);
    CHECK(n_merges == 0);
    CHECK(adjacent(&s, group, CAP, 0));
    free(merges);
    free(group);
    ps_star_free(&s);
}

/* Moves the `count` points of arm `arm` farthest from the centre to
 * segment CAP. */
static void cut_tip(const ps_star *s, int arm, size_t count, int *group) {
    memcpy(group, s->part, s->n * sizeof *group);
    for (size_t taken = 0; taken < count; taken++) {
        size_t far = s->n;
        double far_r = -1;
        for (size_t p = 0; p < s->n; p++) {
            const double *x = s->points + 3 * p;
            double r = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
            if (group[p] == arm && r > far_r) far = p, far_r = r;
        }
        group[far] = CAP;
    }
}

static void test_crumb_merges_into_its_arm(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    size_t count = (size_t)(0.004 * (double)s.n);
    REQUIRE(count >= 3);
    int *group = malloc(s.n * sizeof *group), leaf[N_GROUPS], n_merges;
    REQUIRE(group);
    for (int flat = 0; flat < 2; flat++) {
        cut_tip(&s, 1, count, group);
        ps_merge *merges;
        CHECK(run_merge(&s, flat ? 0.0 : 1.0, group, leaf, &merges, &n_merges) == PS_OK);
        REQUIRE(n_merges == 1);
        CHECK(merges[0].segment == CAP && merges[0].into == 1);
        CHECK(leaf[CAP] == 1);
        CHECK(memcmp(group, s.part, s.n * sizeof *group) == 0);
        free(merges);
    }
    cut_tip(&s, 1, (size_t)(0.006 * (double)s.n) + 1, group); /* a part's size: stays */
    ps_merge *merges;
    CHECK(run_merge(&s, 0.0, group, leaf, &merges, &n_merges) == PS_OK);
    CHECK(n_merges == 0);
    free(merges);
    free(group);
    ps_star_free(&s);
}

PS_TEST_MAIN(TEST(test_true_parts_stay_apart), TEST(test_flat_cap_merges_back),
             TEST(test_patch_larger_than_its_neighbour_stays),
             TEST(test_protruding_patch_stays), TEST(test_flat_input_left_alone),
             TEST(test_crumb_merges_into_its_arm))
