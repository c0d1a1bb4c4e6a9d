/*
 * ensemble.c: method auto's ensembles of samplings (ensemble.h): fills of
 * a mesh, or disjoint draws of a denser input.
 *
 * A fill's points are surface_fill.c's (the mesh's own first), so each
 * fill answers the caller's points itself.  The draws' points (and
 * normals) are copied out of the whole input, each draw (or fill) runs
 * the phases of pipeline.h, a phase for several at once with their
 * progress merged under a lock, a FLANN index over each draw's
 * points (nearest.h, built side by side) finds a point's nearest in a draw
 * it is not in, and the chosen draw's distinct points become the result's:
 * result.c reads every caller's point through unique_of (its point in the
 * draw) and each distinct point's stand-in through first_of (its index in
 * the whole input).
 */
#include "ensemble.h"

#include "features/centrality.h"
#include "graph/nearest.h"
#include "graph/reference_density.h"
#include "graph/surface_fill.h"
#include "segment.h"
#include "util/control.h"
#include "util/morton.h"
#include "util/parallel.h"
#include "util/sort_util.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* The draws' progress reported as the whole's: a phase's fraction is the
 * mean of the draws' fractions in it, reported under a lock, since draws
 * run side by side (ps_control's callback is never called concurrently
 * with itself). */
typedef struct progress_board {
    const ps_control *whole;
    int count;
    pthread_mutex_t lock;
    double fraction[PS_PHASE_COUNT][PS_ENSEMBLE_MAX_DRAWS];
} progress_board;

typedef struct progress_share {
    progress_board *board;
    int j;
} progress_share;

typedef struct draw {
    ps_input in;         /* the draw's points (and normals), no faces */
    uint32_t *members;   /* #D index in the whole input of each point (draws) */
    uint32_t *host;      /* fills: the added points' stand-ins (surface_fill.h) */
    ps_pipeline pl;
    ps_control ctl;
    progress_share share;
    ps_nearest_index *index; /* over the pipeline's distinct points */
} draw;

typedef struct ensemble {
    const ps_pipeline *whole;
    int count;
    int fills;          /* 1: the draws are fills of a mesh (ps_ensemble_fill) */
    size_t distinct;    /* distinct points of the whole input */
    size_t size;        /* distinct points a draw takes (ps_ensemble_draw_points) */
    uint32_t *key;      /* #P each point's key (ps_ensemble_keys) */
    uint8_t *draw_of;   /* #P the draw of each point of the whole input, or
                           PS_ENSEMBLE_NONE */
    uint32_t *local_of; /* #P its index within its draw */
    draw d[PS_ENSEMBLE_MAX_DRAWS];
    progress_board board;
} ensemble;

int ps_ensemble_draws(const ps_params *p, size_t n) {
    if (p->method != PS_METHOD_AUTO || n <= PS_DENSITY_REFERENCE_POINTS) return 0;
    size_t fit = n / PS_DENSITY_REFERENCE_POINTS;
    int draws = fit < PS_ENSEMBLE_MAX_DRAWS ? (int)fit : PS_ENSEMBLE_MAX_DRAWS;
    return draws % 2 ? draws : draws - 1;
}

size_t ps_ensemble_draw_points(size_t n) {
    size_t share = (n + PS_ENSEMBLE_MAX_DRAWS - 1) / PS_ENSEMBLE_MAX_DRAWS;
    return share > PS_DENSITY_REFERENCE_POINTS ? share : PS_DENSITY_REFERENCE_POINTS;
}

int ps_ensemble_side_by_side(int threads, int count) {
    threads = ps_parallel_threads(threads);
    return threads < count ? threads : count;
}

/* splitmix64's finalizer: index i to 64 well-mixed bits. */
static uint64_t mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

/* |x - origin - centre| over dim coordinates (x - origin first: that
 * difference is exact for a point near the origin, whatever the offset). */
static double from_centre(const double *x, const double *origin, const double *centre,
                          int dim) {
    double d = 0;
    for (int c = 0; c < dim; c++) {
        double r = (x[c] - origin[c]) - centre[c];
        d += r * r;
    }
    return sqrt(d);
}

