/*
 * parallel.h: a parallel for loop over [0, count) on short-lived pthreads,
 * and the same item by item with a caller's cancel flag and progress
 * (ps_control, pointseg.h).
 *
 * Work is handed out in chunks from a shared atomic counter, so uneven items
 * balance themselves.  Callers that need results independent of the thread
 * count write per-item outputs (or integer sums) and never depend on which
 * worker ran an item.
 */
#ifndef PS_PARALLEL_H
#define PS_PARALLEL_H

#include "pointseg.h"

#include <stddef.h>

/* Threads to use for a request: requested if > 0, else the online cores. */
int ps_parallel_threads(int requested);

/* fn(ctx, begin, end, worker) runs on disjoint ranges covering [0, count);
 * worker is in [0, threads).  chunk = items per hand-out (0 picks one).
 * Runs inline when threads == 1 or count is small. */
typedef void (*ps_range_fn)(void *ctx, size_t begin, size_t end, int worker);
void ps_parallel_for(int threads, size_t count, size_t chunk, ps_range_fn fn,
                     void *ctx);

/* What a tracked loop reports: fractions of phase from lo to hi through
 * ctl (may be NULL; so may its progress callback and cancel flag). */
typedef struct ps_progress_span {
    const ps_control *ctl;
    ps_phase phase;
    double lo, hi;
} ps_progress_span;

/* The fraction share (in [0, 1]) of the way from span->lo to span->hi. */
double ps_progress_span_at(const ps_progress_span *span, double share);

/* fn(ctx, item, worker) for every item in [0, count), as ps_parallel_for
 * with chunk items per hand-out.  Before each item a worker checks the
 * cancel flag; once it is raised no worker starts another item.  After
 * each item, worker 0 alone reports lo + (hi - lo) x items done / count
 * (so fractions are nondecreasing and never reported concurrently), and
 * hi once all are done.  Returns PS_ERR_CANCELLED when cancelled (some
 * items not run), else PS_OK. */
typedef void (*ps_item_fn)(void *ctx, size_t item, int worker);
ps_status ps_parallel_for_tracked(int threads, size_t count, size_t chunk, ps_item_fn fn,
                                  void *ctx, const ps_progress_span *span);

#endif
