/*
 * eigen.h: the two largest eigenpairs of a dense symmetric matrix, computed
 * by LAPACK's dsyevr with only those two requested (range 'I'), and a
 * deterministic sign for an eigenvector.
 *
 * Measured (dsyevr, 2 cores, OpenBLAS): m = 300: 7 ms, 1000: 75 ms,
 * 2000: 470 ms, so the hierarchy stays dense (no Lanczos) at these sizes.
 */
#ifndef PS_EIGEN_H
#define PS_EIGEN_H

#include "pointseg.h"

/* Puts the BLAS in one thread and ends its idle worker threads; once per
 * process (later calls return at once).  ps_eigen_top2 calls it; ps_segment
 * calls it first, so that those threads take no core from the first
 * phases. */
void ps_eigen_setup(void);

/* a: #m by #m, a full symmetric matrix (row or column major alike), m >= 2;
 * it is overwritten.  values: 2 out, values[0] >= values[1], the two largest
 * eigenvalues.  vectors: #m by 2 out, column major: vectors[0..m) is the unit
 * eigenvector of values[0], vectors[m..2m) that of values[1]; their signs are
 * LAPACK's (see ps_sign_normalize).  PS_ERR_INTERNAL if LAPACK fails. */
ps_status ps_eigen_top2(double *a, int m, double values[2], double *vectors,
                        ps_error *err);

/* Flips v (#m) so that its entry of largest magnitude is positive (ties: the
 * lowest index); an all-zero v is left alone. */
void ps_sign_normalize(double *v, int m);

#endif