/* origin out: #dim the middle of the bounding box, the same for any order
 * of the points. */
static void box_middle(const double *points, size_t n, int dim, double *origin) {
    for (int c = 0; c < dim; c++) {
        double lo = points[c], hi = points[c];
        for (size_t i = 1; i < n; i++) {
            double v = points[i * (size_t)dim + (size_t)c];
            lo = v < lo ? v : lo, hi = v > hi ? v : hi;
        }
        origin[c] = lo + (hi - lo) / 2;
    }
}

/* The centroid is summed relative to the box's middle: summed as given, a
 * scan in georeferenced coordinates (millions of metres) rounded its
 * centroid by about 1e-4 of the scan's size, so that every key moved and
 * the draws were others than a local copy's. */
void ps_ensemble_keys(const double *points, size_t n, int dim, uint32_t *key) {
    double origin[PS_MAX_DIM] = {0}, centre[PS_MAX_DIM] = {0}, far = 0;
    if (n == 0) return;
    box_middle(points, n, dim, origin);
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < dim; c++) centre[c] += points[i * (size_t)dim + (size_t)c] - origin[c];
    for (int c = 0; c < dim; c++) centre[c] /= (double)n;
    for (size_t i = 0; i < n; i++) {
        double d = from_centre(points + i * (size_t)dim, origin, centre, dim);
        if (d > far) far = d;
    }
    double scale = far > 0 ? (double)(1u << PS_ENSEMBLE_KEY_BITS) / far : 0;
    for (size_t i = 0; i < n; i++)
        key[i] = (uint32_t)fmin(from_centre(points + i * (size_t)dim, origin, centre, dim) * scale,
                                (double)((1u << PS_ENSEMBLE_KEY_BITS) - 1));
}

/* The draw of hash h: its slot of size among n, or none past the draws. */
static uint8_t draw_of_hash(uint64_t h, size_t n, int draws, size_t size) {
    uint64_t j = h % (uint64_t)n / (uint64_t)size;
    return j < (uint64_t)draws ? (uint8_t)j : PS_ENSEMBLE_NONE;
}

void ps_ensemble_assign(const uint32_t *key, size_t n, size_t distinct, int draws, size_t size,
                        uint8_t *draw_of) {
    size_t got[PS_ENSEMBLE_MAX_DRAWS] = {0};
    for (size_t i = 0; i < n; i++)
        if ((draw_of[i] = draw_of_hash(mix(key[i]), distinct, draws, size)) != PS_ENSEMBLE_NONE)
            got[draw_of[i]]++;
    for (int j = 0; j < draws; j++)
        if (got[j] < size / 2) {
            for (size_t i = 0; i < n; i++) draw_of[i] = draw_of_hash(mix(i), distinct, draws, size);
            return;
        }
}

int ps_ensemble_compared(uint32_t key, size_t n, size_t s) {
    return mix((uint64_t)key ^ 0x5851f42d4c957f2dULL) % (uint64_t)n < (uint64_t)s;
}

int ps_ensemble_medoid(const int *labels, int draws, size_t s, double margin) {
    double cost[PS_ENSEMBLE_MAX_DRAWS] = {0};
    for (int a = 0; a < draws; a++)
        for (int b = a + 1; b < draws; b++) {
            double e = ps_rand_index_error(labels + (size_t)a * s, labels + (size_t)b * s, s);
            cost[a] += e, cost[b] += e;
        }
    int best = 0;
    for (int a = 1; a < draws; a++)
        if (cost[a] < cost[best]) best = a;
    return cost[0] - cost[best] <= margin ? 0 : best;
}

/* The draws' shared progress board; ensemble_free destroys it. */
static void ensemble_begin(ensemble *e) {
    e->board.whole = e->whole->ctl;
    e->board.count = e->count;
    pthread_mutex_init(&e->board.lock, NULL);
}

static void ensemble_free(ensemble *e) {
    pthread_mutex_destroy(&e->board.lock);
    for (int j = 0; j < e->count; j++) {
        draw *d = &e->d[j];
        if (d->pl.in) ps_pipeline_free(&d->pl);
        free((double *)d->in.points), free((double *)d->in.normals);
        free(d->members), free(d->host);
        ps_nearest_free(d->index);
    }
    free(e->key), free(e->draw_of), free(e->local_of);
}

