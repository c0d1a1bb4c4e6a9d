/*
 * normals_outward.c: the divergence and convexity votes that turn each
 * component's normals outward (normals_outward.h).
 */
#include "features/normals_outward.h"

#include "features/crease.h"

#include <math.h>
#include <stdlib.h>

/* One component's sums. */
typedef struct outward_votes {
    double divergence; /* sum n . (x - c) */
    double spread;     /* sum |x - c| */
    double convexity;  /* sum over edges of the convex angular terms less the concave ones */
    double bending;    /* sum over edges of the angular terms */
    int flip;          /* the votes' sum is negative */
} outward_votes;

/* Point x's share of the divergence vote: n its normal, c its component's
 * centroid. */
static void add_divergence(outward_votes *v, const double *x, const double *n, const double *c) {
    double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    v->divergence += d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
    v->spread += sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* Point p's edges (each edge is seen from both ends, alike).  With eta
 * -1 for convex edges the angular term is the bend signed: negative on a
 * convex edge, positive on a concave one. */
static void add_convexity(outward_votes *v, const ps_graph *g, const double *points,
                          const double *normals, size_t p) {
    const double *x = points + 3 * p, *n = normals + 3 * p;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        size_t q = g->neighbors[e];
        double concave = ps_crease_angular(x, n, points + 3 * q, normals + 3 * q, -1.0);
        v->convexity -= concave;
        v->bending += fabs(concave);
    }
}

/* Whether a component's normals point in: its two votes' sum is negative. */
static int points_in(const outward_votes *v) {
    double divergence = v->spread > 0 ? v->divergence / v->spread : 0;
    double convexity = v->bending > 0 ? v->convexity / v->bending : 0;
    return divergence + convexity < 0;
}

int ps_normals_point_outward(const ps_graph *g, const double *points, const int *component,
                             int n_components, const double *centroid, double *normals) {
    outward_votes *votes = calloc(n_components > 0 ? (size_t)n_components : 1, sizeof *votes);
    if (!votes) return -1;
    for (size_t p = 0; p < g->n; p++) {
        outward_votes *v = &votes[component[p]];
        add_divergence(v, points + 3 * p, normals + 3 * p, centroid + 3 * component[p]);
        add_convexity(v, g, points, normals, p);
    }
    for (int c = 0; c < n_components; c++) votes[c].flip = points_in(&votes[c]);
    for (size_t p = 0; p < g->n; p++)
        if (votes[component[p]].flip)
            for (int i = 0; i < 3; i++) normals[3 * p + i] = -normals[3 * p + i];
    free(votes);
    return 0;
}
