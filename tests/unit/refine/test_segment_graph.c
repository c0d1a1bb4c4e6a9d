/*
 * test_segment_graph.c: the segments' adjacency (segment_graph.h) on a
 * hand-made path: one record per adjacent pair with its edge and marked
 * counts, sizes and f ranges; a merge sums the records, renames the loser,
 * records the loser's feature size, and is applied to points and leaves;
 * a boundary's width is the spread of its edges' midpoints.  A segment's
 * bulge is +1 on a sphere with outward normals, -1 on the inside of a
 * sphere, 0 on a plane, and a merge sums it exactly.  One segment has no
 * boundary records, and many boundaries (more than one allocation of
 * records) sum as few.  The records, gathered side by side, are the same
 * bit for bit for 1, 2 and 3 threads, their sums those of one pass in edge
 * order.  Looking only at the edges found between finer segments gives
 * the coarser segments the same records and edges as looking at all.
 */
#include "hand_graph.h"
#include "refine/segment_graph.h"
#include "random_bits.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Marks the edge 3-4 only. */
static int mark_3_4(void *context, const int *group, size_t p, size_t q) {
    (void)context, (void)group;
    return p + q == 7 && (p == 3 || q == 3);
}

/* The path 0 - 1 - ... - 7 in segments 0 0 1 1 2 2 0 0: segment 0 meets 1
 * once (edge 1-2) and 2 once (edge 5-6); 1 meets 2 once (edge 3-4). */
static const int path_group[8] = {0, 0, 1, 1, 2, 2, 0, 0};
static const double path_f[8] = {0, 1, 2, 3, 4, 5, 6, 7};

/* Point p at (p, 1000, -1000): far from the origin. */
static double path_points[24];

static void build_path(ps_hand_graph *h, ps_segment_graph *sg, int *group) {
    for (int p = 0; p < 8; p++) {
        group[p] = path_group[p];
        path_points[3 * p] = p, path_points[3 * p + 1] = 1000, path_points[3 * p + 2] = -1000;
    }
    ps_hand_graph_path(h, 8, 1.0, 0);
    ps_error err = {0};
    ps_segment_graph_input in = {
        .graph = &h->g, .f = path_f, .points = path_points, .group = group, .n_groups = 3,
        .mark = mark_3_4};
    REQUIRE(ps_segment_graph_build(sg, &in, &err) == PS_OK);
}

static void test_records_per_pair(void) {
    ps_hand_graph h;
    ps_segment_graph sg;
    int group[8];
    build_path(&h, &sg, group);
    REQUIRE(sg.count == 3);
    CHECK(sg.list[0].a == 0 && sg.list[0].b == 1 && sg.list[0].edges == 1);
    CHECK(sg.list[0].marked == 0); /* edge 1-2 */
    CHECK(sg.list[1].a == 0 && sg.list[1].b == 2 && sg.list[1].marked == 0); /* 5-6 */
    CHECK(sg.list[2].a == 1 && sg.list[2].b == 2 && sg.list[2].marked == 1); /* 3-4 */
    CHECK(sg.size[0] == 4 && sg.size[1] == 2 && sg.size[2] == 2);
    CHECK(sg.f_min[0] == 0 && sg.f_max[0] == 7 && sg.f_min[2] == 4 && sg.f_max[2] == 5);
    CHECK(ps_boundary_width(&sg.list[0]) == 0); /* one edge */
    ps_segment_graph_free(&sg);
}

