/*
 * test_maxflow.c: Dinic's max flow (maxflow.h) on small undirected graphs
 * whose maximum flow and minimum cut are known by hand: a chain, a diamond,
 * a grid with a weak column, a graph the sink cannot be reached in; the same
 * answer on every run; a graph that is not symmetric is refused.
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

PS_TEST_MAIN(TEST(test_chain_bottleneck), TEST(test_diamond), TEST(test_grid_weak_column),
             TEST(test_unreachable_sink), TEST(test_rejects_asymmetric_and_bad_terminals))
