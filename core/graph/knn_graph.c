/*
 * knn_graph.c: the symmetrized kNN graph of knn_graph.h, and its connected
 * components.
 *
 * FLANN's single kd-tree (an exact search) on the double coordinates finds
 * k + PS_KNN_EXTRA candidates per point; their distances are recomputed here in
 * double, rounded to single precision, and the k nearest other points kept
 * by (rounded distance, index): the equal distances of a regular grid stay
 * ties broken by index when a rotation moves them apart in the last bits
 * (for tie sets that fit in the extra candidates), and the thread count
 * never changes the graph.  The index and the queries' order are built
 * side by side; queries go in Morton order
 * (morton.h), blocks of them per worker, which keeps the tree walks in
 * cache for inputs in any order.  The directed lists are then
 * mirrored into CSR rows, sorted by neighbour index and freed of duplicates
 * row by row in parallel.  A build may keep its index and directed lists
 * (ps_knn_memo, knn_memo.h) for ps_knn_graph_prune (knn_prune.c).
 */
#include "graph/knn_graph.h"
#include "graph/knn_memo.h"

#include "graph/kdtree_query.h"
#include "util/control.h"
#include "util/morton.h"
#include "util/sort_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define QUERY_BLOCK 2048      /* rows per FLANN query call and per work item */
#define INDEX_SHARE 0.25      /* progress of the span after the index build ... */
#define QUERIES_SHARE 0.8     /* ... after the queries ... */
#define ROWS_SHARE 0.9        /* ... after the rows are mirrored; the weights follow */

typedef struct candidate {
    float dist;      /* the distance to single precision: a tie key */
    uint32_t index;
} candidate;

double ps_knn_distance(const double *a, const double *b, int dim) {
    double s = 0.0;
    for (int i = 0; i < dim; i++) {
        double d = a[i] - b[i];
        s += d * d;
    }
    return sqrt(s);
}

static int candidate_less(const candidate *a, const candidate *b) {
    return a->dist < b->dist || (a->dist == b->dist && a->index < b->index);
}

static void sort_candidates(candidate *c, int m) {
    for (int i = 1; i < m; i++) {
        candidate x = c[i];
        int j = i;
        for (; j > 0 && candidate_less(&x, &c[j - 1]); j--) c[j] = c[j - 1];
        c[j] = x;
    }
}

/* The rows to query on the shared index (kdtree_query.h); each keeps its k
 * nearest other points in memo->knn. */
typedef struct query_job {
    ps_knn_memo *memo;
    const double *points;   /* current points, #P by dim */
    const uint32_t *order;  /* rows to query (Morton order: nearby queries in a row) */
} query_job;

/* Row p's candidates by (exact distance, index), self left out; 0, or -1
 * when FLANN returned fewer than k usable neighbours. */
static int keep_nearest(const query_job *j, size_t p, const int *found) {
    const ps_knn_memo *mm = j->memo;
    candidate c[PS_MAX_K + PS_KNN_EXTRA + 1];
    const double *x = j->points + p * (size_t)mm->dim;
    int m = 0;
    for (int t = 0; t < mm->m; t++) {
        if (found[t] < 0) continue;
        uint32_t q = mm->current_of ? mm->current_of[found[t]] : (uint32_t)found[t];
        if (q == p) continue;
        c[m].index = q;
        c[m].dist = (float)ps_knn_distance(x, j->points + (size_t)q * (size_t)mm->dim, mm->dim);
        m++;
    }
    if (m < mm->k) return -1;
    sort_candidates(c, m);
    for (int t = 0; t < mm->k; t++) mm->knn[p * (size_t)mm->k + (size_t)t] = c[t].index;
    if (mm->saturated) mm->saturated[p] = c[m - 1].dist == c[mm->k - 1].dist;
    return 0;
}

