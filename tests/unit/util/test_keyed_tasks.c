/*
 * test_keyed_tasks.c: the keyed task runner (keyed_tasks.h).  On 1, 2 and 4
 * workers every task runs once, the tasks of each key in index order and
 * each after every earlier task sharing a key had finished, and the
 * progress reports count up to the total one by one; a failing task stops
 * the run, returns its status and names its worker slot; no tasks is fine.
 */
#include "testlib.h"
#include "util/keyed_tasks.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define TASKS 200
#define KEYS 12

typedef struct log {
    int key_a[TASKS], key_b[TASKS];
    pthread_mutex_t lock;
    int order[TASKS];       /* tasks in the order they finished */
    int started[TASKS];     /* finish count when each started */
    int finished_at[TASKS]; /* its place in order */
    int n_finished, runs[TASKS], reports_ok, last_report;
    int fail_task;          /* -1: none */
} log;

static ps_status run(void *ctx, size_t task, int worker) {
    log *l = ctx;
    (void)worker;
    pthread_mutex_lock(&l->lock);
    l->started[task] = l->n_finished;
    pthread_mutex_unlock(&l->lock);
    struct timespec pause = {0, 20000 * (long)(task % 7 + 1)}; /* tasks of uneven length */
    nanosleep(&pause, NULL);
    pthread_mutex_lock(&l->lock);
    l->runs[task]++;
    l->finished_at[task] = l->n_finished;
    l->order[l->n_finished++] = (int)task;
    pthread_mutex_unlock(&l->lock);
    return (int)task == l->fail_task ? PS_ERR_NOMEM : PS_OK;
}

static void report(void *ctx, size_t done) {
    log *l = ctx;
    if ((int)done != l->last_report + 1) l->reports_ok = 0;
    l->last_report = (int)done;
}

static void fill(log *l, int fail_task) {
    memset(l, 0, sizeof *l);
    pthread_mutex_init(&l->lock, NULL);
    unsigned s = 7;
    for (int i = 0; i < TASKS; i++) {
        s = s * 1103515245u + 12345u;
        l->key_a[i] = (int)((s >> 16) % KEYS);
        s = s * 1103515245u + 12345u;
        l->key_b[i] = (int)((s >> 16) % KEYS);
    }
    l->reports_ok = 1;
    l->fail_task = fail_task;
}

/* Every task j < i that shares a key with i finished before i started. */
static int order_kept(const log *l) {
    for (int i = 0; i < TASKS; i++)
        for (int j = 0; j < i; j++) {
            int shares = l->key_a[j] == l->key_a[i] || l->key_a[j] == l->key_b[i] ||
                         l->key_b[j] == l->key_a[i] || l->key_b[j] == l->key_b[i];
            if (shares && l->finished_at[j] >= l->started[i]) return 0;
        }
    return 1;
}

static void test_order_for_any_worker_count(void) {
    int counts[] = {1, 2, 4};
    for (int c = 0; c < 3; c++) {
        log l;
        fill(&l, -1);
        ps_keyed_tasks t = {.count = TASKS, .key_a = l.key_a, .key_b = l.key_b, .n_keys = KEYS,
                            .run = run, .report = report, .ctx = &l};
        int failed = -2;
        CHECK(ps_keyed_tasks_run(&t, counts[c], &failed) == PS_OK);
        CHECK(failed == -1);
        int once = 1;
        for (int i = 0; i < TASKS; i++) once &= l.runs[i] == 1;
        CHECK_MSG(once && l.n_finished == TASKS, "%d workers: every task once", counts[c]);
        CHECK_MSG(order_kept(&l), "%d workers: a task started before an earlier one of its key "
                  "finished", counts[c]);
        CHECK(l.reports_ok && l.last_report == TASKS);
        pthread_mutex_destroy(&l.lock);
    }
}

static void test_failure_stops(void) {
    log l;
    fill(&l, 50);
    ps_keyed_tasks t = {.count = TASKS, .key_a = l.key_a, .key_b = l.key_b, .n_keys = KEYS,
                        .run = run, .ctx = &l};
    int failed = -2;
    CHECK(ps_keyed_tasks_run(&t, 2, &failed) == PS_ERR_NOMEM);
    CHECK(failed == 0 || failed == 1);
    CHECK(l.runs[50] == 1 && l.n_finished < TASKS);
    pthread_mutex_destroy(&l.lock);
}

static void test_no_tasks(void) {
    ps_keyed_tasks t = {.count = 0, .n_keys = 0, .run = run};
    int failed = -2;
    CHECK(ps_keyed_tasks_run(&t, 2, &failed) == PS_OK && failed == -1);
}

PS_TEST_MAIN(TEST(test_order_for_any_worker_count), TEST(test_failure_stops),
             TEST(test_no_tasks))
