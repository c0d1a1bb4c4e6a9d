/*
 * decode_util.h: pieces every decoder shares (internal to api/): limits with
 * their defaults, the checks a decoded set must pass, and growing arrays for
 * formats whose counts are not known up front.
 */
#ifndef PS_DECODE_UTIL_H
#define PS_DECODE_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "decode.h"

/* lim, or the defaults (no point limit, PS_MAX_DIM) where lim is NULL or a
 * field is 0. */
ps_decode_limits ps_decode_limits_of(const ps_decode_limits *lim);

/* Steps over a UTF-8 byte order mark at the start of a text: the bytes
 * after it (*len shortened), or bytes unchanged. */
const char *ps_skip_bom(const char *bytes, size_t *len);

/* 413 when n points exceed lim.max_points. */
int ps_decode_check_points(size_t n, const ps_decode_limits *lim, ps_api_error *err);

/* 422 unless 2 <= dim <= lim.max_dim. */
int ps_decode_check_dim(long long dim, const ps_decode_limits *lim, ps_api_error *err);

/* Checks a decoded set: n >= 1 (422 "no points"), dim in range, every
 * coordinate and normal finite (422 naming the point as `noun` i, 0-based).
 * On failure frees *ps.  Returns 0 or -1. */
int ps_decode_finish(ps_pointset *ps, const ps_decode_limits *lim, const char *noun,
                     ps_api_error *err);

/* A growing array of doubles (v: #len). */
typedef struct ps_dvec {
    double *v;
    size_t len, cap;
} ps_dvec;

/* Appends x (#n); 500 on allocation failure. */
int ps_dvec_push(ps_dvec *a, const double *x, size_t n, ps_api_error *err);

/* A growing list of triangles (v: #len/3 by 3). */
typedef struct ps_tris {
    uint32_t *v;
    size_t len, cap;
} ps_tris;

/* Makes room for n_tris triangles in total; 500 on allocation failure. */
int ps_tris_reserve(ps_tris *t, size_t n_tris, ps_api_error *err);

/* Appends the triangle (a, b, c). */
int ps_tris_push(ps_tris *t, uint32_t a, uint32_t b, uint32_t c, ps_api_error *err);

/* A polygon being fan-triangulated: its corners are given one by one with
 * ps_fan_add; start from ps_fan fan = {0} for each polygon. */
typedef struct ps_fan {
    uint32_t first, prev;  /* the polygon's first corner and the last one given */
    size_t corners;        /* how many were given */
} ps_fan;

/* Adds corner v to the polygon; from the third corner on, appends the
 * triangle (first, previous corner, v) to t.  500 on allocation failure. */
int ps_fan_add(ps_fan *fan, ps_tris *t, uint32_t v, ps_api_error *err);

/* The end of a mesh decoder (OFF, PLY, OBJ).  failed != 0 (err already
 * set): frees the triangles and *ps and returns -1.  Else hands the
 * triangles to ps (faces #F by 3, NULL when none; n_faces) and returns
 * ps_decode_finish(ps, lim, "vertex", err).  Either way t is left empty. */
int ps_decode_finish_mesh(int failed, ps_tris *t, ps_pointset *ps, const ps_decode_limits *lim,
                          ps_api_error *err);

#endif
