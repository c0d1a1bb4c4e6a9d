/*
 * ply_colors.c: reads vertex red/green/blue from a PLY (ply_colors.h),
 * using the PLY header parser and binary value reader of api/
 * (decode_ply_header.h).
 */
#include "ply_colors.h"

#include "decode_ply_header.h"

#include <stdlib.h>
#include <string.h>

typedef struct color_plan {
    const ps_ply_header *h;
    const ps_ply_element *vertex;
    int channel[3];       /* property index within the vertex element */
    size_t offset[3];     /* byte offset within a binary record */
    size_t record_bytes;  /* binary: bytes per vertex */
} color_plan;

static const ps_ply_property *vertex_property(const color_plan *p, int i) {
    return ps_ply_property_of(p->h, p->vertex, i);
}

static int is_float(ps_ply_type t) { return t == PS_PLY_FLOAT32 || t == PS_PLY_FLOAT64; }

static unsigned char to_byte(double v, ps_ply_type t) {
    if (is_float(t)) v *= 255.0;
    if (!(v > 0)) return 0;
    return v >= 255 ? 255 : (unsigned char)(v + 0.5);
}

/* 1 when the vertex element is first, has only scalars and all three
 * colour channels; fills the plan. */
static int make_plan(const ps_ply_header *h, color_plan *p) {
    static const char *const names[3] = {"red", "green", "blue"};
    p->h = h;
    p->vertex = h->n_elements > 0 ? &h->elements[0] : NULL;
    if (!p->vertex || strcmp(p->vertex->name, "vertex") != 0) return 0;
    for (int c = 0; c < 3; c++) p->channel[c] = -1;
    for (int i = 0; i < p->vertex->n_properties; i++) {
        const ps_ply_property *prop = vertex_property(p, i);
        if (prop->is_list) return 0;
        for (int c = 0; c < 3; c++) {
            if (strcmp(prop->name, names[c]) != 0) continue;
            p->channel[c] = i;
            p->offset[c] = ps_ply_scalar_offset(h, p->vertex, i);
        }
    }
    p->record_bytes = ps_ply_scalar_offset(h, p->vertex, p->vertex->n_properties);
    return p->channel[0] >= 0 && p->channel[1] >= 0 && p->channel[2] >= 0;
}

static int read_binary(const color_plan *p, const char *data, size_t avail, size_t n,
                       unsigned char *rgb) {
    if (avail / p->record_bytes < n) return -1;
    int swap = ps_ply_needs_swap(p->h->format);
    for (size_t v = 0; v < n; v++) {
        const char *record = data + v * p->record_bytes;
        for (int c = 0; c < 3; c++) {
            ps_ply_type t = vertex_property(p, p->channel[c])->type;
            double value = ps_ply_load_binary(record + p->offset[c], t, swap);
            rgb[3 * v + (size_t)c] = to_byte(value, t);
        }
    }
    return 1;
}

/* ASCII: one vertex per line, whitespace-separated values.  The gaps are
 * space, tab, \r and \n only (not the \v and \f of api's ps_skip_space)
 * and a value ends at any byte <= ' '. */
static int read_ascii(const color_plan *p, const char *data, const char *end, size_t n,
                      unsigned char *rgb) {
    char token[64];
    for (size_t v = 0; v < n; v++) {
        for (int i = 0; i < p->vertex->n_properties; i++) {
            while (data < end && (*data == ' ' || *data == '\t' || *data == '\r' || *data == '\n'))
                data++;
            size_t t = 0;
            while (data < end && t + 1 < sizeof token && *data > ' ') token[t++] = *data++;
            if (t == 0) return -1;
            token[t] = 0;
            for (int c = 0; c < 3; c++)
                if (p->channel[c] == i)
                    rgb[3 * v + (size_t)c] =
                        to_byte(strtod(token, NULL), vertex_property(p, i)->type);
        }
    }
    return 1;
}

int cli_ply_read_colors(const char *bytes, size_t len, size_t n, unsigned char *rgb) {
    ps_ply_header *h = malloc(sizeof *h);
    ps_api_error err;
    color_plan plan;
    int rc = 0;
    if (!h) return -1;
    if (ps_ply_parse_header(bytes, len, h, &err) == 0 && make_plan(h, &plan) &&
        plan.vertex->count == n) {
        const char *data = bytes + h->data_offset;
        rc = h->format == PS_PLY_ASCII ? read_ascii(&plan, data, bytes + len, n, rgb)
                                       : read_binary(&plan, data, len - h->data_offset, n, rgb);
    }
    free(h);
    return rc;
}
