/*
 * ncut_tree.c: recursive normalized-cut bisection of supernodes on a dense
 * similarity matrix, and the tree's release (ncut_tree.h).
 *
 * The best threshold is found in O(k^2) for a node of k supernodes: the
 * members are sorted by y descending and moved into A one by one, keeping
 * cut(A,B) and assoc(A,U) up to date; each candidate t is scored once all
 * members with y > t are in A.  The reported NCut is then recomputed exactly
 * for the chosen split.
 */
#include "hierarchy/ncut_tree.h"

#include "hierarchy/eigen.h"
#include "util/control.h"

#include <math.h>
#include <stdlib.h>

typedef struct keyed_member {
    double y;
    int index; /* position in the node's supernode list */
} keyed_member;

/* Scratch for one bisection, sized for the root, allocated once. */
typedef struct bisect_work {
    const double *W;       /* #S by #S */
    int m;                 /* #S */
    double *scaled;        /* #S by #S: D^{-1/2} W_U D^{-1/2}, destroyed by LAPACK */
    double *vectors;       /* #S by 2 eigenvectors */
    double *degree;        /* #S degrees within the node */
    double *y;             /* #S the node's Fiedler vector */
    keyed_member *sorted;  /* #S members by y descending */
    int *in_a;             /* #S 1 for members on side A */
} bisect_work;

typedef struct tree_builder {
    ps_tree_node *nodes;   /* #capacity, the first count in use */
    int count, capacity;
} tree_builder;


static void work_free(bisect_work *w) {
    free(w->scaled);
    free(w->vectors);
    free(w->degree);
    free(w->y);
    free(w->sorted);
    free(w->in_a);
}

static int work_init(bisect_work *w, const double *W, int m) {
    size_t s = (size_t)m;
    *w = (bisect_work){.W = W, .m = m};
    w->scaled = malloc(s * s * sizeof *w->scaled);
    w->vectors = malloc(2 * s * sizeof *w->vectors);
    w->degree = malloc(s * sizeof *w->degree);
    w->y = malloc(s * sizeof *w->y);
    w->sorted = malloc(s * sizeof *w->sorted);
    w->in_a = malloc(s * sizeof *w->in_a);
    return w->scaled && w->vectors && w->degree && w->y && w->sorted && w->in_a;
}

static double weight(const bisect_work *w, const int *set, int i, int j) {
    return w->W[(size_t)set[i] * w->m + set[j]];
}

static void fill_degrees(bisect_work *w, const int *set, int k) {
    for (int i = 0; i < k; i++) {
        double sum = 0;
        for (int j = 0; j < k; j++) sum += weight(w, set, i, j);
        w->degree[i] = sum;
    }
}

static void fill_scaled(bisect_work *w, const int *set, int k) {
    for (int i = 0; i < k; i++)
        for (int j = 0; j < k; j++)
            w->scaled[(size_t)i * k + j] =
                weight(w, set, i, j) / sqrt(w->degree[i] * w->degree[j]);
}

/* y = D^{-1/2} z for z the 2nd eigenvector of the scaled W_U, sign fixed. */
static ps_status fiedler_vector(bisect_work *w, const int *set, int k, ps_error *err) {
    double values[2];
    fill_degrees(w, set, k);
    fill_scaled(w, set, k);
    ps_status st = ps_eigen_top2(w->scaled, k, values, w->vectors, err);
    if (st != PS_OK) return st;
    for (int i = 0; i < k; i++) w->y[i] = w->vectors[k + i] / sqrt(w->degree[i]);
    ps_sign_normalize(w->y, k);
    return PS_OK;
}

static int by_y_descending(const void *pa, const void *pb) {
    const keyed_member *a = pa, *b = pb;
    if (a->y != b->y) return a->y > b->y ? -1 : 1;
    return (a->index > b->index) - (a->index < b->index);
}

static double ncut_value(double cut, double assoc_a, double assoc_b) {
    return cut / assoc_a + cut / assoc_b;
}

