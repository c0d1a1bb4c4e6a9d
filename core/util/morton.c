/* morton.c: Z-order of points by their first three coordinates (morton.h),
 * sorted by a radix sort of the codes. */
#include "util/morton.h"

#include <stdlib.h>

#define AXES 3
#define BITS 21 /* per axis: 3 * 21 = 63 bits of code */

typedef struct keyed {
    uint64_t code;
    uint32_t index;
} keyed;

#define DIGIT_BITS 16
#define DIGITS 4 /* 4 x 16 bits cover the 63-bit code */
#define BUCKETS (1u << DIGIT_BITS)

static unsigned digit_of(uint64_t code, int d) {
    return (unsigned)(code >> (d * DIGIT_BITS)) & (BUCKETS - 1);
}

/* Stable LSD radix sort by code, digit by digit (a digit shared by every
 * key is skipped), between keys and scratch; returns the one holding the
 * result.  Keys in index order come out with ties by index. */
static keyed *radix_sort(keyed *keys, keyed *scratch, size_t n, size_t *count) {
    for (int d = 0; d < DIGITS; d++) {
        for (unsigned b = 0; b < BUCKETS; b++) count[b] = 0;
        for (size_t p = 0; p < n; p++) count[digit_of(keys[p].code, d)]++;
        if (count[digit_of(keys[0].code, d)] == n) continue;
        size_t sum = 0;
        for (unsigned b = 0; b < BUCKETS; b++) {
            size_t c = count[b];
            count[b] = sum;
            sum += c;
        }
        for (size_t p = 0; p < n; p++) scratch[count[digit_of(keys[p].code, d)]++] = keys[p];
        keyed *sorted = scratch;
        scratch = keys;
        keys = sorted;
    }
    return keys;
}

/* Spreads the low 21 bits of x to every third bit. */
static uint64_t spread_bits(uint64_t x) {
    x &= 0x1FFFFF;
    x = (x | x << 32) & 0x1F00000000FFFFULL;
    x = (x | x << 16) & 0x1F0000FF0000FFULL;
    x = (x | x << 8) & 0x100F00F00F00F00FULL;
    x = (x | x << 4) & 0x10C30C30C30C30C3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}

static void bounding_box(const double *points, size_t n, int dim, int axes, double *lo,
                         double *hi) {
    for (int a = 0; a < axes; a++) lo[a] = hi[a] = points[a];
    for (size_t p = 1; p < n; p++)
        for (int a = 0; a < axes; a++) {
            double x = points[p * (size_t)dim + (size_t)a];
            if (x < lo[a]) lo[a] = x;
            if (x > hi[a]) hi[a] = x;
        }
}

ps_status ps_morton_order(const double *points, size_t n, int dim, uint32_t *order) {
    if (n == 0) return PS_OK;
    keyed *keys = malloc(n * sizeof *keys), *scratch = malloc(n * sizeof *scratch);
    size_t *count = malloc(BUCKETS * sizeof *count);
    if (!keys || !scratch || !count) {
        free(keys), free(scratch), free(count);
        return PS_ERR_NOMEM;
    }
    int axes = dim < AXES ? dim : AXES;
    double lo[AXES], hi[AXES], scale[AXES];
    bounding_box(points, n, dim, axes, lo, hi);
    for (int a = 0; a < axes; a++)
        scale[a] = hi[a] > lo[a] ? (double)((1u << BITS) - 1) / (hi[a] - lo[a]) : 0.0;
    for (size_t p = 0; p < n; p++) {
        uint64_t code = 0;
        for (int a = 0; a < axes; a++) {
            double x = (points[p * (size_t)dim + (size_t)a] - lo[a]) * scale[a];
            code |= spread_bits((uint64_t)x) << a;
        }
        keys[p] = (keyed){code, (uint32_t)p};
    }
    const keyed *sorted = radix_sort(keys, scratch, n, count);
    for (size_t p = 0; p < n; p++) order[p] = sorted[p].index;
    free(keys), free(scratch), free(count);
    return PS_OK;
}
