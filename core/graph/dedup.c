/*
 * dedup.c: collapse exactly coincident points (dedup.h).
 *
 * One pass in input order over a hash table of the distinct points seen so
 * far (open addressing on their coordinates' bits, -0 as +0): a point not
 * yet in it is the next distinct one, so they are numbered in order of
 * their lowest index.  O(n) expected.
 * ps_dedup_morton renumbers them by the Morton codes of their coordinates.
 */
#include "graph/dedup.h"

#include "util/morton.h"

#include <stdlib.h>
#include <string.h>

#define EMPTY UINT32_MAX

/* The bits of x with -0 as +0, so that equal coordinates hash alike. */
static uint64_t coordinate_bits(double x) {
    uint64_t bits;
    if (x == 0.0) x = 0.0;
    memcpy(&bits, &x, sizeof bits);
    return bits;
}

static uint64_t row_hash(const double *row, int dim) {
    uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (int i = 0; i < dim; i++) {
        h ^= coordinate_bits(row[i]);
        h *= 0xbf58476d1ce4e5b9ULL;
        h ^= h >> 31;
    }
    return h;
}

static int same_row(const double *a, const double *b, int dim) {
    for (int i = 0; i < dim; i++)
        if (a[i] != b[i]) return 0;
    return 1;
}

/* Open addressing: slots hold the input index of a distinct point's first
 * occurrence (EMPTY when free); slots - 1 is the probe mask. */
static void number_points(const double *points, size_t n, int dim, uint32_t *slot, size_t slots,
                          ps_dedup *d) {
    size_t u = 0;
    for (size_t p = 0; p < n; p++) {
        const double *row = points + p * (size_t)dim;
        size_t s = (size_t)row_hash(row, dim) & (slots - 1);
        while (slot[s] != EMPTY && !same_row(points + slot[s] * (size_t)dim, row, dim))
            s = (s + 1) & (slots - 1);
        if (slot[s] == EMPTY) {
            slot[s] = (uint32_t)p;
            d->first[u] = (uint32_t)p;
            d->unique_of[p] = (uint32_t)u++;
        } else {
            d->unique_of[p] = d->unique_of[slot[s]];
        }
    }
    d->n_unique = u;
}

ps_status ps_dedup_build(const double *points, size_t n, int dim, ps_dedup *d,
                         ps_error *err) {
    memset(d, 0, sizeof *d);
    if (!points && n > 0) return ps_fail(err, PS_ERR_INVALID, "dedup: points is NULL");
    if (dim < 1) return ps_fail(err, PS_ERR_INVALID, "dedup: dim %d < 1", dim);
    if (n >= EMPTY) return ps_fail(err, PS_ERR_INVALID, "dedup: too many points (%zu)", n);
    size_t alloc_n = n ? n : 1, slots = 2;
    while (slots < 2 * n) slots *= 2;
    uint32_t *slot = malloc(slots * sizeof *slot);
    d->unique_of = malloc(alloc_n * sizeof *d->unique_of);
    d->first = malloc(alloc_n * sizeof *d->first);
    if (!slot || !d->unique_of || !d->first) {
        free(slot);
        ps_dedup_free(d);
        return ps_fail(err, PS_ERR_NOMEM, "dedup: out of memory for %zu points", n);
    }
    memset(slot, 0xff, slots * sizeof *slot);
    number_points(points, n, dim, slot, slots, d);
    free(slot);
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
    uint32_t *first = malloc((u ? u : 1) * sizeof *first);
    uint32_t *renumber = malloc((u ? u : 1) * sizeof *renumber);
    ps_status st = distinct && order && first && renumber ? PS_OK : PS_ERR_NOMEM;
    for (size_t i = 0; st == PS_OK && i < u; i++)
        memcpy(distinct + i * (size_t)dim, points + (size_t)d->first[i] * (size_t)dim,
               (size_t)dim * sizeof *distinct);
    if (st == PS_OK) st = ps_morton_order(distinct, u, dim, order);
    if (st == PS_OK) {
        for (size_t i = 0; i < u; i++) {
            first[i] = d->first[order[i]];
            renumber[order[i]] = (uint32_t)i;
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
