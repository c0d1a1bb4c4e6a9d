/*
 * vec3.h: the dot product of two 3-vectors, shared by the modules that
 * read normals (normals, patch normals, the convex merge, the surface
 * fill).
 */
#ifndef PS_VEC3_H
#define PS_VEC3_H

static inline double ps_dot3(const double *a, const double *b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

#endif
