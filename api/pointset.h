/*
 * pointset.h: a decoded point set, what every decoder produces and the
 * encoders echo back: coordinates, optional normals, colours and faces, the
 * parameters a request body carried, and warnings about what the decoder
 * tolerated (shown on the CLI's stderr and in the JSON document).
 */
#ifndef PS_POINTSET_H
#define PS_POINTSET_H

#include "pointseg.h"

#include <stddef.h>
#include <stdint.h>

enum { PS_MAX_WARNINGS = 4, PS_WARNING_MAX = 160 };

typedef struct ps_param_pair {
    char *name;
    char *value;  /* as text: "7", "approx", "true", "0.25" */
} ps_param_pair;

typedef struct ps_pointset {
    size_t n;              /* #P */
    int dim;               /* coordinates per point */
    double *points;        /* #P by dim */
    double *normals;       /* #P by dim, or NULL */
    unsigned char *colors; /* #P by 3 red green blue 0..255 (PLY), or NULL */
    size_t n_faces;        /* #F */
    uint32_t *faces;       /* #F by 3 (polygons fan-triangulated), or NULL */
    size_t n_params;
    ps_param_pair *params; /* parameters given inside the body (JSON "params") */
    int n_warnings;
    char warnings[PS_MAX_WARNINGS][PS_WARNING_MAX];
} ps_pointset;

void ps_pointset_free(ps_pointset *ps); /* frees the arrays, zeroes *ps */

/* The core's view of ps (points, normals, faces), borrowing its arrays. */
ps_input ps_pointset_input(const ps_pointset *ps);

/* Adds a warning (truncated to PS_WARNING_MAX - 1 bytes; dropped when
 * PS_MAX_WARNINGS are there). */
void ps_pointset_warn(ps_pointset *ps, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

#endif
