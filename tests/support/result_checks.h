/*
 * result_checks.h: checks of a ps_result for the end-to-end tests
 * (test_segment.c, test_ensemble.c): that it is self-consistent, and that
 * known parts of a synthetic shape come out in segments of their own.
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

#endif
