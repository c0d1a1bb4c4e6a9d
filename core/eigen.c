/* eigen.c: the dense symmetric top-two eigensolver of eigen.h (LAPACKE). */
#include "eigen.h"

#include <lapacke.h>
#include <math.h>

static void swap_columns(double *vectors, int m) {
    for (int i = 0; i < m; i++) {
        double t = vectors[i];
        vectors[i] = vectors[m + i];
        vectors[m + i] = t;
    }
}

ps_status ps_eigen_top2(double *a, int m, double values[2], double *vectors,
                        ps_error *err) {
    if (m < 2) return ps_fail(err, PS_ERR_INVALID, "eigen: need m >= 2, got %d", m);
    lapack_int found = 0;
    lapack_int support[4];
    double ascending[2];
    lapack_int info = LAPACKE_dsyevr(LAPACK_COL_MAJOR, 'V', 'I', 'U', m, a, m, 0.0, 0.0,
                                     m - 1, m, 0.0, &found, ascending, vectors, m, support);
    if (info != 0 || found != 2)
        return ps_fail(err, PS_ERR_INTERNAL, "LAPACKE_dsyevr failed (info %d, found %d, m %d)",
                       (int)info, (int)found, m);
    values[0] = ascending[1];
    values[1] = ascending[0];
    swap_columns(vectors, m);
    return PS_OK;
}

void ps_sign_normalize(double *v, int m) {
    int largest = 0;
    for (int i = 1; i < m; i++)
        if (fabs(v[i]) > fabs(v[largest])) largest = i;
    if (m > 0 && v[largest] < 0)
        for (int i = 0; i < m; i++) v[i] = -v[i];
}
