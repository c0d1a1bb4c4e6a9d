/*
 * select_parallel.h: the k-th smallest of a large array of doubles on
 * several threads, without reordering it: the cell radius of the two-level
 * centrality (coarse_graph.c) is a multiple of the median of every kNN
 * edge length, a pass the other threads would otherwise wait for.
 *
 * The values' range is cut into PS_SELECT_BINS equal bins; the chunks of
 * the array count their values per bin side by side, the bin holding rank
 * k is found from the counts, and its values, gathered side by side, go
 * through ps_select_kth (sort_util.h).  The answer is the k-th smallest
 * value exactly, whatever the thread count.
 */
#ifndef PS_SELECT_PARALLEL_H
#define PS_SELECT_PARALLEL_H

#include <stddef.h>

#define PS_SELECT_BINS 4096

/* The k-th smallest (0-based, k < n) of x #n, finite values, on threads
 * (ps_parallel_threads) threads; x is not changed.  scratch #n.  Returns
 * NAN when out of memory. */
double ps_select_kth_parallel(const double *x, size_t n, size_t k, int threads,
                              double *scratch);

#endif
