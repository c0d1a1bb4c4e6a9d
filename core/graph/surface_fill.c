/*
 * surface_fill.c: points added on a mesh's triangles up to the reference
 * sampling (surface_fill.h).
 *
 * Placement inside a triangle: the i-th point of triangle t takes (u, v) =
 * the fractional parts of h(t) + i (a1, a2), the R2 low-discrepancy
 * sequence (a1, a2 = 1 / phi2, 1 / phi2^2, phi2 the plastic number), and
 * maps it area-uniformly onto the triangle: weights 1 - sqrt(u),
 * sqrt(u) (1 - v), sqrt(u) v.
 */
#include "graph/surface_fill.h"

#include "graph/dedup.h"
#include "graph/reference_density.h"
#include "util/sort_util.h"
#include "util/vec3.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define R2_A1 0.75487766624669276005 /* 1 / phi2 */
#define R2_A2 0.56984029099805326591 /* 1 / phi2^2 */

/* splitmix64's finalizer: a well-mixed 64-bit hash of x. */
static uint64_t mix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

static double unit_of(uint64_t h) { return (double)(h >> 11) * 0x1.0p-53; }

static double squared_distance(const double *a, const double *b) {
    double s = 0;
    for (int d = 0; d < 3; d++) s += (a[d] - b[d]) * (a[d] - b[d]);
    return s;
}

typedef struct filler {
    const ps_input *in;
    ps_surface_fill *out;
    uint64_t seed; /* which fill (ps_surface_fill_build) */
    size_t next;   /* added points placed so far */
} filler;

/* Triangle t's hash in fill seed (seed 0: the triangle's own). */
static uint64_t triangle_hash(size_t t, uint64_t seed, uint64_t salt) {
    return mix64((uint64_t)t ^ salt ^ seed * 0x9E3779B97F4A7C15ull);
}

/* The i-th added point of triangle t (#P + next in out's arrays). */
static void place(filler *fl, size_t t, size_t i) {
    const ps_input *in = fl->in;
    const uint32_t *v = in->faces + 3 * t;
    uint64_t h = triangle_hash(t, fl->seed, 0);
    double u = fmod(unit_of(h) + (double)i * R2_A1, 1.0);
    double s = fmod(unit_of(mix64(h)) + (double)i * R2_A2, 1.0);
    double r = sqrt(u), w[3] = {1 - r, r * (1 - s), r * s};
    size_t a = in->n + fl->next;
    double *p = fl->out->points + 3 * a;
    for (int d = 0; d < 3; d++)
        p[d] = w[0] * in->points[3 * v[0] + d] + w[1] * in->points[3 * v[1] + d] +
               w[2] * in->points[3 * v[2] + d];
    int nearest = 0;
    for (int c = 1; c < 3; c++)
        if (squared_distance(p, in->points + 3 * v[c]) <
            squared_distance(p, in->points + 3 * v[nearest]))
            nearest = c;
    fl->out->host[fl->next] = v[nearest];
    if (in->normals) {
        double *nn = fl->out->normals + 3 * a, len = 0;
        for (int d = 0; d < 3; d++) {
            nn[d] = w[0] * in->normals[3 * v[0] + d] + w[1] * in->normals[3 * v[1] + d] +
                    w[2] * in->normals[3 * v[2] + d];
            len += nn[d] * nn[d];
        }
        for (int d = 0; d < 3; d++)
            nn[d] = len > 0 ? nn[d] / sqrt(len) : in->normals[3 * v[nearest] + d];
    }
    fl->next++;
}

/* Points for a triangle of the given area, step the area per point:
 * area / step rounded up or down by a dither fixed per triangle, so that
 * the expected count is exact and a rounding of the area (a rotated copy)
 * changes a count only where it sits within rounding of a whole number. */
static size_t count_of(size_t t, uint64_t seed, double area, double step) {
    if (!(area > 0)) return 0;
    return (size_t)floor(area / step + unit_of(triangle_hash(t, seed, 0x5F1Dull)));
}

/* normal #F by 3 out: each triangle's normal, twice its area long. */
static void face_normals(const ps_input *in, double *normal) {
    for (size_t t = 0; t < in->n_faces; t++) {
        const uint32_t *v = in->faces + 3 * t;
        const double *a = in->points + 3 * v[0], *b = in->points + 3 * v[1],
                     *c = in->points + 3 * v[2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double *n = normal + 3 * t;
        n[0] = u[1] * w[2] - u[2] * w[1], n[1] = u[2] * w[0] - u[0] * w[2];
        n[2] = u[0] * w[1] - u[1] * w[0];
    }
}

/* The area of the triangle whose face_normals entry is n. */
static double area_of(const double *n) { return 0.5 * sqrt(ps_dot3(n, n)); }

/* The corner of triangle t's c-th vertex: its distinct point (dedup.h),
 * so that a mesh whose triangles do not share their vertices (each with
 * copies of its own) has its corners' normals summed over the triangles
 * that meet there, as a welded mesh's. */
static size_t corner_of(const ps_input *in, const ps_dedup *d, size_t t, int c) {
    return d->unique_of[in->faces[3 * t + (size_t)c]];
}

/* The roughness (surface_fill.h) from the triangles' normals #F by 3 and
 * in's distinct points d; -1 when out of memory. */
static double roughness_of(const ps_input *in, const ps_dedup *d, const double *normal) {
    double *corner = calloc(3 * d->n_unique, sizeof *corner); /* area-weighted normals */
    double *deviation = malloc(in->n_faces * sizeof *deviation);
    if (!corner || !deviation) return free(corner), free(deviation), -1;
    for (size_t t = 0; t < in->n_faces; t++)
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++) corner[3 * corner_of(in, d, t, c) + k] += normal[3 * t + k];
    size_t count = 0;
    for (size_t t = 0; t < in->n_faces; t++) {
        const double *n = normal + 3 * t;
        double m[3] = {0, 0, 0};
        for (int c = 0; c < 3; c++)
            for (int k = 0; k < 3; k++) m[k] += corner[3 * corner_of(in, d, t, c) + k];
        double nn = ps_dot3(n, n), mm = ps_dot3(m, m);
        /* at least 0: a regular mesh's cos rounds a hair above 1, and a
         * negative roughness would read as out of memory */
        if (nn > 0 && mm > 0) deviation[count++] = fmax(0, 1 - ps_dot3(n, m) / sqrt(nn * mm));
    }
    double median = count ? ps_select_kth(deviation, count, count / 2) : 0;
    free(corner), free(deviation);
    return median;
}

