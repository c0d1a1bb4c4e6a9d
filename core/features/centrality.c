/*
 * centrality.c: f(p) = mean geodesic distance to the points of p's
 * component (centrality.h), exact or from farthest-point samples.
 *
 * exact:  one Dijkstra per vertex in parallel; each run sums its own row in
 *         vertex order, so f does not depend on which worker ran it.
 * approx: per component, farthest-point sampling with the pruned
 *         ps_dijkstra_lower (sequential, cheap), then full Dijkstras from all
 *         samples in parallel.  Each worker adds quantized distances
 *         (64-bit fixed point, one scale per component, chosen so no sum can
 *         overflow) into its own array; the integer sums are exact, hence
 *         identical for any thread count.
 * approx from PS_COARSE_MIN_POINTS vertices on: centrality_coarse.c.
 * All run on a breadth-first relabelled copy of the graph (bfs_order.h):
 * the Dijkstras touch memory in order and each component is one range.
 */
#include "features/centrality.h"

#include "features/centrality_coarse.h"
#include "graph/bfs_order.h"
#include "graph/dijkstra.h"
#include "util/control.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>

#define FIXED_POINT_RANGE 1125899906842624.0 /* 2^50: bound on a vertex's sum */
#define FPS_SHARE 0.25                      /* progress share of the sampling */

typedef struct workers {
    int count;
    ps_dijkstra **dijkstra; /* #count */
    double **dist;          /* #count by #P */
    int64_t **sums;         /* #count by #P (approx only) */
} workers;

typedef struct run_ctx {
    const ps_bfs_order *o;
    workers *w;
    const uint32_t *sources;   /* approx: the samples (new ids); exact: NULL */
    const double *scale;       /* approx: #components fixed-point scales */
    const int *component;      /* #P component of each old id */
    double *f;                 /* exact: #P out (old ids) */
    const ps_control *ctl;
} run_ctx;

static void report(const ps_control *ctl, double fraction) {
    ps_control_progress(ctl, PS_PHASE_CENTRALITY, fraction);
}

static void workers_free(workers *w) {
    for (int i = 0; i < w->count; i++) {
        if (w->dijkstra) ps_dijkstra_free(w->dijkstra[i]);
        if (w->dist) free(w->dist[i]);
        if (w->sums) free(w->sums[i]);
    }
    free(w->dijkstra), free(w->dist), free(w->sums);
}

static ps_status workers_build(size_t n, int count, int with_sums, workers *w) {
    w->count = count;
    w->dijkstra = calloc((size_t)count, sizeof *w->dijkstra);
    w->dist = calloc((size_t)count, sizeof *w->dist);
    w->sums = with_sums ? calloc((size_t)count, sizeof *w->sums) : NULL;
    if (!w->dijkstra || !w->dist || (with_sums && !w->sums)) return PS_ERR_NOMEM;
    size_t alloc_n = n ? n : 1;
    for (int i = 0; i < count; i++) {
        w->dijkstra[i] = ps_dijkstra_new(n);
        w->dist[i] = malloc(alloc_n * sizeof *w->dist[i]);
        if (with_sums) w->sums[i] = calloc(alloc_n, sizeof *w->sums[i]);
        if (!w->dijkstra[i] || !w->dist[i] || (with_sums && !w->sums[i])) return PS_ERR_NOMEM;
    }
    return PS_OK;
}

/* f of vertex s (new id) from a Dijkstra from it. */
static void exact_run(void *ctx, size_t s, int worker) {
    run_ctx *r = ctx;
    const ps_bfs_order *o = r->o;
    double *dist = r->w->dist[worker];
    uint32_t source = (uint32_t)s;
    ps_dijkstra_run(r->w->dijkstra[worker], &o->g, &source, 1, dist, NULL);
    int c = r->component[o->old_of[s]];
    double sum = 0.0;
    for (size_t v = o->start[c]; v < o->start[c + 1]; v++) sum += dist[v];
    r->f[o->old_of[s]] = sum / (double)(o->start[c + 1] - o->start[c]);
}

/* Sample s's quantized distances added into the worker's sums. */
static void sample_run(void *ctx, size_t s, int worker) {
    run_ctx *r = ctx;
    const ps_bfs_order *o = r->o;
    double *dist = r->w->dist[worker];
    int64_t *sums = r->w->sums[worker];
    uint32_t source = r->sources[s];
    ps_dijkstra_run(r->w->dijkstra[worker], &o->g, &source, 1, dist, NULL);
    int c = r->component[o->old_of[source]];
    double scale = r->scale[c];
    for (size_t v = o->start[c]; v < o->start[c + 1]; v++) sums[v] += llround(dist[v] * scale);
}

