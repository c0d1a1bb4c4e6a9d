/*
 * coarse_graph.c: cells, local distances and the coarse graph of
 * coarse_graph.h.
 *
 * Steps: the median edge length per component (select_parallel.h), the
 * greedy cover (sequential: each seed depends on the cover so far; one
 * ps_dijkstra_ball within the radius per seed, lowering every vertex's
 * distance to its nearest seed so far and reaching only the vertices it
 * lowers, which then join the seed's cell: the nearest seed's cell is known
 * when the cover ends), the near lists (cell members by counting sort), the
 * local distances (one ps_dijkstra_ball per seed over its near cells, in
 * parallel; the run from c writes only the slots (p, c), so no
 * two workers share a slot) and the coarse graph read off the seeds' rows.
 */
#include "features/coarse_graph.h"

#include "graph/dijkstra.h"
#include "util/control.h"
#include "util/parallel.h"
#include "util/select_parallel.h"
#include "util/sort_util.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define NO_SLOT UINT32_MAX
#define CANCEL_POLL 256 /* seeds between cancel checks and progress in the cover */
#define RADII_SHARE 0.05  /* progress of the span after the cell radii ... */
#define COVER_SHARE 0.45  /* ... after the cover and the cells ... */
#define CELLS_SHARE 0.5   /* ... after the near lists; local distances follow */

/* ---- a Dijkstra over marked cells (one thread's local distances) --------- */

typedef struct ball {
    ps_dijkstra *dijkstra;
    double *dist;       /* #P, INFINITY outside the current run */
    uint32_t *reached;  /* #P vertices of the current run, in settling order */
    size_t n_reached;
    uint32_t *mark;     /* #M cells of the current region hold its stamp */
} ball;

static void ball_free(ball *b) {
    ps_dijkstra_free(b->dijkstra);
    free(b->dist), free(b->reached), free(b->mark);
}

static ps_status ball_init(ball *b, size_t n, size_t n_cells) {
    size_t alloc_n = n ? n : 1, alloc_m = n_cells ? n_cells : 1;
    memset(b, 0, sizeof *b);
    b->dijkstra = ps_dijkstra_new(n);
    b->dist = malloc(alloc_n * sizeof *b->dist);
    b->reached = malloc(alloc_n * sizeof *b->reached);
    b->mark = malloc(alloc_m * sizeof *b->mark);
    if (!b->dijkstra || !b->dist || !b->reached || !b->mark) return PS_ERR_NOMEM;
    for (size_t v = 0; v < n; v++) b->dist[v] = INFINITY;
    for (size_t c = 0; c < n_cells; c++) b->mark[c] = NO_SLOT;
    return PS_OK;
}

/* Dijkstra from source over the vertices whose cell is marked with stamp.
 * b->reached lists them. */
static void ball_run(ball *b, const ps_graph *g, uint32_t source, const uint32_t *cell_of,
                     uint32_t stamp) {
    ps_dijkstra_limits limits = {.radius = INFINITY, .label = cell_of, .mark = b->mark,
                                 .stamp = stamp};
    b->n_reached = ps_dijkstra_ball(b->dijkstra, g, source, &limits, b->dist, b->reached);
}

static void ball_clear(ball *b) {
    for (size_t i = 0; i < b->n_reached; i++) b->dist[b->reached[i]] = INFINITY;
}

/* ---- cells --------------------------------------------------------------- */

double ps_cell_radius_growth(size_t size) {
    return size > PS_CELL_SCALE_POINTS ? sqrt((double)size / PS_CELL_SCALE_POINTS) : 1.0;
}

/* radius #components: PS_CELL_RADIUS_EDGES x median edge length (0 when
 * the component has no edge), grown for a component over
 * PS_CELL_SCALE_POINTS points. */
static ps_status cell_radii(const ps_bfs_order *o, int threads, double *radius) {
    const ps_graph *g = &o->g;
    double *scratch = malloc((g->offsets[g->n] ? g->offsets[g->n] : 1) * sizeof *scratch);
    if (!scratch) return PS_ERR_NOMEM;
    ps_status st = PS_OK;
    for (int k = 0; k < o->n_components && st == PS_OK; k++) {
        size_t first = g->offsets[o->start[k]], count = g->offsets[o->start[k + 1]] - first;
        double growth = ps_cell_radius_growth(o->start[k + 1] - o->start[k]);
        double median = count ? ps_select_kth_parallel(g->weights + first, count, count / 2,
                                                       threads, scratch)
                              : 0.0;
        if (isnan(median)) st = PS_ERR_NOMEM;
        radius[k] = growth * PS_CELL_RADIUS_EDGES * median;
    }
    free(scratch);
    return st;
}

