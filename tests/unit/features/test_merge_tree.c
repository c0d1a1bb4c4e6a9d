/* test_merge_tree.c: parts of several basins on a hand-made animal: two
 * legs and a head on a stem, topped by two ears, all meeting at a centre.
 * Short ears join the head; long ears stay parts of their own; a head on a
 * short stem is no part; the part reaches down the stem as far as its
 * longest ear reaches up. */
#include "features/flow.h"
#include "features/merge_tree.h"
#include "hand_graph.h"
#include "testlib.h"

#include <stdlib.h>

#define LEG 10  /* leg length: f runs 1..LEG along each leg */

typedef struct animal {
    ps_hand_graph h;
    double f[PS_HAND_GRAPH_MAX_V];
    int n;
    int stem_top;  /* the fork where the ears meet */
    int ear_tip[2];
} animal;

/* Appends a path of `length` vertices to `from`, f rising by 1 a vertex. */
static int grow(animal *a, int (*edges)[2], int *n_edges, int from, int length) {
    for (int i = 0; i < length; i++) {
        int v = a->n++;
        a->f[v] = a->f[from] + 1;
        edges[(*n_edges)][0] = from, edges[(*n_edges)++][1] = v;
        from = v;
    }
    return from;
}

static void animal_make(animal *a, int stem, int ear) {
    int edges[PS_HAND_GRAPH_MAX_V][2], n_edges = 0;
    a->n = 1, a->f[0] = 0; /* the centre */
    grow(a, edges, &n_edges, 0, LEG);
    grow(a, edges, &n_edges, 0, LEG);
    a->stem_top = grow(a, edges, &n_edges, 0, stem);
    a->ear_tip[0] = grow(a, edges, &n_edges, a->stem_top, ear);
    a->ear_tip[1] = grow(a, edges, &n_edges, a->stem_top, ear);
    ps_hand_graph_edges(&a->h, (size_t)a->n, (const int(*)[2])edges, n_edges, 1.0);
}

/* Runs the flow and the parts at persistence 0.1 (with a range of 10, a
 * part must live over 2). */
static int parts_of(animal *a, int *part_of) {
    int zero[PS_HAND_GRAPH_MAX_V] = {0}, n_parts = -1;
    ps_flow up;
    size_t count = 0;
    if (ps_flow_build(&a->h.g, a->f, +1, &up, NULL) != PS_OK) return -1;
    ps_saddle *s = ps_flow_border_saddles(&a->h.g, a->f, &up, &count);
    ps_merge_tree_input in = {.graph = &a->h.g, .f = a->f, .component = zero, .n_components = 1,
                              .persistence = 0.1, .up = &up, .saddles = s, .n_saddles = count};
    ps_status st = s ? ps_merge_tree_parts(&in, part_of, &n_parts, NULL) : PS_ERR_NOMEM;
    free(s);
    ps_flow_free(&up);
    return st == PS_OK ? n_parts : -1;
}

static void test_short_ears_join_the_head(void) {
    animal a;
    int part_of[PS_HAND_GRAPH_MAX_V];
    animal_make(&a, 8, 2); /* head lives 8 - 0, ears 2 < 0.5 * 8 */
    REQUIRE(parts_of(&a, part_of) == 1);
    CHECK(part_of[a.ear_tip[0]] == 0 && part_of[a.ear_tip[1]] == 0);
    CHECK(part_of[a.stem_top] == 0);
    for (int v = 0; v < a.n; v++) {
        int in_head = v > 2 * LEG && a.f[v] >= 8 - 2; /* reach: one ear's life */
        CHECK_MSG(part_of[v] == (in_head ? 0 : -1), "vertex %d f %g part %d", v, a.f[v],
                  part_of[v]);
    }
}

static void test_long_ears_stay_apart(void) {
    animal a;
    int part_of[PS_HAND_GRAPH_MAX_V];
    animal_make(&a, 8, 5); /* ears 5 >= 0.5 * 8: parts of their own */
    REQUIRE(parts_of(&a, part_of) == 1);
    CHECK(part_of[a.ear_tip[0]] == -1 && part_of[a.ear_tip[1]] == -1);
    for (int v = 2 * LEG + 1; v < 2 * LEG + 8; v++) /* the stem below the fork */
        CHECK_MSG(part_of[v] == (a.f[v] >= 8 - 5 ? 0 : -1), "stem vertex f %g part %d", a.f[v],
                  part_of[v]);
}

static void test_short_stem_is_no_part(void) {
    animal a;
    int part_of[PS_HAND_GRAPH_MAX_V];
    animal_make(&a, 2, 8); /* the head lives 2, not over 2 * 0.1 * range 10... */
    REQUIRE(parts_of(&a, part_of) == 0);
    for (int v = 0; v < a.n; v++) CHECK(part_of[v] == -1);
    animal_make(&a, 3, 7); /* ...one more step does */
    REQUIRE(parts_of(&a, part_of) == 1);
    CHECK(part_of[2 * LEG + 2] == 0 && part_of[a.ear_tip[0]] == -1); /* stem, f 2 */
}

static void test_no_persistence_no_parts(void) {
    animal a;
    int part_of[PS_HAND_GRAPH_MAX_V], zero[PS_HAND_GRAPH_MAX_V] = {0}, n_parts = -1;
    animal_make(&a, 8, 2);
    ps_flow up;
    REQUIRE(ps_flow_build(&a.h.g, a.f, +1, &up, NULL) == PS_OK);
    ps_merge_tree_input in = {.graph = &a.h.g, .f = a.f, .component = zero, .n_components = 1,
                              .up = &up}; /* persistence 0, no saddles */
    CHECK(ps_merge_tree_parts(&in, part_of, &n_parts, NULL) == PS_OK);
    CHECK(n_parts == 0 && part_of[a.stem_top] == -1);
    ps_flow_free(&up);
}

PS_TEST_MAIN(TEST(test_short_ears_join_the_head), TEST(test_long_ears_stay_apart),
             TEST(test_short_stem_is_no_part), TEST(test_no_persistence_no_parts))
