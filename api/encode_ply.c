/*
 * encode_ply.c: the input points coloured by segment as a
 * binary_little_endian PLY (encode.h): float x y z (the first three
 * coordinates; z = 0 for 2-D input), uchar red green blue from
 * ps_segment_color, and the input's triangles as
 * `list uchar int vertex_indices` when it had faces.  r must be the result
 * for `in` (same #P).
 */
#include "encode.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { VERTEX_BYTES = 3 * 4 + 3, FACE_BYTES = 1 + 3 * 4, HEADER_MAX = 512 };

/* A fixed, well-spread palette (Sasha Trubetskoy's 20 distinct colours;
 * every pair differs by at least 57 in |dr| + |dg| + |db|), cycled for
 * labels beyond it. */
static const unsigned char palette[][3] = {
    {0xE6, 0x19, 0x4B}, {0x3C, 0xB4, 0x4B}, {0xFF, 0xE1, 0x19}, {0x43, 0x63, 0xD8},
    {0xF5, 0x82, 0x31}, {0x91, 0x1E, 0xB4}, {0x42, 0xD4, 0xF4}, {0xF0, 0x32, 0xE6},
    {0xBF, 0xEF, 0x45}, {0xFA, 0xBE, 0xD4}, {0x46, 0x99, 0x90}, {0xDC, 0xBE, 0xFF},
    {0x9A, 0x63, 0x24}, {0xFF, 0xFA, 0xC8}, {0x80, 0x00, 0x00}, {0xAA, 0xFF, 0xC3},
    {0x80, 0x80, 0x00}, {0xFF, 0xD8, 0xB1}, {0x00, 0x00, 0x75}, {0xA9, 0xA9, 0xA9},
};
enum { PALETTE_SIZE = sizeof palette / sizeof palette[0] };

void ps_segment_color(int label, unsigned char rgb[3]) {
    int i = label % PALETTE_SIZE;
    if (i < 0) i += PALETTE_SIZE;
    memcpy(rgb, palette[i], 3);
}

static unsigned char *put_u32_le(unsigned char *p, uint32_t v) {
    p[0] = (unsigned char)v;
    p[1] = (unsigned char)(v >> 8);
    p[2] = (unsigned char)(v >> 16);
    p[3] = (unsigned char)(v >> 24);
    return p + 4;
}

static unsigned char *put_float_le(unsigned char *p, double v) {
    float f = (float)v;
    uint32_t bits;
    memcpy(&bits, &f, sizeof bits);
    return put_u32_le(p, bits);
}

static int write_header(char *out, size_t n, size_t n_faces) {
    int len = snprintf(out, HEADER_MAX,
                       "ply\nformat binary_little_endian 1.0\n"
                       "comment pointseg: points coloured by segment\n"
                       "element vertex %zu\n"
                       "property float x\nproperty float y\nproperty float z\n"
                       "property uchar red\nproperty uchar green\nproperty uchar blue\n",
                       n);
    if (n_faces)
        len += snprintf(out + len, HEADER_MAX - (size_t)len,
                        "element face %zu\nproperty list uchar int vertex_indices\n", n_faces);
    len += snprintf(out + len, HEADER_MAX - (size_t)len, "end_header\n");
    return len;
}

static unsigned char *put_vertex(unsigned char *p, const double *x, int dim, int label) {
    unsigned char rgb[3];
    for (int c = 0; c < 3; c++) p = put_float_le(p, c < dim ? x[c] : 0.0);
    ps_segment_color(label, rgb);
    memcpy(p, rgb, 3);
    return p + 3;
}

static unsigned char *put_face(unsigned char *p, const uint32_t *face) {
    *p++ = 3;
    for (int c = 0; c < 3; c++) p = put_u32_le(p, face[c]);
    return p;
}

char *ps_encode_ply(const ps_pointset *in, const ps_result *r, size_t *len) {
    size_t n_faces = in->faces ? in->n_faces : 0;
    char *out = malloc(HEADER_MAX + in->n * VERTEX_BYTES + n_faces * FACE_BYTES);
    if (!out) return NULL;
    unsigned char *p = (unsigned char *)out + write_header(out, in->n, n_faces);
    for (size_t i = 0; i < in->n; i++)
        p = put_vertex(p, in->points + i * (size_t)in->dim, in->dim,
                       r->labels && i < r->n_points ? r->labels[i] : 0);
    for (size_t f = 0; f < n_faces; f++) p = put_face(p, in->faces + 3 * f);
    if (len) *len = (size_t)(p - (unsigned char *)out);
    return out;
}
