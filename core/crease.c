/*
 * crease.c: the concavity-aware edge lengths of crease.h.
 */
#include "crease.h"

void ps_crease_weights(ps_graph *g, const double *points, const double *normals) {
    size_t edges = g->offsets[g->n];
    if (edges == 0) return;
    const double delta = PS_CREASE_DELTA, eta = PS_CREASE_ETA_CONVEX;
    double sum_len = 0, sum_ang = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            sum_len += g->weights[e];
            sum_ang += ps_crease_angular(points + 3 * p, normals + 3 * p, points + 3 * q,
                                         normals + 3 * q, eta);
        }
    double L = sum_len / (double)edges, A = sum_ang / (double)edges;
    if (A < PS_CREASE_FLAT) return;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            double ang = ps_crease_angular(points + 3 * p, normals + 3 * p, points + 3 * q,
                                           normals + 3 * q, eta);
            g->weights[e] = delta * g->weights[e] + (1 - delta) * L * ang / A;
            if (!(g->weights[e] > 0)) g->weights[e] = 1e-12 * L;
        }
}

void ps_crease_strengths(const ps_graph *g, const double *points, const double *normals,
                         ps_crease_points *cp) {
    double sum = 0;
    for (size_t p = 0; p < g->n; p++) {
        double most = 0;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            double ang = ps_crease_angular(points + 3 * p, normals + 3 * p, points + 3 * q,
                                           normals + 3 * q, 0.0);
            sum += ang;
            if (ang > most) most = ang;
        }
        cp->strength[p] = most;
    }
    cp->mean = g->offsets[g->n] ? sum / (double)g->offsets[g->n] : 0;
}
