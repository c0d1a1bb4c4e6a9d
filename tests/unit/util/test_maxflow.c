/*
 * test_maxflow.c: the max flow of maxflow.h on small undirected graphs
 * whose maximum flow and minimum cut are known by hand: a chain, a diamond,
 * a grid with a weak column, a graph where t cannot be reached; the same
 * answer on every run; a graph that is not symmetric is refused.  On random
 * grids, random sparse graphs and band-like random geometric graphs the
 * flow and the cut equal those of a plain shortest-augmenting-path
 * reference (Edmonds-Karp) written here.  One
 * workspace reused over graphs of growing and shrinking sizes gives the
 * same flow and cut, bit for bit, as fresh calls; a path of 200k nodes (a
 * deep search) does not overflow the stack.
 */
#include "testlib.h"
#include "util/maxflow.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_NODES 64
#define MAX_EDGES 256

/* A CSR flow graph built from an undirected edge list. */
typedef struct csr {
    ps_maxflow_graph g;
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
    c->g = (ps_maxflow_graph){.n = n, .offsets = c->offsets, .heads = c->heads,
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

/* 4 rows by 6 columns; s is tied to column 0, t to column
 * 5; edges between columns 2 and 3 are weak (0.1), the rest 1.  The cut is
 * that column of 4 weak edges: 0.4, s side columns 0..2. */
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

static void test_unreachable_t(void) {
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
    ps_maxflow_graph g = {.n = 2, .offsets = offsets, .heads = heads, .capacity = capacity};
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
    ps_maxflow_graph g = {.n = 3, .offsets = offsets, .heads = heads, .capacity = capacity};
    double flow;
    ps_error err = {0};
    CHECK(ps_maxflow(&g, 0, 2, &flow, NULL, &err) == PS_ERR_INVALID);
    CHECK(strstr(err.message, "symmetric") != NULL);
}

/* rows x cols grid, capacities from a fixed pseudo-random sequence, the
 * s tied to column 0 and t to the last column. */
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

/* Edmonds-Karp on g: the reference flow and s side (#V), with the
 * same saturation tolerance as maxflow.c (1e-12 of the largest capacity). */
static double reference_flow(const ps_maxflow_graph *g, uint32_t s, uint32_t t,
                             unsigned char *side) {
    size_t n = g->n, arcs = g->offsets[n];
    double *residual = malloc((arcs + 1) * sizeof *residual), total = 0, largest = 0;
    size_t *reverse = malloc((arcs + 1) * sizeof *reverse), *via = malloc(n * sizeof *via);
    uint32_t *queue = malloc(n * sizeof *queue);
    if (!residual || !reverse || !via || !queue) {
        CHECK_MSG(0, "reference: out of memory");
        free(residual), free(reverse), free(via), free(queue);
        return NAN;
    }
    for (uint32_t p = 0; p < n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            residual[e] = g->capacity[e];
            if (g->capacity[e] > largest) largest = g->capacity[e];
            for (size_t r = g->offsets[g->heads[e]]; r < g->offsets[g->heads[e] + 1]; r++)
                if (g->heads[r] == p) reverse[e] = r;
        }
    for (;;) {
        memset(side, 0, n);
        size_t head = 0, tail = 0;
        side[s] = 1, queue[tail++] = s;
        while (head < tail) {
            uint32_t v = queue[head++];
            for (size_t e = g->offsets[v]; e < g->offsets[v + 1]; e++) {
                uint32_t q = g->heads[e];
                if (side[q] || residual[e] <= 1e-12 * largest) continue;
                side[q] = 1, via[q] = e, queue[tail++] = q;
            }
        }
        if (!side[t]) break;
        double x = INFINITY;
        for (uint32_t v = t; v != s; v = g->heads[reverse[via[v]]])
            if (residual[via[v]] < x) x = residual[via[v]];
        for (uint32_t v = t; v != s; v = g->heads[reverse[via[v]]])
            residual[via[v]] -= x, residual[reverse[via[v]]] += x;
        total += x;
    }
    free(residual), free(reverse), free(via), free(queue);
    return total;
}

static void check_against_reference(const ps_maxflow_graph *g, uint32_t s, uint32_t t,
                                    const char *what) {
    unsigned char *side = malloc(g->n), *expected = malloc(g->n);
    REQUIRE(side && expected);
    double flow = -1, want = reference_flow(g, s, t, expected);
    ps_error err = {0};
    CHECK(ps_maxflow(g, s, t, &flow, side, &err) == PS_OK);
    CHECK_MSG(fabs(flow - want) <= 1e-9 * (1 + want), "%s: flow %.17g, reference %.17g", what,
              flow, want);
    CHECK_MSG(memcmp(side, expected, g->n) == 0, "%s: the cut differs", what);
    free(side), free(expected);
}

/* Random grids and random sparse graphs: the same flow (to rounding) and
 * the same cut as the reference. */
static void test_matches_reference_on_random_graphs(void) {
    uint32_t seed = 12345;
    for (int k = 0; k < 200; k++) {
        csr c;
        uint32_t n, s, t;
        if (k % 2 == 0) {
            uint32_t rows = 2 + (uint32_t)k % 5, cols = 2 + (uint32_t)k % 7;
            build_random_grid(&c, rows, cols, (uint32_t)k);
            s = rows * cols, t = s + 1, n = t + 1;
        } else {
            edge edges[MAX_EDGES];
            size_t m = 0;
            n = 8 + (uint32_t)k % 40, s = 0, t = n - 1;
            for (uint32_t a = 0; a < n; a++)
                for (int j = 0; j < 3 && m < MAX_EDGES; j++) {
                    seed = seed * 1103515245u + 12345u;
                    uint32_t b = (seed >> 8) % n;
                    int dup = b == a;
                    for (size_t i = 0; i < m && !dup; i++)
                        dup = (edges[i].a == a && edges[i].b == b) ||
                              (edges[i].a == b && edges[i].b == a);
                    if (!dup) edges[m++] = (edge){a, b, 0.01 + (double)(seed >> 20) / 64.0};
                }
            build_csr(&c, n, edges, m);
        }
        char what[32];
        snprintf(what, sizeof what, "graph %d of %u nodes", k, n);
        check_against_reference(&c.g, s, t, what);
    }
}

/* Random points in the unit square, each joined to its 6 nearest (both
 * ways), random capacities, s tied to the left tenth and t
 * to the right tenth, like the boundary cut's bands: thousands of
 * augmentations and orphans, the same flow and cut as the reference. */
static void test_matches_reference_on_band_like_graphs(void) {
    enum { N = 1500, K = 6 };
    for (uint32_t round = 0; round < 3; round++) {
        double *xy = malloc(2 * N * sizeof *xy);
        unsigned char *adj = calloc((size_t)(N + 2) * (N + 2), 1);
        REQUIRE(xy && adj);
        uint32_t seed = 99 + round;
        for (size_t i = 0; i < 2 * N; i++) {
            seed = seed * 1103515245u + 12345u;
            xy[i] = (double)(seed >> 8) / 16777216.0;
        }
        for (uint32_t p = 0; p < N; p++) {
            for (int j = 0; j < K; j++) {
                uint32_t best = p;
                double best_d = INFINITY;
                for (uint32_t q = 0; q < N; q++) {
                    double dx = xy[2 * p] - xy[2 * q], dy = xy[2 * p + 1] - xy[2 * q + 1];
                    double d = dx * dx + dy * dy;
                    if (q != p && !adj[(size_t)p * (N + 2) + q] && d < best_d) best = q, best_d = d;
                }
                adj[(size_t)p * (N + 2) + best] = adj[(size_t)best * (N + 2) + p] = 1;
            }
            if (xy[2 * p] < 0.1) adj[(size_t)p * (N + 2) + N] = adj[(size_t)N * (N + 2) + p] = 1;
            if (xy[2 * p] > 0.9)
                adj[(size_t)p * (N + 2) + N + 1] = adj[(size_t)(N + 1) * (N + 2) + p] = 1;
        }
        size_t *offsets = malloc((N + 3) * sizeof *offsets), arcs = 0;
        for (size_t p = 0; p < N + 2; p++)
            for (size_t q = 0; q < N + 2; q++) arcs += adj[p * (N + 2) + q];
        uint32_t *heads = malloc(arcs * sizeof *heads);
        double *capacity = malloc(arcs * sizeof *capacity);
        REQUIRE(offsets && heads && capacity);
        arcs = 0;
        for (uint32_t p = 0; p < N + 2; p++) {
            offsets[p] = arcs;
            for (uint32_t q = 0; q < N + 2; q++) {
                if (!adj[(size_t)p * (N + 2) + q]) continue;
                uint32_t lo = p < q ? p : q, hi = p < q ? q : p, h = lo * 2654435761u ^ hi * 40503u;
                heads[arcs] = q;
                capacity[arcs++] = hi >= N ? 100.0 : 0.05 + (double)(h >> 12 & 0xfff) / 4096.0;
            }
        }
        offsets[N + 2] = arcs;
        ps_maxflow_graph g = {.n = N + 2, .offsets = offsets, .heads = heads, .capacity = capacity};
        char what[32];
        snprintf(what, sizeof what, "band-like graph %u", round);
        check_against_reference(&g, N, N + 1, what);
        free(xy), free(adj), free(offsets), free(heads), free(capacity);
    }
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
    ps_maxflow_graph g = {.n = N, .offsets = offsets, .heads = heads, .capacity = capacity};
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
             TEST(test_unreachable_t), TEST(test_rejects_asymmetric_and_bad_terminals),
             TEST(test_rejects_cycle_without_reverse_arcs),
             TEST(test_workspace_reuse_matches_fresh_calls),
             TEST(test_matches_reference_on_random_graphs),
             TEST(test_matches_reference_on_band_like_graphs),
             TEST(test_long_path_no_stack_overflow))