static void gather_rows(void *ctx, size_t first, size_t rows, double *out) {
    const query_job *j = ctx;
    size_t width = (size_t)j->memo->dim;
    for (size_t r = 0; r < rows; r++)
        memcpy(out + r * width, j->points + j->order[first + r] * width, width * sizeof *out);
}

static int take_rows(void *ctx, size_t first, size_t rows, const int *found) {
    const query_job *j = ctx;
    for (size_t r = 0; r < rows; r++)
        if (keep_nearest(j, j->order[first + r], found + r * (size_t)j->memo->m) != 0) return -1;
    return 0;
}

ps_status ps_knn_query_rows(ps_knn_memo *memo, const double *points, const uint32_t *rows,
                            size_t n_rows, int threads, const ps_progress_span *span,
                            ps_error *err) {
    query_job j = {.memo = memo, .points = points, .order = rows};
    ps_kd_batch batch = {.index = memo->index, .dim = memo->dim, .neighbours = memo->m,
                         .count = n_rows, .block = QUERY_BLOCK, .gather = gather_rows,
                         .take = take_rows, .ctx = &j};
    ps_status st = ps_kd_query(&batch, threads, span);
    if (st == PS_ERR_NOMEM) return ps_fail(err, st, "knn: out of memory for the query blocks");
    if (st == PS_ERR_CANCELLED) return ps_fail(err, st, "knn: cancelled");
    if (st != PS_OK) return ps_fail(err, st, "knn: FLANN search failed");
    return PS_OK;
}

/* The two set-ups of the queries, independent of each other, run side by
 * side: item 0 the Morton order of the queries, item 1 the index. */
typedef struct query_setup {
    ps_knn_memo *memo;
    const double *points;
    size_t n;
    uint32_t *order;  /* #P out */
    ps_status order_status;
} query_setup;

static void set_up_item(void *ctx, size_t begin, size_t end, int worker) {
    query_setup *q = ctx;
    (void)worker;
    for (size_t item = begin; item < end; item++) {
        if (item == 0) {
            q->order_status = ps_morton_order(q->points, q->n, q->memo->dim, q->order);
            continue;
        }
        struct FLANNParameters fp = ps_kd_parameters();
        float speedup = 0.0f;
        q->memo->index = flann_build_index_double((double *)q->points, (int)q->n, q->memo->dim,
                                                  &speedup, &fp);
    }
}

/* memo->index on the points and memo->knn: each point's k nearest other
 * points, queried in Morton order; progress through span up to
 * QUERIES_SHARE. */
static ps_status directed_knn(ps_knn_memo *memo, const double *points, size_t n, int threads,
                              const ps_progress_span *span, ps_error *err) {
    query_setup q = {.memo = memo, .points = points, .n = n, .order = malloc(n * sizeof *q.order)};
    if (!q.order) return ps_fail(err, PS_ERR_NOMEM, "knn: out of memory for the query order");
    ps_parallel_for(ps_parallel_threads(threads), 2, 1, set_up_item, &q);
    ps_status st = PS_OK;
    if (q.order_status != PS_OK)
        st = ps_fail(err, PS_ERR_NOMEM, "knn: out of memory for the query order");
    else if (!memo->index)
        st = ps_fail(err, PS_ERR_INTERNAL, "knn: FLANN index build failed");
    if (st == PS_OK) {
        ps_progress_span queries = {span->ctl, span->phase, ps_progress_span_at(span, INDEX_SHARE),
                                    ps_progress_span_at(span, QUERIES_SHARE)};
        ps_control_progress(span->ctl, span->phase, queries.lo);
        st = ps_knn_query_rows(memo, points, q.order, n, threads, &queries, err);
    }
    free(q.order);
    return st;
}

void ps_knn_memo_free(ps_knn_memo *memo) {
    if (!memo) return;
    struct FLANNParameters fp = ps_kd_parameters();
    if (memo->index) flann_free_index_double(memo->index, &fp);
    free(memo->knn), free(memo->saturated), free(memo->current_of);
    free(memo);
}