/* Moves sorted[next] into A: cut gains its edges to B, loses those to A. */
static double cut_after_move(const bisect_work *w, const int *set, int moved,
                             double cut) {
    int i = w->sorted[moved].index;
    double to_a = 0;
    for (int a = 0; a < moved; a++) to_a += weight(w, set, i, w->sorted[a].index);
    return cut + (w->degree[i] - weight(w, set, i, i)) - 2 * to_a;
}

/* The candidate threshold minimizing NCut (ties: the lowest one). */
static double best_threshold(bisect_work *w, const int *set, int k, double y_min,
                             double y_max, double total) {
    double step = (y_max - y_min) / (PS_NCUT_CANDIDATES + 1);
    double cut = 0, assoc_a = 0, best_ncut = INFINITY;
    double best_t = y_min + step;
    int moved = 0;
    for (int c = PS_NCUT_CANDIDATES; c >= 1; c--) {
        double t = y_min + c * step;
        while (moved < k && w->sorted[moved].y > t) {
            cut = cut_after_move(w, set, moved, cut);
            assoc_a += w->degree[w->sorted[moved].index];
            moved++;
        }
        if (moved == 0 || moved == k) continue;
        double ncut = ncut_value(cut, assoc_a, total - assoc_a);
        if (ncut <= best_ncut) {
            best_ncut = ncut;
            best_t = t;
        }
    }
    return best_t;
}

/* Exact NCut of the split w->in_a of the node. */
static double split_ncut(const bisect_work *w, const int *set, int k) {
    double cut = 0, assoc_a = 0, assoc_b = 0;
    for (int i = 0; i < k; i++) {
        if (w->in_a[i]) assoc_a += w->degree[i];
        else assoc_b += w->degree[i];
        for (int j = 0; j < k; j++)
            if (w->in_a[i] && !w->in_a[j]) cut += weight(w, set, i, j);
    }
    return ncut_value(cut, assoc_a, assoc_b);
}

/* Spectral bisection of a node inside one component: w->in_a and *ncut
 * out; *ncut = -1 when y is constant (no split possible). */
static ps_status spectral_bisect(bisect_work *w, const int *set, int k, double *ncut,
                                 ps_error *err) {
    ps_status st = fiedler_vector(w, set, k, err);
    if (st != PS_OK) return st;
    double total = 0;
    for (int i = 0; i < k; i++) {
        w->sorted[i] = (keyed_member){.y = w->y[i], .index = i};
        total += w->degree[i];
    }
    qsort(w->sorted, (size_t)k, sizeof *w->sorted, by_y_descending);
    double y_max = w->sorted[0].y, y_min = w->sorted[k - 1].y;
    if (!(y_max > y_min)) {
        *ncut = -1;
        return PS_OK;
    }
    double t = best_threshold(w, set, k, y_min, y_max, total);
    for (int i = 0; i < k; i++) w->in_a[i] = w->y[i] > t;
    *ncut = split_ncut(w, set, k);
    return PS_OK;
}

/* 1 when the node's supernodes span several components; then w->in_a
 * marks the component of its lowest supernode. */
static int split_components(bisect_work *w, const int *component, const int *set, int k) {
    int first = component[set[0]], several = 0;
    for (int i = 0; i < k; i++) {
        w->in_a[i] = component[set[i]] == first;
        several |= !w->in_a[i];
    }
    return several;
}

static int add_node(tree_builder *b, int parent, int count) {
    ps_tree_node *node = &b->nodes[b->count];
    *node = (ps_tree_node){.id = b->count, .parent = parent, .children = {-1, -1},
                           .n_supernodes = count, .ncut = -1};
    node->supernodes = malloc((size_t)count * sizeof *node->supernodes);
    if (!node->supernodes) return -1;
    return b->count++;
}

/* Makes the two children of node id from w->in_a; children[0] is the side
 * of the node's lowest supernode. */
