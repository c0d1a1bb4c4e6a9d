/*
 * parallel.h: a parallel for loop over [0, count) on short-lived pthreads.
 *
 * Work is handed out in chunks from a shared atomic counter, so uneven items
 * balance themselves.  Callers that need results independent of the thread
 * count write per-item outputs (or integer sums) and never depend on which
 * worker ran an item.
 */
#ifndef PS_PARALLEL_H
#define PS_PARALLEL_H

#include <stddef.h>

/* Threads to use for a request: requested if > 0, else the online cores. */
int ps_parallel_threads(int requested);

/* fn(ctx, begin, end, worker) runs on disjoint ranges covering [0, count);
 * worker is in [0, threads).  chunk = items per hand-out (0 picks one).
 * Runs inline when threads == 1 or count is small. */
typedef void (*ps_range_fn)(void *ctx, size_t begin, size_t end, int worker);
void ps_parallel_for(int threads, size_t count, size_t chunk, ps_range_fn fn,
                     void *ctx);

#endif
