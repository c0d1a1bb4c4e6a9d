/* mesh_sample.c: uniform area sampling of a triangle mesh (mesh_sample.h). */
#include "mesh_sample.h"

#include <math.h>
#include <stdlib.h>

static uint64_t xorshift64(uint64_t *s) {
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

static double uniform01(uint64_t *s) { return (double)(xorshift64(s) >> 11) * 0x1.0p-53; }

static double triangle_area(const double *a, const double *b, const double *c) {
    double u[3], v[3];
    for (int i = 0; i < 3; i++) { u[i] = b[i] - a[i]; v[i] = c[i] - a[i]; }
    double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
           z = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

/* Index of the first cumulative area above target (cumulative increasing). */
static size_t find_face(const double *cumulative, size_t n_faces, double target) {
    size_t lo = 0, hi = n_faces - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (cumulative[mid] > target) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

int ps_mesh_sample_surface(const ps_pointset *mesh, size_t n, uint64_t seed, double **out) {
    *out = NULL;
    if (mesh->n_faces == 0) return -1;
    double *cumulative = malloc(mesh->n_faces * sizeof *cumulative);
    double *points = malloc(3 * (n ? n : 1) * sizeof *points);
    if (!cumulative || !points) { free(cumulative); free(points); return -1; }
    double total = 0;
    for (size_t f = 0; f < mesh->n_faces; f++) {
        const uint32_t *v = mesh->faces + 3 * f;
        total += triangle_area(mesh->points + 3 * v[0], mesh->points + 3 * v[1],
                               mesh->points + 3 * v[2]);
        cumulative[f] = total;
    }
    if (!(total > 0)) { free(cumulative); free(points); return -1; }
    uint64_t state = seed ? seed : 0x9E3779B97F4A7C15ull;
    for (size_t i = 0; i < n; i++) {
        const uint32_t *v = mesh->faces + 3 * find_face(cumulative, mesh->n_faces,
                                                        uniform01(&state) * total);
        double r1 = sqrt(uniform01(&state)), r2 = uniform01(&state);
        double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2;
        for (int d = 0; d < 3; d++)
            points[3 * i + d] = wa * mesh->points[3 * v[0] + d] +
                                wb * mesh->points[3 * v[1] + d] + wc * mesh->points[3 * v[2] + d];
    }
    free(cumulative);
    *out = points;
    return 0;
}
