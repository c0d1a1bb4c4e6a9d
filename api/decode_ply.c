/* decode_ply.c: PLY (ascii, binary little and big endian) to a ps_pointset:
 * vertex x y [z], optional normals and red green blue colours of any scalar
 * type, faces fan-triangulated, every other property and element skipped. */
#include "decode.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "decode_ply_header.h"
#include "decode_scan.h"
#include "decode_util.h"

enum { COORDS = 6, MAX_FIELDS = 9 }; /* x y z nx ny nz, then red green blue */

typedef struct ply_reader {
    const char *base, *pos, *end;
    ps_ply_format format;
} ply_reader;

/* A vertex property that is kept: where vertex i's value goes, dst[i * dim]
 * (coordinates, normals) or color[i * 3] (a colour channel, 0..255). */
typedef struct ply_field {
    int property;     /* index within the vertex element */
    size_t offset;    /* byte offset within a fixed-size binary record */
    ps_ply_type type;
    double *dst;
    unsigned char *color;
} ply_field;

typedef struct ply_vertex_plan {
    int dim, has_normals, has_colors, n_fields;
    ply_field fields[MAX_FIELDS];
} ply_vertex_plan;

/* A colour channel as a byte: integer types as they are, float types
 * (0..1) scaled by 255; clamped, rounded. */
static unsigned char color_byte(double v, ps_ply_type t) {
    if (t == PS_PLY_FLOAT32 || t == PS_PLY_FLOAT64) v *= 255.0;
    if (!(v > 0)) return 0;
    return v >= 255 ? 255 : (unsigned char)(v + 0.5);
}

static void store(const ply_field *f, size_t dim, size_t i, double v) {
    if (f->color) f->color[i * 3] = color_byte(v, f->type);
    else f->dst[i * dim] = v;
}

static size_t offset_of(const ply_reader *r) { return (size_t)(r->pos - r->base); }

static int truncated(const ply_reader *r, ps_api_error *err) {
    return ps_api_fail(err, 400, "PLY data truncated at byte offset %zu", offset_of(r));
}

static int read_ascii(ply_reader *r, double *v, ps_api_error *err) {
    r->pos = ps_skip_space(r->pos, r->end);
    if (r->pos == r->end) return truncated(r, err);
    const char *stop = ps_token_end(r->pos, r->end, NULL);
    if (ps_parse_double(r->pos, (size_t)(stop - r->pos), v))
        return ps_api_fail(err, 400, "PLY data: expected a number at byte offset %zu",
                           offset_of(r));
    r->pos = stop;
    return 0;
}

/* An ASCII PLY record is one line (it may wrap onto more): only blanks may
 * follow its last value on that line.  A line with a value too many or too
 * few would otherwise shift every later value silently. */
static int end_record(ply_reader *r, const ps_ply_element *e, uint64_t i, ps_api_error *err) {
    if (r->format != PS_PLY_ASCII) return 0;
    r->pos = ps_skip_blanks(r->pos, r->end);
    if (r->pos == r->end || ps_is_line_end(*r->pos)) return 0;
    return ps_api_fail(err, 400, "PLY data: values left on the line of %s %llu (%d properties) at byte "
                       "offset %zu: an ascii PLY line holds one %s", e->name, (unsigned long long)i,
                       e->n_properties, offset_of(r), e->name);
}

static int read_value(ply_reader *r, ps_ply_type t, double *v, ps_api_error *err) {
    if (r->format == PS_PLY_ASCII) return read_ascii(r, v, err);
    size_t size = ps_ply_type_size(t);
    if ((size_t)(r->end - r->pos) < size) return truncated(r, err);
    *v = ps_ply_load_binary(r->pos, t, ps_ply_needs_swap(r->format));
    r->pos += size;
    return 0;
}

static int read_list_count(ply_reader *r, ps_ply_type t, uint32_t *count, ps_api_error *err) {
    size_t at = offset_of(r);
    double v;
    if (read_value(r, t, &v, err)) return -1;
    if (!(v >= 0 && v <= UINT32_MAX && v == floor(v)))
        return ps_api_fail(err, 400, "PLY data: bad list length at byte offset %zu", at);
    *count = (uint32_t)v;
    return 0;
}

