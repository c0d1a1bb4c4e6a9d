/*
 * refine.c: phase 3 (refine.h): segments with a small feature merge into a
 * neighbour.
 *
 * Segments start as the hierarchy leaves and keep the id of their surviving
 * leaf.  Their borders and f ranges are those of segment_graph.h (for each
 * pair of adjacent segments, the number of kNN edges joining their points,
 * each undirected edge once; combined when two segments merge).  Each step
 * takes the segment with the smallest feature size
 * (ties: lowest leaf id) that is below feature_threshold * (range of f over
 * its component) and has a neighbour, and merges it into the neighbour with
 * the largest (shared border edges) * (neighbour's feature size): a long
 * border with a large part wins (ties: lowest id).  The survivor's feature
 * size becomes max f - min f over the union.  A step costs O(segments +
 * adjacent pairs); a segment alone in its component never merges.
 */
#include "refine/refine.h"

#include "features/component_range.h"
#include "refine/segment_graph.h"

#include <stdlib.h>

/* The leaves' merge thresholds over segment_graph.h's adjacency. */
typedef struct segments {
    ps_segment_graph graph;  /* groups = tree ids; only leaves have points */
    double *threshold;       /* #n_tree merge below this feature size */
    int *has_border;         /* #n_tree scratch: 1 when some pair record holds it */
} segments;

static double feature_size(const segments *s, int id) {
    return s->graph.f_max[id] - s->graph.f_min[id];
}

static void segments_free(segments *s) {
    ps_segment_graph_free(&s->graph);
    free(s->threshold);
    free(s->has_border);
}

/* #S = the largest supernode id in the tree + 1, or -1 when one is negative. */
static int supernode_count(const ps_tree_node *tree, int n_tree) {
    int m = 0;
    for (int i = 0; i < n_tree; i++)
        for (int j = 0; j < tree[i].n_supernodes; j++) {
            if (tree[i].supernodes[j] < 0) return -1;
            if (tree[i].supernodes[j] >= m) m = tree[i].supernodes[j] + 1;
        }
    return m;
}

/* leaf_of #S out: the leaf holding each supernode (-1 if none). */
static void fill_leaf_of(const ps_tree_node *tree, int n_tree, int *leaf_of, int m) {
    for (int u = 0; u < m; u++) leaf_of[u] = -1;
    for (int i = 0; i < n_tree; i++)
        if (tree[i].children[0] < 0)
            for (int j = 0; j < tree[i].n_supernodes; j++) leaf_of[tree[i].supernodes[j]] = i;
}

static ps_status component_ranges(const double *f, const int *component, size_t n,
                                  double **range, ps_error *err) {
    int n_comp = 0;
    for (size_t p = 0; p < n; p++)
        if (component[p] >= n_comp) n_comp = component[p] + 1;
    *range = malloc((size_t)(n_comp > 0 ? n_comp : 1) * sizeof **range);
    if (!*range || ps_component_range(f, component, n, n_comp, *range) != 0)
        return ps_fail(err, PS_ERR_NOMEM, "refine: out of memory");
    return PS_OK;
}

/* threshold #n_tree out: feature_threshold x the range of f over the
 * component of each leaf's points (0 for a leaf without points). */
static ps_status thresholds(const ps_refine_input *in, const int *seg_of_point,
                            double *threshold, ps_error *err) {
    double *range = NULL;
    ps_status st = component_ranges(in->f, in->component, in->graph->n, &range, err);
    for (int i = 0; st == PS_OK && i < in->n_tree; i++) threshold[i] = 0;
    for (size_t p = 0; st == PS_OK && p < in->graph->n; p++)
        threshold[seg_of_point[p]] = in->feature_threshold * range[in->component[p]];
    free(range);
    return st;
}

/* The mergeable segment with the smallest feature size, or -1. */
static int smallest_feature(segments *s) {
    const ps_segment_graph *sg = &s->graph;
    for (int i = 0; i < sg->n_groups; i++) s->has_border[i] = 0;
    for (size_t r = 0; r < sg->count; r++)
        s->has_border[sg->list[r].a] = s->has_border[sg->list[r].b] = 1;
    int best = -1;
    for (int i = 0; i < sg->n_groups; i++) {
        if (!s->has_border[i]) continue;
        double size = feature_size(s, i);
        if (size < s->threshold[i] && (best < 0 || size < feature_size(s, best))) best = i;
    }
    return best;
}

