/* mesh_sample.c: area sampling of a triangle mesh, uniform or graded along
 * an axis, its area and bounding box (mesh_sample.h). */
#include "mesh_sample.h"
#include "random_bits.h"

#include <math.h>
#include <stdlib.h>

static double triangle_area(const double *a, const double *b, const double *c) {
    double u[3], v[3];
    for (int i = 0; i < 3; i++) { u[i] = b[i] - a[i]; v[i] = c[i] - a[i]; }
    double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
           z = u[0] * v[1] - u[1] * v[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

double ps_mesh_area(const ps_pointset *mesh) {
    double area = 0;
    for (size_t f = 0; f < mesh->n_faces; f++) {
        const uint32_t *v = mesh->faces + 3 * f;
        area += triangle_area(mesh->points + 3 * v[0], mesh->points + 3 * v[1],
                              mesh->points + 3 * v[2]);
    }
    return area;
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

void ps_mesh_bounds(const ps_pointset *mesh, double lo[3], double hi[3]) {
    for (int d = 0; d < 3; d++) lo[d] = hi[d] = mesh->n ? mesh->points[d] : 0;
    for (size_t i = 0; i < mesh->n; i++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], mesh->points[3 * i + d]);
            hi[d] = fmax(hi[d], mesh->points[3 * i + d]);
        }
}

/* The slot and extent of the longest axis of the mesh's bounding box. */
static int longest_axis(const ps_pointset *mesh, double *low, double *extent) {
    double lo[3], hi[3];
    ps_mesh_bounds(mesh, lo, hi);
    int axis = 0;
    for (int d = 1; d < 3; d++)
        if (hi[d] - lo[d] > hi[axis] - lo[axis]) axis = d;
    *low = lo[axis], *extent = hi[axis] - lo[axis];
    return axis;
}

int ps_mesh_sample_graded(const ps_pointset *mesh, size_t n, double far, uint64_t seed,
                          double **out) {
    *out = NULL;
    if (!(far > 0 && far <= 1)) return -1;
    size_t batch = (size_t)ceil((double)n / far) + 16, kept = 0;
    double *points = malloc(3 * (n ? n : 1) * sizeof *points), *candidates = NULL, low, extent;
    int axis = longest_axis(mesh, &low, &extent);
    uint64_t state = (seed ? seed : 0x9E3779B97F4A7C15ull) ^ 0xD1B54A32D192ED03ull;
    for (uint64_t round = 0; points && kept < n; round++) {
        if (ps_mesh_sample_surface(mesh, batch, seed + round, &candidates) != 0) break;
        for (size_t i = 0; i < batch && kept < n; i++) {
            const double *c = candidates + 3 * i;
            double t = extent > 0 ? (c[axis] - low) / extent : 0;
            if (ps_uniform_next(&state) >= 1 - (1 - far) * t) continue;
            for (int d = 0; d < 3; d++) points[3 * kept + d] = c[d];
            kept++;
        }
        free(candidates);
        candidates = NULL;
    }
    if (!points || kept < n) { free(points); return -1; }
    *out = points;
    return 0;
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
                                                        ps_uniform_next(&state) * total);
        double r1 = sqrt(ps_uniform_next(&state)), r2 = ps_uniform_next(&state);
        double wa = 1 - r1, wb = r1 * (1 - r2), wc = r1 * r2;
        for (int d = 0; d < 3; d++)
            points[3 * i + d] = wa * mesh->points[3 * v[0] + d] +
                                wb * mesh->points[3 * v[1] + d] + wc * mesh->points[3 * v[2] + d];
    }
    free(cumulative);
    *out = points;
    return 0;
}