static ps_status out_of_memory(ps_error *err) {
    return ps_fail(err, PS_ERR_NOMEM, "out of memory (ensemble draws)");
}

/* Each draw's points, normals and members, copied in the order of their
 * keys (so that a reordered copy of the input gives the draws the same
 * points in the same order). */
static ps_status split(ensemble *e, ps_error *err) {
    const ps_input *in = e->whole->in;
    size_t n = in->n, dim = (size_t)in->dim, size[PS_ENSEMBLE_MAX_DRAWS] = {0};
    e->key = malloc(n * sizeof *e->key);
    e->draw_of = malloc(n * sizeof *e->draw_of);
    e->local_of = malloc(n * sizeof *e->local_of);
    uint32_t *order = malloc(n * sizeof *order);
    if (!e->key || !e->draw_of || !e->local_of || !order) {
        free(order);
        return out_of_memory(err);
    }
    ps_ensemble_keys(in->points, n, in->dim, e->key);
    ps_ensemble_assign(e->key, n, e->distinct, e->count, e->size, e->draw_of);
    ps_order_by_u32(e->key, n, order, e->local_of); /* local_of: its scratch */
    for (size_t t = 0; t < n; t++) {
        size_t i = order[t];
        if (e->draw_of[i] != PS_ENSEMBLE_NONE) e->local_of[i] = (uint32_t)size[e->draw_of[i]]++;
    }
    free(order);
    ps_status st = PS_OK;
    for (int j = 0; st == PS_OK && j < e->count; j++) {
        draw *d = &e->d[j];
        d->in = (ps_input){.n = size[j], .dim = in->dim};
        d->in.points = malloc(size[j] * dim * sizeof *d->in.points);
        if (in->normals) d->in.normals = malloc(size[j] * 3 * sizeof *d->in.normals);
        d->members = malloc(size[j] * sizeof *d->members);
        if (!d->in.points || (in->normals && !d->in.normals) || !d->members)
            st = out_of_memory(err);
    }
    for (size_t i = 0; st == PS_OK && i < n; i++) {
        if (e->draw_of[i] == PS_ENSEMBLE_NONE) continue;
        draw *d = &e->d[e->draw_of[i]];
        size_t l = e->local_of[i];
        d->members[l] = (uint32_t)i;
        memcpy((double *)d->in.points + l * dim, in->points + i * dim, dim * sizeof(double));
        if (in->normals)
            memcpy((double *)d->in.normals + l * 3, in->normals + i * 3, 3 * sizeof(double));
    }
    return st;
}

static void report_share(void *user, ps_phase phase, double fraction) {
    const progress_share *s = user;
    progress_board *b = s->board;
    pthread_mutex_lock(&b->lock);
    b->fraction[phase][s->j] = fraction;
    double sum = 0;
    for (int j = 0; j < b->count; j++) sum += b->fraction[phase][j];
    ps_control_progress(b->whole, phase, sum / b->count);
    pthread_mutex_unlock(&b->lock);
}

/* Draw j's pipeline: the whole's parameters, its share of the centrality
 * samples (those of one run over all the draws' points; a fill its own),
 * its share of the progress, the whole's cancel flag. */
static void draw_setup(ensemble *e, int j) {
    const ps_pipeline *whole = e->whole;
    draw *d = &e->d[j];
    d->share = (progress_share){&e->board, j};
    if (whole->ctl) d->ctl = (ps_control){report_share, &d->share, whole->ctl->cancel};
    d->pl = (ps_pipeline){.in = &d->in, .n_input = d->in.n, .ctl = whole->ctl ? &d->ctl : NULL,
                          .params = whole->params, .threads = whole->threads};
    d->pl.points = (double *)d->in.points;
    if (e->fills) { /* each fill runs as one run over its points would */
        d->pl.n_input = whole->in->n, d->pl.host_of_added = d->host;
        size_t repeated = whole->in->n - e->distinct;
        if (!whole->params.samples)
            d->pl.params.samples = ps_centrality_default_samples(d->in.n - repeated);
        return;
    }
    size_t drawn = e->size * (size_t)e->count;
    int samples = whole->params.samples
                      ? whole->params.samples
                      : ps_centrality_default_samples(drawn < e->distinct ? drawn : e->distinct);
    d->pl.params.samples = (samples + e->count - 1) / e->count;
}

