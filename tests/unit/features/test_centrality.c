/* test_centrality.c: exact centrality has the path graph's closed form,
 * approx (full Dijkstras and the two-level scheme) is close to exact on the
 * shapes (RMS of normalized f < 0.08), all are bit-identical for any thread
 * count, cancel / progress behave, the default sample count is
 * ceil(sqrt(n)) up to its cap, and borrowing the graph changes nothing. */
#include "features/centrality.h"
#include "graph/knn_graph.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Paths 0..a-1 and a..n-1 with unit edges, and an isolated last vertex. */
static void two_paths(size_t a, size_t n, ps_graph *g) {
    g->n = n;
    g->offsets = malloc((n + 1) * sizeof *g->offsets);
    g->neighbors = malloc(2 * n * sizeof *g->neighbors);
    g->weights = malloc(2 * n * sizeof *g->weights);
    size_t m = 0;
    for (size_t p = 0; p < n; p++) {
        g->offsets[p] = m;
        int last = p == n - 1;
        if (p != 0 && p != a && !last) g->neighbors[m] = (uint32_t)p - 1, g->weights[m++] = 1.0;
        if (p + 1 != a && p + 2 < n) g->neighbors[m] = (uint32_t)p + 1, g->weights[m++] = 1.0;
    }
    g->offsets[n] = m;
}

/* The centrality input on two_paths's g, with the default threshold. */
static ps_centrality_input paths_input(const ps_graph *g, const int *comp,
                                       ps_centrality_mode mode, int samples, int threads) {
    return (ps_centrality_input){.graph = g, .component = comp, .n_components = 3,
                                 .mode = mode, .samples = samples, .threads = threads,
                                 .coarse_min = PS_COARSE_MIN_POINTS};
}

/* sum_j |i - j| / len on a path of len vertices */
static double path_mean(size_t i, size_t len) {
    double left = (double)i * (double)(i + 1) / 2.0;
    double right = (double)(len - 1 - i) * (double)(len - i) / 2.0;
    return (left + right) / (double)len;
}

static void test_exact_path_closed_form(void) {
    size_t a = 30, n = 51;
    ps_graph g;
    two_paths(a, n, &g);
    int comp[51];
    REQUIRE(ps_graph_components(&g, comp) == 3);
    double f[51];
    int used = -1;
    uint32_t *ids = (uint32_t *)1;
    ps_centrality_input in = paths_input(&g, comp, PS_CENTRALITY_EXACT, 0, 2);
    REQUIRE(ps_centrality(&in, f, &ids, &used, NULL) == PS_OK);
    CHECK(used == 0 && ids == NULL);
    for (size_t i = 0; i < a; i++) CHECK_NEAR(f[i], path_mean(i, a), 1e-12);
    for (size_t i = a; i < n - 1; i++) CHECK_NEAR(f[i], path_mean(i - a, n - 1 - a), 1e-12);
    CHECK(f[n - 1] == 0.0);
    ps_graph_free(&g);
}

/* With as many samples as points, approx samples every vertex: it is exact. */
static void test_approx_all_samples_is_exact(void) {
    size_t a = 30, n = 51;
    ps_graph g;
    two_paths(a, n, &g);
    int comp[51];
    ps_graph_components(&g, comp);
    double f[51];
    int used = 0;
    uint32_t *ids = NULL;
    ps_centrality_input in = paths_input(&g, comp, PS_CENTRALITY_APPROX, 51, 3);
    REQUIRE(ps_centrality(&in, f, &ids, &used, NULL) == PS_OK);
    CHECK(used == 51);
    REQUIRE(ids);
    CHECK(ids[0] == 0 && ids[1] == a - 1); /* lowest vertex, then the far end */
    CHECK(ids[a] == a && ids[n - 1] == n - 1);
    for (size_t i = 0; i < a; i++) CHECK_NEAR(f[i], path_mean(i, a), 1e-9);
    for (size_t i = a; i < n - 1; i++) CHECK_NEAR(f[i], path_mean(i - a, n - 1 - a), 1e-9);
    CHECK(f[n - 1] == 0.0);
    free(ids);
    ps_graph_free(&g);
}

