/*
 * crease_split.c: supernodes cut along closed concave creases
 * (crease_split.h).  One selection for the crease threshold, then
 * breadth-first passes over the kNN graph: the pieces off creases, then
 * the points left over joining the nearest kept piece; then the
 * supernodes are rebuilt.  O(E), deterministic.
 */
#include "features/crease_split.h"

#include "features/crease.h"
#include "features/persistence.h"
#include "util/sort_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct split_work {
    const ps_graph *g;
    const ps_supernodes *sn;
    int *piece;               /* #P piece of each point off creases; -1 before its fill,
                                 ON_CREASE on a crease */
    size_t *piece_size;       /* #P (at most one piece per point) */
    int *label;               /* #P new supernode, -1 while unknown */
    int *new_of_piece;        /* #P new supernode of a kept piece, else -1 */
    int *whole;               /* #S new supernode of an unsplit supernode, else -1 */
    uint32_t *queue;          /* #P */
    int n_new;
} split_work;

#define ON_CREASE (-2)

/* Flood fill of one piece from seed over non-crease points; its size.
 * A neighbour joins when it has no piece yet and is off creases (piece
 * -1) and in the same supernode, the two tests taken together. */
static size_t fill_piece(split_work *w, uint32_t seed, int id) {
    const ps_graph *g = w->g;
    const int *supernode_of = w->sn->supernode_of;
    size_t head = 0, tail = 0;
    w->piece[seed] = id;
    w->queue[tail++] = seed;
    while (head < tail) {
        uint32_t p = w->queue[head++];
        int s = supernode_of[p];
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if ((w->piece[q] != -1) | (supernode_of[q] != s)) continue;
            w->piece[q] = id;
            w->queue[tail++] = q;
        }
    }
    return tail;
}

/* Pieces of the points whose strength is below crease, and the new
 * supernode of each point of a kept piece (numbered in order of their
 * lowest point). */
static void label_pieces(split_work *w, const double *strength, double crease) {
    size_t n = w->g->n;
    int n_pieces = 0;
    for (size_t p = 0; p < n; p++) {
        w->piece[p] = strength[p] >= crease ? ON_CREASE : -1;
        w->label[p] = -1;
    }
    for (size_t p = 0; p < n; p++)
        if (w->piece[p] == -1) {
            w->piece_size[n_pieces] = fill_piece(w, (uint32_t)p, n_pieces);
            w->new_of_piece[n_pieces++] = -1;
        }
    size_t need = (size_t)(PS_CREASE_SPLIT_MIN_FRACTION * (double)n);
    if (need < PS_PERSISTENCE_MIN_BASIN) need = PS_PERSISTENCE_MIN_BASIN;
    for (size_t p = 0; p < n; p++) {
        int c = w->piece[p];
        if (c < 0) continue;
        if (w->piece_size[c] < need) continue;
        if (w->new_of_piece[c] < 0) w->new_of_piece[c] = w->n_new++;
        w->label[p] = w->new_of_piece[c];
    }
}

/* A supernode without a kept piece stays whole; then every unlabelled
 * point takes the label of a labelled neighbour in its supernode, breadth
 * first from all labelled points in point order. */
static void spread_labels(split_work *w) {
    const ps_graph *g = w->g;
    size_t n = g->n, head = 0, tail = 0;
    for (int s = 0; s < w->sn->m; s++) w->whole[s] = 0;
    for (size_t p = 0; p < n; p++)
        if (w->label[p] >= 0) w->whole[w->sn->supernode_of[p]] = 1;
    for (int s = 0; s < w->sn->m; s++) w->whole[s] = w->whole[s] ? -1 : w->n_new++;
    for (size_t p = 0; p < n; p++) {
        int s = w->sn->supernode_of[p];
        if (w->whole[s] >= 0) w->label[p] = w->whole[s];
        else if (w->label[p] >= 0) w->queue[tail++] = (uint32_t)p;
    }
    while (head < tail) {
        uint32_t p = w->queue[head++];
        int s = w->sn->supernode_of[p];
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if ((w->label[q] >= 0) | (w->sn->supernode_of[q] != s)) continue;
            w->label[q] = w->label[p];
            w->queue[tail++] = q;
        }
    }
}

/* A point the spread could not reach (its supernode is not connected)
 * takes the label of the supernode's lowest labelled point. */
static void label_the_rest(split_work *w) {
    const int *supernode_of = w->sn->supernode_of;
    for (size_t p = w->g->n; p-- > 0;)
        if (w->label[p] >= 0) w->whole[supernode_of[p]] = w->label[p];
    for (size_t p = 0; p < w->g->n; p++)
        if (w->label[p] < 0) w->label[p] = w->whole[supernode_of[p]];
}

static void work_free(split_work *w) {
    free(w->piece);
    free(w->piece_size);
    free(w->label);
    free(w->new_of_piece);
    free(w->whole);
    free(w->queue);
}

static int work_alloc(split_work *w, size_t n, int m) {
    w->piece = malloc(n * sizeof *w->piece);
    w->piece_size = malloc(n * sizeof *w->piece_size);
    w->label = malloc(n * sizeof *w->label);
    w->new_of_piece = malloc(n * sizeof *w->new_of_piece);
    w->whole = malloc((size_t)(m > 0 ? m : 1) * sizeof *w->whole);
    w->queue = malloc(n * sizeof *w->queue);
    return w->piece && w->piece_size && w->label && w->new_of_piece &&
           w->whole && w->queue;
}

/* The strength that puts a point on a crease: PS_CREASE_SPLIT_STRENGTH x
 * the mean angular term, raised to the strength of the point at the
 * PS_CREASE_SPLIT_MAX_POINTS quantile from the top when more points than
 * that pass it, and to PS_CREASE_NOISE x the median strength (noise).
 * 0 when out of memory. */
static int crease_threshold(const ps_crease_points *creases, size_t n, double *threshold) {
    double *copy = malloc(n * sizeof *copy);
    if (!copy) return 0;
    memcpy(copy, creases->strength, n * sizeof *copy);
    size_t rank = (size_t)((1.0 - PS_CREASE_SPLIT_MAX_POINTS) * (double)(n - 1));
    double top = ps_select_kth(copy, n, rank);
    free(copy);
    *threshold = fmax(fmax(PS_CREASE_SPLIT_STRENGTH * creases->mean, top),
                      PS_CREASE_NOISE * creases->median);
    return 1;
}

ps_status ps_crease_split(const ps_graph *g, const ps_crease_points *creases, const double *f,
                          ps_supernodes *sn, ps_error *err) {
    if (g->n == 0) return PS_OK;
    split_work w = {.g = g, .sn = sn};
    ps_status st = PS_OK;
    if (!work_alloc(&w, g->n, sn->m)) {
        work_free(&w);
        return ps_fail(err, PS_ERR_NOMEM, "crease split: out of memory");
    }
    double crease = INFINITY; /* a flat surface has no creases */
    if (creases->mean >= PS_CREASE_FLAT && !crease_threshold(creases, g->n, &crease)) {
        work_free(&w);
        return ps_fail(err, PS_ERR_NOMEM, "crease split: out of memory");
    }
    label_pieces(&w, creases->strength, crease);
    spread_labels(&w);
    if (w.n_new > sn->m && w.n_new <= PS_MAX_SUPERNODES) {
        label_the_rest(&w);
        st = ps_supernodes_relabel(sn, w.label, w.n_new, f, g->n, err);
    }
    work_free(&w);
    return st;
}
