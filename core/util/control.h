/*
 * control.h: reading a caller's ps_control (pointseg.h) from inside the
 * core: whether the cancel flag is raised, and reporting progress.
 *
 * The cancel flag is written by another thread while the core runs, so it
 * is read atomically (relaxed: it only asks work to stop soon).
 */
#ifndef PS_CONTROL_H
#define PS_CONTROL_H

#include "pointseg.h"

#include <stdatomic.h>

/* 1 when the flag (may be NULL) is raised. */
static inline int ps_cancel_raised(const volatile int *cancel) {
    return cancel &&
           atomic_load_explicit((const volatile atomic_int *)cancel, memory_order_relaxed);
}

/* 1 when ctl (may be NULL) asks to cancel. */
static inline int ps_control_cancelled(const ps_control *ctl) {
    return ctl && ps_cancel_raised(ctl->cancel);
}

/* Reports fraction of phase to ctl's progress callback, if any. */
static inline void ps_control_progress(const ps_control *ctl, ps_phase phase, double fraction) {
    if (ctl && ctl->progress) ctl->progress(ctl->user, phase, fraction);
}

#endif