static void test_merge_sums_and_applies(void) {
    ps_hand_graph h;
    ps_segment_graph sg;
    int group[8], leaf[3] = {0, -1, 2}, n_merges = 0;
    build_path(&h, &sg, group);
    ps_merge *merges = NULL;
    REQUIRE(ps_segment_graph_merge(&sg, 2, 1, &merges, &n_merges));
    REQUIRE(n_merges == 1);
    CHECK(merges[0].segment == 2 && merges[0].into == 1 && merges[0].feature_size == 1);
    REQUIRE(sg.count == 1); /* 0-1 and 0-2 became one record of two edges */
    CHECK(sg.list[0].a == 0 && sg.list[0].b == 1 && sg.list[0].edges == 2);
    /* midpoints x = 1.5 and 5.5: twice their RMS distance from x = 3.5 */
    CHECK_NEAR(ps_boundary_width(&sg.list[0]), 4.0, 1e-9);
    CHECK(sg.size[1] == 4 && sg.f_min[1] == 2 && sg.f_max[1] == 5);
    CHECK(ps_segment_graph_survivor(&sg, 2) == 1 && ps_segment_graph_survivor(&sg, 0) == 0);
    ps_segment_graph_apply(&sg, group, 8, leaf);
    for (int p = 0; p < 8; p++) CHECK(group[p] == (path_group[p] == 2 ? 1 : path_group[p]));
    CHECK(leaf[0] == 0 && leaf[1] == -1 && leaf[2] == 1);
    free(merges);
    ps_segment_graph_free(&sg);
}

#define BULGE_EACH 20 /* points per segment */

/* Point i of BULGE_EACH spread over the unit sphere (a Fibonacci spiral). */
static void sphere_point(int i, double *x) {
    double z = 1 - (2.0 * i + 1) / BULGE_EACH, r = sqrt(1 - z * z), turn = 2.399963229728653 * i;
    x[0] = r * cos(turn), x[1] = r * sin(turn), x[2] = z;
}

/* Segment 0: a sphere of radius 1 at (1000, 0, 0), normals outwards;
 * segment 1: a sphere of radius 2 at (1000, 10, 0), normals inwards (the
 * inside of a round room); segment 2: a square of the plane z = 5, normal
 * +z. */
static void bulge_shapes(double *points, double *normals, int *group) {
    for (int i = 0; i < BULGE_EACH; i++) {
        double u[3];
        sphere_point(i, u);
        for (int d = 0; d < 3; d++) {
            points[3 * i + d] = u[d] + (d == 0 ? 1000 : 0), normals[3 * i + d] = u[d];
            points[3 * (BULGE_EACH + i) + d] = 2 * u[d] + (d == 0 ? 1000 : d == 1 ? 10 : 0);
            normals[3 * (BULGE_EACH + i) + d] = -u[d];
        }
        double *q = points + 3 * (2 * BULGE_EACH + i), *m = normals + 3 * (2 * BULGE_EACH + i);
        q[0] = 1000 + i % 5, q[1] = i / 5, q[2] = 5, m[0] = 0, m[1] = 0, m[2] = 1;
        group[i] = 0, group[BULGE_EACH + i] = 1, group[2 * BULGE_EACH + i] = 2;
    }
}

/* n . (p - c) over |p - c| as RMS, directly over the points of the groups in
 * the mask. */
static double direct_bulge(const double *points, const double *normals, const int *group,
                           int mask) {
    double c[3] = {0, 0, 0}, dot = 0, r2 = 0;
    int n = 0;
    for (int p = 0; p < 3 * BULGE_EACH; p++)
        if (mask >> group[p] & 1) {
            for (int d = 0; d < 3; d++) c[d] += points[3 * p + d];
            n++;
        }
    for (int d = 0; d < 3; d++) c[d] /= n;
    for (int p = 0; p < 3 * BULGE_EACH; p++)
        if (mask >> group[p] & 1)
            for (int d = 0; d < 3; d++) {
                double x = points[3 * p + d] - c[d];
                dot += normals[3 * p + d] * x, r2 += x * x;
            }
    return (dot / n) / sqrt(r2 / n);
}

