/*
 * profile_split.h: a maximum's supernode cut where its level-set profile
 * jumps (method auto, 3-D), so that a thin limb and the wide part its
 * basin flows down over (a glasses arm and its lens, a finger and the palm)
 * become two supernodes.  No closed crease need ring the junction: what
 * tells the two apart is the width of the shape across f.
 *
 * For a maximum's supernode S with top point m, S's points are walked down
 * from f(m) in bands of f of width h = PS_PROFILE_BAND_SPACINGS times the
 * median spacing of S's points (a point's spacing: its mean kNN edge
 * length, measured on the points).  A band's cross-section perimeter is
 * P = (sum of its points' areas) / h, a point's area its spacing squared,
 * so that the estimate does not depend on the sampling density.  The tip's
 * cap (the bands down to the limb's radius, median P / 2 pi) is left out of
 * the reference, the median P of the bands between the cap and the current
 * one (at least PS_PROFILE_MIN_BANDS of them).  The first band whose P,
 * and that of the PS_PROFILE_PERSIST bands below it, exceeds
 * PS_PROFILE_JUMP times the reference, at a depth f(m) - t of at least the
 * reference / pi (an elongated part above: as long as it is wide), gives
 * the level t: the points of S at f >= t connected to m through such
 * points become a new supernode, when both it and the rest hold at least
 * PS_PERSISTENCE_MIN_BASIN points and PS_PROFILE_MIN_SHARE of S (up to
 * PS_PROFILE_TRIES levels are tried).  At most one cut per supernode.
 * docs/method.md, section 2, has the measurements.
 */
#ifndef PS_PROFILE_SPLIT_H
#define PS_PROFILE_SPLIT_H

#include "features/supernodes.h"

#define PS_PROFILE_BAND_SPACINGS 3.0 /* band width, in median point spacings */
#define PS_PROFILE_JUMP 3.0          /* a band this much wider than the reference is a jump */
#define PS_PROFILE_PERSIST 2         /* bands below the jump that must be as wide */
#define PS_PROFILE_MIN_BANDS 3       /* bands in the reference at least */
#define PS_PROFILE_MIN_SHARE 0.05    /* each piece at least this share of the supernode */
#define PS_PROFILE_TRIES 4           /* levels tried per supernode at most */

/* g the kNN graph, points #P by 3, f #P the centrality, spacing #P each
 * point's mean kNN edge length (Euclidean; ps_crease_weights gives them
 * from its pass over the edges).  sn is replaced by its refinement (ps_supernodes_relabel): every new
 * supernode lies inside one old one and keeps its is_minimum; minima's
 * supernodes are not cut, nor is a supernode with more bands than points.
 * O(P + E + S), plus O(B^2) per supernode of B bands (B is at most its f
 * range over the band width, and at most its point count). */
ps_status ps_profile_split(const ps_graph *g, const double *points, const double *f,
                           const double *spacing, ps_supernodes *sn, ps_error *err);

#endif
