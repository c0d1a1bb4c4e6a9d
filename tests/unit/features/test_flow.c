/* test_flow.c: steepest ascent pointers and sinks on a hand-made graph, and
 * on the shapes: every vertex reaches a local maximum, the star's six arm
 * tips and the dumbbell's two ends hold the big supernodes. */
#include "features/centrality.h"
#include "features/flow.h"
#include "graph/knn_graph.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Path 0-1-2-3-4-5 with unit weights except 2-3 of length 4. */
static void small_path(ps_graph *g) {
    static size_t offsets[] = {0, 1, 3, 5, 7, 9, 10};
    static uint32_t neighbors[] = {1, 0, 2, 1, 3, 2, 4, 3, 5, 4};
    static double weights[] = {1, 1, 1, 1, 4, 4, 1, 1, 1, 1};
    *g = (ps_graph){6, offsets, neighbors, weights};
}

static void test_small_path(void) {
    ps_graph g;
    small_path(&g);
    const double f[6] = {1, 3, 2, 0, 5, 4};
    ps_flow fl;
    REQUIRE(ps_flow_build(&g, f, +1, &fl, NULL) == PS_OK);
    REQUIRE(fl.n_sinks == 2);
    CHECK(fl.sinks[0] == 1 && fl.sinks[1] == 4);
    const int up[6] = {0, 0, 0, 1, 1, 1}; /* 3 climbs to 4 (slope 5) not 2 (slope 0.5) */
    for (int v = 0; v < 6; v++) CHECK(fl.sink_of[v] == up[v]);
    ps_flow_free(&fl);
    REQUIRE(ps_flow_build(&g, f, -1, &fl, NULL) == PS_OK);
    REQUIRE(fl.n_sinks == 3);
    CHECK(fl.sinks[0] == 0 && fl.sinks[1] == 3 && fl.sinks[2] == 5);
    const int down[6] = {0, 0, 1, 1, 1, 2}; /* 4 descends to 3 (slope 1.25) not 5 (1) */
    for (int v = 0; v < 6; v++) CHECK(fl.sink_of[v] == down[v]);
    ps_flow_free(&fl);
    CHECK(ps_flow_build(&g, f, 0, &fl, NULL) == PS_ERR_INVALID);
}

/* Equal f: no strictly higher neighbour anywhere, so every vertex is a sink;
 * a tie in slope goes to the lower neighbour. */
static void test_plateau_and_ties(void) {
    ps_graph g;
    small_path(&g);
    const double flat[6] = {2, 2, 2, 2, 2, 2};
    ps_flow fl;
    REQUIRE(ps_flow_build(&g, flat, +1, &fl, NULL) == PS_OK);
    CHECK(fl.n_sinks == 6);
    ps_flow_free(&fl);
    const double valley[6] = {3, 2, 3, 9, 9, 9};
    REQUIRE(ps_flow_build(&g, valley, +1, &fl, NULL) == PS_OK);
    CHECK(fl.sink_of[1] == fl.sink_of[0]); /* 0 and 2 rise equally: 0 wins */
    ps_flow_free(&fl);
}

typedef struct flow_case {
    size_t n;
    double *pts;
    ps_graph g;
    double *f;
    ps_flow fl;
} flow_case;

static int flow_case_make(double *pts, size_t n, int direction, flow_case *c) {
    c->n = n;
    c->pts = pts;
    c->f = malloc(n * sizeof *c->f);
    int *comp = malloc(n * sizeof *comp);
    int ok = pts && c->f && comp && ps_knn_graph_build(pts, n, 3, 7, 2, &c->g, NULL) == PS_OK;
    int nc = ok ? ps_graph_components(&c->g, comp) : 0;
    ps_centrality_input in = {.graph = &c->g, .component = comp, .n_components = nc,
                              .mode = PS_CENTRALITY_EXACT, .threads = 2,
                              .coarse_min = PS_COARSE_MIN_POINTS};
    ok = ok && ps_centrality(&in, c->f, NULL, NULL, NULL) == PS_OK;
    ok = ok && ps_flow_build(&c->g, c->f, direction, &c->fl, NULL) == PS_OK;
    free(comp);
    return ok;
}

static void flow_case_free(flow_case *c) {
    ps_flow_free(&c->fl);
    ps_graph_free(&c->g);
    free(c->f), free(c->pts);
}