static void test_bulge(void) {
    double points[9 * BULGE_EACH], normals[9 * BULGE_EACH], f[3 * BULGE_EACH] = {0};
    int group[3 * BULGE_EACH], n_merges = 0;
    bulge_shapes(points, normals, group);
    ps_hand_graph h;
    ps_hand_graph_path(&h, 3 * BULGE_EACH, 1.0, 0);
    ps_segment_graph sg;
    ps_error err = {0};
    ps_segment_graph_input in = {.graph = &h.g, .f = f, .points = points, .normals = normals,
                                 .group = group, .n_groups = 3};
    REQUIRE(ps_segment_graph_build(&sg, &in, &err) == PS_OK);
    CHECK_NEAR(ps_segment_bulge(&sg, 0), direct_bulge(points, normals, group, 1), 1e-9);
    CHECK(ps_segment_bulge(&sg, 0) > 0.95);
    CHECK(ps_segment_bulge(&sg, 1) < -0.95);
    CHECK_NEAR(ps_segment_bulge(&sg, 2), 0, 1e-9);
    ps_merge *merges = NULL;
    REQUIRE(ps_segment_graph_merge(&sg, 0, 1, &merges, &n_merges));
    CHECK_NEAR(ps_segment_bulge(&sg, 1), direct_bulge(points, normals, group, 3), 1e-9);
    free(merges);
    ps_segment_graph_free(&sg);
    in.normals = NULL; /* no normals: no bulges */
    REQUIRE(ps_segment_graph_build(&sg, &in, &err) == PS_OK);
    CHECK(ps_segment_bulge(&sg, 0) == 0);
    ps_segment_graph_free(&sg);
}

static void test_one_segment_no_records(void) {
    ps_hand_graph h;
    ps_segment_graph sg;
    int group[8] = {0};
    ps_hand_graph_path(&h, 8, 1.0, 0);
    ps_error err = {0};
    ps_segment_graph_input in = {.graph = &h.g, .f = path_f, .group = group, .n_groups = 1};
    REQUIRE(ps_segment_graph_build(&sg, &in, &err) == PS_OK);
    CHECK(sg.count == 0);
    CHECK(sg.size[0] == 8 && sg.f_min[0] == 0 && sg.f_max[0] == 7);
    ps_segment_graph_free(&sg);
}

/* A path of 40,000 points in segments alternating every point: 39,999
 * boundary edges, gathered past each chunk's first allocation, sum into
 * one record with every edge. */
static void test_many_boundary_edges(void) {
    enum { N = 40000 };
    static size_t offsets[N + 1];
    static uint32_t neighbors[2 * N];
    static int group[N];
    static double f[N];
    size_t arcs = 0;
    for (uint32_t p = 0; p < N; p++) {
        offsets[p] = arcs;
        if (p > 0) neighbors[arcs++] = p - 1;
        if (p + 1 < N) neighbors[arcs++] = p + 1;
        group[p] = (int)(p % 2), f[p] = p;
    }
    offsets[N] = arcs;
    ps_graph path = {.n = N, .offsets = offsets, .neighbors = neighbors};
    ps_segment_graph sg;
    ps_error err = {0};
    ps_segment_graph_input in = {.graph = &path, .f = f, .group = group, .n_groups = 2};
    REQUIRE(ps_segment_graph_build(&sg, &in, &err) == PS_OK);
    REQUIRE(sg.count == 1);
    CHECK(sg.list[0].a == 0 && sg.list[0].b == 1 && sg.list[0].edges == N - 1);
    CHECK(sg.size[0] == N / 2 && sg.size[1] == N / 2);
    ps_segment_graph_free(&sg);
}

enum { HELIX = 20000 };
static size_t helix_offsets[HELIX + 1];
static uint32_t helix_neighbors[2 * HELIX];
static int helix_group[HELIX];
static double helix_f[HELIX], helix_points[3 * HELIX];

/* A path of HELIX points on a helix in 7 segments, labels scattered. */
static ps_graph helix(void) {
    size_t arcs = 0;
    uint64_t s = 99;
    for (uint32_t p = 0; p < HELIX; p++) {
        helix_offsets[p] = arcs;
        if (p > 0) helix_neighbors[arcs++] = p - 1;
        if (p + 1 < HELIX) helix_neighbors[arcs++] = p + 1;
        helix_group[p] = (int)(ps_random_bits(&s) % 7), helix_f[p] = p;
        helix_points[3 * p] = cos(p * 0.01), helix_points[3 * p + 1] = sin(p * 0.01);
        helix_points[3 * p + 2] = p * 1e-3;
    }
    helix_offsets[HELIX] = arcs;
    return (ps_graph){.n = HELIX, .offsets = helix_offsets, .neighbors = helix_neighbors};
}

