/*
 * centrality_coarse.c: the two-level approximate centrality
 * (centrality_coarse.h).
 *
 * D is one block per component: a row per cell of the component, its
 * samples contiguous, the row length rounded up to LANES floats (padding
 * 0).  Coarse searches (Dial's, dial.h: the seeds are more than a cell
 * radius apart) run in parallel, BLOCK samples per task: a task
 * gathers its columns in a worker buffer and writes them row by row.
 * The fine level loops over vertices (outer, parallel) and samples (inner,
 * LANES at a time, a loop gcc and clang vectorize at -O2 with SSE2); the
 * sum over samples is in double with LANES partial sums in a fixed order.
 * Last, SMOOTH_STEPS Jacobi rounds replace f(p) by the mean of f over p and
 * its graph neighbours (two buffers: the order of workers does not matter).
 */
#include "features/centrality_coarse.h"

#include "features/coarse_graph.h"
#include "graph/dial.h"
#include "util/control.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>

#define LANES 8            /* floats per step of the inner loops */
#define BLOCK 16           /* samples per coarse Dijkstra task */
#define FINE_CHUNK 256     /* vertices per fine-level task */
#ifndef SMOOTH_STEPS
#define SMOOTH_STEPS 5     /* neighbour-averaging steps on f (-D to tune) */
#endif
#define BUILD_SHARE 0.3    /* progress after the coarse graph */
#define SAMPLES_SHARE 0.35 /* ... after the sampling */
#define COARSE_SHARE 0.6   /* ... after the coarse Dijkstras */

typedef struct table {
    size_t *first;     /* #components+1: samples of component k are
                          cells[first[k] .. first[k+1]) */
    uint32_t *cells;   /* #S sample cells */
    size_t *stride;    /* #components row length of component k's block */
    size_t *base;      /* #components+1 offset of component k's block in d */
    float *d;          /* D: cell rows, see the top comment */
} table;

typedef struct two_level {
    const ps_bfs_order *o;
    const ps_coarse_graph *cg;
    table t;
    size_t *task_first;  /* #tasks+1: coarse tasks as sample indices */
    const ps_control *ctl;
    double *f;           /* #P out, old ids */
    double *fine;        /* #P f in new ids, then smoothed */
    double *spare;       /* #P the smoothing's other buffer */
} two_level;

static void report(const ps_control *ctl, double fraction) {
    ps_control_progress(ctl, PS_PHASE_CENTRALITY, fraction);
}

/* fn(ctx, item, worker) for items [0, count), one per hand-out, with
 * progress from lo to hi. */
static ps_status run_parallel(const two_level *x, int threads, size_t count, ps_item_fn fn,
                              void *ctx, double lo, double hi) {
    ps_progress_span span = {x->ctl, PS_PHASE_CENTRALITY, lo, hi};
    return ps_parallel_for_tracked(threads, count, 1, fn, ctx, &span);
}

static void table_free(table *t) {
    free(t->first), free(t->cells), free(t->stride), free(t->base), free(t->d);
}

/* ---- samples on the coarse graph ----------------------------------------- */

/* Samples of component k: round(S * size / n), at least 1, at most its cells. */
static size_t share_of(size_t samples, size_t size, size_t n, size_t cells) {
    size_t s = (size_t)llround((double)samples * (double)size / (double)n);
    if (s < 1) s = 1;
    return s > cells ? cells : s;
}

/* The cell of [begin, end) farthest from the samples (ties: lowest). */
static uint32_t farthest_cell(size_t begin, size_t end, const double *mind) {
    size_t best = begin;
    for (size_t c = begin; c < end; c++)
        if (mind[c] > mind[best]) best = c;
    return (uint32_t)best;
}

static ps_status table_layout(const ps_bfs_order *o, const ps_coarse_graph *cg, size_t samples,
                              table *t) {
    size_t count = (size_t)o->n_components;
    t->first = malloc((count + 1) * sizeof *t->first);
    t->stride = malloc(count * sizeof *t->stride);
    t->base = malloc((count + 1) * sizeof *t->base);
    if (!t->first || !t->stride || !t->base) return PS_ERR_NOMEM;
    t->first[0] = t->base[0] = 0;
    for (size_t k = 0; k < count; k++) {
        size_t cells = cg->cell_start[k + 1] - cg->cell_start[k];
        size_t s = share_of(samples, o->start[k + 1] - o->start[k], o->g.n, cells);
        t->first[k + 1] = t->first[k] + s;
        t->stride[k] = (s + LANES - 1) / LANES * LANES;
        t->base[k + 1] = t->base[k] + cells * t->stride[k];
    }
    t->cells = malloc(t->first[count] * sizeof *t->cells);
    t->d = calloc(t->base[count] ? t->base[count] : 1, sizeof *t->d);
    return t->cells && t->d ? PS_OK : PS_ERR_NOMEM;
}

