/* mesh_seen.c: a mesh's part seen from some of the six axis directions, by
 * one depth buffer per view (mesh_seen.h). */
#include "mesh_seen.h"

#include <math.h>
#include <stdlib.h>

#include "mesh_sample.h"

#define N_VIEWS 6
#define DEPTH_SLACK 2.0 /* a point within this many pixels of the nearest depth is seen */

/* Six depth buffers: view v looks along axis v / 2 from its high (v even)
 * or low end; depth is the coordinate along the axis towards the viewer,
 * so the nearest surface has the largest; -INFINITY where no triangle is. */
struct ps_seen {
    ps_pointset mesh; /* the arrays borrowed */
    unsigned used;    /* the views' bits */
    double lo[3];     /* the bounding box's low corner */
    double pixel;     /* a pixel's side */
    double *depth;    /* #N_VIEWS by PS_SEEN_PIXELS^2 */
};

/* The pixel of coordinates (a, b) on the view's two other axes. */
static int pixel_of(const ps_seen *w, double a, double b, int axis_a, int axis_b, int *i, int *j) {
    double x = (a - w->lo[axis_a]) / w->pixel, y = (b - w->lo[axis_b]) / w->pixel;
    *i = (int)floor(x), *j = (int)floor(y);
    if (*i == PS_SEEN_PIXELS) *i = PS_SEEN_PIXELS - 1;
    if (*j == PS_SEEN_PIXELS) *j = PS_SEEN_PIXELS - 1;
    return *i >= 0 && *j >= 0 && *i < PS_SEEN_PIXELS && *j < PS_SEEN_PIXELS;
}

/* Writes triangle (p, q, r) into view v's buffer: at every pixel centre
 * inside it, the largest depth of the triangle there. */
