/*
 * normals_smooth.c: the noise estimate of a scan and the normal smoothing
 * scaled to it (normals_smooth.h).
 */
#include "features/normals_smooth.h"

#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ps_noise_add(ps_noise_estimate *e, double ratio) {
    size_t bin = ratio >= 1 ? PS_NOISE_BINS - 1 : (size_t)(ratio * PS_NOISE_BINS);
    e->counts[bin]++;
    e->n++;
}

double ps_noise_median(const ps_noise_estimate *e) {
    size_t seen = 0;
    for (size_t bin = 0; bin < PS_NOISE_BINS; bin++) {
        seen += e->counts[bin];
        if (2 * seen > e->n) return ((double)bin + 0.5) / PS_NOISE_BINS;
    }
    return 0;
}

int ps_noise_clean(double noise) {
    return !(noise > PS_NOISE_FLOOR);
}

int ps_noise_iterations(double noise) {
    if (ps_noise_clean(noise)) return 0;
    long t = lround((noise - PS_NOISE_FLOOR) / PS_NOISE_STEP);
    return t > PS_SMOOTH_MAX ? PS_SMOOTH_MAX : (int)t;
}

double ps_density_iterations(size_t n) {
    double t = (double)n / PS_DENSITY_REFERENCE_POINTS - 1;
    return t > 0 ? (t < PS_SMOOTH_MAX ? t : PS_SMOOTH_MAX) : 0;
}

typedef struct smooth_step {
    const ps_graph *g;
    const double *from;
    double *to;
    double share; /* of the iteration taken: in (0, 1] */
} smooth_step;

/* to = the unit vector along (x, y, z), or from where that is 0. */
static inline void unit_or(double x, double y, double z, const double *from, double *to) {
    double len = sqrt(x * x + y * y + z * z);
    to[0] = len > 0 ? x / len : from[0];
    to[1] = len > 0 ? y / len : from[1];
    to[2] = len > 0 ? z / len : from[2];
}

/* One iteration over points [begin, end): the unit sum of a point's normal
 * and its neighbours', or, for a share under 1, the unit blend of the
 * point's normal (1 - share) and that sum (share); a ps_range_fn. */
static void average_range(void *context, size_t begin, size_t end, int worker) {
    (void)worker;
    const smooth_step *step = context;
    const ps_graph *g = step->g;
    const double *from = step->from;
    const double share = step->share;
    for (size_t p = begin; p < end; p++) {
        const double *own = from + 3 * p;
        double x = own[0], y = own[1], z = own[2], whole[3];
        for (size_t e = g->offsets[p], last = g->offsets[p + 1]; e < last; e++) {
            const double *n = from + 3 * (size_t)g->neighbors[e];
            x += n[0], y += n[1], z += n[2];
        }
        if (share >= 1) {
            unit_or(x, y, z, own, step->to + 3 * p);
            continue;
        }
        unit_or(x, y, z, own, whole);
        unit_or((1 - share) * own[0] + share * whole[0], (1 - share) * own[1] + share * whole[1],
                (1 - share) * own[2] + share * whole[2], own, step->to + 3 * p);
    }
}

/* Each iteration reads one buffer and writes the other (normals and a
 * scratch copy in turn); the last one's result is copied back to normals
 * when it lies in the scratch. */
ps_status ps_normals_smooth(const ps_graph *g, double *normals, double iterations, int threads,
                            ps_error *err) {
    if (!(iterations > 0) || g->n == 0) return PS_OK;
    double *scratch = malloc(3 * g->n * sizeof *scratch);
    if (!scratch) return ps_fail(err, PS_ERR_NOMEM, "normals: out of memory (smoothing)");
    double *from = normals, *to = scratch;
    for (double left = iterations; left > 0; left -= 1) {
        smooth_step step = {g, from, to, left < 1 ? left : 1};
        ps_parallel_for(ps_parallel_threads(threads), g->n, 0, average_range, &step);
        double *swap = from;
        from = to, to = swap;
    }
    if (from != normals) memcpy(normals, from, 3 * g->n * sizeof *normals);
    free(scratch);
    return PS_OK;
}
