/*
 * result.c: builds the public ps_result.  Final segments are the groups the
 * refinement left (hierarchy leaves and what merged into them, with the
 * points the boundary cut moved), numbered by decreasing size in input
 * points, ties by their lowest input point, so the labels do not depend on
 * the order the phases visited anything.  A supernode's segment is its
 * sink's, the segment of its points (for a sink among the points added on
 * the faces, surface_fill.h: of its stand-in, a caller's point of the same
 * supernode); sizes, feature sizes and supernode lists are counted from
 * the points' groups, sizes over the caller's points only.
 */
#include "result.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct group_order {
    int group;           /* surviving leaf id */
    size_t size;         /* input points */
    size_t first_point;  /* lowest input index */
} group_order;

static int by_size_then_first(const void *a, const void *b) {
    const group_order *x = a, *y = b;
    if (x->size != y->size) return x->size > y->size ? -1 : 1;
    return (x->first_point > y->first_point) - (x->first_point < y->first_point);
}

/* segment_of_group #n_tree: final label of each group id (-1 when no point
 * is in it). */
static int number_segments(const ps_result_parts *pp, int *segment_of_group) {
    int n_tree = pp->n_tree;
    group_order *order = calloc((size_t)n_tree, sizeof *order);
    if (!order) return -1;
    for (int t = 0; t < n_tree; t++) {
        segment_of_group[t] = -1;
        order[t] = (group_order){.group = t, .size = 0, .first_point = SIZE_MAX};
    }
    for (size_t i = 0; i < pp->n_input; i++) {
        group_order *g = &order[pp->group_of_point[pp->unique_of[i]]];
        if (g->size++ == 0) g->first_point = i;
    }
    qsort(order, (size_t)n_tree, sizeof *order, by_size_then_first);
    int n_segments = 0;
    while (n_segments < n_tree && order[n_segments].size > 0) {
        segment_of_group[order[n_segments].group] = n_segments;
        n_segments++;
    }
    free(order);
    return n_segments;
}

static void fill_points(const ps_result_parts *pp, const int *segment_of_group, ps_result *r) {
    for (size_t i = 0; i < pp->n_input; i++) {
        size_t u = pp->unique_of[i];
        int s = pp->supernode_of[u];
        r->point_supernode[i] = s;
        r->centrality[i] = pp->f[u];
        r->labels[i] = segment_of_group[pp->group_of_point[u]];
        ps_segment_info *seg = &r->segments[r->labels[i]];
        seg->size++;
        r->supernodes[s].size++;
    }
}

/* nearest #S out: each supernode's caller's point whose f is nearest its
 * sink's (ties: the lowest), SIZE_MAX for a supernode with none. */
static void nearest_members(const ps_result_parts *pp, size_t *nearest) {
    for (int s = 0; s < pp->n_supernodes; s++) nearest[s] = SIZE_MAX;
    for (size_t i = 0; i < pp->n_input; i++) {
        uint32_t u = pp->unique_of[i];
        int s = pp->supernode_of[u];
        double sink_f = pp->f[pp->sinks[s]];
        if (nearest[s] == SIZE_MAX ||
            fabs(pp->f[u] - sink_f) < fabs(pp->f[pp->unique_of[nearest[s]]] - sink_f))
            nearest[s] = i;
    }
}

/* The input point that stands for supernode s's sink: its lowest input
 * index; for a sink among the points added on the faces, its host vertex
 * when that is in s (or s holds none of the caller's points), else s's
 * point nearest it in f (nearest_members), so that a supernode lies in
 * the segment of its points. */
static size_t sink_stand_in(const ps_result_parts *pp, int s, const size_t *nearest) {
    size_t i = pp->first_of[pp->sinks[s]];
    if (i < pp->n_input) return i;
    size_t host = pp->host_of_added[i - pp->n_input];
    int host_in_s = pp->supernode_of[pp->unique_of[host]] == s;
    return host_in_s || nearest[s] == SIZE_MAX ? host : nearest[s];
}

/* nearest: nearest_members's, NULL when no point was added on the faces. */
static void fill_supernodes(const ps_result_parts *pp, const int *segment_of_group,
                            const size_t *nearest, ps_result *r) {
    for (int s = 0; s < pp->n_supernodes; s++) {
        uint32_t sink = pp->sinks[s];
        ps_supernode *sn = &r->supernodes[s];
        sn->sink = sink_stand_in(pp, s, nearest);
        sn->centrality = pp->f[sink];
        sn->is_minimum = pp->is_minimum[s];
        sn->segment = segment_of_group[pp->group_of_point[pp->unique_of[sn->sink]]];
        r->segments[sn->segment].n_supernodes++;
    }
}

