/*
 * patch_merge.c: crumbs and nearly flat segments merge into the neighbour
 * they share the most boundary with (patch_merge.h), over the adjacency of
 * segment_graph.h and each segment's sum of unit normals.
 */
#include "refine/patch_merge.h"

#include "features/crease.h"
#include "refine/segment_graph.h"

#include <math.h>
#include <stdlib.h>

/* sum #n_groups by 3: each segment's sum of normals. */
static double *normal_sums(const ps_merge_input *in, const int *group) {
    double *sum = calloc(3 * (size_t)(in->n_groups > 0 ? in->n_groups : 1), sizeof *sum);
    for (size_t p = 0; sum && p < in->graph->n; p++)
        for (int i = 0; i < 3; i++) sum[3 * group[p] + i] += in->normals[3 * p + i];
    return sum;
}

/* Each segment's widest boundary: its neighbour with the most boundary
 * edges (ties: the lowest id), or -1, and that boundary's record. */
typedef struct widest_boundaries {
    int *neighbour; /* #n_groups */
    long *edges;    /* #n_groups */
    size_t *record; /* #n_groups */
} widest_boundaries;

/* w's arrays for sg, in one pass over the records. */
static void widest_neighbours(const ps_segment_graph *sg, widest_boundaries *w) {
    for (int a = 0; a < sg->n_groups; a++) w->neighbour[a] = -1, w->edges[a] = 0;
    for (size_t i = 0; i < sg->count; i++) {
        const ps_boundary *r = &sg->list[i];
        int ends[2] = {r->a, r->b};
        for (int k = 0; k < 2; k++) {
            int a = ends[k], other = ends[1 - k];
            if (r->edges > w->edges[a] || (r->edges == w->edges[a] && other < w->neighbour[a]))
                w->neighbour[a] = other, w->edges[a] = r->edges, w->record[a] = i;
        }
    }
}

/* The smallest surviving segment under min_size points that has a
 * neighbour (*into: its widest), or -1. */
static int smallest_crumb(const ps_segment_graph *sg, const widest_boundaries *w,
                          double min_size, int *into) {
    int best = -1;
    for (int a = 0; a < sg->n_groups; a++) {
        if (sg->alias[a] != a || sg->size[a] == 0 || w->neighbour[a] < 0) continue;
        if ((double)sg->size[a] >= min_size || (best >= 0 && sg->size[a] >= sg->size[best]))
            continue;
        best = a, *into = w->neighbour[a];
    }
    return best;
}

/* The flattest surviving segment over the threshold whose widest
 * neighbour (*into) is no smaller and which does not stick out of their
 * boundary, or -1. */
static int flattest_patch(const ps_segment_graph *sg, const double *sum,
                          const widest_boundaries *w, int *into) {
    int best = -1;
    double best_flatness = PS_PATCH_MERGE_FLATNESS;
    for (int a = 0; a < sg->n_groups; a++) {
        if (sg->alias[a] != a || sg->size[a] == 0) continue;
        const double *s = sum + 3 * a;
        double flatness = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / (double)sg->size[a];
        int b = w->neighbour[a];
        if (flatness <= best_flatness || b < 0 || sg->size[b] < sg->size[a]) continue;
        if (ps_segment_protrudes(sg, a, &sg->list[w->record[a]], PS_PATCH_MERGE_PROTRUSION))
            continue;
        best = a, best_flatness = flatness, *into = b;
    }
    return best;
}

/* The next segment that is no part (crumbs first), or -1; *into: where it
 * goes. */
static int next_merge(const ps_merge_input *in, const ps_segment_graph *sg,
                      const double *sum, widest_boundaries *w, int *into) {
    widest_neighbours(sg, w);
    int a = smallest_crumb(sg, w, PS_PATCH_MERGE_MIN_SHARE * (double)in->graph->n, into);
    if (a >= 0 || in->mean_angular < PS_CREASE_FLAT) return a; /* flat input: one patch */
    return flattest_patch(sg, sum, w, into);
}

ps_status ps_patch_merge(const ps_merge_input *in, int *group_of_point,
                         int *group_of_leaf, ps_merge **merges, int *n_merges,
                         ps_error *err) {
    ps_segment_graph sg;
    ps_segment_graph_input sgi = {
        .graph = in->graph, .f = in->f, .points = in->points, .group = group_of_point,
        .n_groups = in->n_groups, .threads = in->threads};
    ps_status st = ps_segment_graph_build_along(&sg, &sgi, in->boundary, err);
    size_t m = (size_t)(in->n_groups > 0 ? in->n_groups : 1);
    double *sum = st == PS_OK ? normal_sums(in, group_of_point) : NULL;
    widest_boundaries w = {malloc(m * sizeof *w.neighbour), malloc(m * sizeof *w.edges),
                           malloc(m * sizeof *w.record)};
    if (st == PS_OK && (!sum || !w.neighbour || !w.edges || !w.record))
        st = ps_fail(err, PS_ERR_NOMEM, "out of memory (patch merge)");
    for (int a, b; st == PS_OK && (a = next_merge(in, &sg, sum, &w, &b)) >= 0;) {
        if (!ps_segment_graph_merge(&sg, a, b, merges, n_merges))
            st = ps_fail(err, PS_ERR_NOMEM, "out of memory (patch merge)");
        for (int i = 0; i < 3; i++) sum[3 * b + i] += sum[3 * a + i];
    }
    if (st == PS_OK) ps_segment_graph_apply(&sg, group_of_point, in->graph->n, group_of_leaf);
    ps_segment_graph_free(&sg);
    free(sum), free(w.neighbour), free(w.edges), free(w.record);
    return st;
}
