/*
 * normals.c: PCA normals (in parallel), their MST orientation, and on noisy
 * scans their smoothing (normals.h, normals_smooth.h).
 */
#include "features/normals.h"

#include "features/normals_outward.h"
#include "features/normals_smooth.h"
#include "util/control.h"
#include "util/sym3.h"
#include "util/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PCA_BLOCK 4096 /* points per work item of the PCA */
#define PCA_SHARE 0.6  /* progress share of the PCA; the orientation follows */
#define PROGRESS_STEP 65536 /* vertices between reports of the orientation */

/* n: the PCA normal of p and its neighbours.  Returns the noise ratio of
 * normals_smooth.h: their RMS distance to the PCA plane over p's mean edge
 * length (0 for an isolated point). */
static double pca_normal(const ps_graph *g, const double *points, size_t p, double n[3]) {
    double mean[3] = {0, 0, 0}, cov[3][3] = {{0}};
    size_t count = g->offsets[p + 1] - g->offsets[p] + 1;
    for (size_t e = g->offsets[p]; e <= g->offsets[p + 1]; e++) {
        const double *x = points + 3 * (e < g->offsets[p + 1] ? g->neighbors[e] : p);
        for (int i = 0; i < 3; i++) mean[i] += x[i] / (double)count;
    }
    for (size_t e = g->offsets[p]; e <= g->offsets[p + 1]; e++) {
        const double *x = points + 3 * (e < g->offsets[p + 1] ? g->neighbors[e] : p);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) cov[i][j] += (x[i] - mean[i]) * (x[j] - mean[j]);
    }
    double residual = sqrt(fmax(ps_sym3_smallest(cov, n), 0) / (double)count), edges = 0;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) edges += g->weights[e];
    return edges > 0 ? residual * (double)(count - 1) / edges : 0;
}

/* n made unit; a zero n becomes (1, 0, 0).  A given normal whose squared
 * length overflows or underflows (components near 1e300 or 1e-200) is
 * first divided by its largest component, so that its direction stays. */
static void normalize(double n[3]) {
    double len = sqrt(ps_dot3(n, n));
    if (!(len > 0) || isinf(len)) {
        double largest = fmax(fabs(n[0]), fmax(fabs(n[1]), fabs(n[2])));
        if (largest > 0) n[0] /= largest, n[1] /= largest, n[2] /= largest;
        len = sqrt(ps_dot3(n, n));
    }
    if (len > 0) n[0] /= len, n[1] /= len, n[2] /= len;
    else n[0] = 1, n[1] = n[2] = 0;
}

/* Prim's tree over the graph: an indexed 4-ary min-heap of the vertices
 * reached but not yet in the tree, keyed by (cost, vertex), each with the
 * tree vertex it would hang from. */
#define IN_TREE UINT32_MAX
#define UNREACHED (UINT32_MAX - 1)

typedef struct orient_walk {
    uint32_t *heap;    /* #P vertices, heap-ordered */
    uint32_t *pos;     /* #P heap slot, UNREACHED or IN_TREE */
    double *cost;      /* #P 1 - |n_parent . n_v| of the best edge so far */
    uint32_t *parent;  /* #P that edge's tree end */
    size_t len, reached;
    const ps_progress_span *span;
} orient_walk;

static int key_less(const orient_walk *w, uint32_t a, uint32_t b) {
    return w->cost[a] < w->cost[b] || (w->cost[a] == w->cost[b] && a < b);
}

static void heap_place(orient_walk *w, size_t i, uint32_t v) {
    w->heap[i] = v;
    w->pos[v] = (uint32_t)i;
}

static void sift_up(orient_walk *w, size_t i, uint32_t v) {
    while (i > 0 && key_less(w, v, w->heap[(i - 1) / 4])) {
        heap_place(w, i, w->heap[(i - 1) / 4]);
        i = (i - 1) / 4;
    }
    heap_place(w, i, v);
}

static uint32_t heap_pop(orient_walk *w) {
    uint32_t top = w->heap[0], v = w->heap[--w->len];
    size_t i = 0;
    for (;;) {
        size_t first = 4 * i + 1, last = first + 4 < w->len ? first + 4 : w->len, best = i;
        uint32_t best_v = v;
        for (size_t c = first; c < last; c++)
            if (key_less(w, w->heap[c], best_v)) best = c, best_v = w->heap[c];
        if (best == i) break;
        heap_place(w, i, best_v);
        i = best;
    }
    if (w->len > 0) heap_place(w, i, v);
    w->pos[top] = IN_TREE;
    return top;
}