/* Greedy cover in vertex order: seed #M out (sized #P), cell_start out,
 * and cell_of: each vertex's nearest seed (a vertex's nearest seed is
 * within the radius, so that seed's ball lowered it; ties go to the lower
 * cell, as a ball lowers only strictly).  nearest #P: INFINITY on entry,
 * each vertex's distance to its nearest seed on return. */
static ps_status cover(const ps_bfs_order *o, const double *radius, ps_dijkstra *dij,
                       uint32_t *reached, const ps_progress_span *span, double *nearest,
                       ps_coarse_graph *cg) {
    size_t m = 0;
    for (int k = 0; k < o->n_components; k++) {
        cg->cell_start[k] = m;
        for (size_t v = o->start[k]; v < o->start[k + 1]; v++) {
            if (nearest[v] < INFINITY) continue;
            if (m % CANCEL_POLL == 0) {
                if (ps_control_cancelled(span->ctl)) return PS_ERR_CANCELLED;
                ps_control_progress(span->ctl, span->phase,
                                    span->lo + (span->hi - span->lo) * (double)v / (double)o->g.n);
            }
            cg->seed[m] = (uint32_t)v;
            ps_dijkstra_limits limits = {.radius = radius[k]};
            size_t lowered = ps_dijkstra_ball(dij, &o->g, (uint32_t)v, &limits, nearest, reached);
            for (size_t i = 0; i < lowered; i++) cg->cell_of[reached[i]] = (uint32_t)m;
            m++;
        }
    }
    cg->cell_start[o->n_components] = m;
    cg->n_cells = m;
    return PS_OK;
}

/* ---- near lists ------------------------------------------------------------ */

static void sort_cells(uint32_t *x, size_t n) {
    for (size_t i = 1; i < n; i++) {
        uint32_t v = x[i];
        size_t j = i;
        for (; j > 0 && x[j - 1] > v; j--) x[j] = x[j - 1];
        x[j] = v;
    }
}

static ps_status near_push(ps_coarse_graph *cg, size_t *cap, size_t len, uint32_t cell) {
    if (len == *cap) {
        uint32_t *grown = realloc(cg->near, 2 * *cap * sizeof *grown);
        if (!grown) return PS_ERR_NOMEM;
        cg->near = grown, *cap *= 2;
    }
    cg->near[len] = cell;
    return PS_OK;
}

/* near lists from the members of each cell; mark #M scratch (NO_SLOT). */
static ps_status near_lists(const ps_graph *g, const size_t *first, const uint32_t *members,
                            uint32_t *mark, ps_coarse_graph *cg) {
    size_t cap = 8 * cg->n_cells, len = 0;
    cg->near = malloc(cap * sizeof *cg->near);
    if (!cg->near) return PS_ERR_NOMEM;
    for (uint32_t a = 0; a < cg->n_cells; a++) {
        cg->near_offsets[a] = len;
        mark[a] = a;
        if (near_push(cg, &cap, len++, a) != PS_OK) return PS_ERR_NOMEM;
        for (size_t i = first[a]; i < first[a + 1]; i++)
            for (size_t e = g->offsets[members[i]]; e < g->offsets[members[i] + 1]; e++) {
                uint32_t b = cg->cell_of[g->neighbors[e]];
                if (mark[b] == a) continue;
                mark[b] = a;
                if (near_push(cg, &cap, len++, b) != PS_OK) return PS_ERR_NOMEM;
            }
        sort_cells(cg->near + cg->near_offsets[a], len - cg->near_offsets[a]);
    }
    cg->near_offsets[cg->n_cells] = len;
    return PS_OK;
}

static ps_status build_near(const ps_graph *g, uint32_t *mark, ps_coarse_graph *cg) {
    size_t *first = malloc((cg->n_cells + 1) * sizeof *first);
    uint32_t *members = malloc((g->n ? g->n : 1) * sizeof *members);
    ps_status st = first && members ? PS_OK : PS_ERR_NOMEM;
    if (st == PS_OK) {
        ps_group_by_label(cg->cell_of, g->n, cg->n_cells, first, members);
        st = near_lists(g, first, members, mark, cg);
    }
    free(first), free(members);
    return st;
}