double ps_surface_fill_roughness(const ps_input *in, const ps_dedup *corners) {
    if (in->dim != 3 || !in->faces || in->n_faces == 0) return 0;
    double *normal = malloc(3 * in->n_faces * sizeof *normal);
    if (!normal) return -1;
    face_normals(in, normal);
    double roughness = roughness_of(in, corners, normal);
    free(normal);
    return roughness;
}

/* out's arrays for the #P input points and m added ones, the input's
 * copied in; 0 when out of memory (out freed). */
static int allocate(const ps_input *in, size_t m, ps_surface_fill *out) {
    out->points = malloc(3 * (in->n + m) * sizeof *out->points);
    out->host = malloc(m * sizeof *out->host);
    if (in->normals) out->normals = malloc(3 * (in->n + m) * sizeof *out->normals);
    if (!out->points || !out->host || (in->normals && !out->normals)) {
        ps_surface_fill_free(out);
        return 0;
    }
    memcpy(out->points, in->points, 3 * in->n * sizeof *out->points);
    if (in->normals) memcpy(out->normals, in->normals, 3 * in->n * sizeof *out->normals);
    out->n_added = m;
    return 1;
}

/* Whether the triangles (normals #F by 3, face_normals) take points:
 * they have area (*total, their sum) and are no rougher than
 * PS_FILL_MAX_ROUGHNESS; -1 when out of memory. */
static int fillable(const ps_input *in, const ps_dedup *corners, const double *normal,
                    double *total) {
    *total = 0;
    for (size_t t = 0; t < in->n_faces; t++) *total += area_of(normal + 3 * t);
    if (!(*total > 0) || !isfinite(*total)) return 0;
    double roughness = roughness_of(in, corners, normal);
    if (roughness < 0) return -1;
    return roughness <= PS_FILL_MAX_ROUGHNESS;
}

/* Fill seed of the triangles (normals #F by 3, of area total) into out,
 * or out left empty when it would add nothing; 0 when out of memory. */
static int fill_seed(const ps_input *in, size_t target, uint64_t seed, const double *normal,
                     double total, ps_surface_fill *out) {
    double step = total / (double)(target - in->n);
    size_t m = 0;
    for (size_t t = 0; t < in->n_faces; t++)
        m += count_of(t, seed, area_of(normal + 3 * t), step);
    if (m == 0) return 1;
    if (!allocate(in, m, out)) return 0;
    filler fl = {in, out, seed, 0};
    for (size_t t = 0; t < in->n_faces; t++) {
        size_t count = count_of(t, seed, area_of(normal + 3 * t), step);
        for (size_t i = 0; i < count; i++) place(&fl, t, i);
    }
    return 1;
}

int ps_surface_fill_wanted(const ps_params *params, int dim, size_t n) {
    return params->method == PS_METHOD_AUTO && params->centrality != PS_CENTRALITY_EXACT &&
           dim == 3 && n < PS_DENSITY_REFERENCE_POINTS;
}

ps_status ps_surface_fill_build(const ps_input *in, const ps_dedup *corners, size_t target,
                                int fills, ps_surface_fill *out, ps_error *err) {
    memset(out, 0, (size_t)fills * sizeof *out);
    if (in->dim != 3 || !in->faces || in->n_faces == 0 || in->n >= target) return PS_OK;
    double *normal = malloc(3 * in->n_faces * sizeof *normal), total = 0;
    int ok = normal != NULL, take = 0;
    if (ok) {
        face_normals(in, normal);
        take = fillable(in, corners, normal, &total);
        ok = take >= 0;
    }
    for (int j = 0; ok && take && j < fills; j++)
        ok = fill_seed(in, target, (uint64_t)j, normal, total, &out[j]);
    free(normal);
    if (ok) return PS_OK;
    for (int j = 0; j < fills; j++) ps_surface_fill_free(&out[j]);
    return ps_fail(err, PS_ERR_NOMEM, "out of memory (surface fill)");
}

void ps_surface_fill_free(ps_surface_fill *s) {
    free(s->points);
    free(s->normals);
    free(s->host);
    memset(s, 0, sizeof *s);
}
