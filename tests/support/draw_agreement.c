/*
 * draw_agreement.c: the draws' agreement of draw_agreement.h.
 */
#include "draw_agreement.h"

#include "pointseg.h"

#include <float.h>

#define MAX_DRAWS 16

ps_draw_agreement ps_draws_agree(const int *const *labels, int draws, size_t n) {
    double to_others[MAX_DRAWS] = {0}, total = 0;
    if (draws > MAX_DRAWS) draws = MAX_DRAWS;
    for (int a = 0; a < draws; a++)
        for (int b = a + 1; b < draws; b++) {
            double e = ps_rand_index_error(labels[a], labels[b], n);
            to_others[a] += e, to_others[b] += e, total += e;
        }
    ps_draw_agreement out = {total / (draws * (draws - 1) / 2.0), 0};
    double least = DBL_MAX;
    for (int d = 0; d < draws; d++)
        if (to_others[d] < least) least = to_others[d], out.medoid = d;
    return out;
}
