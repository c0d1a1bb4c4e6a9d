/*
 * keyed_tasks.c: the keyed task runner of keyed_tasks.h.
 *
 * Each task knows the latest earlier task of each of its keys (after_a,
 * after_b, index + 1; 0 for none): it may start once those two are done,
 * for each of them waited in turn for the one before it.  The worker slots
 * are the items of a ps_parallel_for; under one mutex a slot takes the
 * lowest waiting task that may start, or sleeps until a task finishes.
 * With one slot the tasks simply run in index order.
 */
#include "util/keyed_tasks.h"

#include "util/parallel.h"

#include <pthread.h>
#include <stdlib.h>

enum { WAITING, RUNNING, DONE };

typedef struct runner {
    const ps_keyed_tasks *t;
    size_t *after_a, *after_b; /* #T */
    unsigned char *state;      /* #T */
    size_t first_waiting;      /* no task below it is WAITING */
    size_t done, running;
    ps_status status;
    int failed_worker;
    pthread_mutex_t lock;
    pthread_cond_t finished;
} runner;

static int may_start(const runner *r, size_t i) {
    return r->state[i] == WAITING && (r->after_a[i] == 0 || r->state[r->after_a[i] - 1] == DONE) &&
           (r->after_b[i] == 0 || r->state[r->after_b[i] - 1] == DONE);
}

/* The lowest task that may start, or SIZE_MAX. */
static size_t next_task(runner *r) {
    while (r->first_waiting < r->t->count && r->state[r->first_waiting] != WAITING)
        r->first_waiting++;
    for (size_t i = r->first_waiting; i < r->t->count; i++)
        if (may_start(r, i)) return i;
    return SIZE_MAX;
}

/* Called with the lock held: the task's end, its report and its wake-up. */
static void finish(runner *r, size_t task, ps_status st, int worker) {
    r->state[task] = DONE;
    r->running--;
    r->done++;
    if (st != PS_OK && r->status == PS_OK) r->status = st, r->failed_worker = worker;
    if (r->t->report && st == PS_OK) r->t->report(r->t->ctx, r->done);
    pthread_cond_broadcast(&r->finished);
}

static void worker_slot(void *ctx, size_t begin, size_t end, int thread) {
    runner *r = ctx;
    (void)thread;
    for (size_t slot = begin; slot < end; slot++) {
        pthread_mutex_lock(&r->lock);
        while (r->status == PS_OK && r->done + r->running < r->t->count) {
            size_t task = next_task(r);
            if (task == SIZE_MAX && r->running == 0) break; /* only if a key is out of range */
            if (task == SIZE_MAX) {
                pthread_cond_wait(&r->finished, &r->lock);
                continue;
            }
            r->state[task] = RUNNING;
            r->running++;
            pthread_mutex_unlock(&r->lock);
            ps_status st = r->t->run(r->t->ctx, task, (int)slot);
            pthread_mutex_lock(&r->lock);
            finish(r, task, st, (int)slot);
        }
        pthread_mutex_unlock(&r->lock);
    }
}

/* after_a and after_b from the keys, in one pass. */
static int link_tasks(runner *r) {
    const ps_keyed_tasks *t = r->t;
    size_t *last = calloc(t->n_keys > 0 ? (size_t)t->n_keys : 1, sizeof *last);
    if (!last) return -1;
    for (size_t i = 0; i < t->count; i++) {
        r->after_a[i] = last[t->key_a[i]];
        r->after_b[i] = last[t->key_b[i]];
        last[t->key_a[i]] = last[t->key_b[i]] = i + 1;
    }
    free(last);
    return 0;
}

ps_status ps_keyed_tasks_run(const ps_keyed_tasks *t, int workers, int *failed_worker) {
    size_t n = t->count ? t->count : 1;
    runner r = {.t = t, .status = PS_OK, .failed_worker = -1,
                .after_a = malloc(n * sizeof *r.after_a), .after_b = malloc(n * sizeof *r.after_b),
                .state = calloc(n, sizeof *r.state)};
    ps_status st = r.after_a && r.after_b && r.state && link_tasks(&r) == 0 ? PS_OK : PS_ERR_NOMEM;
    if (st == PS_OK) {
        pthread_mutex_init(&r.lock, NULL);
        pthread_cond_init(&r.finished, NULL);
        ps_parallel_for(workers > 1 ? workers : 1, (size_t)(workers > 1 ? workers : 1), 1,
                        worker_slot, &r);
        pthread_cond_destroy(&r.finished);
        pthread_mutex_destroy(&r.lock);
        st = r.status;
        if (failed_worker) *failed_worker = r.failed_worker;
    }
    free(r.after_a), free(r.after_b), free(r.state);
    return st;
}
