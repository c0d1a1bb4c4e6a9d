/*
 * refine.c: phase 3 (refine.h): segments with a small feature merge into a
 * neighbour.
 *
 * Segments start as the hierarchy leaves and keep the id of their surviving
 * leaf.  Their borders are counted once, in O(E): for each pair of adjacent
 * segments, the number of kNN edges joining their points (each undirected
 * edge once), kept in small per-segment lists that are combined when two
 * segments merge.  Each step takes the segment with the smallest feature size
 * (ties: lowest leaf id) that is below feature_threshold * (range of f over
 * its component) and has a neighbour, and merges it into the neighbour with
 * the largest (shared border edges) * (neighbour's feature size): a long
 * border with a large part wins (ties: lowest id).  The survivor's feature
 * size becomes max f - min f over the union.  A step costs O(segments +
 * border list lengths); a segment alone in its component never merges.
 */
#include "refine.h"

#include "component_range.h"

#include <math.h>
#include <stdlib.h>

typedef struct border {
    int segment; /* the neighbour's leaf id */
    long edges;  /* kNN edges shared with it */
} border;

typedef struct border_list {
    border *items;
    int count, capacity;
} border_list;

/* Per tree id; only leaves are used. */
typedef struct segments {
    int n_tree;
    double *f_min, *f_max;  /* #n_tree f range over the segment's points */
    double *threshold;      /* #n_tree merge below this feature size */
    int *alive;             /* #n_tree 1 for a leaf not yet merged away */
    int *merged_into;       /* #n_tree leaf id it merged into, or -1 */
    border_list *borders;   /* #n_tree */
} segments;

static double feature_size(const segments *s, int id) {
    return s->f_max[id] - s->f_min[id];
}

static int find_border(const border_list *list, int segment) {
    for (int i = 0; i < list->count; i++)
        if (list->items[i].segment == segment) return i;
    return -1;
}

static int add_border(border_list *list, int segment, long edges) {
    int i = find_border(list, segment);
    if (i >= 0) {
        list->items[i].edges += edges;
        return 1;
    }
    if (list->count == list->capacity) {
        int capacity = list->capacity ? 2 * list->capacity : 4;
        border *items = realloc(list->items, (size_t)capacity * sizeof *items);
        if (!items) return 0;
        list->items = items;
        list->capacity = capacity;
    }
    list->items[list->count++] = (border){.segment = segment, .edges = edges};
    return 1;
}

static void remove_border(border_list *list, int segment) {
    int i = find_border(list, segment);
    if (i < 0) return;
    for (; i + 1 < list->count; i++) list->items[i] = list->items[i + 1];
    list->count--;
}

static void segments_free(segments *s) {
    for (int i = 0; s->borders && i < s->n_tree; i++) free(s->borders[i].items);
    free(s->borders);
    free(s->f_min);
    free(s->f_max);
    free(s->threshold);
    free(s->alive);
    free(s->merged_into);
}

static int segments_alloc(segments *s, int n_tree) {
    size_t n = (size_t)n_tree;
    *s = (segments){.n_tree = n_tree};
    s->f_min = malloc(n * sizeof *s->f_min);
    s->f_max = malloc(n * sizeof *s->f_max);
    s->threshold = malloc(n * sizeof *s->threshold);
    s->alive = malloc(n * sizeof *s->alive);
    s->merged_into = malloc(n * sizeof *s->merged_into);
    s->borders = calloc(n, sizeof *s->borders);
    return s->f_min && s->f_max && s->threshold && s->alive && s->merged_into && s->borders;
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

/* f range of each leaf's points (0 for a leaf without points), and its
 * merge threshold from the range of f over its component. */
static ps_status measure(segments *s, const ps_tree_node *tree, size_t n, const double *f,
                         const int *component, const int *seg_of_point,
                         double feature_threshold, ps_error *err) {
    double *range = NULL;
    ps_status st = component_ranges(f, component, n, &range, err);
    if (st != PS_OK) {
        free(range);
        return st;
    }
    for (int i = 0; i < s->n_tree; i++) {
        s->f_min[i] = INFINITY;
        s->f_max[i] = -INFINITY;
        s->threshold[i] = 0;
        s->alive[i] = tree[i].children[0] < 0;
        s->merged_into[i] = -1;
    }
    for (size_t p = 0; p < n; p++) {
        int id = seg_of_point[p];
        s->f_min[id] = fmin(s->f_min[id], f[p]);
        s->f_max[id] = fmax(s->f_max[id], f[p]);
        s->threshold[id] = feature_threshold * range[component[p]];
    }
    for (int i = 0; i < s->n_tree; i++)
        if (s->f_min[i] > s->f_max[i]) s->f_min[i] = s->f_max[i] = 0;
    free(range);
    return PS_OK;
}

static ps_status count_borders(segments *s, const ps_graph *g, const int *seg_of_point,
                               ps_error *err) {
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            int a = seg_of_point[p], b = seg_of_point[q];
            if (q <= p || a == b) continue;
            if (!add_border(&s->borders[a], b, 1) || !add_border(&s->borders[b], a, 1))
                return ps_fail(err, PS_ERR_NOMEM, "refine: out of memory");
        }
    return PS_OK;
}

/* The mergeable segment with the smallest feature size, or -1. */
static int smallest_feature(const segments *s) {
    int best = -1;
    for (int i = 0; i < s->n_tree; i++) {
        if (!s->alive[i] || s->borders[i].count == 0) continue;
        double size = feature_size(s, i);
        if (size < s->threshold[i] && (best < 0 || size < feature_size(s, best))) best = i;
    }
    return best;
}

