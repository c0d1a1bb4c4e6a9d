/* eigen.c: the dense symmetric top-two eigensolver of eigen.h (LAPACKE).
 *
 * OpenBLAS is kept to one thread: the core parallelizes on its own (and the
 * daemon runs several jobs side by side), and a BLAS whose reductions split
 * differently with the thread count could change an eigenvector's last bits
 * and so a split: results must not depend on the machine's core count.
 * OpenBLAS starts its worker threads when it is loaded, and they spin
 * (sched_yield) for about 0.1 s before they sleep, taking a core from the
 * first phases of every process; ps_eigen_setup also ends them, through
 * blas_thread_shutdown_, which OpenBLAS exports for its fork handler (weak:
 * a BLAS without it keeps its threads, asleep after their spin). */
#include "hierarchy/eigen.h"

#include <lapacke.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

void openblas_set_num_threads(int num_threads);       /* OpenBLAS's own API */
int blas_thread_shutdown_(void) __attribute__((weak)); /* OpenBLAS, not declared */

static pthread_once_t blas_once = PTHREAD_ONCE_INIT;

static void single_threaded_blas(void) {
    openblas_set_num_threads(1);
    if (blas_thread_shutdown_) blas_thread_shutdown_();
}

void ps_eigen_setup(void) { pthread_once(&blas_once, single_threaded_blas); }

static void swap_columns(double *vectors, int m) {
    for (int i = 0; i < m; i++) {
        double t = vectors[i];
        vectors[i] = vectors[m + i];
        vectors[m + i] = t;
    }
}

/* dsyevr uses the eigenvalue array (#m) as workspace and may write 2m
 * support indices, whatever the number of eigenpairs asked for. */
static ps_status call_dsyevr(double *a, int m, double *all_values, lapack_int *support,
                             double values[2], double *vectors, ps_error *err) {
    lapack_int found = 0;
    lapack_int info = LAPACKE_dsyevr(LAPACK_COL_MAJOR, 'V', 'I', 'U', m, a, m, 0.0, 0.0,
                                     m - 1, m, 0.0, &found, all_values, vectors, m, support);
    if (info != 0 || found != 2)
        return ps_fail(err, PS_ERR_INTERNAL, "LAPACKE_dsyevr failed (info %d, found %d, m %d)",
                       (int)info, (int)found, m);
    values[0] = all_values[1];
    values[1] = all_values[0];
    swap_columns(vectors, m);
    return PS_OK;
}

ps_status ps_eigen_top2(double *a, int m, double values[2], double *vectors,
                        ps_error *err) {
    if (m < 2) return ps_fail(err, PS_ERR_INVALID, "eigen: need m >= 2, got %d", m);
    ps_eigen_setup();
    double *all_values = malloc((size_t)m * sizeof *all_values);
    lapack_int *support = malloc(2 * (size_t)m * sizeof *support);
    ps_status st = all_values && support
                       ? call_dsyevr(a, m, all_values, support, values, vectors, err)
                       : ps_fail(err, PS_ERR_NOMEM, "eigen: out of memory (m %d)", m);
    free(all_values);
    free(support);
    return st;
}

void ps_sign_normalize(double *v, int m) {
    int largest = 0;
    for (int i = 1; i < m; i++)
        if (fabs(v[i]) > fabs(v[largest])) largest = i;
    if (m > 0 && v[largest] < 0)
        for (int i = 0; i < m; i++) v[i] = -v[i];
}