/* Farthest-point sampling of each component's cells; mind #M scratch. */
static ps_status choose_samples(const ps_coarse_graph *cg, int n_components, ps_dial *dial,
                                double *mind, const ps_control *ctl, table *t) {
    for (size_t c = 0; c < cg->n_cells; c++) mind[c] = INFINITY;
    size_t total = t->first[n_components];
    for (int k = 0; k < n_components; k++) {
        size_t begin = cg->cell_start[k], end = cg->cell_start[k + 1];
        for (size_t i = t->first[k]; i < t->first[k + 1]; i++) {
            if (ps_control_cancelled(ctl)) return PS_ERR_CANCELLED;
            uint32_t c = i == t->first[k] ? (uint32_t)begin : farthest_cell(begin, end, mind);
            ps_dial_lower(dial, c, mind);
            t->cells[i] = c;
            double done = (double)(i + 1) / (double)total;
            report(ctl, BUILD_SHARE + (SAMPLES_SHARE - BUILD_SHARE) * done);
        }
    }
    return PS_OK;
}

/* ---- coarse Dijkstras ------------------------------------------------------ */

typedef struct coarse_worker {
    ps_dial *dial;
    double *dist;    /* #M */
    float *columns;  /* BLOCK by (largest component's cells) */
} coarse_worker;

typedef struct coarse_ctx {
    two_level *x;
    coarse_worker *w;  /* #threads */
} coarse_ctx;

/* The last range k in [0, count) with start[k] <= i (start increasing):
 * the component of a sample (start = table.first) or of a vertex (start =
 * the BFS order's component starts). */
static int range_of(const size_t *start, int count, size_t i) {
    int lo = 0, hi = count - 1;
    while (lo < hi) {
        int mid = lo + (hi - lo + 1) / 2;
        if (start[mid] <= i) lo = mid;
        else hi = mid - 1;
    }
    return lo;
}

static void coarse_block(two_level *x, coarse_worker *w, size_t first, size_t end) {
    const table *t = &x->t;
    const ps_coarse_graph *cg = x->cg;
    int k = range_of(t->first, x->o->n_components, first);
    size_t begin = cg->cell_start[k], cells = cg->cell_start[k + 1] - begin;
    for (size_t i = first; i < end; i++) {
        ps_dial_run(w->dial, t->cells[i], w->dist);
        float *col = w->columns + (i - first) * cells;
        for (size_t c = 0; c < cells; c++) col[c] = (float)w->dist[begin + c];
    }
    size_t stride = t->stride[k], offset = first - t->first[k];
    for (size_t c = 0; c < cells; c++) {
        float *row = t->d + t->base[k] + c * stride + offset;
        for (size_t i = first; i < end; i++) row[i - first] = w->columns[(i - first) * cells + c];
    }
}

static void coarse_task(void *ctx, size_t task, int worker) {
    coarse_ctx *c = ctx;
    two_level *x = c->x;
    coarse_block(x, &c->w[worker], x->task_first[task], x->task_first[task + 1]);
}

/* Tasks: up to BLOCK consecutive samples of one component.  Returns count. */
static size_t make_tasks(const table *t, int n_components, size_t *task_first) {
    size_t count = 0;
    for (int k = 0; k < n_components; k++)
        for (size_t i = t->first[k]; i < t->first[k + 1]; i += BLOCK) task_first[count++] = i;
    task_first[count] = t->first[n_components];
    return count;
}

static void coarse_workers_free(coarse_worker *w, int threads) {
    for (int i = 0; w && i < threads; i++) {
        ps_dial_free(w[i].dial);
        free(w[i].dist), free(w[i].columns);
    }
    free(w);
}

static size_t largest_component_cells(const ps_coarse_graph *cg, int n_components) {
    size_t most = 1;
    for (int k = 0; k < n_components; k++) {
        size_t cells = cg->cell_start[k + 1] - cg->cell_start[k];
        if (cells > most) most = cells;
    }
    return most;
}