typedef struct shape_graph {
    size_t n;
    ps_graph g;
    int *comp;
    int n_comp;
} shape_graph;

static int shape_graph_make(double *pts, size_t n, shape_graph *s) {
    s->n = n;
    s->comp = malloc(n * sizeof *s->comp);
    int ok = pts && s->comp && ps_knn_graph_build(pts, n, 3, 7, 2, &s->g, NULL) == PS_OK;
    if (ok) s->n_comp = ps_graph_components(&s->g, s->comp);
    free(pts);
    return ok;
}

static void shape_graph_free(shape_graph *s) {
    ps_graph_free(&s->g);
    free(s->comp);
}

/* The centrality input on s, on 2 threads without a control. */
static ps_centrality_input shape_input(const shape_graph *s, ps_centrality_mode mode,
                                       int samples, size_t coarse_min) {
    return (ps_centrality_input){.graph = &s->g, .component = s->comp,
                                 .n_components = s->n_comp, .mode = mode, .samples = samples,
                                 .threads = 2, .coarse_min = coarse_min};
}

/* RMS difference of f and h, each normalized to [0, 1] per component. */
static double normalized_rms(const shape_graph *s, const double *f, const double *h) {
    double lo[2][64], hi[2][64], sq = 0.0;
    for (int c = 0; c < s->n_comp && c < 64; c++) lo[0][c] = lo[1][c] = INFINITY, hi[0][c] = hi[1][c] = -INFINITY;
    for (size_t v = 0; v < s->n; v++) {
        int c = s->comp[v];
        lo[0][c] = fmin(lo[0][c], f[v]), hi[0][c] = fmax(hi[0][c], f[v]);
        lo[1][c] = fmin(lo[1][c], h[v]), hi[1][c] = fmax(hi[1][c], h[v]);
    }
    for (size_t v = 0; v < s->n; v++) {
        int c = s->comp[v];
        double a = (f[v] - lo[0][c]) / (hi[0][c] - lo[0][c]);
        double b = (h[v] - lo[1][c]) / (hi[1][c] - lo[1][c]);
        sq += (a - b) * (a - b);
    }
    return sqrt(sq / (double)s->n);
}

static void check_approx_close(double *pts, size_t n, size_t coarse_min, const char *name) {
    shape_graph s;
    REQUIRE(shape_graph_make(pts, n, &s));
    REQUIRE(s.n_comp < 64);
    double *exact = malloc(n * sizeof *exact), *approx = malloc(n * sizeof *approx);
    REQUIRE(exact && approx);
    int used = 0;
    ps_centrality_input in = shape_input(&s, PS_CENTRALITY_EXACT, 0, PS_COARSE_MIN_POINTS);
    REQUIRE(ps_centrality(&in, exact, NULL, NULL, NULL) == PS_OK);
    uint32_t *ids = NULL;
    in = shape_input(&s, PS_CENTRALITY_APPROX, 0, coarse_min);
    REQUIRE(ps_centrality(&in, approx, &ids, &used, NULL) == PS_OK);
    CHECK(used >= (int)ceil(sqrt((double)n)) && used <= (int)ceil(sqrt((double)n)) + s.n_comp);
    CHECK(ids && ids[0] == 0); /* the first component's lowest vertex */
    double rms = normalized_rms(&s, exact, approx);
    CHECK_MSG(rms < 0.08, "%s (coarse from %zu): RMS of normalized approx - exact = %g", name,
              coarse_min, rms);
    free(ids);
    free(exact), free(approx);
    shape_graph_free(&s);
}

static void check_shapes_close(size_t coarse_min) {
    size_t n;
    double *p = ps_shape_dumbbell(0.0, &n, NULL);
    check_approx_close(p, n, coarse_min, "dumbbell");
    p = ps_shape_star(0.0, &n, NULL);
    check_approx_close(p, n, coarse_min, "star");
    p = ps_shape_hand(40.0, &n, NULL);
    check_approx_close(p, n, coarse_min, "hand");
}

