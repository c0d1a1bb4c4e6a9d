/*
 * sort_util.c: the qsort / bsearch comparisons, the radix sort and the
 * selection of sort_util.h.
 */
#include "util/sort_util.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

int ps_compare_u32(const void *a, const void *b) {
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* The sort key of item x: key[x], or x itself without key. */
static inline uint32_t sort_key(const uint32_t *key, uint32_t x) { return key ? key[x] : x; }

/* LSD radix sort of the n items x (scratch: #n) by sort_key, a byte per
 * pass, each pass stable; a pass where every item has the same byte is
 * skipped. */
static void radix_sort(uint32_t *x, size_t n, const uint32_t *key, uint32_t *scratch) {
    if (n < 2) return;
    uint32_t *from = x, *to = scratch;
    for (int shift = 0; shift < 32; shift += 8) {
        size_t start[257] = {0};
        for (size_t i = 0; i < n; i++) start[((sort_key(key, from[i]) >> shift) & 255u) + 1]++;
        if (start[((sort_key(key, from[0]) >> shift) & 255u) + 1] == n) continue; /* one byte for all */
        for (int d = 0; d < 256; d++) start[d + 1] += start[d];
        for (size_t i = 0; i < n; i++)
            to[start[(sort_key(key, from[i]) >> shift) & 255u]++] = from[i];
        uint32_t *t = from;
        from = to, to = t;
    }
    if (from != x) memcpy(x, from, n * sizeof *x);
}

void ps_sort_u32(uint32_t *x, size_t n, uint32_t *scratch) { radix_sort(x, n, NULL, scratch); }

void ps_order_by_u32(const uint32_t *key, size_t n, uint32_t *order, uint32_t *scratch) {
    for (size_t i = 0; i < n; i++) order[i] = (uint32_t)i;
    radix_sort(order, n, key, scratch);
}

void ps_group_by_label(const uint32_t *label, size_t n, size_t groups, size_t *first,
                       uint32_t *members) {
    memset(first, 0, (groups + 1) * sizeof *first);
    for (size_t i = 0; i < n; i++) first[label[i] + 1]++;
    for (size_t g = 0; g < groups; g++) first[g + 1] += first[g];
    for (size_t i = 0; i < n; i++) members[first[label[i]]++] = (uint32_t)i;
    for (size_t g = groups; g > 0; g--) first[g] = first[g - 1];
    first[0] = 0;
}

double ps_select_kth(double *x, size_t n, size_t k) {
    ptrdiff_t lo = 0, hi = (ptrdiff_t)n - 1, target = (ptrdiff_t)k;
    while (lo < hi) {
        double pivot = x[lo + (hi - lo) / 2];
        ptrdiff_t i = lo, j = hi;
        while (i <= j) {
            while (x[i] < pivot) i++;
            while (x[j] > pivot) j--;
            if (i > j) break;
            double t = x[i];
            x[i++] = x[j];
            x[j--] = t;
        }
        if (target <= j) hi = j;
        else if (target >= i) lo = i;
        else break;
    }
    return x[k];
}
