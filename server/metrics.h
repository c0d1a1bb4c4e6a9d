/*
 * metrics.h: the daemon's Prometheus counters: requests by route and status,
 * a request latency histogram per route, and (from the job backend's stats)
 * queue depth, running jobs, jobs by outcome and points segmented; with a
 * Redis job store, the shared queue's length and pending jobs, reclaimed
 * jobs, and Redis commands, errors and latency; and connections the guard
 * cut (guard.h).
 * Thread safe.
 */
#ifndef PS_METRICS_H
#define PS_METRICS_H

#include <stddef.h>

#include "jobs.h"
#include "jobstore.h"

typedef enum ps_route {
    PS_ROUTE_SEGMENT = 0, PS_ROUTE_JOBS, PS_ROUTE_JOB, PS_ROUTE_JOB_RESULT,
    PS_ROUTE_HEALTHZ, PS_ROUTE_READYZ, PS_ROUTE_METRICS, PS_ROUTE_OPENAPI,
    PS_ROUTE_VERSION, PS_ROUTE_STATIC, PS_ROUTE_OTHER, PS_ROUTE_COUNT
} ps_route;

const char *ps_route_name(ps_route r); /* "/segment", "/jobs/{id}", ... */

/* Counts one answered request that took `seconds`. */
void ps_metrics_observe(ps_route route, int status, double seconds);

/* Counts n connections cut for being slow, idle or abandoned. */
void ps_metrics_connections_cut(size_t n);

/* The text exposition document (malloc'ed, *len its length), or NULL. */
char *ps_metrics_render(const ps_jobs_stats *jobs, const ps_jobstore_stats *store, size_t *len);

#endif