static void test_approx_close_to_exact(void) { check_shapes_close(SIZE_MAX); }
static void test_two_level_close_to_exact(void) { check_shapes_close(0); }

static void check_threads_identical(ps_centrality_mode mode, size_t coarse_min) {
    size_t n;
    shape_graph s;
    double *pts = ps_shape_hand(30.0, &n, NULL);
    REQUIRE(shape_graph_make(pts, n, &s));
    double *f[3];
    ps_centrality_input in = shape_input(&s, mode, 50, coarse_min);
    for (int t = 0; t < 3; t++) {
        f[t] = malloc(n * sizeof *f[t]);
        REQUIRE(f[t]);
        in.threads = t + 1;
        REQUIRE(ps_centrality(&in, f[t], NULL, NULL, NULL) == PS_OK);
    }
    CHECK(memcmp(f[0], f[1], n * sizeof *f[0]) == 0);
    CHECK(memcmp(f[0], f[2], n * sizeof *f[0]) == 0);
    CHECK(f[0][0] > 0.0);
    for (int t = 0; t < 3; t++) free(f[t]);
    shape_graph_free(&s);
}

static void test_threads_identical_exact(void) {
    check_threads_identical(PS_CENTRALITY_EXACT, 0);
}
static void test_threads_identical_approx(void) {
    check_threads_identical(PS_CENTRALITY_APPROX, SIZE_MAX);
}
static void test_threads_identical_two_level(void) {
    check_threads_identical(PS_CENTRALITY_APPROX, 0);
}

typedef struct progress_log {
    int calls, monotone, wrong_phase;
    double first, last;
    volatile int *cancel_on_call; /* raised by the first report: it comes before
                                     the runs, so cancelling never races them */
} progress_log;

static void on_progress(void *user, ps_phase phase, double fraction) {
    progress_log *log = user;
    if (log->calls++ == 0) log->first = fraction;
    log->wrong_phase += phase != PS_PHASE_CENTRALITY;
    if (fraction < log->last || fraction > 1.0) log->monotone = 0;
    log->last = fraction;
    if (log->cancel_on_call) *log->cancel_on_call = 1;
}

static void check_progress_and_cancel(ps_centrality_mode mode, size_t coarse_min) {
    size_t n;
    shape_graph s;
    double *pts = ps_shape_star(20.0, &n, NULL);
    REQUIRE(shape_graph_make(pts, n, &s));
    double *f = malloc(n * sizeof *f);
    REQUIRE(f);
    ps_centrality_input in = shape_input(&s, mode, 40, coarse_min);
    for (int threads = 1; threads <= 2; threads++) {
        progress_log log = {0, 1, 0, 0.0, 0.0, NULL};
        ps_control ctl = {on_progress, &log, NULL};
        in.threads = threads, in.ctl = &ctl;
        REQUIRE(ps_centrality(&in, f, NULL, NULL, NULL) == PS_OK);
        CHECK(log.calls > 10 && log.monotone && log.wrong_phase == 0 && log.last == 1.0);
        /* where progress starts is pinned on one thread only: with two, the
         * other worker may run many items before the reporting one ends
         * its first */
        if (threads == 1) CHECK_MSG(log.first < 0.05, "first report %g", log.first);
    }

    volatile int cancel = 0;
    progress_log stop = {0, 1, 0, 0.0, 0.0, &cancel};
    ps_control cctl = {on_progress, &stop, &cancel};
    ps_error err = {0};
    in.threads = 2, in.ctl = &cctl;
    CHECK(ps_centrality(&in, f, NULL, NULL, &err) == PS_ERR_CANCELLED);
    CHECK(err.status == PS_ERR_CANCELLED && stop.last < 1.0);
    free(f);
    shape_graph_free(&s);
}

static void test_progress_and_cancel(void) {
    check_progress_and_cancel(PS_CENTRALITY_EXACT, SIZE_MAX);
    check_progress_and_cancel(PS_CENTRALITY_APPROX, SIZE_MAX);
}

static void test_progress_and_cancel_two_level(void) {
    check_progress_and_cancel(PS_CENTRALITY_APPROX, 0);
}

/* Above the default threshold, PS_COARSE_MIN_POINTS, approx takes the
 * two-level path. */
