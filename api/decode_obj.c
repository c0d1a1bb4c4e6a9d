/* decode_obj.c: Wavefront OBJ: "v x y z" vertices, "vn" normals (kept when
 * there is one per vertex), "f" polygons (v, v/vt, v/vt/vn, v//vn; negative
 * indices count back from the last vertex) fan-triangulated; every other
 * line ignored. */
#include "decode.h"

#include <stdlib.h>
#include <string.h>

#include "decode_scan.h"
#include "decode_util.h"

typedef struct obj_data {
    ps_dvec points, normals;
    ps_tris tris;
} obj_data;

static int keyword_is(const char *s, const char *t, const char *kw) {
    return (size_t)(t - s) == strlen(kw) && !memcmp(s, kw, (size_t)(t - s));
}

/* Appends the first three numbers of the line to dst. */
static int read_triple(const char *s, const char *e, size_t line, ps_dvec *dst,
                       ps_api_error *err) {
    double xyz[3];
    for (int k = 0; k < 3; k++) {
        const char *fs, *ft;
        if (ps_next_field(&s, e, NULL, &fs, &ft) != 1)
            return ps_api_fail(err, 400, "line %zu: expected 3 numbers", line);
        if (ps_field_number(fs, ft, line, &xyz[k], err)) return -1;
    }
    return ps_dvec_push(dst, xyz, 3, err);
}

/* The vertex (0-based) that the face corner [s, t) names ("7", "7/2", "-1//3"). */
static int corner_vertex(const char *s, const char *t, size_t line, size_t n_vertices,
                         uint32_t *v, ps_api_error *err) {
    const char *slash = memchr(s, '/', (size_t)(t - s));
    long long idx;
    if (ps_parse_integer(s, (size_t)((slash ? slash : t) - s), &idx) || idx == 0)
        return ps_api_fail(err, 400, "line %zu: bad face vertex", line);
    long long zero_based = idx > 0 ? idx - 1 : (long long)n_vertices + idx;
    if (zero_based < 0 || (unsigned long long)zero_based >= n_vertices)
        return ps_api_fail(err, 422, "line %zu: face refers to vertex %lld (%zu vertices so far)",
                           line, idx, n_vertices);
    *v = (uint32_t)zero_based;
    return 0;
}

static int read_face(const char *s, const char *e, size_t line, obj_data *d, ps_api_error *err) {
    const char *fs, *ft;
    uint32_t v = 0;
    ps_fan fan = {0};
    size_t n_vertices = d->points.len / 3;
    while (ps_next_field(&s, e, NULL, &fs, &ft) == 1)
        if (corner_vertex(fs, ft, line, n_vertices, &v, err) ||
            ps_fan_add(&fan, &d->tris, v, err))
            return -1;
    return 0;
}

static int read_line(const char *s, const char *e, size_t line, const ps_decode_limits *lim,
                     obj_data *d, ps_api_error *err) {
    const char *kw = s, *kw_end = ps_token_end(s, e, NULL);
    if (keyword_is(kw, kw_end, "v"))
        return ps_decode_check_points(d->points.len / 3 + 1, lim, err) ||
               read_triple(kw_end, e, line, &d->points, err);
    if (keyword_is(kw, kw_end, "vn")) return read_triple(kw_end, e, line, &d->normals, err);
    if (keyword_is(kw, kw_end, "f")) return read_face(kw_end, e, line, d, err);
    return 0;
}

static int read_lines(const char *bytes, size_t len, const ps_decode_limits *lim, obj_data *d,
                      ps_api_error *err) {
    ps_lines lines;
    const char *s, *e;
    ps_lines_init(&lines, bytes, len);
    while (ps_lines_next_data(&lines, &s, &e))
        if (read_line(s, e, lines.line, lim, d, err)) return -1;
    return 0;
}

/* Hands the vertices to out, and the normals when there is one per vertex. */
static void move_vertices(obj_data *d, ps_pointset *out) {
    out->n = d->points.len / 3;
    out->dim = 3;
    out->points = d->points.v;
    if (d->normals.len == d->points.len) out->normals = d->normals.v;
    else free(d->normals.v);
}

int ps_decode_obj(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err) {
    obj_data d = {{0}, {0}, {0}};
    memset(out, 0, sizeof *out);
    int failed = read_lines(bytes, len, lim, &d, err);
    if (failed) {
        free(d.points.v);
        free(d.normals.v);
    } else {
        move_vertices(&d, out);
    }
    return ps_decode_finish_mesh(failed, &d.tris, out, lim, err);
}
