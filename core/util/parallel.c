/* parallel.c: the chunked parallel for loop of parallel.h on pthreads, and
 * its tracked form (cancel and progress between items). */
#include "util/parallel.h"

#include "util/control.h"

#include <pthread.h>
#include <stdatomic.h>
#include <unistd.h>

typedef struct loop {
    atomic_size_t next;
    size_t count, chunk;
    ps_range_fn fn;
    void *ctx;
} loop;

typedef struct worker_arg {
    loop *l;
    int worker;
} worker_arg;

int ps_parallel_threads(int requested) {
    if (requested > 0) return requested;
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    return cores > 0 ? (int)cores : 1;
}

static void *run_worker(void *p) {
    worker_arg *a = p;
    loop *l = a->l;
    for (;;) {
        size_t begin = atomic_fetch_add(&l->next, l->chunk);
        if (begin >= l->count) break;
        size_t end = begin + l->chunk < l->count ? begin + l->chunk : l->count;
        l->fn(l->ctx, begin, end, a->worker);
    }
    return NULL;
}

#define MAX_THREADS 256

void ps_parallel_for(int threads, size_t count, size_t chunk, ps_range_fn fn,
                     void *ctx) {
    if (count == 0) return;
    if (threads > MAX_THREADS) threads = MAX_THREADS;
    if (chunk == 0) chunk = count / ((size_t)threads * 8) + 1;
    if (threads <= 1 || count <= chunk) {
        fn(ctx, 0, count, 0);
        return;
    }
    loop l = {.count = count, .chunk = chunk, .fn = fn, .ctx = ctx};
    atomic_init(&l.next, 0);
    pthread_t tid[MAX_THREADS];
    worker_arg args[MAX_THREADS];
    int started = 0;
    for (int w = 1; w < threads; w++) {
        args[w] = (worker_arg){&l, w};
        if (pthread_create(&tid[w], NULL, run_worker, &args[w]) != 0) break;
        started = w;
    }
    args[0] = (worker_arg){&l, 0};
    run_worker(&args[0]); /* the caller works too; it also finishes what
                             threads that failed to start would have done */
    for (int w = 1; w <= started; w++) pthread_join(tid[w], NULL);
}

typedef struct tracked {
    ps_item_fn fn;
    void *ctx;
    const ps_progress_span *span;
    size_t count;
    atomic_int cancelled; /* a worker saw the cancel flag */
    atomic_size_t done;   /* items finished */
} tracked;

static int tracked_stop(tracked *t) {
    if (atomic_load(&t->cancelled)) return 1;
    if (!ps_control_cancelled(t->span->ctl)) return 0;
    atomic_store(&t->cancelled, 1);
    return 1;
}

static void tracked_range(void *p, size_t begin, size_t end, int worker) {
    tracked *t = p;
    const ps_progress_span *s = t->span;
    for (size_t i = begin; i < end && !tracked_stop(t); i++) {
        t->fn(t->ctx, i, worker);
        size_t done = atomic_fetch_add(&t->done, 1) + 1;
        if (worker == 0)
            ps_control_progress(s->ctl, s->phase,
                                s->lo + (s->hi - s->lo) * (double)done / (double)t->count);
    }
}

double ps_progress_span_at(const ps_progress_span *span, double share) {
    return span->lo + (span->hi - span->lo) * share;
}

ps_status ps_parallel_for_tracked(int threads, size_t count, size_t chunk, ps_item_fn fn,
                                  void *ctx, const ps_progress_span *span) {
    tracked t = {.fn = fn, .ctx = ctx, .span = span, .count = count};
    atomic_init(&t.cancelled, 0);
    atomic_init(&t.done, 0);
    ps_parallel_for(threads, count, chunk, tracked_range, &t);
    if (atomic_load(&t.cancelled)) return PS_ERR_CANCELLED;
    ps_control_progress(span->ctl, span->phase, span->hi);
    return PS_OK;
}
