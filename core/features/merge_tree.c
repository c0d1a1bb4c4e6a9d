/*
 * merge_tree.c: the merge tree of the ascent flow's basins and the parts
 * its long-lived nodes make (merge_tree.h).  The tree comes from one sweep
 * of the border saddles with a union-find over the basins; each point
 * below its basin's highest saddle finds the node alive at its height by
 * binary lifting along its leaf's ancestors, whose death heights fall
 * towards the root.
 */
#include "features/merge_tree.h"

#include "features/component_range.h"
#include "features/persistence.h"
#include "util/union_find.h"

#include <stdlib.h>
#include <string.h>

#define NO_NODE (-1)
#define NEVER (-1e300) /* the death height of a root */

typedef struct tree {
    int n_leaves, n_nodes, levels;
    int *parent;          /* #N, NO_NODE for a root; a parent's id exceeds its children's */
    int *component;       /* #N */
    double *birth, *death; /* #N: heights where the node's group forms and ends */
    double *longest_child; /* #N: the longest life among its children */
    int *part;            /* #N: part index, or -1 */
    int *top;             /* #N: the part that absorbs the node, or the node itself */
    int *jump;            /* #levels by #N: the 2^k-th ancestor, or NO_NODE */
} tree;

static void tree_free(tree *t) {
    free(t->parent), free(t->component), free(t->birth), free(t->death);
    free(t->longest_child), free(t->part), free(t->top), free(t->jump);
}

static int tree_alloc(tree *t, int n_leaves) {
    size_t cap = 2 * (size_t)(n_leaves > 0 ? n_leaves : 1);
    int levels = 1;
    while (((size_t)1 << levels) < cap) levels++;
    memset(t, 0, sizeof *t);
    t->n_leaves = n_leaves, t->levels = levels;
    t->parent = malloc(cap * sizeof *t->parent);
    t->component = malloc(cap * sizeof *t->component);
    t->birth = malloc(cap * sizeof *t->birth);
    t->death = malloc(cap * sizeof *t->death);
    t->longest_child = calloc(cap, sizeof *t->longest_child);
    t->part = malloc(cap * sizeof *t->part);
    t->top = malloc(cap * sizeof *t->top);
    t->jump = malloc((size_t)levels * cap * sizeof *t->jump);
    return t->parent && t->component && t->birth && t->death && t->longest_child && t->part &&
                   t->top && t->jump
               ? 0
               : -1;
}

static double life(const tree *t, int v) { return t->birth[v] - t->death[v]; }

/* Leaves are in->up's basins, born at their peaks; each of in->saddles
 * joining two groups makes a node.  group #S scratch (union-find), node_of
 * #S scratch. */
static void tree_sweep(tree *t, const ps_merge_tree_input *in, int *group, int *node_of) {
    const ps_flow *up = in->up;
    const ps_saddle *s = in->saddles;
    int m = t->n_leaves, n = m;
    for (int b = 0; b < m; b++) {
        group[b] = b, node_of[b] = b, t->parent[b] = NO_NODE;
        t->birth[b] = in->f[up->sinks[b]], t->death[b] = NEVER;
        t->component[b] = in->component[up->sinks[b]];
    }
    for (size_t i = 0; i < in->n_saddles; i++) {
        int a = ps_union_find_root(group, up->sink_of[s[i].p]);
        int b = ps_union_find_root(group, up->sink_of[s[i].q]);
        if (a == b) continue;
        int c = n++;
        t->parent[c] = NO_NODE, t->birth[c] = s[i].height, t->death[c] = NEVER;
        t->component[c] = t->component[node_of[a]];
        t->death[node_of[a]] = t->death[node_of[b]] = s[i].height;
        t->parent[node_of[a]] = t->parent[node_of[b]] = c;
        group[b] = a, node_of[a] = c;
    }
    t->n_nodes = n;
}

/* Parts: inner nodes, not roots, that live long enough; then each node's
 * top, climbing while the node is short against the part above it.
 * Returns the number of parts. */
static int tree_parts(tree *t, const double *threshold) {
    int n_parts = 0;
    for (int v = 0; v < t->n_nodes; v++) {
        int p = t->parent[v];
        if (p != NO_NODE && life(t, v) > t->longest_child[p]) t->longest_child[p] = life(t, v);
    }
    for (int v = 0; v < t->n_nodes; v++) {
        int is_part = v >= t->n_leaves && t->parent[v] != NO_NODE &&
                      life(t, v) > PS_PART_PERSISTENCE * threshold[t->component[v]];
        t->part[v] = is_part ? n_parts++ : -1;
    }
    for (int v = t->n_nodes - 1; v >= 0; v--) {
        int p = t->parent[v];
        int absorbed = p != NO_NODE && t->part[p] >= 0 && life(t, v) < PS_PART_ABSORB * life(t, p);
        t->top[v] = absorbed ? t->top[p] : v;
    }
    return n_parts;
}

static void tree_jumps(tree *t) {
    int n = t->n_nodes;
    for (int v = 0; v < n; v++) t->jump[v] = t->parent[v];
    for (int k = 1; k < t->levels; k++)
        for (int v = 0; v < n; v++) {
            int half = t->jump[(size_t)(k - 1) * n + v];
            t->jump[(size_t)k * n + v] = half == NO_NODE ? NO_NODE : t->jump[(size_t)(k - 1) * n + half];
        }
}

/* The node alive at height h among leaf's ancestors, for h below the
 * leaf's death: the parent of the highest ancestor that died at or above h
 * (a root never dies, so that parent exists). */
static int node_at(const tree *t, int leaf, double h) {
    int v = leaf, n = t->n_nodes;
    for (int k = t->levels - 1; k >= 0; k--) {
        int a = t->jump[(size_t)k * n + v];
        if (a != NO_NODE && t->death[a] >= h) v = a;
    }
    return t->parent[v];
}

static int part_of_point(const tree *t, int leaf, double h) {
    int v = h < t->death[leaf] ? node_at(t, leaf, h) : leaf;
    int top = t->top[v];
    if (top == leaf || t->part[top] < 0) return -1;
    if (h < t->birth[top] - PS_PART_REACH * t->longest_child[top]) return -1;
    return t->part[top];
}

ps_status ps_merge_tree_parts(const ps_merge_tree_input *in, int *part_of, int *n_parts,
                              ps_error *err) {
    size_t n = in->graph->n;
    const ps_flow *up = in->up;
    for (size_t p = 0; p < n; p++) part_of[p] = -1;
    *n_parts = 0;
    if (in->persistence <= 0 || up->n_sinks < 2) return PS_OK;
    int m = up->n_sinks;
    tree t;
    int alloc_failed = tree_alloc(&t, m);
    int *group = malloc((size_t)m * sizeof *group), *node_of = malloc((size_t)m * sizeof *node_of);
    double *threshold = ps_component_thresholds(in->f, in->component, n, in->n_components,
                                                in->persistence);
    int ok = !alloc_failed && group && node_of && threshold;
    if (ok) {
        tree_sweep(&t, in, group, node_of);
        *n_parts = tree_parts(&t, threshold);
    }
    if (ok && *n_parts) {
        tree_jumps(&t);
        for (size_t p = 0; p < n; p++) part_of[p] = part_of_point(&t, up->sink_of[p], in->f[p]);
    }
    tree_free(&t);
    free(group), free(node_of), free(threshold);
    return ok ? PS_OK : ps_fail(err, PS_ERR_NOMEM, "merge tree: out of memory");
}
