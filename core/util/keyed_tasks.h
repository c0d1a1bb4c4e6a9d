/*
 * keyed_tasks.h: tasks run side by side in an order their keys constrain
 * (the boundary cut's pairs of segments, boundary_cut.c).
 *
 * Task i (of #T, in index order) has two keys, ints in [0, n_keys): the
 * two segments of a pair.  A task starts only once every earlier task
 * sharing a key with it has finished, and a free worker takes the lowest
 * task that may start.  So the tasks of one key run one after the other in
 * index order, and a task that reads and writes only what belongs to its
 * keys sees exactly what a run of all tasks in index order on one worker
 * would show it: the results do not depend on the worker count.
 */
#ifndef PS_KEYED_TASKS_H
#define PS_KEYED_TASKS_H

#include "pointseg.h"

/* Runs task on worker slot worker (each slot runs one task at a time). */
typedef ps_status (*ps_keyed_task_fn)(void *ctx, size_t task, int worker);
/* Told, one call at a time and in increasing order, how many tasks are done. */
typedef void (*ps_keyed_report_fn)(void *ctx, size_t done);

typedef struct ps_keyed_tasks {
    size_t count;               /* #T */
    const int *key_a, *key_b;   /* #T each, in [0, n_keys) */
    int n_keys;
    ps_keyed_task_fn run;
    ps_keyed_report_fn report;  /* may be NULL */
    void *ctx;
} ps_keyed_tasks;

/* Runs every task on workers (>= 1) worker slots.  Once a task fails no
 * other starts; returns the first failure (*failed_worker: its slot) or
 * PS_OK; PS_ERR_NOMEM when out of memory before any task ran. */
ps_status ps_keyed_tasks_run(const ps_keyed_tasks *t, int workers, int *failed_worker);

#endif
