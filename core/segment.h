/*
 * segment.h: PRIVATE to the top of core/ (segment.c, ensemble.c): one
 * phase of the method on a pipeline, its steps as segment.c's table lists
 * them.
 */
#ifndef PS_SEGMENT_H
#define PS_SEGMENT_H

#include "pipeline.h"

/* The steps of phase ph that pl's method and input call for, in order, on
 * pl (after ps_pipeline_dedup and the phases before it): progress 0 and 1
 * around the phase, each step's wall time and the phase's in pl->timings;
 * fails with PS_ERR_CANCELLED when pl->ctl asks to cancel before a step. */
ps_status ps_segment_phase(ps_pipeline *pl, ps_phase ph, ps_error *err);

#endif
