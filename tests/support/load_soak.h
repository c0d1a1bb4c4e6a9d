/*
 * load_soak.h: a soak of pointsegd with mixed valid and invalid requests
 * (bench_load's part c): a fixed list of requests, each with the status it
 * must get (small segmentations with extra arrays, async jobs, health and
 * metrics, and malformed bodies, headers and parameters), cycled over N
 * concurrent keep-alive connections until a number of requests is done,
 * with the daemon's VmRSS read at the start, the middle and the end.
 */
#ifndef PS_LOAD_SOAK_H
#define PS_LOAD_SOAK_H

#include <stddef.h>
#include <sys/types.h>

typedef struct ps_soak_stats {
    size_t done;          /* requests answered or failed */
    size_t wrong_status;  /* answered with another status than expected */
    size_t transport_errors;
    size_t kinds;         /* distinct requests in the cycle */
    double seconds;
    long rss_kb[3];       /* start, middle, end */
    long hwm_kb;
} ps_soak_stats;

/* Runs requests over connections against base_url ("http://127.0.0.1:P"),
 * the daemon being process pid; 0, or -1 when it could not start. */
int ps_soak_run(const char *base_url, pid_t pid, size_t requests, int connections, ps_soak_stats *st);

/* A "Name:   123 kB" line of /proc/PID/status, in kB; -1 if absent. */
long ps_proc_status_kb(pid_t pid, const char *name);

#endif
