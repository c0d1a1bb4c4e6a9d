/* test_coarse_graph.c: cells partition the vertices (seed in its own cell,
 * no cell across components, each vertex with its nearest seed), local distances from the own seed equal a full
 * Dijkstra and the others are never shorter, coarse edge weights are the
 * smaller local geodesic of the two seeds, components stay apart, cancel,
 * and the cell radius grows past PS_CELL_SCALE_POINTS so that the cell
 * count stays bounded. */
#include "features/coarse_graph.h"
#include "graph/dijkstra.h"
#include "graph/knn_graph.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct fixture {
    ps_graph g;
    ps_bfs_order o;
    ps_coarse_graph cg;
} fixture;

/* A sphere, or a sphere and a far copy of it (two components). */
static int fixture_make(int two, fixture *fx) {
    size_t n;
    double *one = ps_shape_sphere(200.0, &n, NULL);
    size_t total = two ? 2 * n : n;
    double *pts = malloc(total * 3 * sizeof *pts);
    int ok = one && pts;
    if (ok) {
        memcpy(pts, one, n * 3 * sizeof *pts);
        for (size_t i = 0; two && i < 3 * n; i++)
            pts[3 * n + i] = one[i] + (i % 3 == 0 ? 10.0 : 0.0); /* shifted along x */
    }
    ok = ok && ps_knn_graph_build(pts, total, 3, 7, 2, &fx->g, NULL) == PS_OK;
    free(one), free(pts);
    ok = ok && ps_bfs_order_build(&fx->g, &fx->o, NULL) == PS_OK;
    return ok && ps_coarse_graph_build(&fx->o, 2, NULL, &fx->cg, NULL) == PS_OK;
}

static void fixture_free(fixture *fx) {
    ps_coarse_graph_free(&fx->cg);
    ps_bfs_order_free(&fx->o);
    ps_graph_free(&fx->g);
}

static size_t near_position(const ps_coarse_graph *cg, uint32_t a, uint32_t c) {
    for (size_t i = cg->near_offsets[a]; i < cg->near_offsets[a + 1]; i++)
        if (cg->near[i] == c) return i - cg->near_offsets[a];
    return SIZE_MAX;
}

static float local_of(const ps_coarse_graph *cg, uint32_t p, uint32_t c) {
    size_t j = near_position(cg, cg->cell_of[p], c);
    return j == SIZE_MAX ? NAN : cg->local[cg->local_offsets[p] + j];
}

static int component_of(const ps_bfs_order *o, size_t v) {
    int k = 0;
    while (o->start[k + 1] <= v) k++;
    return k;
}

static void test_cells_partition(void) {
    fixture fx;
    REQUIRE(fixture_make(0, &fx));
    const ps_coarse_graph *cg = &fx.cg;
    size_t n = fx.g.n, m = cg->n_cells;
    CHECK_MSG(n / m >= 8 && n / m <= 40, "%zu points in %zu cells", n, m);
    size_t *size = calloc(m, sizeof *size);
    REQUIRE(size);
    for (size_t v = 0; v < n; v++) {
        REQUIRE(cg->cell_of[v] < m);
        size[cg->cell_of[v]]++;
    }
    size_t sum = 0;
    for (size_t c = 0; c < m; c++) {
        CHECK(size[c] >= 1);
        CHECK(cg->cell_of[cg->seed[c]] == c);
        if (c) CHECK(cg->seed[c] > cg->seed[c - 1]);
        sum += size[c];
    }
    CHECK(sum == n && cg->seed[0] == 0);
    CHECK(cg->cell_start[0] == 0 && cg->cell_start[1] == m);
    free(size);
    fixture_free(&fx);
}

/* Each vertex is in the cell of its nearest seed (ties: the lower cell),
 * as a multi-source Dijkstra from all the seeds assigns it. */
static void test_cells_are_nearest_seed(void) {
    fixture fx;
    REQUIRE(fixture_make(1, &fx));
    const ps_coarse_graph *cg = &fx.cg;
    size_t n = fx.o.g.n;
    ps_dijkstra *dij = ps_dijkstra_new(n);
    double *dist = malloc(n * sizeof *dist);
    int *owner = malloc(n * sizeof *owner);
    REQUIRE(dij && dist && owner);
    ps_dijkstra_run(dij, &fx.o.g, cg->seed, cg->n_cells, dist, owner);
    size_t same = 0;
    for (size_t v = 0; v < n; v++) same += cg->cell_of[v] == (uint32_t)owner[v];
    CHECK_MSG(same == n, "%zu of %zu vertices in their nearest seed's cell", same, n);
    ps_dijkstra_free(dij);
    free(dist), free(owner);
    fixture_free(&fx);
}

