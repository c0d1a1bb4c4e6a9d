/* test_dijkstra.c: distances and owners equal Bellman-Ford on random graphs
 * (integer weights make ties exact), unreachable vertices get INFINITY, and
 * ps_dijkstra_lower equals the minimum of full runs; ps_dijkstra_lower_many
 * from a cap equals a multi-source run clipped at the cap. */
#include "dijkstra.h"
#include "knn_graph.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct rng {
    unsigned long long s;
} rng;

static unsigned next_u(rng *r, unsigned bound) {
    r->s ^= r->s << 13, r->s ^= r->s >> 7, r->s ^= r->s << 17;
    return (unsigned)((r->s >> 20) % bound);
}

/* A random symmetric graph on n vertices with about `degree` edges per
 * vertex and integer weights 1..9 (vertex n-1 isolated). */
static void random_graph(size_t n, int degree, unsigned long long seed, ps_graph *g) {
    rng r = {seed};
    double *w = calloc(n * n, sizeof *w);
    for (size_t e = 0; w && e < n * (size_t)degree / 2; e++) {
        size_t a = next_u(&r, (unsigned)n - 1), b = next_u(&r, (unsigned)n - 1);
        if (a != b) w[a * n + b] = w[b * n + a] = 1 + next_u(&r, 9);
    }
    g->n = n;
    g->offsets = malloc((n + 1) * sizeof *g->offsets);
    g->neighbors = malloc(n * n * sizeof *g->neighbors);
    g->weights = malloc(n * n * sizeof *g->weights);
    size_t m = 0;
    for (size_t p = 0; w && p < n; p++) {
        g->offsets[p] = m;
        for (size_t q = 0; q < n; q++)
            if (w[p * n + q] > 0) g->neighbors[m] = (uint32_t)q, g->weights[m++] = w[p * n + q];
    }
    g->offsets[n] = m;
    free(w);
}

static void bellman_ford(const ps_graph *g, uint32_t source, double *d) {
    for (size_t v = 0; v < g->n; v++) d[v] = INFINITY;
    d[source] = 0;
    for (int changed = 1; changed;) {
        changed = 0;
        for (size_t p = 0; p < g->n; p++)
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
                if (d[p] + g->weights[e] < d[g->neighbors[e]])
                    d[g->neighbors[e]] = d[p] + g->weights[e], changed = 1;
    }
}

static void test_single_source(void) {
    size_t n = 120;
    ps_graph g;
    random_graph(n, 4, 7, &g);
    ps_dijkstra *w = ps_dijkstra_new(n);
    double *d = malloc(n * sizeof *d), *ref = malloc(n * sizeof *ref);
    REQUIRE(w && d && ref && g.weights);
    for (uint32_t s = 0; s < n; s += 7) {
        ps_dijkstra_run(w, &g, &s, 1, d, NULL);
        bellman_ford(&g, s, ref);
        for (size_t v = 0; v < n; v++) CHECK(d[v] == ref[v]);
    }
    uint32_t zero = 0;
    ps_dijkstra_run(w, &g, &zero, 1, d, NULL);
    CHECK(isinf(d[n - 1]));
    free(d), free(ref);
    ps_dijkstra_free(w);
    ps_graph_free(&g);
}

/* Owners: the lowest source index among the nearest sources. */
static void test_multi_source_owner(void) {
    size_t n = 150;
    ps_graph g;
    random_graph(n, 3, 11, &g);
    const uint32_t sources[] = {40, 3, 97, 3, 12, 140};
    size_t ns = sizeof sources / sizeof sources[0];
    ps_dijkstra *w = ps_dijkstra_new(n);
    double *d = malloc(n * sizeof *d), *ref = malloc(ns * n * sizeof *ref);
    int *owner = malloc(n * sizeof *owner);
    REQUIRE(w && d && ref && owner && g.weights);
    for (size_t s = 0; s < ns; s++) bellman_ford(&g, sources[s], ref + s * n);
    ps_dijkstra_run(w, &g, sources, ns, d, owner);
    size_t ties = 0;
    for (size_t v = 0; v < n; v++) {
        double best = INFINITY;
        int who = -1, nearest = 0;
        for (size_t s = 0; s < ns; s++) {
            if (ref[s * n + v] < best) best = ref[s * n + v], who = (int)s, nearest = 1;
            else if (ref[s * n + v] == best && isfinite(best)) nearest++;
        }
        ties += nearest > 1;
        CHECK(d[v] == best);
        CHECK_MSG(owner[v] == who, "vertex %zu: owner %d, want %d", v, owner[v], who);
    }
    CHECK(ties > 3); /* the test really exercises tie breaking */
    CHECK(owner[n - 1] == -1 && isinf(d[n - 1]));
    free(d), free(ref), free(owner);
    ps_dijkstra_free(w);
    ps_graph_free(&g);
}

static void test_lower_is_min_of_runs(void) {
    size_t n = 400;
    double *pts = malloc(n * 3 * sizeof *pts);
    REQUIRE(pts);
    rng r = {5};
    for (size_t i = 0; i < 3 * n; i++) pts[i] = next_u(&r, 1000000) / 1e6;
    ps_graph g;
    REQUIRE(ps_knn_graph_build(pts, n, 3, 6, 1, &g, NULL) == PS_OK);
    ps_dijkstra *w = ps_dijkstra_new(n);
    double *low = malloc(n * sizeof *low), *full = malloc(n * sizeof *full),
           *mins = malloc(n * sizeof *mins);
    REQUIRE(w && low && full && mins);
    for (size_t v = 0; v < n; v++) low[v] = mins[v] = INFINITY;
    const uint32_t src[] = {0, 250, 17, 399, 250};
    for (size_t s = 0; s < sizeof src / sizeof src[0]; s++) {
        ps_dijkstra_lower(w, &g, src[s], low);
        ps_dijkstra_run(w, &g, &src[s], 1, full, NULL);
        for (size_t v = 0; v < n; v++) {
            mins[v] = fmin(mins[v], full[v]);
            CHECK_NEAR(low[v], mins[v], 1e-12);
        }
    }
    free(low), free(full), free(mins), free(pts);
    ps_dijkstra_free(w);
    ps_graph_free(&g);
}

static void test_lower_many_is_capped_run(void) {
    size_t n = 300;
    ps_graph g;
    random_graph(n, 4, 11, &g);
    ps_dijkstra *w = ps_dijkstra_new(n);
    double *capped = malloc(n * sizeof *capped), *full = malloc(n * sizeof *full);
    REQUIRE(w && capped && full);
    const uint32_t src[] = {3, 120, 77};
    const double cap = 6;
    for (size_t v = 0; v < n; v++) capped[v] = cap;
    ps_dijkstra_lower_many(w, &g, src, 3, capped);
    ps_dijkstra_run(w, &g, src, 3, full, NULL);
    size_t below = 0;
    for (size_t v = 0; v < n; v++) {
        CHECK(capped[v] == fmin(full[v], cap));
        below += full[v] < cap;
    }
    CHECK(below > 10 && below < n - 10); /* the cap really cuts the search */
    free(capped), free(full);
    ps_dijkstra_free(w);
    ps_graph_free(&g);
}

PS_TEST_MAIN(TEST(test_single_source), TEST(test_multi_source_owner),
             TEST(test_lower_is_min_of_runs), TEST(test_lower_many_is_capped_run))
