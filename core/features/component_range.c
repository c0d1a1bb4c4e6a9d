/*
 * component_range.c: max f - min f per component, and thresholds as a
 * fraction of it (component_range.h).
 */
#include "features/component_range.h"

#include <stdlib.h>

int ps_component_range(const double *f, const int *component, size_t n, int n_components,
                       double *range) {
    double *lo = malloc((size_t)(n_components > 0 ? n_components : 1) * sizeof *lo);
    if (!lo) return -1;
    for (int c = 0; c < n_components; c++) lo[c] = 1e300, range[c] = -1e300;
    for (size_t p = 0; p < n; p++) {
        int c = component[p];
        if (f[p] < lo[c]) lo[c] = f[p];
        if (f[p] > range[c]) range[c] = f[p];
    }
    for (int c = 0; c < n_components; c++) range[c] -= lo[c];
    free(lo);
    return 0;
}

double *ps_component_thresholds(const double *f, const int *component, size_t n,
                                int n_components, double fraction) {
    double *threshold = malloc((size_t)(n_components > 0 ? n_components : 1) *
                               sizeof *threshold);
    if (!threshold || ps_component_range(f, component, n, n_components, threshold) != 0) {
        free(threshold);
        return NULL;
    }
    for (int c = 0; c < n_components; c++) threshold[c] *= fraction;
    return threshold;
}
