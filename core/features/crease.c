/*
 * crease.c: the concavity-aware edge lengths and crease strengths of
 * crease.h, on all cores.  The sums behind their means are taken per block
 * of CREASE_BLOCK points and added in block order, so the result does not
 * depend on the thread count.
 */
#include "features/crease.h"

#include "graph/dijkstra.h"
#include "util/parallel.h"
#include "util/sort_util.h"

#include <stdlib.h>
#include <string.h>

#define CREASE_BLOCK 4096

/* One pass over blocks of points: sums[SUMS b + i] is block b's sum i
 * (what they are depends on the pass). */
typedef struct crease_pass {
    const ps_graph *g;
    double *weights;          /* the weights pass: g's weights, rewritten */
    const double *points, *normals;
    double L, A;              /* the weights pass: the metric's means */
    double *spacing;          /* the sums pass: #P mean edge length of each point, or NULL */
    ps_crease_points *cp;     /* the strengths pass */
    double *sums;             /* #blocks by SUMS */
} crease_pass;

#define SUMS 3

static size_t block_count(size_t n) {
    return (n + CREASE_BLOCK - 1) / CREASE_BLOCK;
}

/* One past the last point of block b of n points. */
static size_t block_end(size_t n, size_t b) {
    return (b + 1) * CREASE_BLOCK < n ? (b + 1) * CREASE_BLOCK : n;
}

static inline double arc_angular(const crease_pass *c, size_t p, size_t e, double eta) {
    size_t q = c->g->neighbors[e];
    return ps_crease_angular(c->points + 3 * p, c->normals + 3 * p, c->points + 3 * q,
                             c->normals + 3 * q, eta);
}

/* Each block's sums of edge lengths, of the metric's angular terms and of
 * the concave ones (the same while PS_CREASE_ETA_CONVEX is 0), and each
 * point's spacing when asked; in the weights pass each arc's weight is
 * then replaced by its angular term, which the weighing reads back (the
 * length it recomputes from the points); a ps_range_fn over blocks. */
static void sum_blocks(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    crease_pass *c = ctx;
    const ps_graph *g = c->g;
    for (size_t b = begin; b < end; b++) {
        double len = 0, ang = 0, concave = 0;
        for (size_t p = b * CREASE_BLOCK, end_p = block_end(g->n, b); p < end_p; p++) {
            double row = 0;
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
                double a0 = arc_angular(c, p, e, 0.0);
                double term = PS_CREASE_ETA_CONVEX == 0 ? a0
                                                        : arc_angular(c, p, e, PS_CREASE_ETA_CONVEX);
                len += g->weights[e];
                row += g->weights[e];
                ang += term;
                concave += a0;
                if (c->weights) c->weights[e] = term;
            }
            size_t degree = g->offsets[p + 1] - g->offsets[p];
            if (c->spacing) c->spacing[p] = degree ? row / (double)degree : 0.0;
        }
        c->sums[SUMS * b] = len, c->sums[SUMS * b + 1] = ang, c->sums[SUMS * b + 2] = concave;
    }
}

/* |p q|, the weight the kNN graph gave arc e out of p (ps_knn_distance's
 * sum in the same order). */
static double arc_length(const crease_pass *c, size_t p, size_t e) {
    return ps_distance3(c->points + 3 * p, c->points + 3 * (size_t)c->g->neighbors[e]);
}

/* The metric's weights of the arcs out of points [begin, end), from their
 * angular terms in the weights and their lengths. */
static void weigh_points(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    crease_pass *c = ctx;
    const ps_graph *g = c->g;
    double *w = c->weights;
    const double delta = PS_CREASE_DELTA;
    for (size_t p = begin; p < end; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            w[e] = delta * arc_length(c, p, e) + (1 - delta) * c->L * w[e] / c->A;
            if (!(w[e] > 0)) w[e] = 1e-12 * c->L;
        }
}

/* The lengths back in the weights of the arcs out of points [begin, end)
 * (a flat surface keeps them). */
static void restore_lengths(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    crease_pass *c = ctx;
    for (size_t p = begin; p < end; p++)
        for (size_t e = c->g->offsets[p]; e < c->g->offsets[p + 1]; e++)
            c->weights[e] = arc_length(c, p, e);
}