/* A memo for n points: no index yet, directed lists (and saturation flags
 * when it is to be kept) allocated; NULL when out of memory. */
static ps_knn_memo *memo_new(size_t n, int dim, int k, int keep) {
    ps_knn_memo *memo = calloc(1, sizeof *memo);
    if (!memo) return NULL;
    *memo = (ps_knn_memo){.n_first = n, .dim = dim, .k = k,
                          .m = k + 1 + PS_KNN_EXTRA < (int)n ? k + 1 + PS_KNN_EXTRA : (int)n,
                          .knn = malloc(n * (size_t)k * sizeof *memo->knn),
                          .saturated = keep ? malloc(n ? n : 1) : NULL};
    if (memo->knn && (!keep || memo->saturated)) return memo;
    ps_knn_memo_free(memo);
    return NULL;
}

/* Insertion sort for the usual short row; qsort for a hub's long one. */
static void sort_row(uint32_t *row, size_t len) {
    if (len > 64) {
        qsort(row, len, sizeof *row, ps_compare_u32);
        return;
    }
    for (size_t i = 1; i < len; i++) {
        uint32_t x = row[i];
        size_t j = i;
        for (; j > 0 && x < row[j - 1]; j--) row[j] = row[j - 1];
        row[j] = x;
    }
}

typedef struct rows_job {
    ps_graph *g;
    size_t *unique; /* #P out: distinct neighbours of each row */
} rows_job;

/* Sorts each row in place and moves its distinct entries to its front. */
static void sort_rows(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    const rows_job *j = ctx;
    for (size_t p = begin; p < end; p++) {
        uint32_t *row = j->g->neighbors + j->g->offsets[p];
        size_t len = j->g->offsets[p + 1] - j->g->offsets[p], kept = 0;
        sort_row(row, len);
        for (size_t i = 0; i < len; i++)
            if (i == 0 || row[i] != row[kept - 1]) row[kept++] = row[i];
        j->unique[p] = kept;
    }
}

/* Mirrors the directed lists into g->offsets / g->neighbors (with room for
 * duplicates), sorts and dedups the rows in parallel, then packs them. */
static void symmetrize(const uint32_t *knn, size_t n, int k, int threads, ps_graph *g,
                       size_t *fill) {
    memset(fill, 0, n * sizeof *fill);
    for (size_t p = 0; p < n * (size_t)k; p++) fill[knn[p]]++;
    g->offsets[0] = 0;
    for (size_t p = 0; p < n; p++) g->offsets[p + 1] = g->offsets[p] + (size_t)k + fill[p];
    for (size_t p = 0; p < n; p++) fill[p] = g->offsets[p];
    for (size_t p = 0; p < n; p++)
        for (int t = 0; t < k; t++) {
            uint32_t q = knn[p * (size_t)k + (size_t)t];
            g->neighbors[fill[p]++] = q;
            g->neighbors[fill[q]++] = (uint32_t)p;
        }
    rows_job rj = {g, fill};
    ps_parallel_for(threads, n, 0, sort_rows, &rj);
    size_t out = 0;
    for (size_t p = 0; p < n; p++) {
        memmove(g->neighbors + out, g->neighbors + g->offsets[p], fill[p] * sizeof *g->neighbors);
        g->offsets[p] = out;
        out += fill[p];
    }
    g->offsets[n] = out;
}

typedef struct weight_job {
    const double *points;
    int dim;
    ps_graph *g;
} weight_job;

