/* progress_seen.c: the recording progress callback of progress_seen.h. */
#include "progress_seen.h"

void ps_progress_seen_record(void *user, ps_phase phase, double fraction) {
    ps_progress_seen *s = user;
    if (fraction < s->last[phase]) s->went_back = 1;
    if (fraction > 0 && fraction < 1 && fraction != s->last[phase]) s->inside[phase]++;
    s->last[phase] = fraction;
    s->calls[phase]++;
}
