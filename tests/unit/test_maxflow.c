/*
 * test_maxflow.c: Dinic's max flow (maxflow.h) on small undirected graphs
 * whose maximum flow and minimum cut are known by hand: a chain, a diamond,
 * a grid with a weak column, a graph the sink cannot be reached in; the same
 * answer on every run; a graph that is not symmetric is refused.  One
 * workspace reused over graphs of growing and shrinking sizes gives the
 * same flow and cut, bit for bit, as fresh calls; a path of 200k nodes (a
 * deep search) does not overflow the stack.
 */
#include "maxflow.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

#define MAX_NODES 64
#define MAX_EDGES 256

/* A CSR flow graph built from an undirected edge list. */
typedef struct csr {
    ps_flow_graph g;
    size_t offsets[MAX_NODES + 1];
    uint32_t heads[2 * MAX_EDGES];
    double capacity[2 * MAX_EDGES];
} csr;

typedef struct edge {
    uint32_t a, b;
    double capacity;
} edge;

static void build_csr(csr *c, size_t n, const edge *edges, size_t m) {
    memset(c, 0, sizeof *c);
    for (size_t i = 0; i < m; i++) c->offsets[edges[i].a + 1]++, c->offsets[edges[i].b + 1]++;
    for (size_t v = 0; v < n; v++) c->offsets[v + 1] += c->offsets[v];
    size_t fill[MAX_NODES];
    memcpy(fill, c->offsets, n * sizeof *fill);
    /* visiting heads in increasing order keeps every row sorted */
    for (uint32_t head = 0; head < n; head++)
        for (size_t i = 0; i < m; i++) {
            const edge *e = &edges[i];
            if (e->b == head) c->heads[fill[e->a]] = head, c->capacity[fill[e->a]++] = e->capacity;
            if (e->a == head) c->heads[fill[e->b]] = head, c->capacity[fill[e->b]++] = e->capacity;
        }
    c->g = (ps_flow_graph){.n = n, .offsets = c->offsets, .heads = c->heads,
                           .capacity = c->capacity};
}

static double solve(const csr *c, uint32_t s, uint32_t t, unsigned char *side) {
    double flow = -1;
    ps_error err = {0};
    ps_status st = ps_maxflow(&c->g, s, t, &flow, side, &err);
    CHECK_MSG(st == PS_OK, "ps_maxflow: %s", err.message);
    return flow;
}

static void test_chain_bottleneck(void) {
    static const edge edges[] = {{0, 1, 5}, {1, 2, 1}, {2, 3, 5}};
    csr c;
    build_csr(&c, 4, edges, 3);
    unsigned char side[4];
    CHECK_NEAR(solve(&c, 0, 3, side), 1.0, 1e-12);
    CHECK(side[0] == 1 && side[1] == 1 && side[2] == 0 && side[3] == 0);
    /* reversed roles: undirected, the same value */
    CHECK_NEAR(solve(&c, 3, 0, side), 1.0, 1e-12);
    CHECK(side[3] == 1 && side[2] == 1 && side[1] == 0 && side[0] == 0);
}

/* s=0, a=1, b=2, t=3: cuts {s} 5, {s,a} 5, {s,b} 7, {s,a,b} 5; max flow 5,
 * and the flow must use a-b to route through both sides. */
static void test_diamond(void) {
    static const edge edges[] = {{0, 1, 3}, {1, 3, 2}, {0, 2, 2}, {2, 3, 3}, {1, 2, 1}};
    csr c;
    build_csr(&c, 4, edges, 5);
    unsigned char side[4];
    CHECK_NEAR(solve(&c, 0, 3, side), 5.0, 1e-12);
    CHECK(side[0] == 1 && side[3] == 0);
}

/* 4 rows by 6 columns; the source is tied to column 0, the sink to column
 * 5; edges between columns 2 and 3 are weak (0.1), the rest 1.  The cut is
 * that column of 4 weak edges: 0.4, source side columns 0..2. */
