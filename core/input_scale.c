/* input_scale.c: the power of two a point set is segmented at, and the
 * result back in the caller's units (input_scale.h).  The median
 * magnitude is read off a count of the points' binary exponents. */
#include "input_scale.h"

#include <math.h>
#include <stdlib.h>

#define EXPONENT_LOW (-1075) /* below frexp's exponent of the smallest subnormal */
#define EXPONENT_COUNT 2101  /* EXPONENT_LOW to 1025, above frexp's of the largest double */

/* frexp's exponent of the point's largest |coordinate|; EXPONENT_LOW for the origin. */
static int magnitude_exponent(const double *x, int dim) {
    double largest = 0;
    for (int d = 0; d < dim; d++) largest = fmax(largest, fabs(x[d]));
    int e = EXPONENT_LOW;
    if (largest > 0) frexp(largest, &e);
    return e;
}

int ps_input_scale_exponent(const double *points, size_t n, int dim) {
    size_t *count = calloc(EXPONENT_COUNT, sizeof *count);
    if (!count) return 0;
    for (size_t i = 0; i < n; i++)
        count[magnitude_exponent(points + i * (size_t)dim, dim) - EXPONENT_LOW]++;
    int median = EXPONENT_LOW, largest = EXPONENT_LOW;
    size_t below = 0;
    for (int b = 0; b < EXPONENT_COUNT; b++) {
        if (count[b] && below < (n + 1) / 2) median = b + EXPONENT_LOW;
        if (count[b]) largest = b + EXPONENT_LOW;
        below += count[b];
    }
    free(count);
    if (median == EXPONENT_LOW || (median > PS_SCALE_MIN_EXPONENT && median <= PS_SCALE_MAX_EXPONENT))
        return 0;
    int e = -median, headroom = PS_SCALE_CEILING_EXPONENT - largest;
    return e > 0 && e > headroom ? (headroom > 0 ? headroom : 0) : e;
}

void ps_result_unscale(ps_result *r, int e) {
    for (size_t i = 0; i < r->n_points; i++) r->centrality[i] = ldexp(r->centrality[i], -e);
    for (int s = 0; s < r->n_supernodes; s++)
        r->supernodes[s].centrality = ldexp(r->supernodes[s].centrality, -e);
    for (int g = 0; g < r->n_segments; g++)
        r->segments[g].feature_size = ldexp(r->segments[g].feature_size, -e);
    for (int m = 0; m < r->n_merges; m++)
        r->merges[m].feature_size = ldexp(r->merges[m].feature_size, -e);
}