/* Feature sizes over the distinct points, supernode lists, tree leaf ids. */
static int fill_segments(const ps_result_parts *pp, const int *segment_of_group, ps_result *r) {
    int n = r->n_segments;
    double *lo = malloc((size_t)n * sizeof *lo), *hi = malloc((size_t)n * sizeof *hi);
    int ok = lo && hi;
    for (int g = 0; ok && g < n; g++) {
        ps_segment_info *seg = &r->segments[g];
        seg->supernodes = malloc((size_t)(seg->n_supernodes ? seg->n_supernodes : 1) *
                                 sizeof *seg->supernodes);
        ok = seg->supernodes != NULL;
        seg->n_supernodes = 0;
        lo[g] = 1e300, hi[g] = -1e300;
    }
    for (int s = 0; ok && s < pp->n_supernodes; s++) {
        ps_segment_info *seg = &r->segments[r->supernodes[s].segment];
        seg->supernodes[seg->n_supernodes++] = s;
    }
    for (size_t u = 0; ok && u < pp->n_unique; u++) {
        int g = segment_of_group[pp->group_of_point[u]];
        if (g < 0) continue; /* added points only */
        if (pp->f[u] < lo[g]) lo[g] = pp->f[u];
        if (pp->f[u] > hi[g]) hi[g] = pp->f[u];
    }
    for (int t = 0; ok && t < pp->n_tree; t++)
        if (pp->group_of_leaf[t] == t && segment_of_group[t] >= 0)
            r->segments[segment_of_group[t]].tree_node = t;
    for (int g = 0; ok && g < n; g++) r->segments[g].feature_size = hi[g] - lo[g];
    free(lo);
    free(hi);
    return ok ? 0 : -1;
}

static int allocate(ps_result *r, const ps_result_parts *pp, int n_segments) {
    size_t n = pp->n_input;
    r->labels = malloc(n * sizeof *r->labels);
    r->point_supernode = malloc(n * sizeof *r->point_supernode);
    r->centrality = malloc(n * sizeof *r->centrality);
    r->supernodes = calloc((size_t)pp->n_supernodes + 1, sizeof *r->supernodes);
    r->segments = calloc((size_t)n_segments + 1, sizeof *r->segments);
    r->merges = malloc(((size_t)pp->n_merges + 1) * sizeof *r->merges);
    return r->labels && r->point_supernode && r->centrality && r->supernodes && r->segments &&
                   r->merges
               ? 0
               : -1;
}

ps_status ps_result_build(const ps_result_parts *pp, const ps_params *params,
                          ps_result **out, ps_error *err) {
    ps_result *r = calloc(1, sizeof *r);
    int *segment_of_group = malloc((size_t)pp->n_tree * sizeof *segment_of_group);
    size_t *nearest = pp->host_of_added
                          ? malloc(((size_t)pp->n_supernodes + 1) * sizeof *nearest)
                          : NULL;
    int n_segments = -1;
    if (r && segment_of_group && (nearest || !pp->host_of_added))
        n_segments = number_segments(pp, segment_of_group);
    int ok = n_segments > 0 && allocate(r, pp, n_segments) == 0;
    if (ok) {
        if (nearest) nearest_members(pp, nearest);
        r->n_points = pp->n_input;
        r->dim = pp->dim;
        r->n_components = pp->n_components;
        r->normal_smoothing = pp->normal_smoothing;
        r->n_filled = pp->n_filled;
        r->n_outliers = pp->n_outliers;
        r->n_supernodes = pp->n_supernodes;
        r->n_segments = n_segments;
        r->params = *params;
        fill_supernodes(pp, segment_of_group, nearest, r);
        fill_points(pp, segment_of_group, r);
        ok = fill_segments(pp, segment_of_group, r) == 0;
        memcpy(r->merges, pp->merges, (size_t)pp->n_merges * sizeof *r->merges);
        r->n_merges = pp->n_merges;
    }
    free(segment_of_group);
    free(nearest);
    if (!ok) {
        ps_result_free(r);
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (result)");
    }
    r->tree = pp->tree;
    r->n_tree_nodes = pp->n_tree;
    *out = r;
    return PS_OK;
}

void ps_result_free(ps_result *r) {
    if (!r) return;
    free(r->labels);
    free(r->point_supernode);
    free(r->centrality);
    free(r->supernodes);
    for (int g = 0; r->segments && g < r->n_segments; g++) free(r->segments[g].supernodes);
    free(r->segments);
    for (int t = 0; r->tree && t < r->n_tree_nodes; t++) free(r->tree[t].supernodes);
    free(r->tree);
    free(r->merges);
    free(r);
}
