/*
 * control.c: the caller's side of ps_control (pointseg.h): raising a cancel
 * flag while a run reads it (util/control.h is the run's side).
 */
#include "pointseg.h"

#include <stdatomic.h>

void ps_cancel_raise(volatile int *flag) {
    atomic_store_explicit((volatile atomic_int *)flag, 1, memory_order_relaxed);
}
