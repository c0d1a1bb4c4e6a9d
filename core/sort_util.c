/*
 * sort_util.c: the qsort / bsearch comparisons of sort_util.h.
 */
#include "sort_util.h"

#include <stdint.h>

int ps_compare_u32(const void *a, const void *b) {
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}