static int add_children(tree_builder *b, const bisect_work *w, int id) {
    int k = b->nodes[id].n_supernodes, size_a = 0;
    for (int i = 0; i < k; i++) size_a += w->in_a[i];
    int first_in_a = w->in_a[0];
    int side_size[2] = {first_in_a ? size_a : k - size_a, first_in_a ? k - size_a : size_a};
    int child[2];
    for (int s = 0; s < 2; s++) {
        child[s] = add_node(b, id, side_size[s]);
        if (child[s] < 0) return 0;
        b->nodes[id].children[s] = child[s];
    }
    int fill[2] = {0, 0};
    const int *set = b->nodes[id].supernodes;
    for (int i = 0; i < k; i++) {
        int s = w->in_a[i] == first_in_a ? 0 : 1;
        b->nodes[child[s]].supernodes[fill[s]++] = set[i];
    }
    return 1;
}

/* Splits node id or leaves it a leaf; *leaf_size = its supernodes if leaf. */
static ps_status process_node(tree_builder *b, bisect_work *w, const int *component,
                              double threshold, int id, int *leaf_size, ps_error *err) {
    ps_tree_node *node = &b->nodes[id];
    int k = node->n_supernodes;
    const int *set = node->supernodes;
    double ncut = -1;
    *leaf_size = k;
    if (k < 2) return PS_OK;
    if (split_components(w, component, set, k)) {
        ncut = 0;
    } else {
        ps_status st = spectral_bisect(w, set, k, &ncut, err);
        if (st != PS_OK) return st;
    }
    node->ncut = ncut;
    if (ncut < 0 || ncut > threshold) return PS_OK;
    *leaf_size = 0;
    if (!add_children(b, w, id)) return ps_fail(err, PS_ERR_NOMEM, "ncut: out of memory");
    return PS_OK;
}

static ps_status check_input(const double *W, int m, ps_error *err) {
    if (m < 1) return ps_fail(err, PS_ERR_INVALID, "ncut: no supernodes");
    for (int u = 0; u < m; u++)
        if (!(W[(size_t)u * m + u] > 0))
            return ps_fail(err, PS_ERR_INVALID, "ncut: W(%d,%d) must be > 0", u, u);
    return PS_OK;
}

static ps_status grow_tree(tree_builder *b, bisect_work *w, const int *component,
                           double threshold, const ps_control *ctl, ps_error *err) {
    int finalized = 0;
    for (int id = 0; id < b->count; id++) {
        if (ps_control_cancelled(ctl)) return ps_fail(err, PS_ERR_CANCELLED, "cancelled");
        int leaf_size = 0;
        ps_status st = process_node(b, w, component, threshold, id, &leaf_size, err);
        if (st != PS_OK) return st;
        if (leaf_size > 0) {
            finalized += leaf_size;
            ps_control_progress(ctl, PS_PHASE_HIERARCHY, (double)finalized / w->m);
        }
    }
    return PS_OK;
}

ps_status ps_ncut_tree_build(const double *W, int m, const int *component,
                             double threshold, const ps_control *ctl,
                             ps_tree_node **tree, int *n_tree, ps_error *err) {
    *tree = NULL;
    *n_tree = 0;
    ps_status st = check_input(W, m, err);
    if (st != PS_OK) return st;
    tree_builder b = {.capacity = 2 * m - 1};
    bisect_work w;
    b.nodes = calloc((size_t)b.capacity, sizeof *b.nodes);
    if (!work_init(&w, W, m) || !b.nodes || add_node(&b, -1, m) < 0) {
        st = ps_fail(err, PS_ERR_NOMEM, "ncut: out of memory for %d supernodes", m);
    } else {
        for (int u = 0; u < m; u++) b.nodes[0].supernodes[u] = u;
        st = grow_tree(&b, &w, component, threshold, ctl, err);
    }
    work_free(&w);
    if (st != PS_OK) {
        ps_tree_free(b.nodes, b.count);
        return st;
    }
    *tree = b.nodes;
    *n_tree = b.count;
    return PS_OK;
}

void ps_tree_free(ps_tree_node *tree, int n_tree) {
    if (!tree) return;
    for (int i = 0; i < n_tree; i++) free(tree[i].supernodes);
    free(tree);
}