/* Draw d's copy of its points once its pipeline has its own (distinct
 * points, after the kNN phase's stray points). */
static void drop_copy(draw *d) {
    if (d->pl.points == d->in.points) return;
    free((double *)d->in.points), free((double *)d->in.normals);
    d->in.points = d->in.normals = NULL;
}

/* Phase ph's times and its steps' in from, added to to. */
static void add_phase_timings(ps_timings *to, const ps_timings *from, ps_phase ph) {
    to->ms[ph] += from->ms[ph];
    for (int s = 0; s < PS_STEP_COUNT; s++)
        if (ps_step_phase((ps_step)s) == ph) to->step_ms[s] += from->step_ms[s];
}

/* One phase of every draw, the draws side by side. */
typedef struct phase_job {
    ensemble *e;
    ps_phase ph;
    ps_status st[PS_ENSEMBLE_MAX_DRAWS];
    ps_error err[PS_ENSEMBLE_MAX_DRAWS];
} phase_job;

static void run_draw_phase(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    phase_job *job = ctx;
    for (size_t j = begin; j < end; j++) {
        draw *d = &job->e->d[j];
        job->st[j] = ps_segment_phase(&d->pl, job->ph, &job->err[j]);
        if (job->st[j] == PS_OK && job->ph == PS_PHASE_KNN) drop_copy(d);
    }
}

/* Phase ph of every draw: as many draws at once as the whole has threads,
 * each on the whole's threads, so that one draw's serial work overlaps
 * another's (the labels are the same for any thread count).  The phase's
 * time is its wall time, shared among its steps as the draws' step times
 * are.  On failure, the error of the first draw that failed. */
static ps_status run_phase(ensemble *e, ps_pipeline *whole, ps_phase ph, ps_error *err) {
    phase_job job = {.e = e, .ph = ph};
    double start = ps_now_ms();
    ps_parallel_for(ps_ensemble_side_by_side(whole->threads, e->count), (size_t)e->count, 1,
                    run_draw_phase, &job);
    double wall = ps_now_ms() - start;
    ps_timings draws = {0};
    for (int j = 0; j < e->count; j++) {
        if (job.st[j] != PS_OK) {
            *err = job.err[j];
            return job.st[j];
        }
        add_phase_timings(&draws, &e->d[j].pl.timings, ph);
    }
    double summed = draws.ms[ph];
    for (int s = 0; s < PS_STEP_COUNT; s++)
        if (ps_step_phase((ps_step)s) == ph)
            whole->timings.step_ms[s] += summed > 0 ? draws.step_ms[s] * wall / summed : 0;
    whole->timings.ms[ph] += wall;
    return PS_OK;
}

/* The phases, each over every draw before the next; then each draw keeps
 * only what its answers need. */
static ps_status run(ensemble *e, ps_pipeline *whole, ps_error *err) {
    ps_status st = PS_OK;
    for (int j = 0; st == PS_OK && j < e->count; j++) {
        draw_setup(e, j);
        st = ps_pipeline_dedup(&e->d[j].pl, err);
    }
    for (int ph = 0; st == PS_OK && ph < PS_PHASE_COUNT; ph++)
        st = run_phase(e, whole, (ps_phase)ph, err);
    for (int j = 0; st == PS_OK && j < e->count; j++) ps_pipeline_shed(&e->d[j].pl);
    return st;
}

static void index_draws(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    ensemble *e = ctx;
    for (size_t j = begin; j < end; j++)
        e->d[j].index = ps_nearest_build(e->d[j].pl.points, e->d[j].pl.dedup.n_unique,
                                         e->whole->in->dim);
}