static void test_grid_weak_column(void) {
    enum { ROWS = 4, COLS = 6, S = ROWS * COLS, T = S + 1 };
    edge edges[MAX_EDGES];
    size_t m = 0;
    for (uint32_t r = 0; r < ROWS; r++)
        for (uint32_t col = 0; col < COLS; col++) {
            uint32_t v = r * COLS + col;
            if (col + 1 < COLS) edges[m++] = (edge){v, v + 1, col == 2 ? 0.1 : 1.0};
            if (r + 1 < ROWS) edges[m++] = (edge){v, v + COLS, 1.0};
            if (col == 0) edges[m++] = (edge){S, v, 100.0};
            if (col == COLS - 1) edges[m++] = (edge){v, T, 100.0};
        }
    csr c;
    build_csr(&c, T + 1, edges, m);
    unsigned char side[T + 1], again[T + 1];
    CHECK_NEAR(solve(&c, S, T, side), 0.4, 1e-12);
    for (uint32_t v = 0; v < S; v++)
        CHECK_MSG(side[v] == (v % COLS <= 2), "node %u on the wrong side", v);
    CHECK_NEAR(solve(&c, S, T, again), 0.4, 1e-12);
    CHECK(memcmp(side, again, sizeof side) == 0);
}

static void test_unreachable_sink(void) {
    static const edge edges[] = {{0, 1, 2}, {2, 3, 2}};
    csr c;
    build_csr(&c, 4, edges, 2);
    unsigned char side[4];
    CHECK_NEAR(solve(&c, 0, 3, side), 0.0, 0);
    CHECK(side[0] == 1 && side[1] == 1 && side[2] == 0 && side[3] == 0);
}

static void test_rejects_asymmetric_and_bad_terminals(void) {
    static const size_t offsets[] = {0, 1, 1};
    static const uint32_t heads[] = {1};
    static const double capacity[] = {1};
    ps_flow_graph g = {.n = 2, .offsets = offsets, .heads = heads, .capacity = capacity};
    double flow;
    ps_error err = {0};
    CHECK(ps_maxflow(&g, 0, 1, &flow, NULL, &err) == PS_ERR_INVALID);
    CHECK(strstr(err.message, "symmetric") != NULL);
    CHECK(ps_maxflow(&g, 0, 0, &flow, NULL, &err) == PS_ERR_INVALID);
    CHECK(ps_maxflow(&g, 0, 2, &flow, NULL, &err) == PS_ERR_INVALID);
}

/* A directed 3-cycle: every row holds one arc, yet no arc has a reverse. */
static void test_rejects_cycle_without_reverse_arcs(void) {
    static const size_t offsets[] = {0, 1, 2, 3};
    static const uint32_t heads[] = {1, 2, 0};
    static const double capacity[] = {1, 1, 1};
    ps_flow_graph g = {.n = 3, .offsets = offsets, .heads = heads, .capacity = capacity};
    double flow;
    ps_error err = {0};
    CHECK(ps_maxflow(&g, 0, 2, &flow, NULL, &err) == PS_ERR_INVALID);
    CHECK(strstr(err.message, "symmetric") != NULL);
}

/* rows x cols grid, capacities from a fixed pseudo-random sequence, the
 * source tied to column 0 and the sink to the last column. */
static void build_random_grid(csr *c, uint32_t rows, uint32_t cols, uint32_t seed) {
    edge edges[MAX_EDGES];
    size_t m = 0;
    uint32_t s = rows * cols, t = s + 1;
    for (uint32_t r = 0; r < rows; r++)
        for (uint32_t col = 0; col < cols; col++) {
            uint32_t v = r * cols + col;
            seed = seed * 1103515245u + 12345u;
            double w = 0.05 + (double)(seed >> 16 & 0x3ff) / 1024.0;
            if (col + 1 < cols) edges[m++] = (edge){v, v + 1, w};
            if (r + 1 < rows) edges[m++] = (edge){v, v + cols, 1.3 - w};
            if (col == 0) edges[m++] = (edge){s, v, 50.0};
            if (col == cols - 1) edges[m++] = (edge){v, t, 50.0};
        }
    build_csr(c, t + 1, edges, m);
}