/* Samples per component: round(S * size / n), at least 1, at most size. */
int ps_centrality_default_samples(size_t n) {
    double s = ceil(sqrt((double)n));
    return s < PS_MAX_DEFAULT_SAMPLES ? (int)s : PS_MAX_DEFAULT_SAMPLES;
}

static size_t share_of(size_t samples, size_t size, size_t n) {
    size_t s = (size_t)llround((double)samples * (double)size / (double)n);
    if (s < 1) s = 1;
    return s > size ? size : s;
}

/* The vertex of component c farthest from the samples (ties: lowest old id). */
static uint32_t farthest_member(const ps_bfs_order *o, int c, const double *mind) {
    uint32_t best = (uint32_t)o->start[c];
    for (size_t v = o->start[c]; v < o->start[c + 1]; v++)
        if (mind[v] > mind[best] || (mind[v] == mind[best] && o->old_of[v] < o->old_of[best]))
            best = (uint32_t)v;
    return best;
}

typedef struct sampling {
    uint32_t *ids;    /* #total samples (new ids), component by component */
    size_t total;
    double *scale;    /* #components fixed-point scale */
    size_t *count;    /* #components samples in each */
} sampling;

static void sampling_free(sampling *s) {
    free(s->ids), free(s->scale), free(s->count);
}

/* Farthest-point sampling of every component; mind #P scratch. */
static ps_status choose_samples(const ps_bfs_order *o, size_t samples, ps_dijkstra *dij,
                                double *mind, const ps_control *ctl, sampling *s) {
    int count = o->n_components;
    s->scale = malloc((size_t)count * sizeof *s->scale);
    s->count = malloc((size_t)count * sizeof *s->count);
    if (!s->scale || !s->count) return PS_ERR_NOMEM;
    s->total = 0;
    for (int c = 0; c < count; c++) {
        s->count[c] = share_of(samples, o->start[c + 1] - o->start[c], o->g.n);
        s->total += s->count[c];
    }
    s->ids = malloc(s->total * sizeof *s->ids);
    if (!s->ids) return PS_ERR_NOMEM;
    for (size_t v = 0; v < o->g.n; v++) mind[v] = INFINITY;
    size_t chosen = 0;
    for (int c = 0; c < count; c++) {
        double bound = 0.0;
        for (size_t i = 0; i < s->count[c]; i++) {
            if (ps_control_cancelled(ctl)) return PS_ERR_CANCELLED;
            uint32_t v = i == 0 ? (uint32_t)o->start[c] : farthest_member(o, c, mind);
            ps_dijkstra_lower(dij, &o->g, v, mind);
            /* After the first run mind holds distances from one vertex; twice
             * its eccentricity bounds every distance in the component. */
            if (i == 0) bound = 2.0 * mind[farthest_member(o, c, mind)];
            s->ids[chosen++] = v;
            report(ctl, FPS_SHARE * (double)chosen / (double)s->total);
        }
        s->scale[c] = bound > 0.0 ? FIXED_POINT_RANGE / (bound * (double)s->count[c]) : 1.0;
    }
    return PS_OK;
}

static void fixed_point_means(const ps_bfs_order *o, const sampling *s, const workers *w,
                              double *f) {
    for (int c = 0; c < o->n_components; c++)
        for (size_t v = o->start[c]; v < o->start[c + 1]; v++) {
            int64_t total = 0;
            for (int k = 0; k < w->count; k++) total += w->sums[k][v];
            f[o->old_of[v]] = (double)total / s->scale[c] / (double)s->count[c];
        }
}

/* fn for runs [0, count), progress from lo to 1. */
static ps_status run_parallel(run_ctx *r, int threads, size_t count, ps_item_fn fn, double lo) {
    ps_progress_span span = {r->ctl, PS_PHASE_CENTRALITY, lo, 1.0};
    return ps_parallel_for_tracked(threads, count, 1, fn, r, &span);
}

static ps_status approx_centrality(run_ctx *r, size_t samples, sampling *s) {
    workers *w = r->w;
    ps_status st = choose_samples(r->o, samples, w->dijkstra[0], w->dist[0], r->ctl, s);
    if (st != PS_OK) return st;
    r->sources = s->ids;
    r->scale = s->scale;
    st = run_parallel(r, w->count, s->total, sample_run, FPS_SHARE);
    if (st == PS_OK) fixed_point_means(r->o, s, w, r->f);
    return st;
}

/* Sample ids back to old ids, handed to the caller. */
static void give_samples(const ps_bfs_order *o, sampling *s, uint32_t **sample_ids,
                         int *samples_used) {
    for (size_t i = 0; i < s->total; i++) s->ids[i] = o->old_of[s->ids[i]];
    if (samples_used) *samples_used = (int)s->total;
    if (sample_ids) *sample_ids = s->ids, s->ids = NULL;
}

