/*
 * deadline.h: the server's two clocks.
 * ps_deadline_in_ms: the absolute time `ms` milliseconds from now on
 * CLOCK_REALTIME, the clock pthread_cond_timedwait measures its deadline on.
 *   ms  milliseconds from now, >= 0
 *   returns  the deadline, tv_nsec normalized to [0, 1e9)
 * ps_monotonic_seconds: seconds on CLOCK_MONOTONIC, for measuring how long
 * something took (no wall-clock steps).
 */
#ifndef PS_DEADLINE_H
#define PS_DEADLINE_H

#include <time.h>

static inline struct timespec ps_deadline_in_ms(long ms) {
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    ts.tv_sec += ms / 1000;
    ts.tv_nsec += ms % 1000 * 1000000L;
    if (ts.tv_nsec >= 1000000000L) {
        ts.tv_sec++;
        ts.tv_nsec -= 1000000000L;
    }
    return ts;
}

static inline double ps_monotonic_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

#endif
