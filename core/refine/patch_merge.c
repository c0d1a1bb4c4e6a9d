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

/* widest #n_groups out: each segment's neighbour with the most boundary
 * edges (ties: the lowest id), or -1; edges #n_groups scratch.  One pass
 * over the records. */
static void widest_neighbours(const ps_segment_graph *sg, int *widest, long *edges) {
    for (int a = 0; a < sg->n_groups; a++) widest[a] = -1, edges[a] = 0;
    for (size_t i = 0; i < sg->count; i++) {
        const ps_boundary *r = &sg->list[i];
        int ends[2] = {r->a, r->b};
        for (int k = 0; k < 2; k++) {
            int a = ends[k], other = ends[1 - k];
            if (r->edges > edges[a] || (r->edges == edges[a] && other < widest[a]))
                widest[a] = other, edges[a] = r->edges;
        }
    }
}

/* The smallest surviving segment under min_size points that has a
 * neighbour (*into: its widest), or -1. */
static int smallest_crumb(const ps_segment_graph *sg, const int *widest, double min_size,
                          int *into) {
    int best = -1;
    for (int a = 0; a < sg->n_groups; a++) {
        if (sg->alias[a] != a || sg->size[a] == 0 || widest[a] < 0) continue;
        if ((double)sg->size[a] >= min_size || (best >= 0 && sg->size[a] >= sg->size[best]))
            continue;
        best = a, *into = widest[a];
    }
    return best;
}

/* The flattest surviving segment over the threshold whose widest
 * neighbour (*into) is no smaller, or -1. */
static int flattest_patch(const ps_segment_graph *sg, const double *sum, const int *widest,
                          int *into) {
    int best = -1;
    double best_flatness = PS_PATCH_MERGE_FLATNESS;
    for (int a = 0; a < sg->n_groups; a++) {
        if (sg->alias[a] != a || sg->size[a] == 0) continue;
        const double *s = sum + 3 * a;
        double flatness = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]) / (double)sg->size[a];
        int b = widest[a];
        if (flatness <= best_flatness || b < 0 || sg->size[b] < sg->size[a]) continue;
        best = a, best_flatness = flatness, *into = b;
    }
    return best;
}

/* The next segment that is no part (crumbs first), or -1; *into: where it
 * goes. */
static int next_merge(const ps_merge_input *in, const ps_segment_graph *sg,
                      const double *sum, int *widest, long *edges, int *into) {
    widest_neighbours(sg, widest, edges);
    int a = smallest_crumb(sg, widest, PS_PATCH_MERGE_MIN_SHARE * (double)in->graph->n, into);
    if (a >= 0 || in->mean_angular < PS_CREASE_FLAT) return a; /* flat input: one patch */
    return flattest_patch(sg, sum, widest, into);
}

ps_status ps_patch_merge(const ps_merge_input *in, int *group_of_point,
                         int *group_of_leaf, ps_merge **merges, int *n_merges,
                         ps_error *err) {
    ps_segment_graph sg;
    ps_segment_graph_input sgi = {
        .graph = in->graph, .f = in->f, .group = group_of_point, .n_groups = in->n_groups,
        .threads = in->threads};
    ps_status st = ps_segment_graph_build_along(&sg, &sgi, in->boundary, err);
    size_t m = (size_t)(in->n_groups > 0 ? in->n_groups : 1);
    double *sum = st == PS_OK ? normal_sums(in, group_of_point) : NULL;
    int *widest = malloc(m * sizeof *widest);
    long *edges = malloc(m * sizeof *edges);
    if (st == PS_OK && (!sum || !widest || !edges))
        st = ps_fail(err, PS_ERR_NOMEM, "out of memory (patch merge)");
    for (int a, b; st == PS_OK && (a = next_merge(in, &sg, sum, widest, edges, &b)) >= 0;) {
        if (!ps_segment_graph_merge(&sg, a, b, merges, n_merges))
            st = ps_fail(err, PS_ERR_NOMEM, "out of memory (patch merge)");
        for (int i = 0; i < 3; i++) sum[3 * b + i] += sum[3 * a + i];
    }
    if (st == PS_OK) ps_segment_graph_apply(&sg, group_of_point, in->graph->n, group_of_leaf);
    ps_segment_graph_free(&sg);
    free(sum), free(widest), free(edges);
    return st;
}
