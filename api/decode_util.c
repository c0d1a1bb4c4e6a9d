/* decode_util.c: limits, final validation, growing arrays and fan
 * triangulation shared by the decoders (decode_util.h). */
#include "decode_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "pointseg.h"

ps_decode_limits ps_decode_limits_of(const ps_decode_limits *lim) {
    ps_decode_limits out = {0, PS_MAX_DIM};
    if (lim) {
        out.max_points = lim->max_points;
        if (lim->max_dim > 0) out.max_dim = lim->max_dim;
    }
    return out;
}

const char *ps_skip_bom(const char *bytes, size_t *len) {
    if (*len < 3 || memcmp(bytes, "\xEF\xBB\xBF", 3)) return bytes;
    *len -= 3;
    return bytes + 3;
}

int ps_decode_check_points(size_t n, const ps_decode_limits *lim, ps_api_error *err) {
    ps_decode_limits l = ps_decode_limits_of(lim);
    if (l.max_points && n > l.max_points)
        return ps_api_fail(err, 413, "%zu points exceed the limit of %zu", n, l.max_points);
    return 0;
}

int ps_decode_check_dim(long long dim, const ps_decode_limits *lim, ps_api_error *err) {
    ps_decode_limits l = ps_decode_limits_of(lim);
    if (dim < 2 || dim > l.max_dim)
        return ps_api_fail(err, 422, "dimension %lld is outside [2, %d]", dim, l.max_dim);
    return 0;
}

static size_t first_non_finite(const double *v, size_t count) {
    for (size_t i = 0; i < count; i++)
        if (!isfinite(v[i])) return i;
    return count;
}

static int fail_and_free(ps_pointset *ps) {
    ps_pointset_free(ps);
    return -1;
}

int ps_decode_finish(ps_pointset *ps, const ps_decode_limits *lim, const char *noun,
                     ps_api_error *err) {
    if (ps->n == 0) {
        ps_api_fail(err, 422, "no points");
        return fail_and_free(ps);
    }
    if (ps_decode_check_dim(ps->dim, lim, err) || ps_decode_check_points(ps->n, lim, err))
        return fail_and_free(ps);
    size_t count = ps->n * (size_t)ps->dim;
    size_t bad = first_non_finite(ps->points, count);
    if (bad < count) {
        ps_api_fail(err, 422, "%s %zu has a non-finite coordinate", noun, bad / (size_t)ps->dim);
        return fail_and_free(ps);
    }
    bad = ps->normals ? first_non_finite(ps->normals, count) : count;
    if (bad < count) {
        ps_api_fail(err, 422, "%s %zu has a non-finite normal", noun, bad / (size_t)ps->dim);
        return fail_and_free(ps);
    }
    return 0;
}

static int grow(void **data, size_t *cap, size_t need, size_t elem, ps_api_error *err) {
    if (need <= *cap) return 0;
    size_t cap2 = *cap ? *cap : 64;
    while (cap2 < need) {
        if (cap2 > SIZE_MAX / 2 / elem) return ps_api_fail(err, 500, "out of memory");
        cap2 *= 2;
    }
    void *p = realloc(*data, cap2 * elem);
    if (!p) return ps_api_fail(err, 500, "out of memory");
    *data = p;
    *cap = cap2;
    return 0;
}

int ps_dvec_push(ps_dvec *a, const double *x, size_t n, ps_api_error *err) {
    void *data = a->v;
    if (grow(&data, &a->cap, a->len + n, sizeof *a->v, err)) return -1;
    a->v = data;
    for (size_t i = 0; i < n; i++) a->v[a->len + i] = x[i];
    a->len += n;
    return 0;
}

int ps_tris_reserve(ps_tris *t, size_t n_tris, ps_api_error *err) {
    if (n_tris > SIZE_MAX / 3) return ps_api_fail(err, 500, "out of memory");
    void *data = t->v;
    if (grow(&data, &t->cap, 3 * n_tris, sizeof *t->v, err)) return -1;
    t->v = data;
    return 0;
}

int ps_tris_push(ps_tris *t, uint32_t a, uint32_t b, uint32_t c, ps_api_error *err) {
    if (t->len + 3 > t->cap && ps_tris_reserve(t, t->len / 3 + 1, err)) return -1;
    t->v[t->len++] = a;
    t->v[t->len++] = b;
    t->v[t->len++] = c;
    return 0;
}

int ps_fan_add(ps_fan *fan, ps_tris *t, uint32_t v, ps_api_error *err) {
    if (fan->corners == 0) fan->first = v;
    else if (fan->corners >= 2 && ps_tris_push(t, fan->first, fan->prev, v, err)) return -1;
    fan->prev = v;
    fan->corners++;
    return 0;
}

/* Hands the triangles to ps (NULL when none) and empties t. */
static void tris_move(ps_tris *t, ps_pointset *ps) {
    ps->n_faces = t->len / 3;
    ps->faces = ps->n_faces ? t->v : NULL;
    if (!ps->n_faces) free(t->v);
    t->v = NULL;
    t->len = t->cap = 0;
}

int ps_decode_finish_mesh(int failed, ps_tris *t, ps_pointset *ps, const ps_decode_limits *lim,
                          ps_api_error *err) {
    if (failed) {
        free(t->v);
        *t = (ps_tris){0};
        return fail_and_free(ps);
    }
    tris_move(t, ps);
    return ps_decode_finish(ps, lim, "vertex", err);
}