static int skip_values(ply_reader *r, ps_ply_type t, uint32_t count, ps_api_error *err) {
    if (r->format != PS_PLY_ASCII) {
        size_t bytes = (size_t)count * ps_ply_type_size(t);
        if ((size_t)(r->end - r->pos) < bytes) return truncated(r, err);
        r->pos += bytes;
        return 0;
    }
    double v;
    for (uint32_t i = 0; i < count; i++)
        if (read_value(r, t, &v, err)) return -1;
    return 0;
}

static int skip_property(ply_reader *r, const ps_ply_property *p, ps_api_error *err) {
    uint32_t count = 1;
    if (p->is_list && read_list_count(r, p->count_type, &count, err)) return -1;
    return skip_values(r, p->type, count, err);
}

/* Smallest bytes one record of e can take. */
static size_t min_record_bytes(const ps_ply_header *h, const ps_ply_element *e) {
    size_t bytes = 0;
    for (int i = 0; i < e->n_properties; i++) {
        const ps_ply_property *p = ps_ply_property_of(h, e, i);
        if (h->format == PS_PLY_ASCII) bytes += 2;
        else bytes += ps_ply_type_size(p->is_list ? p->count_type : p->type);
    }
    return bytes;
}

static int has_lists(const ps_ply_header *h, const ps_ply_element *e) {
    for (int i = 0; i < e->n_properties; i++)
        if (ps_ply_property_of(h, e, i)->is_list) return 1;
    return 0;
}

/* 400 when e's count cannot fit in the bytes left (checked before allocating). */
static int check_count(const ps_ply_header *h, const ps_ply_element *e, const ply_reader *r,
                       ps_api_error *err) {
    uint64_t need = min_record_bytes(h, e);
    uint64_t remain = (uint64_t)(r->end - r->pos) + (h->format == PS_PLY_ASCII);
    if (need == 0 || e->count <= remain / need) return 0;
    if (e->count > UINT64_MAX / need)
        return ps_api_fail(err, 400, "%s count %llu exceeds the data (needs more than %llu bytes, "
                           "%llu remain)", e->name, (unsigned long long)e->count,
                           (unsigned long long)UINT64_MAX, (unsigned long long)remain);
    return ps_api_fail(err, 400, "%s count %llu exceeds the data (needs %llu bytes, %llu remain)",
                       e->name, (unsigned long long)e->count,
                       (unsigned long long)(e->count * need), (unsigned long long)remain);
}

static int skip_element(const ps_ply_header *h, const ps_ply_element *e, ply_reader *r,
                        ps_api_error *err) {
    if (check_count(h, e, r, err)) return -1;
    if (r->format != PS_PLY_ASCII && !has_lists(h, e)) {
        r->pos += e->count * min_record_bytes(h, e);
        return 0;
    }
    for (uint64_t i = 0; i < (e->n_properties ? e->count : 0); i++) {
        for (int k = 0; k < e->n_properties; k++)
            if (skip_property(r, ps_ply_property_of(h, e, k), err)) return -1;
        if (end_record(r, e, i, err)) return -1;
    }
    return 0;
}

static void add_field(ply_vertex_plan *plan, const ps_ply_header *h, const ps_ply_element *e,
                      int property, double *dst, unsigned char *color) {
    ply_field *f = &plan->fields[plan->n_fields++];
    f->property = property;
    f->type = ps_ply_property_of(h, e, property)->type;
    f->dst = dst;
    f->color = color;
    f->offset = ps_ply_scalar_offset(h, e, property);
}

/* Finds x y [z], nx ny [nz] and red green blue; sets plan->dim,
 * has_normals and has_colors. */
static int plan_vertices(const ps_ply_header *h, const ps_ply_element *e,
                         ply_vertex_plan *plan, int idx[MAX_FIELDS], ps_api_error *err) {
    static const char *const names[MAX_FIELDS] = {"x",  "y",  "z",   "nx",   "ny",
                                                  "nz", "red", "green", "blue"};
    for (int k = 0; k < MAX_FIELDS; k++) idx[k] = ps_ply_find_scalar(h, e, names[k]);
    if (idx[0] < 0 || idx[1] < 0)
        return ps_api_fail(err, 422, "PLY vertex element has no scalar property %s",
                           idx[0] < 0 ? "x" : "y");
    plan->dim = idx[2] >= 0 ? 3 : 2;
    plan->has_normals = idx[3] >= 0 && idx[4] >= 0 && (plan->dim == 2 || idx[5] >= 0);
    plan->has_colors = idx[COORDS] >= 0 && idx[COORDS + 1] >= 0 && idx[COORDS + 2] >= 0;
    plan->n_fields = 0;
    return 0;
}

