/*
 * ncut.c: phase 2 (ncut.h): geodesic distances between sinks, the supernode
 * similarity W, then the bisection tree of ncut_tree.c.
 *
 * Sink distances (an approximation, instead of one Dijkstra per sink):
 *   1. ONE multi-source Dijkstra from all sinks gives each vertex its
 *      nearest sink (its cell) and dist to it; components never touch, so
 *      the one run serves every component.
 *   2. Each kNN edge (p, q) joining two cells is a path sink(p) ~> p - q ~>
 *      sink(q) of length dist[p] + |p q| + dist[q]; the shortest one per
 *      pair of cells is an edge of a small "sink graph".
 *   3. d(u, v) is the shortest path on the sink graph (a Dijkstra from each
 *      sink, in parallel).
 * Every sink-graph path is a real path, so d >= the geodesic distance; d is
 * exact when a shortest geodesic from u to v only crosses u's and v's cells
 * (adjacent cells), and otherwise pays a detour through the sinks of the
 * cells in between.  Cost: one Dijkstra on the points, m on the sink graph,
 * O(m^2) memory for the dense W (m = supernodes, not points).
 *
 * W(u, v) = s_u s_v exp(-d(u, v) / sigma_c), W(u, u) = s_u^2, 0 across
 * components, with sigma_c = PS_NCUT_SIGMA_SCALE (ncut.h) * the mean
 * distance between two sinks of component c (component_sigma() below): a
 * length of the shape itself, so labels change neither with the scale nor
 * with how many sinks the shape happens to have (a sigma tied to the sink
 * spacing made the segment count grow with the number of sinks).
 */
#include "hierarchy/ncut.h"

#include "graph/dijkstra.h"
#include "hierarchy/ncut_tree.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>

typedef struct all_pairs_job {
    const ps_graph *sink_graph;
    ps_dijkstra **work; /* one workspace per worker */
    double *D;          /* #S by #S out */
    int m;
} all_pairs_job;

static ps_status cells(const ps_graph *g, const ps_supernode_graph *sg, double *dist,
                       int *owner, ps_error *err) {
    ps_dijkstra *w = ps_dijkstra_new(g->n);
    if (!w) return ps_fail(err, PS_ERR_NOMEM, "ncut: out of memory for Dijkstra");
    ps_dijkstra_run(w, g, sg->sinks, (size_t)sg->m, dist, owner);
    ps_dijkstra_free(w);
    return PS_OK;
}

static void relax(double *D, int m, int a, int b, double length) {
    if (length < D[(size_t)a * m + b]) D[(size_t)a * m + b] = D[(size_t)b * m + a] = length;
}

/* D #S by #S: shortest cell-border path between adjacent sinks, INFINITY
 * elsewhere, 0 on the diagonal (and between two supernodes sharing a sink). */
static void border_lengths(const ps_graph *g, const ps_supernode_graph *sg,
                           const double *dist, const int *owner, double *D) {
    int m = sg->m;
    for (size_t i = 0; i < (size_t)m * m; i++) D[i] = INFINITY;
    for (int u = 0; u < m; u++) {
        D[(size_t)u * m + u] = 0;
        int cell = owner[sg->sinks[u]];
        if (cell != u && cell >= 0) relax(D, m, u, cell, 0);
    }
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            int a = owner[p], b = owner[q];
            if (q > p && a >= 0 && b >= 0 && a != b)
                relax(D, m, a, b, dist[p] + g->weights[e] + dist[q]);
        }
}

/* The finite off-diagonal entries of D as a CSR graph. */
static ps_status sink_graph_from(const double *D, int m, ps_graph *sgraph, ps_error *err) {
    size_t edges = 0;
    for (size_t i = 0; i < (size_t)m * m; i++) edges += isfinite(D[i]) && i % (m + 1) != 0;
    sgraph->n = (size_t)m;
    sgraph->offsets = malloc(((size_t)m + 1) * sizeof *sgraph->offsets);
    sgraph->neighbors = malloc((edges ? edges : 1) * sizeof *sgraph->neighbors);
    sgraph->weights = malloc((edges ? edges : 1) * sizeof *sgraph->weights);
    if (!sgraph->offsets || !sgraph->neighbors || !sgraph->weights)
        return ps_fail(err, PS_ERR_NOMEM, "ncut: out of memory for the sink graph");
    size_t e = 0;
    for (int u = 0; u < m; u++) {
        sgraph->offsets[u] = e;
        for (int v = 0; v < m; v++) {
            double length = D[(size_t)u * m + v];
            if (v == u || !isfinite(length)) continue;
            sgraph->neighbors[e] = (uint32_t)v;
            sgraph->weights[e++] = length;
        }
    }
    sgraph->offsets[m] = e;
    return PS_OK;
}

static void all_pairs_range(void *ctx, size_t begin, size_t end, int worker) {
    all_pairs_job *job = ctx;
    for (size_t u = begin; u < end; u++) {
        uint32_t source = (uint32_t)u;
        ps_dijkstra_run(job->work[worker], job->sink_graph, &source, 1,
                        job->D + u * (size_t)job->m, NULL);
    }
}

/* Overwrites D with all-pairs shortest paths on sgraph, made exactly
 * symmetric (the two directions can differ in the last bit). */