static ps_status index_all(ensemble *e, ps_error *err) {
    ps_parallel_for(e->whole->threads, (size_t)e->count, 1, index_draws, e);
    for (int j = 0; j < e->count; j++)
        if (!e->d[j].index) return out_of_memory(err);
    return PS_OK;
}

/* unique out: #Q for the whole input's points ids[0..Q), the distinct
 * point of draw j that answers for each: its own point's, or the draw's
 * nearest. */
static ps_status locate(const ensemble *e, int j, const uint32_t *ids, size_t q,
                        uint32_t *unique, ps_error *err) {
    const ps_input *in = e->whole->in;
    const ps_dedup *dd = &e->d[j].pl.dedup;
    if (e->fills) { /* every fill holds the caller's points first */
        for (size_t t = 0; t < q; t++) unique[t] = dd->unique_of[ids[t]];
        return PS_OK;
    }
    size_t dim = (size_t)in->dim, m = 0;
    for (size_t t = 0; t < q; t++) m += e->draw_of[ids[t]] != j;
    double *queries = calloc((m ? m : 1) * dim, sizeof *queries);
    uint32_t *found = malloc((m ? m : 1) * sizeof *found);
    if (!queries || !found) {
        free(queries), free(found);
        return out_of_memory(err);
    }
    m = 0;
    for (size_t t = 0; t < q; t++)
        if (e->draw_of[ids[t]] != j)
            memcpy(queries + m++ * dim, in->points + (size_t)ids[t] * dim, dim * sizeof *queries);
    ps_status st = ps_nearest_query(e->d[j].index, queries, m, e->whole->threads, found, err);
    m = 0;
    for (size_t t = 0; st == PS_OK && t < q; t++)
        unique[t] = e->draw_of[ids[t]] == j ? dd->unique_of[e->local_of[ids[t]]] : found[m++];
    free(queries), free(found);
    return st;
}

/* The medoid draw, compared on the points ps_ensemble_compared picks. */
static ps_status choose(const ensemble *e, int *chosen, ps_error *err) {
    size_t n = e->whole->in->n, s = 0;
    *chosen = 0;
    if (e->count == 1) return PS_OK;
    for (size_t i = 0; i < n; i++) s += ps_ensemble_compared(e->key[i], n, PS_ENSEMBLE_SAMPLE);
    uint32_t *ids = calloc(s ? s : 1, sizeof *ids), *unique = malloc((s ? s : 1) * sizeof *unique);
    int *labels = malloc((size_t)e->count * (s ? s : 1) * sizeof *labels);
    ps_status st = ids && unique && labels ? PS_OK : out_of_memory(err);
    for (size_t i = 0, t = 0; st == PS_OK && i < n; i++)
        if (ps_ensemble_compared(e->key[i], n, PS_ENSEMBLE_SAMPLE)) ids[t++] = (uint32_t)i;
    for (int j = 0; st == PS_OK && j < e->count; j++) {
        const ps_pipeline *pl = &e->d[j].pl;
        st = locate(e, j, ids, s, unique, err);
        for (size_t t = 0; st == PS_OK && t < s; t++)
            labels[(size_t)j * s + t] = pl->group_of_point[unique[t]];
    }
    if (st == PS_OK && s)
        *chosen = ps_ensemble_medoid(labels, e->count, s, e->fills ? PS_ENSEMBLE_FILL_MARGIN : 0);
    free(ids), free(unique), free(labels);
    return st;
}

/* unique_of out: #P (the caller's points) the distinct point of draw c
 * whose answers each takes; the queries go in Morton order, near ones
 * together. */
static ps_status caller_points(const ensemble *e, int c, uint32_t *unique_of, ps_error *err) {
    const ps_input *in = e->whole->in;
    size_t n = e->whole->n_input;
    uint32_t *order = malloc(n * sizeof *order), *unique = malloc(n * sizeof *unique);
    ps_status st = order && unique && ps_morton_order(in->points, n, in->dim, order) == PS_OK
                       ? PS_OK
                       : out_of_memory(err);
    if (st == PS_OK) st = locate(e, c, order, n, unique, err);
    for (size_t t = 0; st == PS_OK && t < n; t++) unique_of[order[t]] = unique[t];
    free(order), free(unique);
    return st;
}

