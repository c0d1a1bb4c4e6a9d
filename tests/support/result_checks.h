/*
 * result_checks.h: ps_segment run and its ps_result checked, for the
 * end-to-end tests (test_segment*.c, test_ensemble.c): that the result is
 * self-consistent, that known parts of a synthetic shape come out in
 * segments of their own, that a shape without parts comes out whole, and
 * how far two partitions of the same points are apart.
 * Failures are reported through testlib.h's CHECK, at this file's lines.
 */
#ifndef PS_RESULT_CHECKS_H
#define PS_RESULT_CHECKS_H

#include "pointseg.h"

/* The segment most points of part `which` carry (part: #P each point's
 * true part), and in *purity the share of the part's points it holds. */
int ps_majority_label(const ps_result *r, const int *part, int which, double *purity);

/* Parts first..last each hold at least min_purity of their points in one
 * segment, and no two share that segment. */
void ps_check_parts_separate(const ps_result *r, const int *part, int first, int last,
                             double min_purity);

/* Labels and supernodes in range, each supernode inside its point's
 * segment, finite centrality, segment and supernode sizes adding up to
 * the points (segments largest first), and a hierarchy whose children
 * split their parent's supernodes. */
void ps_check_result_consistent(const ps_result *r);

/* The share of the n points outside the segment of labels_b (#n, ids
 * from 0) that overlaps most with their segment of a: 0 when b is a's
 * partition, under any renaming of its labels.  1 without memory. */
double ps_moved_share(const ps_result *a, const int *labels_b, size_t n);

/* ps_segment of the #n by 3 points with params p, CHECKed to succeed:
 * the result (ps_result_free it), NULL when it failed. */
ps_result *ps_segment_with(const double *pts, size_t n, const ps_params *p);

/* The same with the defaults. */
ps_result *ps_segment_default(const double *pts, size_t n);

/* Segments a synthetic shape (#n by 3 pts, part #n each point's true
 * part) with params p and checks that the result is consistent and its
 * parts first..last come out apart (ps_check_parts_separate, min_purity);
 * frees pts and part.  Returns the result's normal_smoothing (-1 without
 * a result). */
int ps_check_parts_with(double *pts, size_t n, int *part, int first, int last,
                        double min_purity, const ps_params *p);

/* The same with the defaults. */
int ps_check_shape_parts(double *pts, size_t n, int *part, int first, int last,
                         double min_purity);

/* Checks that the default makes one segment of the #n by 3 points (and
 * frees them); name says which in the message. */
void ps_check_one_part(double *pts, size_t n, const char *name);

#endif