/* The neighbour maximizing border edges * feature size (ties: lowest id). */
static int merge_target(const segments *s, int id) {
    const ps_segment_graph *sg = &s->graph;
    int best = -1;
    double best_score = -1;
    for (size_t r = 0; r < sg->count; r++) {
        const ps_boundary *b = &sg->list[r];
        int x = b->a == id ? b->b : b->b == id ? b->a : -1;
        if (x < 0) continue;
        double score = (double)b->edges * feature_size(s, x);
        if (score > best_score || (score == best_score && x < best)) {
            best = x;
            best_score = score;
        }
    }
    return best;
}

static ps_status merge_all(segments *s, ps_merge **merges, int *n_merges, ps_error *err) {
    int id;
    while ((id = smallest_feature(s)) >= 0)
        if (!ps_segment_graph_merge(&s->graph, id, merge_target(s, id), merges, n_merges))
            return ps_fail(err, PS_ERR_NOMEM, "refine: out of memory");
    return PS_OK;
}

static void final_groups(const segments *s, const ps_tree_node *tree, int n_tree,
                         int *group_of_leaf) {
    for (int i = 0; i < n_tree; i++)
        group_of_leaf[i] = tree[i].children[0] < 0 ? ps_segment_graph_survivor(&s->graph, i) : -1;
}

/* A segment holding a minimum's supernode is a central region, not a
 * feature: its f is flat by nature, so it never merges away. */
static void protect_cores(const ps_refine_input *in, const int *seg_of_point,
                          double *threshold) {
    for (size_t p = 0; in->is_minimum && p < in->graph->n; p++)
        if (in->is_minimum[in->supernode_of[p]]) threshold[seg_of_point[p]] = 0;
}

static ps_status refine_with(segments *s, const ps_refine_input *in, const int *seg_of_point,
                             int *group_of_leaf, ps_merge **merges, int *n_merges,
                             ps_error *err) {
    ps_status st = thresholds(in, seg_of_point, s->threshold, err);
    if (st == PS_OK) protect_cores(in, seg_of_point, s->threshold);
    ps_segment_graph_input sgi = {.graph = in->graph, .f = in->f, .group = seg_of_point,
                                  .n_groups = in->n_tree, .threads = 1};
    if (st == PS_OK) st = ps_segment_graph_build(&s->graph, &sgi, err);
    if (st == PS_OK) st = merge_all(s, merges, n_merges, err);
    if (st == PS_OK) final_groups(s, in->tree, in->n_tree, group_of_leaf);
    return st;
}

/* seg_of_point #P: the leaf of each point's supernode. */
static ps_status point_leaves(const ps_refine_input *in, int *seg_of_point, ps_error *err) {
    int m = supernode_count(in->tree, in->n_tree);
    int *leaf_of = m > 0 ? malloc((size_t)m * sizeof *leaf_of) : NULL;
    if (!leaf_of) return ps_fail(err, m > 0 ? PS_ERR_NOMEM : PS_ERR_INVALID,
                                 "refine: no supernodes in the tree (or out of memory)");
    fill_leaf_of(in->tree, in->n_tree, leaf_of, m);
    ps_status st = PS_OK;
    for (size_t p = 0; p < in->graph->n && st == PS_OK; p++) {
        int u = in->supernode_of[p];
        seg_of_point[p] = u >= 0 && u < m ? leaf_of[u] : -1;
        if (seg_of_point[p] < 0)
            st = ps_fail(err, PS_ERR_INVALID, "refine: point %zu has supernode %d, in no leaf",
                         p, u);
    }
    free(leaf_of);
    return st;
}

ps_status ps_refine(const ps_refine_input *in, int *group_of_leaf, ps_merge **merges,
                    int *n_merges, ps_error *err) {
    *merges = NULL;
    *n_merges = 0;
    int n_tree = in->n_tree;
    size_t n = in->graph->n;
    if (n_tree < 1) return ps_fail(err, PS_ERR_INVALID, "refine: empty tree");
    segments s = {.threshold = malloc((size_t)n_tree * sizeof(double)),
                  .has_border = malloc((size_t)n_tree * sizeof(int))};
    int *seg_of_point = malloc((n ? n : 1) * sizeof *seg_of_point);
    ps_merge *list = malloc((size_t)n_tree * sizeof *list);
    ps_status st = s.threshold && s.has_border && seg_of_point && list
                       ? point_leaves(in, seg_of_point, err)
                       : ps_fail(err, PS_ERR_NOMEM, "refine: out of memory");
    if (st == PS_OK) st = refine_with(&s, in, seg_of_point, group_of_leaf, &list, n_merges, err);
    segments_free(&s);
    free(seg_of_point);
    if (st != PS_OK) {
        free(list);
        *n_merges = 0;
        return st;
    }
    *merges = list;
    return PS_OK;
}