static void raster_triangle(ps_seen *w, int v, const double *p, const double *q, const double *r) {
    int axis = v / 2, ax = (axis + 1) % 3, bx = (axis + 2) % 3;
    double sign = v % 2 ? -1 : 1;
    double x[3] = {p[ax], q[ax], r[ax]}, y[3] = {p[bx], q[bx], r[bx]};
    double z[3] = {sign * p[axis], sign * q[axis], sign * r[axis]};
    double det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    if (fabs(det) < 1e-300) return; /* seen edge-on: it hides nothing */
    double min_x = fmin(x[0], fmin(x[1], x[2])), max_x = fmax(x[0], fmax(x[1], x[2]));
    double min_y = fmin(y[0], fmin(y[1], y[2])), max_y = fmax(y[0], fmax(y[1], y[2]));
    int i0 = (int)floor((min_x - w->lo[ax]) / w->pixel), i1 = (int)floor((max_x - w->lo[ax]) / w->pixel);
    int j0 = (int)floor((min_y - w->lo[bx]) / w->pixel), j1 = (int)floor((max_y - w->lo[bx]) / w->pixel);
    if (i0 < 0) i0 = 0;
    if (j0 < 0) j0 = 0;
    if (i1 >= PS_SEEN_PIXELS) i1 = PS_SEEN_PIXELS - 1;
    if (j1 >= PS_SEEN_PIXELS) j1 = PS_SEEN_PIXELS - 1;
    double *buffer = w->depth + (size_t)v * PS_SEEN_PIXELS * PS_SEEN_PIXELS;
    for (int i = i0; i <= i1; i++)
        for (int j = j0; j <= j1; j++) {
            double cx = w->lo[ax] + (i + 0.5) * w->pixel, cy = w->lo[bx] + (j + 0.5) * w->pixel;
            double b1 = ((cx - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (cy - y[0])) / det;
            double b2 = ((x[1] - x[0]) * (cy - y[0]) - (cx - x[0]) * (y[1] - y[0])) / det;
            double b0 = 1 - b1 - b2;
            if (b0 < 0 || b1 < 0 || b2 < 0) continue;
            double d = b0 * z[0] + b1 * z[1] + b2 * z[2];
            double *cell = buffer + (size_t)i * PS_SEEN_PIXELS + (size_t)j;
            if (d > *cell) *cell = d;
        }
}

unsigned ps_mesh_front_view(const ps_pointset *mesh) {
    double lo[3], hi[3];
    ps_mesh_bounds(mesh, lo, hi);
    int axis = 0;
    for (int d = 1; d < 3; d++)
        if (hi[d] - lo[d] < hi[axis] - lo[axis]) axis = d;
    return 1u << (2 * axis);
}

ps_seen *ps_seen_build(const ps_pointset *mesh, unsigned used) {
    size_t cells = (size_t)N_VIEWS * PS_SEEN_PIXELS * PS_SEEN_PIXELS;
    ps_seen *w = malloc(sizeof *w);
    double *depth = malloc(cells * sizeof *depth);
    if (!w || !depth) { free(w); free(depth); return NULL; }
    double hi[3];
    *w = (ps_seen){.mesh = *mesh, .used = used, .depth = depth};
    ps_mesh_bounds(mesh, w->lo, hi);
    double extent = fmax(hi[0] - w->lo[0], fmax(hi[1] - w->lo[1], hi[2] - w->lo[2]));
    w->pixel = extent > 0 ? extent / PS_SEEN_PIXELS : 1;
    for (size_t c = 0; c < cells; c++) depth[c] = -INFINITY;
    for (int v = 0; v < N_VIEWS; v++)
        for (size_t f = 0; (used >> v & 1) && f < mesh->n_faces; f++) {
            const uint32_t *t = mesh->faces + 3 * f;
            raster_triangle(w, v, mesh->points + 3 * t[0], mesh->points + 3 * t[1],
                            mesh->points + 3 * t[2]);
        }
    return w;
}

void ps_seen_free(ps_seen *seen) {
    if (!seen) return;
    free(seen->depth);
    free(seen);
}

/* The nearest depth at pixel (i, j) of view v; at a pixel no triangle
 * covers (a point on the outline, seen edge-on), the nearest of its
 * covered neighbours'. */
static double nearest_depth(const ps_seen *w, int v, int i, int j) {
    const double *buffer = w->depth + (size_t)v * PS_SEEN_PIXELS * PS_SEEN_PIXELS;
    double own = buffer[(size_t)i * PS_SEEN_PIXELS + (size_t)j], around = -INFINITY;
    if (own > -INFINITY) return own;
    for (int a = i - 1; a <= i + 1; a++)
        for (int b = j - 1; b <= j + 1; b++)
            if (a >= 0 && b >= 0 && a < PS_SEEN_PIXELS && b < PS_SEEN_PIXELS)
                around = fmax(around, buffer[(size_t)a * PS_SEEN_PIXELS + (size_t)b]);
    return around;
}

/* 1 when one of the used views sees point p. */
static int views_see(const ps_seen *w, const double *p) {
    for (int v = 0; v < N_VIEWS; v++) {
        int axis = v / 2, ax = (axis + 1) % 3, bx = (axis + 2) % 3, i, j;
        if (!(w->used >> v & 1)) continue;
        if (!pixel_of(w, p[ax], p[bx], ax, bx, &i, &j)) continue;
        double d = (v % 2 ? -1 : 1) * p[axis];
        if (d >= nearest_depth(w, v, i, j) - DEPTH_SLACK * w->pixel) return 1;
    }
    return 0;
}

void ps_seen_flags(const ps_seen *seen, const double *points, size_t n, unsigned char *flags) {
    for (size_t i = 0; i < n; i++) flags[i] = (unsigned char)views_see(seen, points + 3 * i);
}

int ps_seen_sample(const ps_seen *seen, size_t n, uint64_t seed, double **out) {
    *out = NULL;
    double *points = malloc(3 * (n ? n : 1) * sizeof *points), *candidates = NULL;
    size_t batch = 2 * n + 16, kept = 0;
    for (uint64_t round = 0; points && kept < n && round < 64; round++) {
        if (ps_mesh_sample_surface(&seen->mesh, batch, seed + round, &candidates) != 0) break;
        for (size_t i = 0; i < batch && kept < n; i++)
            if (views_see(seen, candidates + 3 * i)) {
                for (int d = 0; d < 3; d++) points[3 * kept + d] = candidates[3 * i + d];
                kept++;
            }
        free(candidates);
        candidates = NULL;
    }
    if (!points || kept < n) { free(points); return -1; }
    *out = points;
    return 0;
}
