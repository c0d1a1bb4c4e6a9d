/* test_dijkstra.c: distances and owners equal Bellman-Ford on random graphs
 * (integer weights make ties exact), unreachable vertices get INFINITY, and
 * ps_dijkstra_lower equals the minimum of full runs.  Ball runs on a
 * hand-built graph: the radius is inclusive, a region detours around the
 * vertices outside it, the reached list is in settling order and resets
 * dist; on a random graph a ball equals Bellman-Ford within the radius; a
 * ball from several sources measuring edges between the points equals,
 * bit for bit, a ball from one added vertex joined to those sources by
 * zero-length edges over a copy of the graph weighted with the lengths; a
 * tracked run answers the same and reports its progress. */
#include "graph/dijkstra.h"
#include "graph/knn_graph.h"
#include "progress_seen.h"
#include "random_graph.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A random graph with lengths 1..9 (vertex n-1 isolated). */
static void random_graph(size_t n, int degree, unsigned long long seed, ps_graph *g) {
    test_random_graph(n, degree, 1, 9, 1, 1, seed, g);
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

/* A ball of radius R from s reaches exactly the vertices with ref <= R, at
 * their ref distance, in settling order; dist (#P) is INFINITY before and
 * after.  Returns how many vertices are exactly at R. */
static size_t check_ball(ps_dijkstra *w, const ps_graph *g, uint32_t s, const double *ref,
                         double radius, double *dist, uint32_t *reached) {
    ps_dijkstra_limits limits = {.radius = radius};
    size_t count = ps_dijkstra_ball(w, g, s, &limits, dist, reached), inside = 0, at = 0;
    for (size_t v = 0; v < g->n; v++) {
        inside += ref[v] <= radius, at += ref[v] == radius;
        CHECK(dist[v] == (ref[v] <= radius ? ref[v] : INFINITY));
    }
    CHECK(count == inside && reached[0] == s);
    for (size_t i = 1; i < count; i++) CHECK(dist[reached[i - 1]] <= dist[reached[i]]);
    for (size_t i = 0; i < count; i++) dist[reached[i]] = INFINITY;
    return at;
}

/* Full runs, and balls of radius 7 (integer weights put many vertices
 * exactly at 7, so the inclusive bound is exercised). */
static void test_single_source_and_ball(void) {
    size_t n = 120;
    ps_graph g;
    random_graph(n, 4, 7, &g);
    ps_dijkstra *w = ps_dijkstra_new(n);
    double *d = malloc(n * sizeof *d), *ref = malloc(n * sizeof *ref),
           *ball = malloc(n * sizeof *ball);
    uint32_t *reached = malloc(n * sizeof *reached);
    REQUIRE(w && d && ref && ball && reached && g.weights);
    for (size_t v = 0; v < n; v++) ball[v] = INFINITY;
    size_t at_radius = 0;
    for (uint32_t s = 0; s < n; s += 7) {
        ps_dijkstra_run(w, &g, &s, 1, d, NULL);
        bellman_ford(&g, s, ref);
        for (size_t v = 0; v < n; v++) CHECK(d[v] == ref[v]);
        at_radius += check_ball(w, &g, s, ref, 7.0, ball, reached);
    }
    CHECK(at_radius > 5);
    uint32_t zero = 0;
    ps_dijkstra_run(w, &g, &zero, 1, d, NULL);
    CHECK(isinf(d[n - 1]));
    free(d), free(ref), free(ball), free(reached);
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
    test_rng r = {5};
    for (size_t i = 0; i < 3 * n; i++) pts[i] = test_rng_below(&r, 1000000) / 1e6;
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

/* g's rows weighted with Euclidean lengths, plus vertex #P whose row is
 * sources (zero lengths): the copy a multi-source ball makes needless. */
static void with_source_vertex(const ps_graph *g, const double *pts, const uint32_t *sources,
                               size_t n_sources, ps_graph *geo) {
    size_t n = g->n, arcs = g->offsets[n];
    geo->n = n + 1;
    geo->offsets = malloc((n + 2) * sizeof *geo->offsets);
    geo->neighbors = malloc((arcs + n_sources) * sizeof *geo->neighbors);
    geo->weights = malloc((arcs + n_sources) * sizeof *geo->weights);
    if (!geo->offsets || !geo->neighbors || !geo->weights) return;
    memcpy(geo->offsets, g->offsets, (n + 1) * sizeof *geo->offsets);
    geo->offsets[n + 1] = arcs + n_sources;
    for (size_t p = 0; p < n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            geo->neighbors[e] = g->neighbors[e];
            geo->weights[e] = ps_distance3(pts + 3 * p, pts + 3 * (size_t)g->neighbors[e]);
        }
    for (size_t s = 0; s < n_sources; s++)
        geo->neighbors[arcs + s] = sources[s], geo->weights[arcs + s] = 0.0;
}

/* Sources in a region of two labels out to a radius, on a kNN graph
 * without weights: the same reached set and the same distances, bit for
 * bit, as the ball from a joining vertex on the weighted copy. */
static void test_ball_from_sources_between_points(void) {
    size_t n = 2000;
    double *pts = malloc(n * 3 * sizeof *pts);
    test_rng r = {9};
    for (size_t i = 0; pts && i < 3 * n; i++) pts[i] = test_rng_below(&r, 1000000) / 1e6;
    ps_graph g, geo = {0};
    REQUIRE(pts && ps_knn_graph_build(pts, n, 3, 7, 1, &g, NULL) == PS_OK);
    const uint32_t sources[] = {5, 77, 1200, 640};
    size_t ns = sizeof sources / sizeof sources[0];
    with_source_vertex(&g, pts, sources, ns, &geo);
    uint32_t *label = malloc((n + 1) * sizeof *label), mark[3] = {4, 4, 0};
    double *d_geo = malloc((n + 1) * sizeof *d_geo), *d = malloc(n * sizeof *d);
    uint32_t *r_geo = malloc((n + 1) * sizeof *r_geo), *reached = malloc(n * sizeof *reached);
    ps_dijkstra *w = ps_dijkstra_new(n + 1);
    REQUIRE(geo.weights && label && d_geo && d && r_geo && reached && w);
    for (size_t p = 0; p <= n; p++) label[p] = pts[3 * (p < n ? p : 0)] < 0.8 ? (p % 2) : 2;
    for (size_t s = 0; s < ns; s++) label[sources[s]] = 0;
    for (size_t p = 0; p <= n; p++) d_geo[p] = p < n ? (d[p] = INFINITY) : INFINITY;
    ps_dijkstra_limits on_geo = {.radius = 0.12, .label = label, .mark = mark, .stamp = 4},
                       on_points = on_geo;
    on_points.points = pts;
    size_t c_geo = ps_dijkstra_ball(w, &geo, (uint32_t)n, &on_geo, d_geo, r_geo);
    free(g.weights);
    g.weights = NULL; /* a ball between points never reads them */
    size_t count = ps_dijkstra_ball_from(w, &g, sources, ns, &on_points, d, reached);
    CHECK(count == c_geo - 1 && count > 4 * ns && count < n / 2);
    for (size_t p = 0; p < n; p++)
        CHECK_MSG(d[p] == d_geo[p], "point %zu: %.17g, want %.17g", p, d[p], d_geo[p]);
    for (size_t i = 0; i < ns; i++) CHECK(d[reached[i]] == 0.0);
    free(label), free(d_geo), free(d), free(r_geo), free(reached), free(pts);
    ps_dijkstra_free(w);
    ps_graph_free(&geo);
    ps_graph_free(&g);
}

/* Hand-built: a path 0-1-2-3-4 of unit edges and a detour 0-5-2 of two
 * edges of length 2.  From 0: d = 0 1 2 3 4 2. */
static const size_t hand_offsets[] = {0, 2, 4, 7, 9, 10, 12};
static const uint32_t hand_neighbors[] = {1, 5, 0, 2, 1, 3, 5, 2, 4, 3, 0, 2};
static const double hand_weights[] = {1, 2, 1, 1, 1, 1, 2, 1, 1, 1, 2, 2};
#define HAND_N 6

/* One workspace on the hand-built graph; dist is INFINITY between balls. */
typedef struct hand_ball {
    ps_graph g;
    ps_dijkstra *w;
    double dist[HAND_N];
    uint32_t reached[HAND_N];
    size_t count;
} hand_ball;

static int hand_open(hand_ball *h) {
    h->g = (ps_graph){HAND_N, (size_t *)hand_offsets, (uint32_t *)hand_neighbors,
                      (double *)hand_weights};
    h->w = ps_dijkstra_new(HAND_N);
    for (size_t v = 0; v < HAND_N; v++) h->dist[v] = INFINITY;
    h->count = 0;
    return h->w != NULL;
}

/* Undoes the last ball through its reached list. */
static void hand_reset(hand_ball *h) {
    for (size_t i = 0; i < h->count; i++) h->dist[h->reached[i]] = INFINITY;
    h->count = 0;
}

static void hand_run(hand_ball *h, uint32_t source, double radius, const uint32_t *label,
                     const uint32_t *mark, uint32_t stamp) {
    hand_reset(h);
    ps_dijkstra_limits limits = {.radius = radius, .label = label, .mark = mark, .stamp = stamp};
    h->count = ps_dijkstra_ball(h->w, &h->g, source, &limits, h->dist, h->reached);
}

static void check_dists(const hand_ball *h, const double *want) {
    for (size_t v = 0; v < HAND_N; v++)
        CHECK_MSG(h->dist[v] == want[v], "dist[%zu] = %g, want %g", v, h->dist[v], want[v]);
}

/* Radius 2 takes vertices 2 and 5, exactly at 2; radius 1.5 does not. */
static void test_ball_radius_is_inclusive(void) {
    hand_ball h;
    REQUIRE(hand_open(&h));
    hand_run(&h, 0, 2.0, NULL, NULL, 0);
    CHECK(h.count == 4);
    check_dists(&h, (const double[HAND_N]){0, 1, 2, INFINITY, INFINITY, 2});
    hand_run(&h, 0, 1.5, NULL, NULL, 0);
    CHECK(h.count == 2 && h.reached[0] == 0 && h.reached[1] == 1);
    check_dists(&h, (const double[HAND_N]){0, 1, INFINITY, INFINITY, INFINITY, INFINITY});
    ps_dijkstra_free(h.w);
}

/* Vertex 1 is in label 1, not stamped: the run goes round by 5. */
static void test_ball_region(void) {
    hand_ball h;
    REQUIRE(hand_open(&h));
    const uint32_t label[HAND_N] = {0, 1, 0, 0, 0, 2}, mark[3] = {7, 3, 7};
    hand_run(&h, 0, INFINITY, label, mark, 7);
    CHECK(h.count == 5);
    check_dists(&h, (const double[HAND_N]){0, INFINITY, 4, 5, 6, 2});
    hand_run(&h, 0, 4.0, label, mark, 7);
    CHECK(h.count == 3);
    check_dists(&h, (const double[HAND_N]){0, INFINITY, 4, INFINITY, INFINITY, 2});
    ps_dijkstra_free(h.w);
}

/* Settling order from 3 within 2.5: 3, then 2 and 4 (1 each, in either
 * order), then 1 (2); 5 and 0 (3) are beyond. */
static void test_ball_reached_list(void) {
    hand_ball h;
    REQUIRE(hand_open(&h));
    hand_run(&h, 3, 2.5, NULL, NULL, 0);
    REQUIRE(h.count == 4);
    const uint32_t *r = h.reached;
    CHECK(r[0] == 3 && r[3] == 1);
    CHECK((r[1] == 2 && r[2] == 4) || (r[1] == 4 && r[2] == 2));
    hand_reset(&h);
    for (size_t v = 0; v < HAND_N; v++) CHECK(isinf(h.dist[v])); /* the list named all it set */
    double full[HAND_N];
    uint32_t source = 3;
    ps_dijkstra_run(h.w, &h.g, &source, 1, full, NULL); /* the workspace is ready again */
    CHECK(full[0] == 3 && full[5] == 3);
    ps_dijkstra_free(h.w);
}

/* A tracked multi-source run gives the untracked run's distances and
 * owners and reports rising progress over its span, ending at its end. */
static void test_tracked_run_same_answer(void) {
    size_t n;
    double *pts = ps_shape_sphere(3000.0, &n, NULL);
    ps_graph g;
    REQUIRE(pts && n > 2 * 16384 && ps_knn_graph_build(pts, n, 3, 7, 2, &g, NULL) == PS_OK);
    const uint32_t sources[] = {0, 17, 4242, (uint32_t)n - 1};
    double *d1 = malloc(n * sizeof *d1), *d2 = malloc(n * sizeof *d2);
    int *o1 = malloc(n * sizeof *o1), *o2 = malloc(n * sizeof *o2);
    ps_dijkstra *w = ps_dijkstra_new(n);
    REQUIRE(d1 && d2 && o1 && o2 && w);
    ps_progress_seen seen = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &seen};
    ps_progress_span span = {&ctl, PS_PHASE_CENTRALITY, 0.2, 0.4};
    ps_dijkstra_run(w, &g, sources, 4, d1, o1);
    ps_dijkstra_run_tracked(w, &g, sources, 4, d2, o2, &span);
    CHECK(memcmp(d1, d2, n * sizeof *d1) == 0 && memcmp(o1, o2, n * sizeof *o1) == 0);
    CHECK_MSG(seen.inside[PS_PHASE_CENTRALITY] >= 2 && !seen.went_back &&
                  seen.last[PS_PHASE_CENTRALITY] == 0.4,
              "%d reports inside, last %g", seen.inside[PS_PHASE_CENTRALITY],
              seen.last[PS_PHASE_CENTRALITY]);
    ps_dijkstra_free(w);
    ps_graph_free(&g);
    free(pts), free(d1), free(d2), free(o1), free(o2);
}

PS_TEST_MAIN(TEST(test_single_source_and_ball), TEST(test_multi_source_owner),
             TEST(test_lower_is_min_of_runs),
             TEST(test_ball_radius_is_inclusive), TEST(test_ball_region),
             TEST(test_ball_reached_list), TEST(test_ball_from_sources_between_points),
             TEST(test_tracked_run_same_answer))
