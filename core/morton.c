/* morton.c: Z-order of points by their first three coordinates (morton.h). */
#include "morton.h"

#include <stdlib.h>

#define AXES 3
#define BITS 21 /* per axis: 3 * 21 = 63 bits of code */

typedef struct keyed {
    uint64_t code;
    uint32_t index;
} keyed;

static int compare_keyed(const void *pa, const void *pb) {
    const keyed *a = pa, *b = pb;
    if (a->code != b->code) return a->code < b->code ? -1 : 1;
    return (a->index > b->index) - (a->index < b->index);
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
    keyed *keys = malloc(n * sizeof *keys);
    if (!keys) return PS_ERR_NOMEM;
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
    qsort(keys, n, sizeof *keys, compare_keyed);
    for (size_t p = 0; p < n; p++) order[p] = keys[p].index;
    free(keys);
    return PS_OK;
}
