/*
 * draw_agreement.h: how far several draws of one model's labels agree
 * (bench_quality --seeds): the mean Rand index error over every pair of
 * draws, and the medoid draw, whose summed error to the others is least.
 * Neither needs people's labels.
 */
#ifndef PS_DRAW_AGREEMENT_H
#define PS_DRAW_AGREEMENT_H

#include <stddef.h>

typedef struct ps_draw_agreement {
    double disagreement; /* mean 1 - RI over the draws' pairs, in [0, 1] */
    int medoid;          /* the draw nearest the others (the first among equals) */
} ps_draw_agreement;

/* labels: #draws arrays of n labels each (draws >= 2). */
ps_draw_agreement ps_draws_agree(const int *const *labels, int draws, size_t n);

#endif