static void check_flow_valid(const flow_case *c, int direction) {
    const ps_flow *fl = &c->fl;
    for (int s = 0; s < fl->n_sinks; s++) {
        uint32_t v = fl->sinks[s];
        if (s > 0) CHECK(v > fl->sinks[s - 1]);
        CHECK(fl->sink_of[v] == s);
        for (size_t e = c->g.offsets[v]; e < c->g.offsets[v + 1]; e++)
            CHECK(direction * (c->f[c->g.neighbors[e]] - c->f[v]) <= 0.0);
    }
    for (size_t v = 0; v < c->n; v++) {
        REQUIRE(fl->sink_of[v] >= 0 && fl->sink_of[v] < fl->n_sinks);
        CHECK(direction * (c->f[fl->sinks[fl->sink_of[v]]] - c->f[v]) >= 0.0);
    }
}

/* Sinks holding more than 5% of the points, as a list of sink vertices. */
static int big_sinks(const flow_case *c, uint32_t *out, int cap) {
    size_t *size = calloc((size_t)c->fl.n_sinks, sizeof *size);
    int count = 0;
    for (size_t v = 0; size && v < c->n; v++) size[c->fl.sink_of[v]]++;
    for (int s = 0; size && s < c->fl.n_sinks; s++)
        if (size[s] * 20 > c->n && count < cap) out[count++] = c->fl.sinks[s];
    free(size);
    return count;
}

static void test_star_arm_tips(void) {
    size_t n;
    flow_case c;
    double *pts = ps_shape_star(0.0, &n, NULL);
    REQUIRE(flow_case_make(pts, n, +1, &c));
    check_flow_valid(&c, +1);
    uint32_t big[16];
    int count = big_sinks(&c, big, 16);
    CHECK_MSG(count == 6, "%d big sinks (of %d)", count, c.fl.n_sinks);
    int arm_seen[6] = {0};
    for (int i = 0; i < count; i++) {
        const double *x = &c.pts[3 * big[i]];
        int axis = fabs(x[0]) > fabs(x[1]) ? 0 : 1;
        if (fabs(x[2]) > fabs(x[axis])) axis = 2;
        CHECK_MSG(fabs(x[axis]) > 3.5, "big sink at %g %g %g is not an arm tip", x[0], x[1], x[2]);
        arm_seen[2 * axis + (x[axis] < 0)]++;
    }
    for (int a = 0; a < 6; a++) CHECK(arm_seen[a] == 1);
    flow_case_free(&c);
}

/* The dumbbell's centrality is nearly flat around the two far poles, so the
 * kNN graph's noise leaves a few local maxima there (5 sinks hold > 5% of
 * the points at the default density); they all sit on the sphere ends and
 * the biggest basin of each end has its sink at the pole. */
static void test_dumbbell_ends(void) {
    size_t n;
    flow_case c;
    double *pts = ps_shape_dumbbell(0.0, &n, NULL);
    REQUIRE(flow_case_make(pts, n, +1, &c));
    check_flow_valid(&c, +1);
    size_t *size = calloc((size_t)c.fl.n_sinks, sizeof *size);
    REQUIRE(size);
    for (size_t v = 0; v < n; v++) size[c.fl.sink_of[v]]++;
    int biggest[2] = {-1, -1};
    for (int s = 0; s < c.fl.n_sinks; s++) {
        double x = c.pts[3 * c.fl.sinks[s]];
        if (size[s] * 20 > n) CHECK_MSG(fabs(x) > 2.4, "big sink at x = %g", x);
        int side = x > 0;
        if (biggest[side] < 0 || size[s] > size[biggest[side]]) biggest[side] = s;
    }
    REQUIRE(biggest[0] >= 0 && biggest[1] >= 0);
    for (int side = 0; side < 2; side++) {
        const double *x = &c.pts[3 * c.fl.sinks[biggest[side]]];
        CHECK_MSG(fabs(x[0]) > 2.9 && size[biggest[side]] * 10 > n,
                  "biggest sink of side %d at x = %g holds %zu points", side, x[0],
                  size[biggest[side]]);
    }
    free(size);
    flow_case_free(&c);
}

/* Descent on the star: the biggest basin is the centre sphere's. */
static void test_star_minimum(void) {
    size_t n;
    flow_case c;
    double *pts = ps_shape_star(40.0, &n, NULL);
    REQUIRE(flow_case_make(pts, n, -1, &c));
    check_flow_valid(&c, -1);
    uint32_t big[16];
    int count = big_sinks(&c, big, 16);
    REQUIRE(count >= 1);
    const double *x = &c.pts[3 * big[0]];
    CHECK(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) < 1.5);
    flow_case_free(&c);
}

PS_TEST_MAIN(TEST(test_small_path), TEST(test_plateau_and_ties), TEST(test_star_arm_tips),
             TEST(test_dumbbell_ends), TEST(test_star_minimum))