static ps_status all_pairs(const ps_graph *sgraph, double *D, int m, int threads,
                           ps_error *err) {
    int workers = ps_parallel_threads(threads);
    all_pairs_job job = {.sink_graph = sgraph, .D = D, .m = m};
    job.work = calloc((size_t)workers, sizeof *job.work);
    ps_status st = job.work ? PS_OK : PS_ERR_NOMEM;
    for (int t = 0; t < workers && st == PS_OK; t++)
        if (!(job.work[t] = ps_dijkstra_new((size_t)m))) st = PS_ERR_NOMEM;
    if (st == PS_OK) ps_parallel_for(workers, (size_t)m, 0, all_pairs_range, &job);
    for (int t = 0; job.work && t < workers; t++) ps_dijkstra_free(job.work[t]);
    free(job.work);
    if (st != PS_OK) return ps_fail(err, st, "ncut: out of memory for sink distances");
    for (int u = 0; u < m; u++)
        for (int v = 0; v < u; v++) {
            double d = fmin(D[(size_t)u * m + v], D[(size_t)v * m + u]);
            D[(size_t)u * m + v] = D[(size_t)v * m + u] = d;
        }
    return PS_OK;
}

/* D #S by #S: geodesic distances between sinks (INFINITY across components). */
static ps_status sink_distances(const ps_graph *g, const ps_supernode_graph *sg,
                                int threads, double *D, ps_error *err) {
    double *dist = malloc(g->n * sizeof *dist);
    int *owner = malloc(g->n * sizeof *owner);
    ps_graph sgraph = {0};
    ps_status st = dist && owner ? cells(g, sg, dist, owner, err)
                                 : ps_fail(err, PS_ERR_NOMEM, "ncut: out of memory");
    if (st == PS_OK) {
        border_lengths(g, sg, dist, owner, D);
        st = sink_graph_from(D, sg->m, &sgraph, err);
    }
    free(dist);
    free(owner);
    if (st == PS_OK) st = all_pairs(&sgraph, D, sg->m, threads, err);
    ps_graph_free(&sgraph);
    return st;
}

/* sigma #C out (C = max component + 1), see PS_NCUT_SIGMA_SCALE; 1 for a
 * component with no two distinct sinks (its sigma is never used then).
 * count #C scratch. */
static void component_sigma(const double *D, int m, const int *component, int n_comp,
                            double *sigma, double *count) {
    for (int c = 0; c < n_comp; c++) sigma[c] = count[c] = 0;
    for (int u = 0; u < m; u++)
        for (int v = u + 1; v < m; v++) {
            double d = D[(size_t)u * m + v];
            if (component[v] != component[u] || !isfinite(d)) continue;
            sigma[component[u]] += d;
            count[component[u]]++;
        }
    for (int c = 0; c < n_comp; c++) {
        double mean = count[c] ? sigma[c] / count[c] : 0;
        sigma[c] = mean > 0 ? PS_NCUT_SIGMA_SCALE * mean : 1;
    }
}

/* Turns D (#S by #S distances) into W in place. */
static void similarity(double *D, int m, const size_t *sizes, const int *component,
                       const double *sigma) {
    for (int u = 0; u < m; u++)
        for (int v = 0; v < m; v++) {
            double *x = &D[(size_t)u * m + v], s = (double)sizes[u] * (double)sizes[v];
            if (u == v) *x = s;
            else if (component[u] != component[v] || !isfinite(*x)) *x = 0;
            else *x = s * exp(-*x / sigma[component[u]]);
        }
}

static ps_status build_similarity(const ps_graph *g, const ps_supernode_graph *sg,
                                  int threads, const int *component, double *W,
                                  ps_error *err) {
    int n_comp = 0;
    for (int u = 0; u < sg->m; u++)
        if (component[u] >= n_comp) n_comp = component[u] + 1;
    double *sigma = malloc((size_t)n_comp * sizeof *sigma);
    double *count = malloc((size_t)n_comp * sizeof *count);
    ps_status st = sigma && count ? sink_distances(g, sg, threads, W, err)
                                  : ps_fail(err, PS_ERR_NOMEM, "ncut: out of memory");
    if (st == PS_OK) {
        component_sigma(W, sg->m, component, n_comp, sigma, count);
        similarity(W, sg->m, sg->sizes, component, sigma);
    }
    free(sigma);
    free(count);
    return st;
}

ps_status ps_ncut_hierarchy(const ps_graph *g, const ps_supernode_graph *sg,
                            double ncut_threshold, int threads,
                            const ps_control *ctl, ps_tree_node **tree,
                            int *n_tree, ps_error *err) {
    *tree = NULL;
    *n_tree = 0;
    int m = sg->m;
    if (m < 1) return ps_fail(err, PS_ERR_INVALID, "ncut: no supernodes");
    for (int u = 0; u < m; u++)
        if (sg->sizes[u] < 1 || sg->sinks[u] >= g->n)
            return ps_fail(err, PS_ERR_INVALID, "ncut: supernode %d is empty or its sink "
                           "is not a vertex", u);
    double *W = malloc((size_t)m * m * sizeof *W);
    int *component = malloc((size_t)m * sizeof *component);
    if (!W || !component) {
        free(W);
        free(component);
        return ps_fail(err, PS_ERR_NOMEM, "ncut: out of memory for %d supernodes", m);
    }
    for (int u = 0; u < m; u++) component[u] = sg->component[sg->sinks[u]];
    ps_status st = build_similarity(g, sg, threads, component, W, err);
    if (st == PS_OK)
        st = ps_ncut_tree_build(W, m, component, ncut_threshold, ctl, tree, n_tree, err);
    free(W);
    free(component);
    return st;
}