/* Position of cell c in near(a) (c is there: near is symmetric). */
static size_t near_index(const ps_coarse_graph *cg, uint32_t a, uint32_t c) {
    size_t lo = cg->near_offsets[a], hi = cg->near_offsets[a + 1];
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (cg->near[mid] <= c) lo = mid;
        else hi = mid;
    }
    return lo - cg->near_offsets[a];
}

/* ---- local distances ------------------------------------------------------- */

typedef struct local_ctx {
    const ps_graph *g;
    ps_coarse_graph *cg;
    ball *balls;              /* #threads */
} local_ctx;

static void local_from_seed(const ps_graph *g, ps_coarse_graph *cg, ball *b, uint32_t c) {
    for (size_t i = cg->near_offsets[c]; i < cg->near_offsets[c + 1]; i++) b->mark[cg->near[i]] = c;
    ball_run(b, g, cg->seed[c], cg->cell_of, c);
    for (size_t i = 0; i < b->n_reached; i++) {
        uint32_t p = b->reached[i];
        size_t j = near_index(cg, cg->cell_of[p], c);
        cg->local[cg->local_offsets[p] + j] = (float)b->dist[p];
    }
    ball_clear(b);
}

static void local_run(void *ctx, size_t c, int worker) {
    local_ctx *l = ctx;
    local_from_seed(l->g, l->cg, &l->balls[worker], (uint32_t)c);
}

static ps_status local_distances(const ps_graph *g, ball *balls, int threads,
                                 const ps_progress_span *span, ps_coarse_graph *cg) {
    cg->local_offsets[0] = 0;
    for (size_t p = 0; p < g->n; p++) {
        uint32_t a = cg->cell_of[p];
        cg->local_offsets[p + 1] =
            cg->local_offsets[p] + cg->near_offsets[a + 1] - cg->near_offsets[a];
    }
    cg->local = malloc((cg->local_offsets[g->n] ? cg->local_offsets[g->n] : 1) * sizeof *cg->local);
    if (!cg->local) return PS_ERR_NOMEM;
    local_ctx l = {g, cg, balls};
    return ps_parallel_for_tracked(threads, cg->n_cells, 0, local_run, &l, span);
}

/* ---- coarse graph ------------------------------------------------------------ */

/* g(c, seed of a) for c in near(a). */
static double local_at_seed(const ps_coarse_graph *cg, uint32_t a, uint32_t c) {
    return cg->local[cg->local_offsets[cg->seed[a]] + near_index(cg, a, c)];
}

static ps_status coarse_edges(ps_coarse_graph *cg) {
    size_t m = cg->n_cells, edges = cg->near_offsets[m] - m;
    ps_graph *cgr = &cg->graph;
    cgr->n = m;
    cgr->offsets = malloc((m + 1) * sizeof *cgr->offsets);
    cgr->neighbors = malloc((edges ? edges : 1) * sizeof *cgr->neighbors);
    cgr->weights = malloc((edges ? edges : 1) * sizeof *cgr->weights);
    if (!cgr->offsets || !cgr->neighbors || !cgr->weights) return PS_ERR_NOMEM;
    size_t out = 0;
    for (uint32_t a = 0; a < m; a++) {
        cgr->offsets[a] = out;
        for (size_t i = cg->near_offsets[a]; i < cg->near_offsets[a + 1]; i++) {
            uint32_t b = cg->near[i];
            if (b == a) continue;
            cgr->neighbors[out] = b;
            cgr->weights[out++] = fmin(local_at_seed(cg, a, b), local_at_seed(cg, b, a));
        }
    }
    cgr->offsets[m] = out;
    return PS_OK;
}

/* ---- build ----------------------------------------------------------------- */

static ps_status alloc_cells(const ps_bfs_order *o, ps_coarse_graph *cg) {
    size_t n = o->g.n, alloc_n = n ? n : 1;
    cg->seed = malloc(alloc_n * sizeof *cg->seed);
    cg->cell_of = malloc(alloc_n * sizeof *cg->cell_of);
    cg->cell_start = malloc(((size_t)o->n_components + 1) * sizeof *cg->cell_start);
    cg->local_offsets = malloc((n + 1) * sizeof *cg->local_offsets);
    return cg->seed && cg->cell_of && cg->cell_start && cg->local_offsets ? PS_OK : PS_ERR_NOMEM;
}