static ps_status coarse_distances(two_level *x, int threads) {
    const ps_coarse_graph *cg = x->cg;
    int count = x->o->n_components;
    size_t m = cg->n_cells, widest = largest_component_cells(cg, count);
    coarse_worker *w = calloc((size_t)threads, sizeof *w);
    x->task_first = malloc((x->t.first[count] + (size_t)count + 1) * sizeof *x->task_first);
    ps_status st = w && x->task_first ? PS_OK : PS_ERR_NOMEM;
    for (int i = 0; st == PS_OK && i < threads; i++) {
        w[i].dial = ps_dial_new(&cg->graph);
        w[i].dist = malloc(m * sizeof *w[i].dist);
        w[i].columns = malloc(BLOCK * widest * sizeof *w[i].columns);
        if (!w[i].dial || !w[i].dist || !w[i].columns) st = PS_ERR_NOMEM;
    }
    if (st == PS_OK) {
        coarse_ctx c = {x, w};
        size_t tasks = make_tasks(&x->t, count, x->task_first);
        st = run_parallel(x, threads, tasks, coarse_task, &c, SAMPLES_SHARE, COARSE_SHARE);
    }
    coarse_workers_free(w, threads);
    return st;
}

/* ---- fine level -------------------------------------------------------------- */

typedef struct fine_ctx {
    two_level *x;
    float **scratch;  /* #threads by (largest stride) */
} fine_ctx;

/* m = min(m, row + g), LANES at a time (length a multiple of LANES). */
static void min_add(float *restrict m, const float *restrict row, float g, size_t length) {
    for (size_t i = 0; i < length; i += LANES)
        for (size_t l = 0; l < LANES; l++) {
            float v = row[i + l] + g;
            m[i + l] = v < m[i + l] ? v : m[i + l];
        }
}

static double lane_sum(const float *m, size_t length) {
    double part[LANES] = {0};
    for (size_t i = 0; i < length; i += LANES)
        for (size_t l = 0; l < LANES; l++) part[l] += m[i + l];
    double sum = 0.0;
    for (size_t l = 0; l < LANES; l++) sum += part[l];
    return sum;
}

/* f of vertex p (new id) of component k; m scratch of the stride. */
static double vertex_mean(const two_level *x, uint32_t p, int k, float *m) {
    const ps_coarse_graph *cg = x->cg;
    const table *t = &x->t;
    size_t stride = t->stride[k], count = t->first[k + 1] - t->first[k];
    const float *block = t->d + t->base[k], *g = cg->local + cg->local_offsets[p];
    uint32_t a = cg->cell_of[p];
    for (size_t i = 0; i < stride; i++) m[i] = INFINITY;
    for (size_t j = cg->near_offsets[a]; j < cg->near_offsets[a + 1]; j++) {
        size_t row = cg->near[j] - cg->cell_start[k];
        min_add(m, block + row * stride, g[j - cg->near_offsets[a]], stride);
    }
    for (size_t i = count; i < stride; i++) m[i] = 0.0f;
    return lane_sum(m, stride) / (double)count;
}

/* f of the vertices of one chunk of FINE_CHUNK. */
static void fine_task(void *ctx, size_t chunk, int worker) {
    fine_ctx *c = ctx;
    two_level *x = c->x;
    const ps_bfs_order *o = x->o;
    size_t first = chunk * FINE_CHUNK, last = first + FINE_CHUNK;
    if (last > o->g.n) last = o->g.n;
    int k = range_of(o->start, o->n_components, first);
    for (size_t p = first; p < last; p++) {
        while (o->start[k + 1] <= p) k++;
        x->fine[p] = vertex_mean(x, (uint32_t)p, k, c->scratch[worker]);
    }
}

static ps_status fine_level(two_level *x, int threads) {
    int count = x->o->n_components;
    size_t widest = LANES;
    for (int k = 0; k < count; k++)
        if (x->t.stride[k] > widest) widest = x->t.stride[k];
    float **scratch = calloc((size_t)threads, sizeof *scratch);
    ps_status st = scratch ? PS_OK : PS_ERR_NOMEM;
    for (int i = 0; st == PS_OK && i < threads; i++)
        if (!(scratch[i] = malloc(widest * sizeof *scratch[i]))) st = PS_ERR_NOMEM;
    if (st == PS_OK) {
        fine_ctx c = {x, scratch};
        size_t chunks = (x->o->g.n + FINE_CHUNK - 1) / FINE_CHUNK;
        st = run_parallel(x, threads, chunks, fine_task, &c, COARSE_SHARE, 1.0);
    }
    for (int i = 0; scratch && i < threads; i++) free(scratch[i]);
    free(scratch);
    return st;
}