/* q reached from tree vertex v at cost c: kept if cheaper than before. */
static void offer(orient_walk *w, uint32_t q, uint32_t v, double c) {
    if (w->pos[q] == UNREACHED) {
        w->cost[q] = c, w->parent[q] = v;
        sift_up(w, w->len++, q);
    } else if (c < w->cost[q]) {
        w->cost[q] = c, w->parent[q] = v;
        sift_up(w, w->pos[q], q);
    }
}

/* Prim's tree from root over its component: each vertex is flipped to
 * agree with its tree parent. */
static void orient_from(const ps_graph *g, uint32_t root, double *n, orient_walk *w) {
    w->cost[root] = 0, w->parent[root] = root;
    sift_up(w, w->len++, root);
    while (w->len > 0) {
        uint32_t v = heap_pop(w), up = w->parent[v];
        if (++w->reached % PROGRESS_STEP == 0)
            ps_control_progress(w->span->ctl, w->span->phase,
                                ps_progress_span_at(w->span, (double)w->reached / (double)g->n));
        if (v != up && ps_dot3(n + 3 * v, n + 3 * up) < 0)
            for (int i = 0; i < 3; i++) n[3 * v + i] = -n[3 * v + i];
        for (size_t e = g->offsets[v]; e < g->offsets[v + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (w->pos[q] != IN_TREE) offer(w, q, v, 1 - fabs(ps_dot3(n + 3 * v, n + 3 * q)));
        }
    }
}

/* Each component's centroid (#C by 3) and its root for the orientation
 * tree (#C): the point farthest from the centroid, which no rotation,
 * scaling or reordering of the points changes. */
static int component_centers(size_t n, const double *points, const int *component,
                             int n_components, double *centroid, uint32_t *root) {
    size_t *count = calloc((size_t)n_components, sizeof *count);
    double *far = malloc((size_t)n_components * sizeof *far);
    if (!count || !far) return free(count), free(far), -1;
    for (size_t p = 0; p < n; p++) {
        for (int i = 0; i < 3; i++) centroid[3 * component[p] + i] += points[3 * p + i];
        count[component[p]]++;
    }
    for (int c = 0; c < n_components; c++) {
        for (int i = 0; i < 3; i++) centroid[3 * c + i] /= (double)(count[c] ? count[c] : 1);
        root[c] = UINT32_MAX;
    }
    for (size_t p = 0; p < n; p++) {
        int c = component[p];
        double d[3];
        for (int i = 0; i < 3; i++) d[i] = points[3 * p + i] - centroid[3 * c + i];
        if (root[c] == UINT32_MAX || ps_dot3(d, d) > far[c]) root[c] = (uint32_t)p, far[c] = ps_dot3(d, d);
    }
    free(count), free(far);
    return 0;
}

/* PCA normals: each component's orientation spreads from its root over
 * the tree. */
static ps_status orient_components(const ps_graph *g, const uint32_t *root, int n_components,
                                   const ps_progress_span *span, double *normals, ps_error *err) {
    size_t alloc_n = g->n ? g->n : 1;
    orient_walk w = {malloc(alloc_n * sizeof *w.heap), malloc(alloc_n * sizeof *w.pos),
                     malloc(alloc_n * sizeof *w.cost), malloc(alloc_n * sizeof *w.parent),
                     0, 0, span};
    ps_status st = w.heap && w.pos && w.cost && w.parent
                       ? PS_OK
                       : ps_fail(err, PS_ERR_NOMEM, "normals: out of memory");
    for (size_t v = 0; st == PS_OK && v < g->n; v++) w.pos[v] = UNREACHED;
    for (int c = 0; st == PS_OK && c < n_components; c++) orient_from(g, root[c], normals, &w);
    free(w.heap), free(w.pos), free(w.cost), free(w.parent);
    return st;
}

/* Unit normals of a block of PCA_BLOCK points, each worker counting its
 * own noise histogram (counts: the sum does not depend on the workers). */
typedef struct pca_job {
    const ps_graph *g;
    const double *points, *given;
    double *normals;
    ps_noise_estimate *noise; /* #threads */
} pca_job;

static void pca_block(void *ctx, size_t block, int worker) {
    const pca_job *j = ctx;
    size_t end = (block + 1) * PCA_BLOCK < j->g->n ? (block + 1) * PCA_BLOCK : j->g->n;
    for (size_t p = block * PCA_BLOCK; p < end; p++) {
        if (j->given) memcpy(j->normals + 3 * p, j->given + 3 * p, 3 * sizeof *j->normals);
        else ps_noise_add(&j->noise[worker], pca_normal(j->g, j->points, p, j->normals + 3 * p));
        normalize(j->normals + 3 * p);
    }
}

/* Every point's unit normal (given or PCA) on threads, progress over span;
 * noise out: the PCA residuals' histogram. */
static ps_status unit_normals(const ps_graph *g, const double *points, const double *given,
                              int threads, const ps_progress_span *span, double *normals,
                              ps_noise_estimate *noise) {
    pca_job j = {g, points, given, normals, calloc((size_t)threads, sizeof *j.noise)};
    if (!j.noise) return PS_ERR_NOMEM;
    ps_status st = ps_parallel_for_tracked(threads, (g->n + PCA_BLOCK - 1) / PCA_BLOCK, 1,
                                           pca_block, &j, span);
    memset(noise, 0, sizeof *noise);
    for (int t = 0; t < threads; t++) {
        for (size_t b = 0; b < PS_NOISE_BINS; b++) noise->counts[b] += j.noise[t].counts[b];
        noise->n += j.noise[t].n;
    }
    free(j.noise);
    return st;
}

/* The unit normals made consistent (PCA normals along each component's
 * tree, progress over span) and outward per component. */
static ps_status orient_outward(const ps_normals_input *in, const ps_progress_span *span,
                                double *normals, ps_error *err) {
    size_t n = in->graph->n;
    int n_components = in->n_components;
    double *centroid = calloc(3 * (size_t)n_components, sizeof *centroid);
    uint32_t *root = malloc((size_t)n_components * sizeof *root);
    ps_status st = centroid && root &&
                           component_centers(n, in->points, in->component, n_components,
                                             centroid, root) == 0
                       ? PS_OK
                       : ps_fail(err, PS_ERR_NOMEM, "normals: out of memory");
    if (st == PS_OK && !in->given)
        st = orient_components(in->graph, root, n_components, span, normals, err);
    if (st == PS_OK && ps_normals_point_outward(in->graph, in->points, in->component,
                                                n_components, centroid, normals) != 0)
        st = ps_fail(err, PS_ERR_NOMEM, "normals: out of memory");
    free(centroid), free(root);
    return st;
}

ps_status ps_normals_build(const ps_normals_input *in, double *normals,
                           ps_normals_report *report, ps_error *err) {
    ps_progress_span untracked = {NULL, PS_PHASE_KNN, 0.0, 0.0};
    return ps_normals_build_tracked(in, 1, &untracked, normals, report, err);
}

ps_status ps_normals_build_tracked(const ps_normals_input *in, int threads,
                                   const ps_progress_span *span, double *normals,
                                   ps_normals_report *report, ps_error *err) {
    ps_noise_estimate noise;
    ps_progress_span pca = {span->ctl, span->phase, span->lo, ps_progress_span_at(span, PCA_SHARE)};
    ps_status pca_status = unit_normals(in->graph, in->points, in->given,
                                        ps_parallel_threads(threads), &pca, normals, &noise);
    if (pca_status == PS_ERR_CANCELLED) return ps_fail(err, pca_status, "normals: cancelled");
    if (pca_status != PS_OK) return ps_fail(err, pca_status, "normals: out of memory");
    ps_progress_span orient = {span->ctl, span->phase, pca.hi, span->hi};
    ps_status st = orient_outward(in, &orient, normals, err);
    double median = ps_noise_median(&noise);
    int iterations = in->given || !in->smooth ? 0 : ps_noise_iterations(median);
    if (report) report->smoothing = iterations, report->noise = median;
    if (st == PS_OK) st = ps_normals_smooth(in->graph, normals, iterations, threads, err);
    if (st == PS_OK) ps_control_progress(span->ctl, span->phase, span->hi);
    return st;
}
