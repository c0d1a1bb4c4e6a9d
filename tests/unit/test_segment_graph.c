/*
 * test_segment_graph.c: the segments' adjacency (segment_graph.h) on a
 * hand-made path: one record per adjacent pair with its edge and marked
 * counts, sizes and f ranges; a merge sums the records, renames the loser,
 * records the loser's feature size, and is applied to points and leaves;
 * a boundary's width is the spread of its edges' midpoints.
 */
#include "hand_graph.h"
#include "segment_graph.h"
#include "testlib.h"

#include <stdlib.h>

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

PS_TEST_MAIN(TEST(test_records_per_pair), TEST(test_merge_sums_and_applies))
