/*
 * progress_seen.h: a progress callback for tests that records, per phase,
 * how often it was called, how many distinct fractions fell strictly
 * between 0 and 1, the last fraction, and whether any phase went back.
 */
#ifndef PS_PROGRESS_SEEN_H
#define PS_PROGRESS_SEEN_H

#include "pointseg.h"

typedef struct ps_progress_seen {
    int calls[PS_PHASE_COUNT];
    int inside[PS_PHASE_COUNT]; /* distinct fractions in (0, 1), in a row */
    double last[PS_PHASE_COUNT];
    int went_back;              /* a fraction below the phase's last one */
} ps_progress_seen;

/* A ps_progress_fn; user is a zeroed ps_progress_seen. */
void ps_progress_seen_record(void *user, ps_phase phase, double fraction);

#endif