static int read_vertices_fixed(const ply_vertex_plan *plan, size_t count, size_t stride,
                               ply_reader *r) {
    int swap = ps_ply_needs_swap(r->format);
    size_t dim = (size_t)plan->dim;
    for (size_t i = 0; i < count; i++) {
        const char *rec = r->pos + i * stride;
        for (int k = 0; k < plan->n_fields; k++) {
            const ply_field *f = &plan->fields[k];
            store(f, dim, i, ps_ply_load_binary(rec + f->offset, f->type, swap));
        }
    }
    r->pos += count * stride;
    return 0;
}

static int read_vertex_record(const ps_ply_header *h, const ps_ply_element *e,
                              const ply_vertex_plan *plan, size_t i, ply_reader *r,
                              ps_api_error *err) {
    for (int k = 0; k < e->n_properties; k++) {
        const ps_ply_property *p = ps_ply_property_of(h, e, k);
        const ply_field *f = NULL;
        for (int j = 0; j < plan->n_fields && !f; j++)
            if (plan->fields[j].property == k) f = &plan->fields[j];
        if (!f) {
            if (skip_property(r, p, err)) return -1;
            continue;
        }
        double v;
        if (read_value(r, p->type, &v, err)) return -1;
        store(f, (size_t)plan->dim, i, v);
    }
    return 0;
}

static int read_vertices(const ps_ply_header *h, const ps_ply_element *e, ply_reader *r,
                         const ps_decode_limits *lim, ps_pointset *out, ps_api_error *err) {
    ply_vertex_plan plan;
    int idx[MAX_FIELDS];
    if (plan_vertices(h, e, &plan, idx, err) || check_count(h, e, r, err) ||
        ps_decode_check_points((size_t)e->count, lim, err))
        return -1;
    size_t count = (size_t)e->count, dim = (size_t)plan.dim;
    out->n = count;
    out->dim = plan.dim;
    out->points = malloc(count * dim * sizeof *out->points + 1);
    out->normals = plan.has_normals ? malloc(count * dim * sizeof *out->normals + 1) : NULL;
    out->colors = plan.has_colors ? malloc(count * 3 + 1) : NULL;
    if (!out->points || (plan.has_normals && !out->normals) || (plan.has_colors && !out->colors))
        return ps_api_fail(err, 500, "out of memory");
    for (size_t k = 0; k < dim; k++) {
        add_field(&plan, h, e, idx[k], out->points + k, NULL);
        if (plan.has_normals) add_field(&plan, h, e, idx[3 + k], out->normals + k, NULL);
    }
    for (int c = 0; plan.has_colors && c < 3; c++)
        add_field(&plan, h, e, idx[COORDS + c], NULL, out->colors + c);
    if (r->format != PS_PLY_ASCII && !has_lists(h, e))
        return read_vertices_fixed(&plan, count, min_record_bytes(h, e), r);
    for (size_t i = 0; i < count; i++)
        if (read_vertex_record(h, e, &plan, i, r, err) || end_record(r, e, i, err)) return -1;
    return 0;
}

/* Index within e of its vertex_indices (or vertex_index) list, or -1. */
static int face_index_property(const ps_ply_header *h, const ps_ply_element *e) {
    for (int i = 0; i < e->n_properties; i++) {
        const ps_ply_property *p = ps_ply_property_of(h, e, i);
        if (p->is_list && (!strcmp(p->name, "vertex_indices") || !strcmp(p->name, "vertex_index")))
            return i;
    }
    return -1;
}

static int integer_type(ps_ply_type t) { return t != PS_PLY_FLOAT32 && t != PS_PLY_FLOAT64; }

/* The common face, read in one go: in a binary file whose index lists have
 * integer counts and indices, a triangle with its corners in range goes
 * straight to tris.  1 when read, 0 when the face is anything else (r
 * unmoved: read_polygon's general path reads it, with its checks and
 * messages), -1 when out of memory. */