/* g(own seed, p) is the full-graph distance; other candidates are >= it. */
static void test_local_distances(void) {
    fixture fx;
    REQUIRE(fixture_make(0, &fx));
    const ps_coarse_graph *cg = &fx.cg;
    size_t n = fx.g.n;
    ps_dijkstra *dij = ps_dijkstra_new(n);
    double *dist = malloc(n * sizeof *dist);
    REQUIRE(dij && dist);
    int bad_own = 0, bad_other = 0, checked = 0;
    for (uint32_t c = 0; c < cg->n_cells; c += 7) {
        ps_dijkstra_run(dij, &fx.o.g, &cg->seed[c], 1, dist, NULL);
        for (uint32_t p = 0; p < n; p++) {
            float g = local_of(cg, p, c);
            if (isnan(g)) continue;
            checked++;
            if (cg->cell_of[p] == c) bad_own += fabs(g - dist[p]) > 1e-6 * (1.0 + dist[p]);
            else bad_other += g < dist[p] - 1e-6 * (1.0 + dist[p]);
        }
    }
    CHECK(checked > (int)n / 2);
    CHECK_MSG(bad_own == 0 && bad_other == 0, "own %d, others %d wrong", bad_own, bad_other);
    for (size_t p = 0; p < n; p++) CHECK(local_of(cg, (uint32_t)p, cg->cell_of[p]) >= 0.0f);
    free(dist);
    ps_dijkstra_free(dij);
    fixture_free(&fx);
}

static void test_coarse_edges(void) {
    fixture fx;
    REQUIRE(fixture_make(0, &fx));
    const ps_coarse_graph *cg = &fx.cg;
    const ps_graph *c = &cg->graph;
    REQUIRE(c->n == cg->n_cells);
    int wrong = 0, asymmetric = 0;
    for (uint32_t a = 0; a < c->n; a++)
        for (size_t e = c->offsets[a]; e < c->offsets[a + 1]; e++) {
            uint32_t b = c->neighbors[e];
            double expect = fmin(local_of(cg, cg->seed[b], a), local_of(cg, cg->seed[a], b));
            wrong += !(c->weights[e] == expect && expect > 0.0);
            int back = 0;
            for (size_t f = c->offsets[b]; f < c->offsets[b + 1]; f++)
                back += c->neighbors[f] == a && c->weights[f] == c->weights[e];
            asymmetric += back != 1;
        }
    CHECK(c->offsets[c->n] > 2 * c->n);
    CHECK_MSG(wrong == 0 && asymmetric == 0, "%d wrong, %d asymmetric", wrong, asymmetric);
    fixture_free(&fx);
}

static void test_two_components(void) {
    fixture fx;
    REQUIRE(fixture_make(2, &fx));
    const ps_coarse_graph *cg = &fx.cg;
    REQUIRE(fx.o.n_components == 2);
    size_t split = cg->cell_start[1];
    CHECK(split > 0 && split < cg->n_cells && cg->cell_start[2] == cg->n_cells);
    CHECK(cg->seed[0] == 0 && cg->seed[split] == fx.o.start[1]);
    int crossing = 0;
    for (size_t v = 0; v < fx.g.n; v++)
        crossing += (cg->cell_of[v] >= split) != (component_of(&fx.o, v) == 1);
    for (uint32_t a = 0; a < cg->n_cells; a++)
        for (size_t i = cg->near_offsets[a]; i < cg->near_offsets[a + 1]; i++)
            crossing += (cg->near[i] >= split) != (a >= split);
    CHECK(crossing == 0);
    fixture_free(&fx);
}

static void test_cancel(void) {
    size_t n;
    double *pts = ps_shape_sphere(20.0, &n, NULL);
    ps_graph g;
    ps_bfs_order o;
    REQUIRE(pts && ps_knn_graph_build(pts, n, 3, 7, 1, &g, NULL) == PS_OK);
    REQUIRE(ps_bfs_order_build(&g, &o, NULL) == PS_OK);
    volatile int cancel = 1;
    ps_control ctl = {.cancel = &cancel};
    ps_progress_span span = {&ctl, PS_PHASE_CENTRALITY, 0.0, 0.3};
    ps_coarse_graph cg;
    ps_error err = {0};
    CHECK(ps_coarse_graph_build(&o, 2, &span, &cg, &err) == PS_ERR_CANCELLED);
    CHECK(err.status == PS_ERR_CANCELLED && cg.seed == NULL && cg.local == NULL);
    ps_bfs_order_free(&o);
    ps_graph_free(&g);
    free(pts);
}

/* Cells cover area ~ radius^2: points per cell grow as size / scale, so
 * the cell count size / (points per cell) is the same from the scale on. */
static void test_radius_growth_bounds_cells(void) {
    CHECK(ps_cell_radius_growth(1000) == 1.0);
    CHECK(ps_cell_radius_growth(PS_CELL_SCALE_POINTS) == 1.0);
    CHECK(fabs(ps_cell_radius_growth(4 * (size_t)PS_CELL_SCALE_POINTS) - 2.0) < 1e-12);
    double g = ps_cell_radius_growth(10 * (size_t)PS_CELL_SCALE_POINTS);
    CHECK(fabs(10.0 * PS_CELL_SCALE_POINTS / (g * g) - PS_CELL_SCALE_POINTS) < 1e-6);
}

PS_TEST_MAIN(TEST(test_cells_partition), TEST(test_cells_are_nearest_seed),
             TEST(test_local_distances), TEST(test_coarse_edges),
             TEST(test_two_components), TEST(test_cancel), TEST(test_radius_growth_bounds_cells))