/* The neighbour maximizing border edges * feature size (ties: lowest id). */
static int merge_target(const segments *s, int id) {
    const border_list *list = &s->borders[id];
    int best = -1;
    double best_score = -1;
    for (int i = 0; i < list->count; i++) {
        int x = list->items[i].segment;
        double score = (double)list->items[i].edges * feature_size(s, x);
        if (score > best_score || (score == best_score && x < best)) {
            best = x;
            best_score = score;
        }
    }
    return best;
}

/* Moves id's borders to into; neighbours now border into instead. */
static int merge(segments *s, int id, int into) {
    border_list *list = &s->borders[id];
    for (int i = 0; i < list->count; i++) {
        int x = list->items[i].segment;
        long edges = list->items[i].edges;
        if (x == into) continue;
        remove_border(&s->borders[x], id);
        if (!add_border(&s->borders[into], x, edges) ||
            !add_border(&s->borders[x], into, edges))
            return 0;
    }
    remove_border(&s->borders[into], id);
    list->count = 0;
    s->f_min[into] = fmin(s->f_min[into], s->f_min[id]);
    s->f_max[into] = fmax(s->f_max[into], s->f_max[id]);
    s->alive[id] = 0;
    s->merged_into[id] = into;
    return 1;
}

static ps_status merge_all(segments *s, ps_merge *merges, int *n_merges, ps_error *err) {
    int id;
    while ((id = smallest_feature(s)) >= 0) {
        int into = merge_target(s, id);
        merges[*n_merges] = (ps_merge){.segment = id, .into = into,
                                       .feature_size = feature_size(s, id)};
        (*n_merges)++;
        if (!merge(s, id, into)) return ps_fail(err, PS_ERR_NOMEM, "refine: out of memory");
    }
    return PS_OK;
}

static void final_groups(const segments *s, const ps_tree_node *tree, int *group_of_leaf) {
    for (int i = 0; i < s->n_tree; i++) {
        int g = -1;
        if (tree[i].children[0] < 0)
            for (g = i; s->merged_into[g] >= 0;) g = s->merged_into[g];
        group_of_leaf[i] = g;
    }
}

/* A segment holding a minimum's supernode is a central region, not a
 * feature: its f is flat by nature, so it never merges away. */
static void protect_cores(segments *s, const int *supernode_of, const int *is_minimum,
                          const int *seg_of_point, size_t n) {
    for (size_t p = 0; is_minimum && p < n; p++)
        if (is_minimum[supernode_of[p]]) s->threshold[seg_of_point[p]] = 0;
}

static ps_status refine_with(segments *s, const ps_graph *g, const double *f,
                             const int *component, const ps_tree_node *tree,
                             const int *seg_of_point, const int *supernode_of,
                             const int *is_minimum, double feature_threshold,
                             int *group_of_leaf, ps_merge *merges, int *n_merges,
                             ps_error *err) {
    ps_status st = measure(s, tree, g->n, f, component, seg_of_point, feature_threshold, err);
    if (st == PS_OK) protect_cores(s, supernode_of, is_minimum, seg_of_point, g->n);
    if (st == PS_OK) st = count_borders(s, g, seg_of_point, err);
    if (st == PS_OK) st = merge_all(s, merges, n_merges, err);
    if (st == PS_OK) final_groups(s, tree, group_of_leaf);
    return st;
}

/* seg_of_point #P: the leaf of each point's supernode. */
static ps_status point_leaves(const ps_tree_node *tree, int n_tree, const int *supernode_of,
                              size_t n, int *seg_of_point, ps_error *err) {
    int m = supernode_count(tree, n_tree);
    int *leaf_of = m > 0 ? malloc((size_t)m * sizeof *leaf_of) : NULL;
    if (!leaf_of) return ps_fail(err, m > 0 ? PS_ERR_NOMEM : PS_ERR_INVALID,
                                 "refine: no supernodes in the tree (or out of memory)");
    fill_leaf_of(tree, n_tree, leaf_of, m);
    ps_status st = PS_OK;
    for (size_t p = 0; p < n && st == PS_OK; p++) {
        int u = supernode_of[p];
        seg_of_point[p] = u >= 0 && u < m ? leaf_of[u] : -1;
        if (seg_of_point[p] < 0)
            st = ps_fail(err, PS_ERR_INVALID, "refine: point %zu has supernode %d, in no leaf",
                         p, u);
    }
    free(leaf_of);
    return st;
}

ps_status ps_refine(const ps_graph *g, const double *f, const int *supernode_of,
                    const int *is_minimum, const int *component,
                    const ps_tree_node *tree, int n_tree,
                    double feature_threshold, int *group_of_leaf,
                    ps_merge **merges, int *n_merges, ps_error *err) {
    *merges = NULL;
    *n_merges = 0;
    if (n_tree < 1) return ps_fail(err, PS_ERR_INVALID, "refine: empty tree");
    segments s;
    int *seg_of_point = malloc((g->n ? g->n : 1) * sizeof *seg_of_point);
    ps_merge *list = malloc((size_t)n_tree * sizeof *list);
    ps_status st = segments_alloc(&s, n_tree) && seg_of_point && list
                       ? point_leaves(tree, n_tree, supernode_of, g->n, seg_of_point, err)
                       : ps_fail(err, PS_ERR_NOMEM, "refine: out of memory");
    if (st == PS_OK)
        st = refine_with(&s, g, f, component, tree, seg_of_point, supernode_of, is_minimum,
                         feature_threshold,
                         group_of_leaf, list, n_merges, err);
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