static int read_triangle(ply_reader *r, const ps_ply_property *p, uint64_t n_vertices,
                         ps_tris *tris, ps_api_error *err) {
    size_t count_size = ps_ply_type_size(p->count_type), size = ps_ply_type_size(p->type);
    int swap = ps_ply_needs_swap(r->format);
    if ((size_t)(r->end - r->pos) < count_size + 3 * size ||
        ps_ply_load_binary(r->pos, p->count_type, swap) != 3)
        return 0;
    double v[3];
    for (int j = 0; j < 3; j++) {
        v[j] = ps_ply_load_binary(r->pos + count_size + (size_t)j * size, p->type, swap);
        if (!(v[j] >= 0 && v[j] < (double)n_vertices && v[j] <= UINT32_MAX)) return 0;
    }
    if (ps_tris_push(tris, (uint32_t)v[0], (uint32_t)v[1], (uint32_t)v[2], err)) return -1;
    r->pos += count_size + 3 * size;
    return 1;
}

static int read_polygon(ply_reader *r, const ps_ply_property *p, uint64_t face,
                        uint64_t n_vertices, ps_tris *tris, ps_api_error *err) {
    if (r->format != PS_PLY_ASCII && integer_type(p->count_type) && integer_type(p->type)) {
        int read = read_triangle(r, p, n_vertices, tris, err);
        if (read != 0) return read < 0 ? -1 : 0;
    }
    uint32_t count;
    ps_fan fan = {0};
    int binary = r->format != PS_PLY_ASCII, swap = ps_ply_needs_swap(r->format);
    size_t size = ps_ply_type_size(p->type);
    if (read_list_count(r, p->count_type, &count, err)) return -1;
    if (binary && (size_t)(r->end - r->pos) / size < count) return truncated(r, err);
    for (uint32_t j = 0; j < count; j++) {
        double v;
        if (binary) {
            v = ps_ply_load_binary(r->pos, p->type, swap);
            r->pos += size;
        } else if (read_ascii(r, &v, err)) {
            return -1;
        }
        if (!(v >= 0 && v < (double)n_vertices && v <= UINT32_MAX && v == floor(v)))
            return ps_api_fail(err, 422, "face %llu refers to vertex %.17g (the file has %llu "
                               "vertices)", (unsigned long long)face, v,
                               (unsigned long long)n_vertices);
        if (ps_fan_add(&fan, tris, (uint32_t)v, err)) return -1;
    }
    return 0;
}

static int read_faces(const ps_ply_header *h, const ps_ply_element *e, uint64_t n_vertices,
                      ply_reader *r, ps_tris *tris, ps_api_error *err) {
    int indices = face_index_property(h, e);
    if (check_count(h, e, r, err) || ps_tris_reserve(tris, tris->len / 3 + e->count, err))
        return -1;
    for (uint64_t i = 0; i < e->count; i++) {
        for (int k = 0; k < e->n_properties; k++) {
            const ps_ply_property *p = ps_ply_property_of(h, e, k);
            int rc = k == indices ? read_polygon(r, p, i, n_vertices, tris, err)
                                  : skip_property(r, p, err);
            if (rc) return -1;
        }
        if (end_record(r, e, i, err)) return -1;
    }
    return 0;
}

static int read_elements(const ps_ply_header *h, const ps_ply_element *vertex, ply_reader *r,
                         const ps_decode_limits *lim, ps_pointset *out, ps_tris *tris,
                         ps_api_error *err) {
    for (int i = 0; i < h->n_elements; i++) {
        const ps_ply_element *e = &h->elements[i];
        int rc;
        if (e == vertex) rc = read_vertices(h, e, r, lim, out, err);
        else if (!strcmp(e->name, "face") && face_index_property(h, e) >= 0)
            rc = read_faces(h, e, vertex->count, r, tris, err);
        else rc = skip_element(h, e, r, err);
        if (rc) return -1;
    }
    return 0;
}

static void warn_skipped(const ps_ply_header *h, ps_pointset *out) {
    for (int i = 0; i < h->n_skipped; i++)
        ps_pointset_warn(out, "PLY header line %zu skipped: no keyword in \"%s\"", h->skipped[i].line,
                         h->skipped[i].preview);
}

int ps_decode_ply(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err) {
    ps_ply_header h;
    ps_tris tris = {0};
    memset(out, 0, sizeof *out);
    if (ps_ply_parse_header(bytes, len, &h, err)) return -1;
    const ps_ply_element *vertex = ps_ply_find_element(&h, "vertex");
    if (!vertex) return ps_api_fail(err, 422, "PLY file has no vertex element");
    ply_reader r = {bytes, bytes + h.data_offset, bytes + len, h.format};
    int failed = read_elements(&h, vertex, &r, lim, out, &tris, err);
    if (ps_decode_finish_mesh(failed, &tris, out, lim, err)) return -1;
    warn_skipped(&h, out);
    return 0;
}
