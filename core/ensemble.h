/*
 * ensemble.h: several samplings of one surface segmented side by side (the
 * phases in step, each phase run for as many samplings at once as the
 * caller has threads, each on all of them, so that one sampling's serial
 * work overlaps another's), the partition the others agree with most
 * kept: the medoid under the Rand index, compared on about
 * PS_ENSEMBLE_SAMPLE of the caller's points.  Method auto only, at the
 * reference sampling (PS_DENSITY_REFERENCE_POINTS, reference_density.h):
 * - a mesh under it: PS_ENSEMBLE_FILLS independent fills of its triangles
 *   (surface_fill.h), each up to the reference with the mesh's points
 *   first, so every fill answers every one of them (ps_ensemble_fill);
 * - an input denser than it: disjoint random draws of its points, each of
 *   the reference sampling (of n / PS_ENSEMBLE_MAX_DRAWS points once that
 *   is more): one draw up to three times the reference, then as many as
 *   fit (an odd number up to PS_ENSEMBLE_MAX_DRAWS); every caller's point
 *   takes the answers (label, supernode, centrality) of its own point in
 *   the chosen draw or of the draw's nearest (ps_ensemble_segment).
 * The supernodes, the hierarchy and the merges are the chosen one's.
 *
 * Why: what the crease steps call a crease depends on the spacing of the
 * points, so the method segments at the sampling its thresholds read,
 * whatever the scanner's; one sampling's partition moves with the sampling
 * (1 - RI 0.05 between two samplings of the same PSB model), and the
 * medoid of several is the typical partition (docs/method.md).  The draws
 * share the centrality samples one run over their points would take (each
 * ceil(S / draws)), so they cost less than one run over the whole input;
 * each fill takes a run's own, and three fills cost three runs.
 */
#ifndef PS_ENSEMBLE_H
#define PS_ENSEMBLE_H

#include "pipeline.h"

#ifndef PS_ENSEMBLE_MAX_DRAWS
#define PS_ENSEMBLE_MAX_DRAWS 5 /* odd: the medoid of two is no choice;
                                   5 against 3 at 200,000 points: method.md */
#endif
#define PS_ENSEMBLE_SAMPLE 4096 /* points the draws are compared on */
#define PS_ENSEMBLE_FILLS 3     /* fills of a mesh under the reference sampling */
#define PS_ENSEMBLE_FILL_MARGIN 0.01 /* fill 0 answers unless another's summed
                                        error is lower by more: near ties
                                        flipped under rotation (method.md) */
#define PS_ENSEMBLE_KEY_BITS 20 /* a key's resolution: a rotated copy's rounding
                                   (1e-15 of the distance) crosses a step of
                                   2^-20 on one point in 10^9 */

#define PS_ENSEMBLE_NONE 0xFF /* a point in no draw */

/* Draws for an input of n distinct points (after any surface fill; a
 * repeated point counts once: the reference is a density) under p: 0 (the
 * whole input in one run) for method paper or n at most the reference
 * sampling, else the largest odd count up to PS_ENSEMBLE_MAX_DRAWS whose
 * draws each keep the reference sampling (1 below three times it). */
int ps_ensemble_draws(const ps_params *p, size_t n);

/* Distinct points each draw of an input of n distinct points takes: the
 * reference sampling, or n / PS_ENSEMBLE_MAX_DRAWS (rounded up) when
 * more, so that the draws cover the whole input from
 * PS_ENSEMBLE_MAX_DRAWS times the reference on and leave the rest out
 * below it. */
size_t ps_ensemble_draw_points(size_t n);

/* How many of count draws (or fills) run a phase at once on a run of
 * threads (ps_parallel_threads: 0 = every core): one a thread, at most
 * count.  The memory estimate counts their working memory with it. */
int ps_ensemble_side_by_side(int threads, int count);

/* key out: #P each point's distance to the centroid over the largest
 * such distance, quantized to PS_ENSEMBLE_KEY_BITS bits: the same, but
 * for rounding, for a rotated, scaled, moved or reordered copy.  points
 * #P by dim. */
void ps_ensemble_keys(const double *points, size_t n, int dim, uint32_t *key);

/* draw_of out: #P the draw of each point, or PS_ENSEMBLE_NONE, a hash of
 * its key: each draw takes about size of the distinct of the n points
 * (copies of a point share its key, so its draw); where keys tie so much
 * that a draw would get under half that (a synthetic sphere: every point
 * as far from the centre), a hash of its index.  distinct <= n; size is
 * at most distinct / draws, rounded up. */
void ps_ensemble_assign(const uint32_t *key, size_t n, size_t distinct, int draws, size_t size,
                        uint8_t *draw_of);

/* 1 when the point with this key is among the about s of n on which the
 * draws are compared (a second hash of the key). */
int ps_ensemble_compared(uint32_t key, size_t n, size_t s);

/* labels: #draws by #S, each draw's labels of the same S items.  The draw
 * with the least summed Rand index error to the others (ties: lowest),
 * but the first unless that error is lower than the first's by more than
 * margin. */
int ps_ensemble_medoid(const int *labels, int draws, size_t s, double margin);

/* A mesh under the reference sampling (whole->in with faces, whole
 * prepared as for one run with whole->dedup built on whole->in,
 * ps_surface_fill_wanted of its distinct points) segmented as fills
 * independent fills of it (ps_surface_fill_build's seeds 0 to fills - 1,
 * each up to the reference sampling in distinct points: the mesh's
 * points, copies and all, then the added ones), their
 * phases in step as the draws', and *out from the medoid fill, compared on
 * about PS_ENSEMBLE_SAMPLE of the mesh's points.  *filled 0 (and *out
 * untouched) when a fill adds nothing: the mesh is then to be segmented
 * as given.  Each fill takes the centrality samples of a run over its own
 * distinct points (shared as the draws share them, the 228 scored 0.0019
 * worse). */
ps_status ps_ensemble_fill(ps_pipeline *whole, int fills, int *filled, ps_result **out,
                           ps_error *err);

/* Segments whole->in (whole prepared as for one run: params, threads,
 * ctl, n_input, host_of_added; distinct: its distinct points, dedup.h)
 * in draws draws (ps_ensemble_draws of distinct), and *out as above.  The
 * phases run draw after draw within each phase, progress per phase over
 * all draws; the phase times are summed over the draws, the medoid and
 * the answers' transfer timed as refine. */
ps_status ps_ensemble_segment(ps_pipeline *whole, int draws, size_t distinct, ps_result **out,
                              ps_error *err);

#endif
