/*
 * knn_graph.c: the symmetrized kNN graph of knn_graph.h, and its connected
 * components.
 *
 * FLANN's single kd-tree (an exact search) on the double coordinates finds
 * k + EXTRA candidates per point; their distances are recomputed here in
 * double and the k nearest other points kept by (distance, index), so ties
 * and the thread count never change the graph.  The directed lists are then
 * mirrored into CSR rows sorted by neighbour index without duplicates.
 */
#include "knn_graph.h"

#include "parallel.h"

#include <flann/flann.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define EXTRA 3               /* candidates beyond k + 1, for exact tie breaks */
#define QUERY_BLOCK 65536     /* points per FLANN query call (bounds scratch) */

typedef struct candidate {
    double dist;
    uint32_t index;
} candidate;

static double point_distance(const double *a, const double *b, int dim) {
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

/* One block of FLANN results reranked into the directed lists knn (#P by k). */
typedef struct rerank_job {
    const double *points;
    int dim, k, m;        /* m candidates per query row */
    size_t first_row;     /* block offset in the point set */
    const int *found;     /* #block by m FLANN indices */
    uint32_t *knn;        /* #P by k out */
} rerank_job;

static void rerank_rows(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    const rerank_job *j = ctx;
    candidate c[64 + EXTRA + 1];
    for (size_t r = begin; r < end; r++) {
        size_t p = j->first_row + r;
        const double *x = j->points + p * (size_t)j->dim;
        int m = 0;
        for (int t = 0; t < j->m; t++) {
            int q = j->found[r * (size_t)j->m + (size_t)t];
            if (q < 0 || (size_t)q == p) continue;
            c[m].index = (uint32_t)q;
            c[m].dist = point_distance(x, j->points + (size_t)q * (size_t)j->dim, j->dim);
            m++;
        }
        sort_candidates(c, m);
        for (int t = 0; t < j->k; t++) j->knn[p * (size_t)j->k + (size_t)t] = c[t].index;
    }
}

static struct FLANNParameters search_parameters(int threads) {
    struct FLANNParameters fp = DEFAULT_FLANN_PARAMETERS;
    fp.algorithm = FLANN_INDEX_KDTREE_SINGLE;
    fp.checks = FLANN_CHECKS_UNLIMITED;
    fp.eps = 0.0f;
    fp.cores = threads;
    fp.log_level = FLANN_LOG_NONE;
    return fp;
}

/* knn #P by k: each point's k nearest other points. */
static ps_status directed_knn(const double *points, size_t n, int dim, int k, int threads,
                              uint32_t *knn, ps_error *err) {
    struct FLANNParameters fp = search_parameters(threads);
    float speedup = 0.0f;
    int m = k + 1 + EXTRA < (int)n ? k + 1 + EXTRA : (int)n;
    size_t block = n < QUERY_BLOCK ? n : QUERY_BLOCK;
    int *found = malloc(block * (size_t)m * sizeof *found);
    double *sq = malloc(block * (size_t)m * sizeof *sq);
    if (!found || !sq) {
        free(found), free(sq);
        return ps_fail(err, PS_ERR_NOMEM, "knn: out of memory for the query block");
    }
    flann_index_t index = flann_build_index_double((double *)points, (int)n, dim, &speedup, &fp);
    ps_status st = index ? PS_OK : ps_fail(err, PS_ERR_INTERNAL, "knn: FLANN index build failed");
    for (size_t first = 0; st == PS_OK && first < n; first += block) {
        size_t rows = n - first < block ? n - first : block;
        if (flann_find_nearest_neighbors_index_double(index, (double *)points + first * (size_t)dim,
                                                      (int)rows, found, sq, m, &fp) != 0) {
            st = ps_fail(err, PS_ERR_INTERNAL, "knn: FLANN search failed");
            break;
        }
        rerank_job job = {points, dim, k, m, first, found, knn};
        ps_parallel_for(threads, rows, 0, rerank_rows, &job);
    }
    if (index) flann_free_index_double(index, &fp);
    free(found), free(sq);
    return st;
}

static void sort_row(uint32_t *row, size_t len) {
    for (size_t i = 1; i < len; i++) {
        uint32_t x = row[i];
        size_t j = i;
        for (; j > 0 && x < row[j - 1]; j--) row[j] = row[j - 1];
        row[j] = x;
    }
}

/* Mirrors the directed lists into g->offsets / g->neighbors (with room for
 * duplicates), then sorts and compacts each row in place. */
static void symmetrize(const uint32_t *knn, size_t n, int k, ps_graph *g, size_t *fill) {
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
    size_t out = 0;
    for (size_t p = 0; p < n; p++) {
        uint32_t *row = g->neighbors + g->offsets[p];
        size_t len = g->offsets[p + 1] - g->offsets[p];
        sort_row(row, len);
        g->offsets[p] = out;
        for (size_t i = 0; i < len; i++)
            if (i == 0 || row[i] != row[i - 1]) g->neighbors[out++] = row[i];
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
            g->weights[e] = point_distance(j->points + p * (size_t)j->dim,
                                           j->points + (size_t)g->neighbors[e] * (size_t)j->dim,
                                           j->dim);
}

static ps_status check_arguments(const double *points, size_t n, int dim, int k, ps_error *err) {
    if (!points) return ps_fail(err, PS_ERR_INVALID, "knn: points is NULL");
    if (dim < 1 || dim > PS_MAX_DIM) return ps_fail(err, PS_ERR_INVALID, "knn: dim %d", dim);
    if (k < 1 || k > 64 || (size_t)k >= n)
        return ps_fail(err, PS_ERR_INVALID, "knn: need 1 <= k <= 64 and k < n, got k = %d, n = %zu",
                       k, n);
    if (n > (size_t)INT32_MAX) return ps_fail(err, PS_ERR_INVALID, "knn: too many points (%zu)", n);
    return PS_OK;
}

ps_status ps_knn_graph_build(const double *points, size_t n, int dim, int k, int threads,
                             ps_graph *g, ps_error *err) {
    memset(g, 0, sizeof *g);
    ps_status st = check_arguments(points, n, dim, k, err);
    if (st != PS_OK) return st;
    threads = ps_parallel_threads(threads);
    size_t directed = n * (size_t)k;
    uint32_t *knn = malloc(directed * sizeof *knn);
    size_t *fill = malloc(n * sizeof *fill);
    g->n = n;
    g->offsets = malloc((n + 1) * sizeof *g->offsets);
    g->neighbors = malloc(2 * directed * sizeof *g->neighbors);
    if (!knn || !fill || !g->offsets || !g->neighbors) {
        st = ps_fail(err, PS_ERR_NOMEM, "knn: out of memory for %zu points", n);
        goto done;
    }
    st = directed_knn(points, n, dim, k, threads, knn, err);
    if (st != PS_OK) goto done;
    symmetrize(knn, n, k, g, fill);
    size_t edges = g->offsets[n];
    uint32_t *shrunk = realloc(g->neighbors, edges * sizeof *shrunk);
    if (shrunk) g->neighbors = shrunk;
    g->weights = malloc(edges * sizeof *g->weights);
    if (!g->weights) {
        st = ps_fail(err, PS_ERR_NOMEM, "knn: out of memory for %zu edges", edges);
        goto done;
    }
    weight_job wj = {points, dim, g};
    ps_parallel_for(threads, n, 0, weigh_rows, &wj);
done:
    free(knn), free(fill);
    if (st != PS_OK) ps_graph_free(g);
    return st;
}

void ps_graph_free(ps_graph *g) {
    if (!g) return;
    free(g->offsets), free(g->neighbors), free(g->weights);
    memset(g, 0, sizeof *g);
}

/* Union-find root with path halving; parents always point to lower ids. */
static int find_root(int *parent, int v) {
    while (parent[v] != v) {
        parent[v] = parent[parent[v]];
        v = parent[v];
    }
    return v;
}

int ps_graph_components(const ps_graph *g, int *component) {
    int n = (int)g->n;
    for (int p = 0; p < n; p++) component[p] = p;
    for (int p = 0; p < n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            int a = find_root(component, p), b = find_root(component, (int)g->neighbors[e]);
            if (a < b) component[b] = a;
            if (b < a) component[a] = b;
        }
    /* Ascending p: a root takes the next label; any other vertex's parent is
     * lower, so it already holds its root's label. */
    int count = 0;
    for (int p = 0; p < n; p++) component[p] = component[p] == p ? count++ : component[component[p]];
    return count;
}
