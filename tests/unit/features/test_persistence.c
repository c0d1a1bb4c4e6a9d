/* test_persistence.c: persistence merging of flow basins: a ripple merges
 * into its neighbour, a prominent peak survives, fraction 0 keeps all, and
 * components are judged by their own range; border saddles come sorted,
 * ties included, and follow merges. */
#include "features/flow.h"
#include "features/persistence.h"
#include "hand_graph.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>

/* f on 9 vertices: big peak at 1 (10), ripple at 4 (5.5) over saddle 3 (5),
 * then rising to a peak at 8 (9).  Range 10 - 5 = 5: the ripple (5.5 over
 * the saddle 5.2 towards 5: persistence 0.3) merges at fraction 0.1; the
 * peak at 8 (persistence 9 - 5 = 4) needs a fraction above 0.8. */
static void test_ripple_merges(void) {
    ps_hand_graph h;
    ps_hand_graph_path(&h, 9, 1, 0);
    ps_graph g = h.g;
    const double f[9] = {9, 10, 6, 5, 5.5, 5.2, 7, 8, 9};
    const int zero[9] = {0};
    ps_flow fl;
    REQUIRE(ps_flow_build(&g, f, +1, &fl, NULL) == PS_OK);
    REQUIRE(fl.n_sinks == 3);
    ps_persistence_input in = {.graph = &g, .f = f, .component = zero, .n_components = 1};
    REQUIRE(ps_persistence_simplify(&in, &fl, NULL) == PS_OK); /* fraction 0 */
    CHECK(fl.n_sinks == 3);
    in.fraction = 0.1;
    REQUIRE(ps_persistence_simplify(&in, &fl, NULL) == PS_OK);
    REQUIRE(fl.n_sinks == 2);
    CHECK(fl.sinks[0] == 1 && fl.sinks[1] == 8);
    CHECK(fl.sink_of[4] == fl.sink_of[8]); /* the ripple joined the peak at 8 */
    CHECK(fl.sink_of[2] == 0 && fl.sink_of[3] != fl.sink_of[4]);
    in.fraction = 0.75;
    REQUIRE(ps_persistence_simplify(&in, &fl, NULL) == PS_OK);
    CHECK(fl.n_sinks == 2);
    in.fraction = 0.85;
    REQUIRE(ps_persistence_simplify(&in, &fl, NULL) == PS_OK);
    CHECK(fl.n_sinks == 1 && fl.sinks[0] == 1);
    for (int v = 0; v < 9; v++) CHECK(fl.sink_of[v] == 0);
    ps_flow_free(&fl);
}

/* Two components, each a path with two peaks; component 0 has a tall range
 * so its second peak is relatively small, component 1 is judged alone. */
static void test_threshold_per_component(void) {
    ps_hand_graph h;
    ps_hand_graph_path(&h, 10, 1, 5); /* no edge 4-5 */
    ps_graph cut = h.g;
    const double f[10] = {100, 0, 1, 0.5, 0.2, 0.01, 1, 0.5, 0.9, 0.02};
    const int comp[10] = {0, 0, 0, 0, 0, 1, 1, 1, 1, 1};
    ps_flow fl;
    REQUIRE(ps_flow_build(&cut, f, +1, &fl, NULL) == PS_OK);
    int before = fl.n_sinks;
    ps_persistence_input in = {.graph = &cut, .f = f, .component = comp, .n_components = 2,
                               .fraction = 0.1};
    REQUIRE(ps_persistence_simplify(&in, &fl, NULL) == PS_OK);
    /* component 0: the peak at 2 (persistence 1 of range 100) merges;
     * component 1: peaks 6 (1) and 8 (0.9 - 0.5 = 0.4 of range 0.99) stay */
    CHECK(fl.n_sinks == before - 1);
    CHECK(fl.sink_of[2] == fl.sink_of[0]);
    CHECK(fl.sink_of[6] != fl.sink_of[8]);
    ps_flow_free(&fl);
}

/* A tall but tiny basin (the 4 points 5..8 under the peak 9) merges into
 * the 5-point basin when min_size asks for 5, and survives with 0; the
 * merged basin keeps the larger basin's sink. */
static void test_tiny_basin_merges(void) {
    ps_hand_graph h;
    ps_hand_graph_path(&h, 9, 1, 0);
    ps_graph g = h.g;
    const double f[9] = {1, 2, 3, 4, 5, 0, 9, 1, 0};
    const int zero[9] = {0};
    ps_flow fl;
    REQUIRE(ps_flow_build(&g, f, +1, &fl, NULL) == PS_OK);
    REQUIRE(fl.n_sinks == 2); /* 4 (vertices 0..4) and 6 (5..8) */
    ps_persistence_input in = {.graph = &g, .f = f, .component = zero, .n_components = 1,
                               .fraction = 0.01};
    REQUIRE(ps_persistence_simplify(&in, &fl, NULL) == PS_OK); /* min_size 0 */
    CHECK(fl.n_sinks == 2);
    in.min_size = 5;
    REQUIRE(ps_persistence_simplify(&in, &fl, NULL) == PS_OK);
    CHECK(fl.n_sinks == 1 && fl.sinks[0] == 4);
    for (int v = 0; v < 9; v++) CHECK(fl.sink_of[v] == 0);
    ps_flow_free(&fl);
}

/* Every vertex its own basin on 64 vertices joined to the next and the one
 * after (125 edges, heights with many ties): every edge is a border
 * saddle, listed once, from high to low, ties by p then q; once vertices
 * 0 to 31 share a basin, the edges among them leave the list. */
static void test_border_saddles_sorted(void) {
    enum { N = 64 };
    int edges[2 * N][2], n_edges = 0;
    for (int v = 0; v + 1 < N; v++) {
        edges[n_edges][0] = v, edges[n_edges++][1] = v + 1;
        if (v + 2 < N) edges[n_edges][0] = v, edges[n_edges++][1] = v + 2;
    }
    ps_hand_graph h;
    ps_hand_graph_edges(&h, N, (const int(*)[2])edges, n_edges, 1.0);
    double f[N];
    int sink_of[N];
    uint32_t sinks[N];
    for (int v = 0; v < N; v++) f[v] = (v * 7) % 5, sink_of[v] = v, sinks[v] = (uint32_t)v;
    ps_flow fl = {N, sinks, sink_of};
    size_t count = 0;
    ps_saddle *s = ps_flow_border_saddles(&h.g, f, &fl, &count);
    REQUIRE(s != NULL);
    CHECK(count == (size_t)n_edges);
    for (size_t i = 0; i < count; i++) {
        CHECK(s[i].p < s[i].q && s[i].height == fmin(f[s[i].p], f[s[i].q]));
        if (i == 0) continue;
        const ps_saddle *a = &s[i - 1], *b = &s[i];
        CHECK(a->height > b->height ||
              (a->height == b->height && (a->p < b->p || (a->p == b->p && a->q < b->q))));
    }
    for (int v = 0; v < N / 2; v++) sink_of[v] = 0;
    ps_saddles_keep_borders(&fl, s, &count);
    CHECK(count == (size_t)n_edges - (N / 2 - 1) - (N / 2 - 2));
    for (size_t i = 0; i < count; i++) CHECK(s[i].q >= N / 2);
    free(s);
}

PS_TEST_MAIN(TEST(test_ripple_merges), TEST(test_threshold_per_component),
             TEST(test_tiny_basin_merges), TEST(test_border_saddles_sorted))