/* The result from draw c, for the caller's points (a fill's pipeline
 * answers them, its first points, itself). */
static ps_status result(ensemble *e, int c, ps_result **out, ps_error *err) {
    if (e->fills) {
        ps_result_parts parts = ps_pipeline_parts(&e->d[c].pl);
        return ps_pipeline_result(&e->d[c].pl, &parts, out, err);
    }
    const ps_pipeline *whole = e->whole;
    ps_pipeline *pl = &e->d[c].pl;
    size_t n = whole->n_input, u = pl->dedup.n_unique;
    uint32_t *unique_of = malloc(n * sizeof *unique_of), *first = malloc(u * sizeof *first);
    ps_status st = unique_of && first ? caller_points(e, c, unique_of, err) : out_of_memory(err);
    for (size_t v = 0; st == PS_OK && v < u; v++) first[v] = e->d[c].members[pl->dedup.first[v]];
    if (st == PS_OK) {
        ps_result_parts parts = ps_pipeline_parts(pl);
        parts.n_input = n;
        parts.host_of_added = whole->host_of_added;
        parts.n_filled = whole->in->n - n;
        parts.unique_of = unique_of;
        parts.first_of = first;
        st = ps_pipeline_result(pl, &parts, out, err);
    }
    free(unique_of), free(first);
    return st;
}

/* The draws' (or fills') phases, their medoid and its answers; the
 * medoid and the answers timed as refine. */
static ps_status segment_all(ensemble *e, ps_pipeline *whole, ps_result **out, ps_error *err) {
    ps_status st = run(e, whole, err);
    double start = ps_now_ms();
    int chosen = 0;
    if (st == PS_OK && !e->fills) st = index_all(e, err);
    if (st == PS_OK) st = choose(e, &chosen, err);
    if (st == PS_OK) st = result(e, chosen, out, err);
    whole->timings.ms[PS_PHASE_REFINE] += ps_now_ms() - start;
    return st;
}

ps_status ps_ensemble_segment(ps_pipeline *whole, int draws, size_t distinct, ps_result **out,
                              ps_error *err) {
    ensemble e = {.whole = whole, .count = draws, .distinct = distinct,
                  .size = ps_ensemble_draw_points(distinct)};
    ensemble_begin(&e);
    ps_status st = split(&e, err);
    if (st == PS_OK) st = segment_all(&e, whole, out, err);
    ensemble_free(&e);
    return st;
}

/* The caller's mesh's fills, one per draw (its points, normals and
 * stand-ins move into the draw), and the keys of the caller's points;
 * *filled 0 when a fill adds nothing (a rough mesh, no area). */
static ps_status fill_all(ensemble *e, int *filled, ps_error *err) {
    const ps_input *in = e->whole->in;
    size_t target = PS_DENSITY_REFERENCE_POINTS + (in->n - e->distinct);
    ps_surface_fill fill[PS_ENSEMBLE_MAX_DRAWS];
    *filled = 0;
    e->key = malloc(in->n * sizeof *e->key);
    if (!e->key) return out_of_memory(err);
    ps_ensemble_keys(in->points, in->n, in->dim, e->key);
    ps_status st = ps_surface_fill_build(in, &e->whole->dedup, target, e->count, fill, err);
    if (st != PS_OK) return st;
    *filled = 1;
    for (int j = 0; j < e->count; j++) {
        e->d[j].in = (ps_input){.points = fill[j].points, .normals = fill[j].normals,
                                .n = in->n + fill[j].n_added, .dim = in->dim};
        e->d[j].host = fill[j].host;
        if (!fill[j].n_added) *filled = 0;
    }
    return PS_OK;
}

ps_status ps_ensemble_fill(ps_pipeline *whole, int fills, int *filled, ps_result **out,
                           ps_error *err) {
    ensemble e = {.whole = whole, .count = fills, .fills = 1,
                  .distinct = whole->dedup.n_unique};
    ensemble_begin(&e);
    ps_status st = fill_all(&e, filled, err);
    if (st == PS_OK && *filled) st = segment_all(&e, whole, out, err);
    ensemble_free(&e);
    return st;
}
