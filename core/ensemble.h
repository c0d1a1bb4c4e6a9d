/*
 * ensemble.h: method auto on an input at least three times the reference
 * sampling (PS_DENSITY_REFERENCE_POINTS, reference_density.h) segments as
 * many disjoint random draws of its points as keep the reference density
 * each (an odd number from 3 to PS_ENSEMBLE_MAX_DRAWS), and keeps the
 * draw whose partition the others agree with most: the medoid under the
 * Rand index, compared on about PS_ENSEMBLE_SAMPLE of the input's points.  Every caller's point takes
 * the answers (label, supernode, centrality) of its own point in that
 * draw or of the draw's nearest; the supernodes, the hierarchy and the
 * merges are that draw's.
 *
 * Why: one sampling's partition moves with the sampling (1 - RI 0.06
 * between two samplings of the same PSB model), and a denser sampling
 * segments worse than the reference one; the medoid of draws at the
 * reference density is the typical partition (docs/method.md).  The
 * draws share one run's centrality samples (each ceil(S / draws), S the
 * whole input's count), so the ensemble costs less than one run.
 */
#ifndef PS_ENSEMBLE_H
#define PS_ENSEMBLE_H

#include "pipeline.h"

#ifndef PS_ENSEMBLE_MAX_DRAWS
#define PS_ENSEMBLE_MAX_DRAWS 5 /* odd: the medoid of two is no choice;
                                   5 against 3 at 200,000 points: method.md */
#endif
#define PS_ENSEMBLE_SAMPLE 4096 /* points the draws are compared on */
#define PS_ENSEMBLE_KEY_BITS 20 /* a key's resolution: a rotated copy's rounding
                                   (1e-15 of the distance) crosses a step of
                                   2^-20 on one point in 10^9 */

/* Draws for an input of n points (after any surface fill) under p: for
 * method auto the largest odd count from 3 to PS_ENSEMBLE_MAX_DRAWS whose
 * draws each keep the reference sampling, else 1 (the whole input in one
 * run). */
int ps_ensemble_draws(const ps_params *p, size_t n);

/* key out: #P each point's distance to the centroid over the largest
 * such distance, quantized to PS_ENSEMBLE_KEY_BITS bits: the same, but
 * for rounding, for a rotated, scaled, moved or reordered copy.  points
 * #P by dim. */
void ps_ensemble_keys(const double *points, size_t n, int dim, uint32_t *key);

/* draw_of out: #P the draw of each point, a hash of its key; where keys
 * tie so much that a draw would get under half its share (a synthetic
 * sphere: every point as far from the centre), a hash of its index. */
void ps_ensemble_assign(const uint32_t *key, size_t n, int draws, uint8_t *draw_of);

/* 1 when the point with this key is among the about s of n on which the
 * draws are compared (a second hash of the key). */
int ps_ensemble_compared(uint32_t key, size_t n, size_t s);

/* labels: #draws by #S, each draw's labels of the same S items.  The draw
 * with the least summed Rand index error to the others (ties: lowest). */
int ps_ensemble_medoid(const int *labels, int draws, size_t s);

/* Segments whole->in (whole prepared as for one run: params, threads,
 * ctl, n_input, host_of_added) in draws draws, and *out as above.  The
 * phases run draw after draw within each phase, progress per phase over
 * all draws; the phase times are summed over the draws, the medoid and
 * the answers' transfer timed as refine. */
ps_status ps_ensemble_segment(ps_pipeline *whole, int draws, ps_result **out, ps_error *err);

#endif
