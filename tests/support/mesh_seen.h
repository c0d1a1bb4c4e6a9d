/*
 * mesh_seen.h: what a scanner sees of a triangle mesh from some of the six
 * directions of its axes: all six (a scan taken from six sides,
 * bench_quality's seen:N mode) or the front alone (one depth image, its
 * view:N mode).  A point is seen when, in at least one of the views
 * (orthographic), it lies on the surface nearest the viewer: a depth
 * buffer of the mesh's triangles per view, PS_SEEN_PIXELS square over the
 * mesh's bounding box.  What no view sees (between a horse's legs, inside
 * a cup; from the front, the back) is missing from the scan.
 * Deterministic.
 */
#ifndef PS_MESH_SEEN_H
#define PS_MESH_SEEN_H

#include <stddef.h>
#include <stdint.h>

#include "pointset.h"

#define PS_SEEN_PIXELS 512 /* the depth buffers' side, over the box's larger extent */

/* The views: bit v looks along axis v / 2 from its high end (v even) or its
 * low end (v odd). */
#define PS_SEEN_SIX 0x3F

/* The bit of the front view: from the high end of the shortest axis of the
 * mesh's bounding box, where the mesh shows its largest outline. */
unsigned ps_mesh_front_view(const ps_pointset *mesh);

/* The depth buffers of some views of a mesh. */
typedef struct ps_seen ps_seen;

/* The buffers of the views (bits) of mesh's #F by 3 triangles; it borrows
 * the mesh's arrays, which must outlive it.  NULL when memory runs out. */
ps_seen *ps_seen_build(const ps_pointset *mesh, unsigned views);
void ps_seen_free(ps_seen *seen);

/* flags[i] = 1 when point i of the #n by 3 points (on the mesh's surface)
 * is within two pixels' depth of the nearest surface at its pixel in one
 * of the views, else 0. */
void ps_seen_flags(const ps_seen *seen, const double *points, size_t n, unsigned char *flags);

/* n points uniform by area on the part of the mesh the views see, into
 * the malloc'ed #n by 3 array *out (seeded by seed).  0, or -1 when the
 * mesh has no faces of positive area, the views see almost none of it, or
 * memory runs out. */
int ps_seen_sample(const ps_seen *seen, size_t n, uint64_t seed, double **out);

#endif