/* Cell radii (in parallel), cells and near lists (sequential). */
static ps_status build_cells(const ps_bfs_order *o, int threads, const ps_progress_span *span,
                             ps_coarse_graph *cg) {
    size_t alloc_n = o->g.n ? o->g.n : 1;
    double *radius = malloc(((size_t)o->n_components + 1) * sizeof *radius);
    ps_status st = radius ? cell_radii(o, threads, radius) : PS_ERR_NOMEM;
    double *nearest = malloc(alloc_n * sizeof *nearest);
    uint32_t *reached = malloc(alloc_n * sizeof *reached);
    ps_dijkstra *dij = ps_dijkstra_new(o->g.n);
    ps_progress_span cover_span = {span->ctl, span->phase, ps_progress_span_at(span, RADII_SHARE),
                                   ps_progress_span_at(span, COVER_SHARE)};
    ps_control_progress(span->ctl, span->phase, cover_span.lo);
    if (st == PS_OK && (!nearest || !reached || !dij)) st = PS_ERR_NOMEM;
    if (st == PS_OK) {
        for (size_t v = 0; v < o->g.n; v++) nearest[v] = INFINITY;
        st = cover(o, radius, dij, reached, &cover_span, nearest, cg);
    }
    free(radius), free(nearest), free(reached);
    ps_dijkstra_free(dij);
    if (st != PS_OK) return st;
    cg->near_offsets = malloc((cg->n_cells + 1) * sizeof *cg->near_offsets);
    uint32_t *mark = malloc((cg->n_cells ? cg->n_cells : 1) * sizeof *mark);
    if (cg->near_offsets && mark) {
        for (size_t c = 0; c < cg->n_cells; c++) mark[c] = NO_SLOT;
        st = build_near(&o->g, mark, cg);
    } else {
        st = PS_ERR_NOMEM;
    }
    free(mark);
    return st;
}

static ps_status build_levels(const ps_bfs_order *o, int threads, const ps_progress_span *span,
                              ball *balls, ps_coarse_graph *cg) {
    ps_status st = alloc_cells(o, cg);
    if (st == PS_OK) st = build_cells(o, threads, span, cg);
    if (st != PS_OK) return st;
    ps_progress_span local = {span->ctl, span->phase, ps_progress_span_at(span, CELLS_SHARE),
                              span->hi};
    ps_control_progress(span->ctl, span->phase, local.lo);
    for (int t = 0; t < threads && st == PS_OK; t++) st = ball_init(&balls[t], o->g.n, cg->n_cells);
    if (st == PS_OK) st = local_distances(&o->g, balls, threads, &local, cg);
    if (st == PS_OK) st = coarse_edges(cg);
    return st;
}

ps_status ps_coarse_graph_build(const ps_bfs_order *o, int threads, const ps_progress_span *span,
                                ps_coarse_graph *cg, ps_error *err) {
    memset(cg, 0, sizeof *cg);
    threads = ps_parallel_threads(threads);
    ps_progress_span untracked = {NULL, PS_PHASE_CENTRALITY, 0.0, 0.0};
    ball *balls = calloc((size_t)threads, sizeof *balls);
    ps_status st = balls ? build_levels(o, threads, span ? span : &untracked, balls, cg)
                         : PS_ERR_NOMEM;
    for (int t = 0; balls && t < threads; t++) ball_free(&balls[t]);
    free(balls);
    if (st == PS_OK) return PS_OK;
    ps_coarse_graph_free(cg);
    if (st == PS_ERR_CANCELLED) return ps_fail(err, st, "coarse graph: cancelled");
    return ps_fail(err, st, "coarse graph: out of memory for %zu vertices", o->g.n);
}

void ps_coarse_graph_free(ps_coarse_graph *cg) {
    if (!cg) return;
    free(cg->seed), free(cg->cell_of), free(cg->cell_start);
    free(cg->near_offsets), free(cg->near), free(cg->local_offsets), free(cg->local);
    ps_graph_free(&cg->graph);
    memset(cg, 0, sizeof *cg);
}
