/*
 * surface_fill.h: a mesh's triangles filled with points, so that a coarse
 * or unevenly sampled mesh reaches the reference sampling.
 *
 * The crease steps of method auto are scaled to about
 * PS_DENSITY_REFERENCE_POINTS points spread evenly over the surface
 * (normals_smooth.h).  A mesh's vertices are rarely that: CAD models put
 * rings of vertices far apart along a smooth turned part, and scanned
 * meshes decimated for display put few vertices on large flat triangles.
 * When the input carries faces, points are added on them, by area, until
 * the set holds the reference count; the vertices keep their answers, the
 * added points only carry the surface between them.
 *
 * The added points are spread by area: a triangle gets its area over
 * (total area / points to add), rounded up or down by a dither fixed per
 * triangle (so the total is the target up to that rounding), placed in the
 * triangle by a low-discrepancy sequence started at a per-triangle hash.
 * Each triangle's points depend on that triangle alone: the result follows
 * the mesh under translation, rotation and scaling, but where a rounded
 * area moves a count across a whole number.
 *
 * A noisy mesh is not filled.  Its triangles are noise, and points spread
 * over them would hide it from the noise measure of normals_smooth.h (each
 * point's neighbours would lie on one or two flat triangles), so that the
 * crease steps took the jagged facets for creases.  Roughness: the median
 * over the triangles of 1 - cos between a triangle's normal and the
 * area-weighted normal of its three corners (a corner is a distinct
 * point, dedup.h: the triangles of a mesh that gives each its own copies
 * of its vertices meet there as a welded mesh's do).  On the 228 development PSB
 * meshes: clean 0 to 0.0047, but for two coarse ones (0.017, 0.024); with
 * Gaussian noise of 0.1 mean edge lengths 0.012 to 0.019, of 0.25 0.07 to
 * 0.12.  Filling noisy meshes cost 0.04 at noise 0.1 (development 0.126
 * -> 0.168) and 0.022 at 0.25; the limit, between clean and noisy, keeps
 * 0.129 and 0.187 there (docs/method.md).
 */
#ifndef PS_SURFACE_FILL_H
#define PS_SURFACE_FILL_H

#include "graph/dedup.h"
#include "pointseg.h"

typedef struct ps_surface_fill {
    double *points;   /* #P+#A by 3: the input points, then the added ones */
    double *normals;  /* #P+#A by 3 when the input has normals (the added
                         ones interpolated over their triangle), else NULL */
    uint32_t *host;   /* #A: for each added point the input vertex of its
                         triangle nearest to it (its stand-in in the result,
                         but as a sink outside the vertex's supernode:
                         result.c) */
    size_t n_added;   /* #A */
} ps_surface_fill;

#define PS_FILL_MAX_ROUGHNESS 0.01

/* The roughness of in's triangles (above; in->dim 3), corners: in's
 * distinct points (ps_dedup_build on in->points); 0 without faces, -1
 * when out of memory. */
double ps_surface_fill_roughness(const ps_input *in, const ps_dedup *corners);

/* Whether params (method auto, centrality not exact: exact is quadratic
 * in the points and runs on the input as given) let a mesh of n points of
 * dim coordinates be filled up to PS_DENSITY_REFERENCE_POINTS; whether it
 * is then depends on its faces (ps_surface_fill_build). */
int ps_surface_fill_wanted(const ps_params *params, int dim, size_t n);

/* out #fills: independent fills of in's triangles (in->dim must be 3),
 * seeds 0 to fills - 1, each with points added until #P+#A reaches about
 * target (within the dither's rounding); a seed keys the per-triangle
 * hashes (dither and sequence start), so seed 0 is the same fill however
 * many are asked for.  The face normals and the roughness are computed
 * once for all.  A fill adds nothing when #P >= target, when the faces
 * have no area, or when they are rougher than PS_FILL_MAX_ROUGHNESS: then
 * its n_added is 0 and its arrays are NULL.  Face indices must be < #P
 * (the caller checks).  corners: in's distinct points, as for the
 * roughness. */
ps_status ps_surface_fill_build(const ps_input *in, const ps_dedup *corners, size_t target,
                                int fills, ps_surface_fill *out, ps_error *err);

void ps_surface_fill_free(ps_surface_fill *s);

#endif