static void test_default_threshold(void) {
    size_t n;
    shape_graph s;
    double *pts = ps_shape_hand(450.0, &n, NULL);
    REQUIRE(n >= PS_COARSE_MIN_POINTS);
    REQUIRE(shape_graph_make(pts, n, &s));
    double *f = malloc(n * sizeof *f), *h = malloc(n * sizeof *h);
    REQUIRE(f && h);
    ps_centrality_input in = shape_input(&s, PS_CENTRALITY_APPROX, 0, PS_COARSE_MIN_POINTS);
    REQUIRE(ps_centrality(&in, f, NULL, NULL, NULL) == PS_OK);
    in.coarse_min = 0;
    REQUIRE(ps_centrality(&in, h, NULL, NULL, NULL) == PS_OK);
    CHECK(memcmp(f, h, n * sizeof *f) == 0);
    free(f), free(h);
    shape_graph_free(&s);
}

static void test_default_samples_capped(void) {
    CHECK(ps_centrality_default_samples(100) == 10);
    CHECK(ps_centrality_default_samples(48485) == 221); /* the horse */
    CHECK(ps_centrality_default_samples(262144) == 512);
    CHECK(ps_centrality_default_samples(262145) == PS_MAX_DEFAULT_SAMPLES);
    CHECK(ps_centrality_default_samples(10000000) == PS_MAX_DEFAULT_SAMPLES);
}

/* Borrowing the graph gives the same f, bit for bit, as a copy does (the
 * two-level scheme on a star over PS_COARSE_MIN_POINTS), and the graph
 * comes back with every byte as it was; in->graph is not read. */
static void test_borrowing_same_f_and_graph(void) {
    size_t n;
    double *pts = ps_shape_star(780.0, &n, NULL);
    ps_graph g, kept;
    REQUIRE(pts && n >= PS_COARSE_MIN_POINTS);
    REQUIRE(ps_knn_graph_build(pts, n, 3, 7, 2, &g, NULL) == PS_OK);
    REQUIRE(ps_knn_graph_build(pts, n, 3, 7, 2, &kept, NULL) == PS_OK);
    int *comp = malloc(n * sizeof *comp);
    double *copied = malloc(n * sizeof *copied), *borrowed = malloc(n * sizeof *borrowed);
    REQUIRE(comp && copied && borrowed);
    int nc = ps_graph_components(&g, comp);
    ps_centrality_input in = {.graph = &kept, .component = comp, .n_components = nc,
                              .mode = PS_CENTRALITY_APPROX, .threads = 2,
                              .coarse_min = PS_COARSE_MIN_POINTS};
    REQUIRE(ps_centrality(&in, copied, NULL, NULL, NULL) == PS_OK);
    in.graph = NULL; /* not read: the graph is the borrowed one */
    REQUIRE(ps_centrality_borrowing(&in, &g, borrowed, NULL, NULL, NULL) == PS_OK);
    CHECK(memcmp(copied, borrowed, n * sizeof *copied) == 0);
    size_t edges = kept.offsets[n];
    CHECK(g.n == n && g.offsets[n] == edges &&
          !memcmp(g.offsets, kept.offsets, (n + 1) * sizeof *g.offsets) &&
          !memcmp(g.neighbors, kept.neighbors, edges * sizeof *g.neighbors) &&
          !memcmp(g.weights, kept.weights, edges * sizeof *g.weights));
    ps_graph_free(&g), ps_graph_free(&kept);
    free(pts), free(comp), free(copied), free(borrowed);
}

PS_TEST_MAIN(TEST(test_exact_path_closed_form), TEST(test_approx_all_samples_is_exact),
             TEST(test_approx_close_to_exact), TEST(test_two_level_close_to_exact),
             TEST(test_threads_identical_exact), TEST(test_threads_identical_approx),
             TEST(test_threads_identical_two_level), TEST(test_progress_and_cancel),
             TEST(test_progress_and_cancel_two_level), TEST(test_default_threshold),
             TEST(test_borrowing_same_f_and_graph),
             TEST(test_default_samples_capped))
