/* input_scale.c: the power of two a point set is segmented at, and the
 * result back in the caller's units (input_scale.h).  The typical extent
 * is read off a count of binary exponents: of each point's largest
 * |coordinate - the axes' medians|. */
#include "input_scale.h"

#include "util/sort_util.h"

#include <math.h>
#include <stdlib.h>

#define EXPONENT_LOW (-1075) /* below frexp's exponent of the smallest subnormal */
#define EXPONENT_COUNT 2101  /* EXPONENT_LOW to 1025, above frexp's of the largest double */

/* frexp's exponent of x (>= 0); EXPONENT_LOW for 0. */
static int exponent_of(double x) {
    int e = EXPONENT_LOW;
    if (x > 0) frexp(x, &e);
    return e;
}

/* frexp's exponent of the largest |x[d] - center[d]|. */
static int spread_exponent(const double *x, const double *center, int dim) {
    double largest = 0;
    for (int d = 0; d < dim; d++) largest = fmax(largest, fabs(x[d] - center[d]));
    return exponent_of(largest);
}

/* frexp's exponent of the largest |coordinate|. */
static int largest_exponent(const double *points, size_t count) {
    double largest = 0;
    for (size_t i = 0; i < count; i++) largest = fmax(largest, fabs(points[i]));
    return exponent_of(largest);
}

/* center out #dim: the median of each coordinate; column #n scratch. */
static void axis_medians(const double *points, size_t n, int dim, double *column, double *center) {
    for (int d = 0; d < dim; d++) {
        for (size_t i = 0; i < n; i++) column[i] = points[i * (size_t)dim + d];
        center[d] = ps_select_kth(column, n, n / 2);
    }
}

/* The median of the points' spread exponents about center; count
 * #EXPONENT_COUNT scratch (zeroed). */
static int median_exponent(const double *points, size_t n, int dim, const double *center,
                           size_t *count) {
    for (size_t i = 0; i < n; i++)
        count[spread_exponent(points + i * (size_t)dim, center, dim) - EXPONENT_LOW]++;
    int median = EXPONENT_LOW;
    size_t below = 0;
    for (int b = 0; b < EXPONENT_COUNT; b++) {
        if (count[b] && below < (n + 1) / 2) median = b + EXPONENT_LOW;
        below += count[b];
    }
    return median;
}

int ps_input_scale_exponent(const double *points, size_t n, int dim, int *short_of) {
    size_t *count = calloc(EXPONENT_COUNT, sizeof *count);
    double *column = malloc(n * sizeof *column), center[PS_MAX_DIM];
    int e = 0;
    if (short_of) *short_of = 0;
    if (count && column) {
        axis_medians(points, n, dim, column, center);
        int spread = median_exponent(points, n, dim, center, count);
        if (spread != EXPONENT_LOW &&
            (spread <= PS_SCALE_MIN_EXPONENT || spread > PS_SCALE_MAX_EXPONENT)) {
            int headroom = PS_SCALE_CEILING_EXPONENT - largest_exponent(points, n * (size_t)dim);
            e = -spread > headroom ? (headroom > 0 ? headroom : 0) : -spread;
            if (short_of) *short_of = spread + e <= PS_SCALE_MIN_EXPONENT;
        }
    }
    free(count);
    free(column);
    return e;
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
