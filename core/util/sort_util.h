/*
 * sort_util.h: comparison functions for qsort and bsearch, a radix sort of
 * unsigned 32-bit keys, a counting sort of items by group, and selection of
 * the k-th smallest value, shared by the core modules.
 */
#ifndef PS_SORT_UTIL_H
#define PS_SORT_UTIL_H

#include <stddef.h>
#include <stdint.h>

/* a, b: each points at one uint32_t.  Returns -1, 0 or 1 as *a is below,
 * equal to or above *b (ascending order). */
int ps_compare_u32(const void *a, const void *b);

/* Sorts x #n ascending in O(n): least significant byte first, skipping a
 * byte every key shares.  scratch #n is overwritten. */
void ps_sort_u32(uint32_t *x, size_t n, uint32_t *scratch);

/* order out #n: 0..n-1 ordered by increasing key[i], ties by index (a
 * stable least significant byte first radix sort).  scratch #n is
 * overwritten. */
void ps_order_by_u32(const uint32_t *key, size_t n, uint32_t *order, uint32_t *scratch);

/* The items 0..n-1 grouped by label[i] (< groups), in O(n + groups):
 * members out #n lists them group by group, each group in index order, and
 * first out #groups+1 bounds them (group g: members[first[g] ..
 * first[g+1])). */
void ps_group_by_label(const uint32_t *label, size_t n, size_t groups, size_t *first,
                       uint32_t *members);

/* The k-th smallest (0-based, k < n) of x #n, in expected O(n): Hoare
 * partition around the middle element.  Reorders x. */
double ps_select_kth(double *x, size_t n, size_t k);

#endif