/* Sizes that grow, shrink and grow again, so the workspace both reallocates
 * and reuses larger arrays; each answer equals a fresh call's, bit for bit. */
static void test_workspace_reuse_matches_fresh_calls(void) {
    static const uint32_t shapes[][2] = {{2, 3}, {5, 8}, {3, 4}, {6, 9}, {1, 2}, {4, 7}};
    ps_maxflow_workspace *ws = ps_maxflow_workspace_new();
    REQUIRE(ws != NULL);
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
        csr c;
        build_random_grid(&c, shapes[k][0], shapes[k][1], (uint32_t)k + 7);
        uint32_t s = shapes[k][0] * shapes[k][1], t = s + 1;
        unsigned char fresh_side[MAX_NODES], reused_side[MAX_NODES];
        double fresh = solve(&c, s, t, fresh_side), reused = -1;
        ps_error err = {0};
        CHECK(ps_maxflow_with(ws, &c.g, s, t, &reused, reused_side, &err) == PS_OK);
        CHECK_MSG(memcmp(&fresh, &reused, sizeof fresh) == 0, "graph %zu: flow %.17g vs %.17g",
                  k, fresh, reused);
        CHECK_MSG(memcmp(fresh_side, reused_side, c.g.n) == 0, "graph %zu: cut differs", k);
        CHECK(fresh > 0 && fresh_side[s] == 1 && fresh_side[t] == 0);
    }
    ps_maxflow_workspace_free(ws);
    ps_maxflow_workspace_free(NULL);
}

/* 0 - 1 - ... - n-1 with one weak edge in the middle: the only augmenting
 * path is n nodes deep. */
static void test_long_path_no_stack_overflow(void) {
    enum { N = 200000, WEAK = N / 2 };
    size_t *offsets = malloc((N + 1) * sizeof *offsets);
    uint32_t *heads = malloc(2 * (N - 1) * sizeof *heads);
    double *capacity = malloc(2 * (N - 1) * sizeof *capacity);
    unsigned char *side = malloc(N);
    REQUIRE(offsets && heads && capacity && side);
    size_t arcs = 0;
    for (uint32_t v = 0; v < N; v++) {
        offsets[v] = arcs;
        if (v > 0) heads[arcs] = v - 1, capacity[arcs++] = v - 1 == WEAK ? 0.25 : 2.0;
        if (v + 1 < N) heads[arcs] = v + 1, capacity[arcs++] = v == WEAK ? 0.25 : 2.0;
    }
    offsets[N] = arcs;
    ps_flow_graph g = {.n = N, .offsets = offsets, .heads = heads, .capacity = capacity};
    double flow = -1;
    ps_error err = {0};
    CHECK(ps_maxflow(&g, 0, N - 1, &flow, side, &err) == PS_OK);
    CHECK_NEAR(flow, 0.25, 0);
    size_t wrong = 0;
    for (uint32_t v = 0; v < N; v++) wrong += side[v] != (v <= WEAK);
    CHECK_MSG(wrong == 0, "%zu nodes on the wrong side", wrong);
    free(offsets);
    free(heads);
    free(capacity);
    free(side);
}

PS_TEST_MAIN(TEST(test_chain_bottleneck), TEST(test_diamond), TEST(test_grid_weak_column),
             TEST(test_unreachable_sink), TEST(test_rejects_asymmetric_and_bad_terminals),
             TEST(test_rejects_cycle_without_reverse_arcs),
             TEST(test_workspace_reuse_matches_fresh_calls), TEST(test_long_path_no_stack_overflow))
