/* test_parallel.c: ps_parallel_for runs every index once; the tracked loop
 * (ps_parallel_for_tracked) runs every item once with 1 or 4 threads,
 * reports nondecreasing fractions of its phase from lo to exactly hi,
 * runs nothing when cancelled before it starts and stops starting items
 * once an item raises the flag. */
#include "testlib.h"
#include "util/parallel.h"

#include <stdatomic.h>

#define ITEMS 1000

typedef struct item_log {
    atomic_int runs[ITEMS];    /* times each item ran */
    atomic_int total;
    volatile int *cancel;      /* raised by the item cancel_at, if set */
    int cancel_at;
} item_log;

static void run_item(void *ctx, size_t item, int worker) {
    item_log *log = ctx;
    (void)worker;
    atomic_fetch_add(&log->runs[item], 1);
    atomic_fetch_add(&log->total, 1);
    if (log->cancel && (int)item == log->cancel_at) *log->cancel = 1;
}

static void run_range(void *ctx, size_t begin, size_t end, int worker) {
    for (size_t i = begin; i < end; i++) run_item(ctx, i, worker);
}

static void log_clear(item_log *log) {
    for (int i = 0; i < ITEMS; i++) atomic_init(&log->runs[i], 0);
    atomic_init(&log->total, 0);
    log->cancel = NULL;
    log->cancel_at = -1;
}

typedef struct reports {
    int count, monotone, wrong_phase;
    double first, last;
} reports;

static void on_progress(void *user, ps_phase phase, double fraction) {
    reports *r = user;
    if (r->count == 0) r->first = fraction;
    else if (fraction < r->last) r->monotone = 0;
    r->wrong_phase += phase != PS_PHASE_REFINE;
    r->last = fraction;
    r->count++;
}

static void test_every_index_once(void) {
    static item_log log;
    for (int threads = 1; threads <= 4; threads += 3) {
        log_clear(&log);
        ps_parallel_for(threads, ITEMS, 0, run_range, &log);
        for (int i = 0; i < ITEMS; i++) CHECK(atomic_load(&log.runs[i]) == 1);
    }
}

static void test_tracked_runs_all_and_reports(void) {
    static item_log log;
    for (int threads = 1; threads <= 4; threads += 3) {
        log_clear(&log);
        reports r = {0, 1, 0, 0.0, 0.0};
        ps_control ctl = {on_progress, &r, NULL};
        ps_progress_span span = {&ctl, PS_PHASE_REFINE, 0.25, 0.75};
        CHECK(ps_parallel_for_tracked(threads, ITEMS, 1, run_item, &log, &span) == PS_OK);
        for (int i = 0; i < ITEMS; i++) CHECK(atomic_load(&log.runs[i]) == 1);
        /* only the calling thread reports along the way, and with 4 threads
         * the others may take every item before it starts: then only the
         * final report comes */
        CHECK(r.count >= (threads == 1 ? 2 : 1) && r.monotone && r.wrong_phase == 0);
        CHECK(r.first > 0.25 && r.first <= 0.75);
        CHECK(r.last == 0.75);
    }
}

static void test_tracked_cancel(void) {
    static item_log log;
    log_clear(&log);
    volatile int cancel = 1;
    reports r = {0, 1, 0, 0.0, 0.0};
    ps_control ctl = {on_progress, &r, &cancel};
    ps_progress_span span = {&ctl, PS_PHASE_REFINE, 0.0, 1.0};
    CHECK(ps_parallel_for_tracked(4, ITEMS, 1, run_item, &log, &span) == PS_ERR_CANCELLED);
    CHECK(atomic_load(&log.total) == 0 && r.count == 0);

    cancel = 0; /* item 10 raises it: with 1 thread the items after it never run */
    log_clear(&log);
    log.cancel = &cancel, log.cancel_at = 10;
    CHECK(ps_parallel_for_tracked(1, ITEMS, 1, run_item, &log, &span) == PS_ERR_CANCELLED);
    CHECK(atomic_load(&log.total) == 11);
    CHECK(r.last < 1.0); /* no final report */
}

PS_TEST_MAIN(TEST(test_every_index_once), TEST(test_tracked_runs_all_and_reports),
             TEST(test_tracked_cancel))
