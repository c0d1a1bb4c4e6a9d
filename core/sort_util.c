/*
 * sort_util.c: the qsort / bsearch comparisons and the selection of
 * sort_util.h.
 */
#include "sort_util.h"

#include <stddef.h>
#include <stdint.h>

int ps_compare_u32(const void *a, const void *b) {
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
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