static void weigh_rows(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    const weight_job *j = ctx;
    const ps_graph *g = j->g;
    for (size_t p = begin; p < end; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            g->weights[e] = ps_knn_distance(j->points + p * (size_t)j->dim,
                                            j->points + (size_t)g->neighbors[e] * (size_t)j->dim,
                                            j->dim);
}

static ps_status check_arguments(const ps_knn_graph_input *in, ps_error *err) {
    size_t n = in->n;
    int dim = in->dim, k = in->k;
    if (!in->points) return ps_fail(err, PS_ERR_INVALID, "knn: points is NULL");
    if (dim < 1 || dim > PS_MAX_DIM) return ps_fail(err, PS_ERR_INVALID, "knn: dim %d", dim);
    if (k < 1 || k > PS_MAX_K || (size_t)k >= n)
        return ps_fail(err, PS_ERR_INVALID, "knn: need 1 <= k <= %d and k < n, got k = %d, n = %zu",
                       PS_MAX_K, k, n);
    if (n > (size_t)INT32_MAX) return ps_fail(err, PS_ERR_INVALID, "knn: too many points (%zu)", n);
    return PS_OK;
}

/* g's weights, the lengths of its edges between in->points, on threads
 * workers; progress to in->span->hi. */
static ps_status weigh_edges(const ps_knn_graph_input *in, int threads, ps_graph *g,
                             ps_error *err) {
    size_t edges = g->offsets[g->n];
    uint32_t *shrunk = realloc(g->neighbors, edges * sizeof *shrunk);
    if (shrunk) g->neighbors = shrunk;
    g->weights = malloc(edges * sizeof *g->weights);
    if (!g->weights) return ps_fail(err, PS_ERR_NOMEM, "knn: out of memory for %zu edges", edges);
    weight_job wj = {in->points, in->dim, g};
    ps_parallel_for(threads, g->n, 0, weigh_rows, &wj);
    ps_control_progress(in->span->ctl, in->span->phase, in->span->hi);
    return PS_OK;
}

ps_status ps_knn_graph_build(const double *points, size_t n, int dim, int k, int threads,
                             ps_graph *g, ps_error *err) {
    ps_progress_span untracked = {NULL, PS_PHASE_KNN, 0.0, 0.0};
    ps_knn_graph_input in = {.points = points, .n = n, .dim = dim, .k = k, .threads = threads,
                             .span = &untracked};
    return ps_knn_graph_build_tracked(&in, g, err);
}

ps_status ps_knn_graph_build_tracked(const ps_knn_graph_input *in, ps_graph *g, ps_error *err) {
    return ps_knn_graph_build_memo(in, g, NULL, err);
}

ps_status ps_knn_graph_build_memo(const ps_knn_graph_input *in, ps_graph *g, ps_knn_memo **memo,
                                  ps_error *err) {
    size_t n = in->n;
    int k = in->k;
    const ps_progress_span *span = in->span;
    memset(g, 0, sizeof *g);
    if (memo) *memo = NULL;
    ps_status st = check_arguments(in, err);
    if (st != PS_OK) return st;
    int threads = ps_parallel_threads(in->threads);
    size_t directed = n * (size_t)k;
    ps_knn_memo *mm = memo_new(n, in->dim, k, memo != NULL);
    size_t *fill = malloc(n * sizeof *fill);
    g->n = n;
    g->offsets = malloc((n + 1) * sizeof *g->offsets);
    g->neighbors = malloc(2 * directed * sizeof *g->neighbors);
    if (!mm || !fill || !g->offsets || !g->neighbors) {
        st = ps_fail(err, PS_ERR_NOMEM, "knn: out of memory for %zu points", n);
        goto done;
    }
    st = directed_knn(mm, in->points, n, threads, span, err);
    if (st != PS_OK) goto done;
    if (!memo) { /* the index is not needed beyond the queries */
        struct FLANNParameters fp = ps_kd_parameters();
        flann_free_index_double(mm->index, &fp);
        mm->index = NULL;
    }
    symmetrize(mm->knn, n, k, threads, g, fill);
    ps_control_progress(span->ctl, span->phase, ps_progress_span_at(span, ROWS_SHARE));
    st = weigh_edges(in, threads, g, err);
done:
    free(fill);
    if (st != PS_OK) ps_graph_free(g);
    if (st == PS_OK && memo) *memo = mm;
    else ps_knn_memo_free(mm);
    return st;
}