static ps_status fail_status(ps_status st, ps_error *err) {
    if (st == PS_ERR_NOMEM) return ps_fail(err, st, "centrality: out of memory");
    return ps_fail(err, st, "centrality: cancelled");
}

/* The two-level scheme of centrality_coarse.h. */
static ps_status coarse_centrality(const ps_bfs_order *o, size_t samples, int threads,
                                   const ps_control *ctl, double *f, uint32_t **sample_ids,
                                   int *samples_used, ps_error *err) {
    uint32_t *ids = NULL;
    size_t used = 0;
    ps_status st = ps_centrality_coarse(o, samples, threads, ctl, f, &ids, &used, err);
    if (st == PS_OK && samples_used) *samples_used = (int)used;
    if (st == PS_OK && sample_ids) *sample_ids = ids;
    else free(ids);
    return st;
}

/* Exact, or approx from full Dijkstras (fine level only). */
static ps_status fine_centrality(const ps_bfs_order *o, const int *component, int exact,
                                 size_t samples, int threads, const ps_control *ctl, double *f,
                                 uint32_t **sample_ids, int *samples_used, ps_error *err) {
    workers w = {0};
    sampling s = {0};
    run_ctx r = {.o = o, .w = &w, .component = component, .f = f, .ctl = ctl};
    ps_status st = workers_build(o->g.n, ps_parallel_threads(threads), !exact, &w);
    if (st == PS_OK && exact) st = run_parallel(&r, w.count, o->g.n, exact_run, 0.0);
    else if (st == PS_OK) st = approx_centrality(&r, samples, &s);
    if (st == PS_OK && !exact) give_samples(o, &s, sample_ids, samples_used);
    sampling_free(&s);
    workers_free(&w);
    return st == PS_OK ? PS_OK : fail_status(st, err);
}

static ps_status check_mode(ps_centrality_mode mode, int samples, uint32_t **sample_ids,
                            int *samples_used, ps_error *err) {
    if (sample_ids) *sample_ids = NULL;
    if (samples_used) *samples_used = 0;
    if (mode != PS_CENTRALITY_EXACT && mode != PS_CENTRALITY_APPROX)
        return ps_fail(err, PS_ERR_INVALID, "centrality: mode must be exact or approx");
    if (samples < 0) return ps_fail(err, PS_ERR_INVALID, "centrality: samples %d < 0", samples);
    return PS_OK;
}

/* f on the breadth-first order o of in->graph (which it does not read). */
static ps_status centrality_on(const ps_bfs_order *o, const ps_centrality_input *in, double *f,
                               uint32_t **sample_ids, int *samples_used, ps_error *err) {
    if (o->n_components != in->n_components)
        return ps_fail(err, PS_ERR_INVALID, "centrality: %d components given, the graph has %d",
                       in->n_components, o->n_components);
    int exact = in->mode == PS_CENTRALITY_EXACT;
    size_t count = in->samples ? (size_t)in->samples
                               : (size_t)ps_centrality_default_samples(o->g.n);
    if (!exact && o->g.n >= in->coarse_min)
        return coarse_centrality(o, count, in->threads, in->ctl, f, sample_ids, samples_used,
                                 err);
    return fine_centrality(o, in->component, exact, count, in->threads, in->ctl, f, sample_ids,
                           samples_used, err);
}

ps_status ps_centrality(const ps_centrality_input *in, double *f, uint32_t **sample_ids,
                        int *samples_used, ps_error *err) {
    ps_status st = check_mode(in->mode, in->samples, sample_ids, samples_used, err);
    if (st != PS_OK || in->graph->n == 0) return st;
    ps_bfs_order o;
    st = ps_bfs_order_build(in->graph, &o, err);
    if (st != PS_OK) return st;
    st = centrality_on(&o, in, f, sample_ids, samples_used, err);
    ps_bfs_order_free(&o);
    return st;
}

ps_status ps_centrality_borrowing(const ps_centrality_input *in, ps_graph *g, double *f,
                                  uint32_t **sample_ids, int *samples_used, ps_error *err) {
    ps_status st = check_mode(in->mode, in->samples, sample_ids, samples_used, err);
    if (st != PS_OK || g->n == 0) return st;
    ps_bfs_order o;
    st = ps_bfs_order_take(g, in->threads, &o, err);
    if (st != PS_OK) return st;
    st = centrality_on(&o, in, f, sample_ids, samples_used, err);
    ps_error back_err;
    ps_status back = ps_bfs_order_give_back(&o, in->threads, g, &back_err);
    if (st == PS_OK && back != PS_OK) {
        st = back;
        if (err) *err = back_err;
    }
    return st;
}
