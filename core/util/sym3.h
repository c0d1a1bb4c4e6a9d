/*
 * sym3.h: the smallest eigenpair of a symmetric 3 by 3 matrix, the plane
 * fit of a PCA normal (normals.c, patch_normal.c).
 */
#ifndef PS_SYM3_H
#define PS_SYM3_H

/* v out: the unit eigenvector of the smallest eigenvalue of the symmetric
 * 3 by 3 matrix a (Jacobi sweeps; a is overwritten); returns that
 * eigenvalue. */
double ps_sym3_smallest(double a[3][3], double v[3]);

#endif