/* ---- smoothing -------------------------------------------------------------- */

typedef struct smooth_ctx {
    two_level *x;
    const double *in;
    double *out;
} smooth_ctx;

static void smooth_tasks(void *ctx, size_t begin, size_t end, int worker) {
    smooth_ctx *c = ctx;
    const ps_graph *g = &c->x->o->g;
    (void)worker;
    for (size_t chunk = begin; chunk < end; chunk++) {
        size_t first = chunk * FINE_CHUNK, last = first + FINE_CHUNK;
        if (last > g->n) last = g->n;
        for (size_t p = first; p < last; p++) {
            double sum = c->in[p];
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
                sum += c->in[g->neighbors[e]];
            c->out[p] = sum / (double)(g->offsets[p + 1] - g->offsets[p] + 1);
        }
    }
}

static void smooth(two_level *x, int threads) {
    size_t chunks = (x->o->g.n + FINE_CHUNK - 1) / FINE_CHUNK;
    for (int step = 0; step < SMOOTH_STEPS; step++) {
        smooth_ctx c = {x, x->fine, x->spare};
        ps_parallel_for(threads, chunks, 1, smooth_tasks, &c);
        double *t = x->fine;
        x->fine = x->spare, x->spare = t;
    }
    for (size_t p = 0; p < x->o->g.n; p++) x->f[x->o->old_of[p]] = x->fine[p];
}

/* ---- entry ---------------------------------------------------------------------- */

static ps_status sample_and_solve(two_level *x, size_t samples, int threads) {
    const ps_coarse_graph *cg = x->cg;
    ps_status st = table_layout(x->o, cg, samples, &x->t);
    if (st != PS_OK) return st;
    ps_dial *dial = ps_dial_new(&cg->graph);
    double *mind = malloc((cg->n_cells ? cg->n_cells : 1) * sizeof *mind);
    st = dial && mind ? choose_samples(cg, x->o->n_components, dial, mind, x->ctl, &x->t)
                     : PS_ERR_NOMEM;
    ps_dial_free(dial);
    free(mind);
    if (st == PS_OK) st = coarse_distances(x, threads);
    if (st == PS_OK) st = fine_level(x, threads);
    if (st == PS_OK) smooth(x, threads);
    return st;
}

/* The samples' seeds as old ids, handed to the caller. */
static ps_status give_samples(const two_level *x, uint32_t **sample_ids, size_t *samples_used) {
    size_t total = x->t.first[x->o->n_components];
    uint32_t *ids = malloc((total ? total : 1) * sizeof *ids);
    if (!ids) return PS_ERR_NOMEM;
    for (size_t i = 0; i < total; i++) ids[i] = x->o->old_of[x->cg->seed[x->t.cells[i]]];
    *samples_used = total;
    *sample_ids = ids;
    return PS_OK;
}

ps_status ps_centrality_coarse(const ps_bfs_order *o, size_t samples, int threads,
                               const ps_control *ctl, double *f, uint32_t **sample_ids,
                               size_t *samples_used, ps_error *err) {
    *sample_ids = NULL;
    *samples_used = 0;
    threads = ps_parallel_threads(threads);
    ps_coarse_graph cg;
    ps_progress_span build = {ctl, PS_PHASE_CENTRALITY, 0.0, BUILD_SHARE};
    report(ctl, 0.0);
    ps_status st = ps_coarse_graph_build(o, threads, &build, &cg, err);
    if (st != PS_OK) return st;
    two_level x = {.o = o, .cg = &cg, .ctl = ctl, .f = f};
    x.fine = malloc(o->g.n * sizeof *x.fine);
    x.spare = malloc(o->g.n * sizeof *x.spare);
    st = x.fine && x.spare ? sample_and_solve(&x, samples, threads) : PS_ERR_NOMEM;
    free(x.fine), free(x.spare);
    if (st == PS_OK) st = give_samples(&x, sample_ids, samples_used);
    table_free(&x.t);
    free(x.task_first);
    ps_coarse_graph_free(&cg);
    if (st == PS_OK) return PS_OK;
    if (st == PS_ERR_NOMEM) return ps_fail(err, st, "centrality: out of memory");
    return ps_fail(err, st, "centrality: cancelled");
}
