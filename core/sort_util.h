/*
 * sort_util.h: comparison functions for qsort and bsearch shared by the
 * core modules.
 */
#ifndef PS_SORT_UTIL_H
#define PS_SORT_UTIL_H

/* a, b: each points at one uint32_t.  Returns -1, 0 or 1 as *a is below,
 * equal to or above *b (ascending order). */
int ps_compare_u32(const void *a, const void *b);

#endif
