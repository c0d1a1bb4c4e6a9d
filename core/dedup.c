/*
 * dedup.c: collapse exactly coincident points (dedup.h).
 *
 * Sorts the row indices lexicographically by coordinates (ties by index), so
 * equal points become runs whose first element is their lowest index; the
 * runs are then numbered in order of that lowest index.  O(n log n).
 * ps_dedup_morton renumbers them by the Morton codes of their coordinates.
 */
#include "dedup.h"

#include "morton.h"

#include <stdlib.h>
#include <string.h>

/* qsort has no context argument; a sort key carries what the comparator needs. */
typedef struct row_key {
    const double *row;
    size_t index;
    int dim;
} row_key;

static int compare_rows(const void *pa, const void *pb) {
    const row_key *a = pa, *b = pb;
    for (int i = 0; i < a->dim; i++) {
        if (a->row[i] < b->row[i]) return -1;
        if (a->row[i] > b->row[i]) return 1;
    }
    return (a->index > b->index) - (a->index < b->index);
}

static int same_row(const row_key *a, const row_key *b) {
    for (int i = 0; i < a->dim; i++)
        if (a->row[i] != b->row[i]) return 0;
    return 1;
}

/* representative #P: for each input index, the lowest index of its run. */
static void mark_runs(const row_key *keys, size_t n, size_t *representative) {
    size_t start = 0;
    for (size_t s = 0; s < n; s++) {
        if (s > 0 && !same_row(&keys[s - 1], &keys[s])) start = s;
        representative[keys[s].index] = keys[start].index;
    }
}

ps_status ps_dedup_build(const double *points, size_t n, int dim, ps_dedup *d,
                         ps_error *err) {
    memset(d, 0, sizeof *d);
    if (!points && n > 0) return ps_fail(err, PS_ERR_INVALID, "dedup: points is NULL");
    if (dim < 1) return ps_fail(err, PS_ERR_INVALID, "dedup: dim %d < 1", dim);
    size_t alloc_n = n ? n : 1;
    row_key *keys = malloc(alloc_n * sizeof *keys);
    d->unique_of = malloc(alloc_n * sizeof *d->unique_of);
    d->first = malloc(alloc_n * sizeof *d->first);
    if (!keys || !d->unique_of || !d->first) {
        free(keys);
        ps_dedup_free(d);
        return ps_fail(err, PS_ERR_NOMEM, "dedup: out of memory for %zu points", n);
    }
    for (size_t p = 0; p < n; p++) keys[p] = (row_key){points + p * (size_t)dim, p, dim};
    qsort(keys, n, sizeof *keys, compare_rows);
    mark_runs(keys, n, d->unique_of);
    free(keys);
    size_t u = 0;
    for (size_t p = 0; p < n; p++) {
        size_t rep = d->unique_of[p]; /* rep <= p, already renumbered if < p */
        if (rep == p) {
            d->first[u] = p;
            d->unique_of[p] = u++;
        } else {
            d->unique_of[p] = d->unique_of[rep];
        }
    }
    d->n_unique = u;
    return PS_OK;
}

int ps_dedup_is_identity(const ps_dedup *d, size_t n) {
    if (d->n_unique != n) return 0;
    for (size_t i = 0; i < n; i++)
        if (d->first[i] != i) return 0;
    return 1;
}

ps_status ps_dedup_morton(ps_dedup *d, const double *points, size_t n, int dim, ps_error *err) {
    size_t u = d->n_unique;
    double *distinct = malloc((u ? u : 1) * (size_t)dim * sizeof *distinct);
    uint32_t *order = malloc((u ? u : 1) * sizeof *order);
    size_t *first = malloc((u ? u : 1) * sizeof *first), *renumber = malloc((u ? u : 1) * sizeof *renumber);
    ps_status st = distinct && order && first && renumber ? PS_OK : PS_ERR_NOMEM;
    for (size_t i = 0; st == PS_OK && i < u; i++)
        memcpy(distinct + i * (size_t)dim, points + d->first[i] * (size_t)dim, (size_t)dim * sizeof *distinct);
    if (st == PS_OK) st = ps_morton_order(distinct, u, dim, order);
    if (st == PS_OK) {
        for (size_t i = 0; i < u; i++) {
            first[i] = d->first[order[i]];
            renumber[order[i]] = i;
        }
        for (size_t p = 0; p < n; p++) d->unique_of[p] = renumber[d->unique_of[p]];
        free(d->first);
        d->first = first;
        first = NULL;
    }
    free(distinct), free(order), free(first), free(renumber);
    return st == PS_OK ? PS_OK : ps_fail(err, st, "dedup: out of memory for the Morton order");
}

void ps_dedup_free(ps_dedup *d) {
    if (!d) return;
    free(d->unique_of);
    free(d->first);
    memset(d, 0, sizeof *d);
}