/* On the helix, segments 1 and 4 then merge into 0: built on the edges
 * found between the 7 segments (on 1 and 3 threads), the records and the
 * edges found are those of a build that looks at every edge. */
static void test_candidates_same_graph(void) {
    ps_graph path = helix();
    ps_error err = {0};
    ps_edge_list fine = {0}, coarse[3] = {{0}};
    ps_segment_graph_input in = {.graph = &path, .f = helix_f, .points = helix_points,
                                 .group = helix_group, .n_groups = 7, .found = &fine};
    ps_segment_graph sg[3];
    REQUIRE(ps_segment_graph_build(&sg[0], &in, &err) == PS_OK);
    ps_segment_graph_free(&sg[0]);
    size_t joins = 0;
    for (uint32_t p = 0; p + 1 < HELIX; p++) joins += helix_group[p] != helix_group[p + 1];
    REQUIRE(fine.count == joins);
    for (uint32_t p = 0; p < HELIX; p++)
        if (helix_group[p] == 1 || helix_group[p] == 4) helix_group[p] = 0;
    for (int t = 0; t < 3; t++) {
        in = (ps_segment_graph_input){.graph = &path, .f = helix_f, .points = helix_points,
                                      .group = helix_group, .n_groups = 7,
                                      .threads = t == 2 ? 3 : 1,
                                      .candidates = t ? &fine : NULL, .found = &coarse[t]};
        REQUIRE(ps_segment_graph_build(&sg[t], &in, &err) == PS_OK);
    }
    CHECK(coarse[0].count < fine.count);
    for (int t = 1; t < 3; t++) {
        CHECK(sg[t].count == sg[0].count && coarse[t].count == coarse[0].count);
        CHECK(memcmp(sg[t].list, sg[0].list, sg[0].count * sizeof *sg[0].list) == 0);
        CHECK(memcmp(coarse[t].ends, coarse[0].ends, 2 * coarse[0].count * sizeof(uint32_t)) == 0);
    }
    for (int t = 0; t < 3; t++) ps_segment_graph_free(&sg[t]), free(coarse[t].ends);
    free(fine.ends);
}

/* On the helix: the records for 1, 2 and 3 threads agree bit for bit, and
 * the midpoint sums of pair (0, 1) are those of one pass over its edges in
 * order. */
static void test_same_for_any_thread_count(void) {
    enum { N = HELIX };
    ps_graph path = helix();
    const int *group = helix_group;
    const double *f = helix_f, *points = helix_points;
    ps_segment_graph sg[3];
    for (int t = 0; t < 3; t++) {
        ps_error err = {0};
        ps_segment_graph_input in = {.graph = &path, .f = f, .points = points, .group = group,
                                     .n_groups = 7, .threads = t + 1};
        REQUIRE(ps_segment_graph_build(&sg[t], &in, &err) == PS_OK);
    }
    for (int t = 1; t < 3; t++) {
        CHECK(sg[t].count == sg[0].count);
        CHECK(memcmp(sg[t].list, sg[0].list, sg[0].count * sizeof *sg[0].list) == 0);
    }
    double sum = 0;
    int first = 1;
    for (uint32_t p = 0; p + 1 < N; p++) {
        int a = group[p], b = group[p + 1];
        if (!((a == 0 && b == 1) || (a == 1 && b == 0))) continue;
        double mid = 0.5 * (points[3 * p] + points[3 * p + 3]) - points[0];
        sum = first ? mid : sum + mid, first = 0;
    }
    REQUIRE(sg[0].count > 0 && sg[0].list[0].a == 0 && sg[0].list[0].b == 1);
    CHECK(sg[0].list[0].midpoint_sum[0] == sum);
    for (int t = 0; t < 3; t++) ps_segment_graph_free(&sg[t]);
}

PS_TEST_MAIN(TEST(test_records_per_pair), TEST(test_merge_sums_and_applies), TEST(test_bulge),
             TEST(test_one_segment_no_records), TEST(test_many_boundary_edges),
             TEST(test_same_for_any_thread_count), TEST(test_candidates_same_graph))
