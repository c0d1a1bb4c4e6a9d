/*
 * normals_smooth.c: the noise estimate of a scan and the normal smoothing
 * scaled to it (normals_smooth.h).
 */
#include "normals_smooth.h"

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

int ps_noise_iterations(double noise) {
    if (!(noise > PS_NOISE_FLOOR)) return 0;
    long t = lround((noise - PS_NOISE_FLOOR) / PS_NOISE_STEP);
    return t > PS_SMOOTH_MAX ? PS_SMOOTH_MAX : (int)t;
}

/* One iteration from `from` into `to`. */
static void average_once(const ps_graph *g, const double *from, double *to) {
    for (size_t p = 0; p < g->n; p++) {
        double sum[3] = {from[3 * p], from[3 * p + 1], from[3 * p + 2]};
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            for (int i = 0; i < 3; i++) sum[i] += from[3 * (size_t)g->neighbors[e] + i];
        double len = sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
        for (int i = 0; i < 3; i++) to[3 * p + i] = len > 0 ? sum[i] / len : from[3 * p + i];
    }
}

ps_status ps_normals_smooth(const ps_graph *g, double *normals, int iterations, ps_error *err) {
    if (iterations <= 0 || g->n == 0) return PS_OK;
    double *scratch = malloc(3 * g->n * sizeof *scratch);
    if (!scratch) return ps_fail(err, PS_ERR_NOMEM, "normals: out of memory (smoothing)");
    for (int it = 0; it < iterations; it++) {
        average_once(g, normals, scratch);
        memcpy(normals, scratch, 3 * g->n * sizeof *normals);
    }
    free(scratch);
    return PS_OK;
}