/* Each point's strength, and each block's sum of angular terms (eta 0). */
static void strength_blocks(void *ctx, size_t begin, size_t end, int worker) {
    (void)worker;
    crease_pass *c = ctx;
    const ps_graph *g = c->g;
    for (size_t b = begin; b < end; b++) {
        double sum = 0;
        for (size_t p = b * CREASE_BLOCK, end_p = block_end(g->n, b); p < end_p; p++) {
            double most = 0;
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
                double ang = arc_angular(c, p, e, 0.0);
                sum += ang;
                if (ang > most) most = ang;
            }
            c->cp->strength[p] = most;
        }
        c->sums[SUMS * b] = sum, c->sums[SUMS * b + 1] = c->sums[SUMS * b + 2] = 0;
    }
}

/* Runs fn over the blocks of g's points; out[i]: sum i over all blocks,
 * in block order.  -1 when out of memory. */
static int over_blocks(crease_pass *c, int threads, ps_range_fn fn, double out[SUMS]) {
    size_t blocks = block_count(c->g->n);
    c->sums = malloc(SUMS * (blocks ? blocks : 1) * sizeof *c->sums);
    if (!c->sums) return -1;
    ps_parallel_for(ps_parallel_threads(threads), blocks, 1, fn, c);
    for (int i = 0; i < SUMS; i++) out[i] = 0;
    for (size_t b = 0; b < blocks; b++)
        for (int i = 0; i < SUMS; i++) out[i] += c->sums[SUMS * b + (size_t)i];
    free(c->sums);
    return 0;
}

/* The sums pass: c's metric means L and A, the scales, and the spacings
 * when asked. */
static ps_status measure(crease_pass *c, int threads, ps_edge_scales *scales, ps_error *err) {
    double edges = (double)c->g->offsets[c->g->n], sums[SUMS];
    *scales = (ps_edge_scales){0, 0};
    if (edges == 0) {
        for (size_t p = 0; c->spacing && p < c->g->n; p++) c->spacing[p] = 0.0;
        return PS_OK;
    }
    if (over_blocks(c, threads, sum_blocks, sums) != 0)
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (crease metric)");
    c->L = sums[0] / edges, c->A = sums[1] / edges;
    *scales = (ps_edge_scales){.mean_length = c->L, .mean_concave = sums[2] / edges};
    return PS_OK;
}

ps_status ps_crease_scales(const ps_graph *g, const double *points, const double *normals,
                           int threads, ps_edge_scales *scales, ps_error *err) {
    crease_pass c = {.g = g, .points = points, .normals = normals};
    return measure(&c, threads, scales, err);
}

ps_status ps_crease_weights(ps_graph *g, const double *points, const double *normals,
                            int threads, ps_edge_scales *scales, double *spacing, ps_error *err) {
    crease_pass c = {.g = g, .weights = g->weights, .points = points, .normals = normals,
                     .spacing = spacing};
    ps_edge_scales measured;
    ps_status st = measure(&c, threads, &measured, err);
    if (scales) *scales = measured;
    if (st != PS_OK) return st;
    /* A flat surface (or one without arcs: A is left at 0) keeps its lengths. */
    ps_range_fn pass = c.A < PS_CREASE_FLAT ? restore_lengths : weigh_points;
    ps_parallel_for(ps_parallel_threads(threads), g->n, 0, pass, &c);
    return PS_OK;
}

ps_status ps_crease_median(size_t n, ps_crease_points *cp, ps_error *err) {
    cp->median = 0;
    if (n == 0) return PS_OK;
    double *copy = malloc(n * sizeof *copy);
    if (!copy) return ps_fail(err, PS_ERR_NOMEM, "out of memory (crease strengths)");
    memcpy(copy, cp->strength, n * sizeof *copy);
    cp->median = ps_select_kth(copy, n, (n - 1) / 2);
    free(copy);
    return PS_OK;
}

ps_status ps_crease_strengths(const ps_graph *g, const double *points, const double *normals,
                              int threads, ps_crease_points *cp, ps_error *err) {
    crease_pass c = {.g = g, .points = points, .normals = normals, .cp = cp};
    double sums[SUMS];
    if (over_blocks(&c, threads, strength_blocks, sums) != 0)
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (crease strengths)");
    cp->mean = g->offsets[g->n] ? sums[0] / (double)g->offsets[g->n] : 0;
    return ps_crease_median(g->n, cp, err);
}

int ps_crease_scale_iterations(int noisy, int smoothed) {
    if (noisy && smoothed == 0) return 0;
    return smoothed >= PS_CREASE_SCALE_SMOOTHING ? 0 : PS_CREASE_SCALE_SMOOTHING - smoothed;
}
