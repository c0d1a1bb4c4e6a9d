/* decode_off.c: OFF meshes (also COFF, NOFF, CNOFF): "OFF", counts
 * "nv nf [ne]", nv vertex lines "x y z [nx ny nz] [colour...]", nf face
 * lines "k i1 .. ik [colour...]" fan-triangulated; '#' comments allowed. */
#include "decode_text.h"

#include <stdlib.h>
#include <string.h>

#include "decode_scan.h"
#include "decode_util.h"

typedef struct off_reader {
    ps_lines lines;
    const char *s, *e; /* rest of the current line */
} off_reader;

/* Reads the next field of the current line as an integer. */
static int next_integer(off_reader *r, const char *what, long long *v, ps_api_error *err) {
    const char *fs, *ft;
    if (ps_next_field(&r->s, r->e, NULL, &fs, &ft) != 1 ||
        ps_parse_integer(fs, (size_t)(ft - fs), v))
        return ps_api_fail(err, 400, "line %zu: expected %s", r->lines.line, what);
    return 0;
}

static int next_line(off_reader *r, const char *what, ps_api_error *err) {
    if (!ps_lines_next_data(&r->lines, &r->s, &r->e))
        return ps_api_fail(err, 400, "line %zu: the file ends before %s", r->lines.line + 1, what);
    return 0;
}

static int parse_variant(off_reader *r, int *has_normals, ps_api_error *err) {
    const char *t = ps_token_end(r->s, r->e, NULL);
    size_t n = (size_t)(t - r->s);
    static const char *const known[] = {"OFF", "COFF", "NOFF", "CNOFF", "NCOFF"};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (n == strlen(known[i]) && !memcmp(r->s, known[i], n)) {
            *has_normals = memchr(r->s, 'N', n) != NULL;
            r->s = t;
            return 0;
        }
    char shown[41];
    ps_preview(r->s, n, shown, sizeof shown);
    return ps_api_fail(err, 422, "line %zu: OFF variant \"%s\" is not supported (OFF, COFF, "
                       "NOFF and CNOFF are)", r->lines.line, shown);
}

/* "nv nf [ne]" on the rest of the first line or on the next data line. */
static int parse_counts(off_reader *r, long long *nv, long long *nf, ps_api_error *err) {
    if (ps_skip_blanks(r->s, r->e) == r->e && next_line(r, "the counts", err)) return -1;
    if (next_integer(r, "\"vertex_count face_count edge_count\"", nv, err) ||
        next_integer(r, "\"vertex_count face_count edge_count\"", nf, err))
        return -1;
    if (*nv < 0 || *nf < 0)
        return ps_api_fail(err, 400, "line %zu: negative count", r->lines.line);
    return 0;
}

/* 400 when the counts cannot fit in the bytes left (a vertex line takes at
 * least 6 bytes, a face line 2), checked before allocating. */
static int check_counts(const off_reader *r, long long nv, long long nf, ps_api_error *err) {
    unsigned long long remain = (unsigned long long)(r->lines.end - r->lines.pos) + 1;
    if ((unsigned long long)nv > remain / 6)
        return ps_api_fail(err, 400, "vertex count %lld exceeds the data (needs %llu bytes, "
                           "%llu remain)", nv, 6ULL * (unsigned long long)nv, remain);
    remain -= 6ULL * (unsigned long long)nv;
    if ((unsigned long long)nf > remain / 2)
        return ps_api_fail(err, 400, "face count %lld exceeds the data (needs %llu bytes, "
                           "%llu remain)", nf, 2ULL * (unsigned long long)nf, remain);
    return 0;
}

static int read_vertex(off_reader *r, size_t i, int has_normals, ps_pointset *out,
                       ps_api_error *err) {
    if (next_line(r, "all vertices", err)) return -1;
    for (int k = 0; k < (has_normals ? 6 : 3); k++) {
        const char *fs, *ft;
        double *dst = k < 3 ? &out->points[3 * i + (size_t)k]
                            : &out->normals[3 * i + (size_t)k - 3];
        if (ps_next_field(&r->s, r->e, NULL, &fs, &ft) != 1)
            return ps_api_fail(err, 400, "line %zu: vertex %zu needs %d numbers", r->lines.line,
                               i, has_normals ? 6 : 3);
        if (ps_field_number(fs, ft, r->lines.line, dst, err)) return -1;
    }
    return 0;
}

static int read_face(off_reader *r, size_t face, size_t nv, ps_tris *tris, ps_api_error *err) {
    long long k, idx;
    ps_fan fan = {0};
    if (next_line(r, "all faces", err) || next_integer(r, "a face's vertex count", &k, err))
        return -1;
    for (long long j = 0; j < k; j++) {
        if (next_integer(r, "a vertex index", &idx, err)) return -1;
        if (idx < 0 || (unsigned long long)idx >= nv)
            return ps_api_fail(err, 422, "line %zu: face %zu refers to vertex %lld (the file "
                               "has %zu vertices)", r->lines.line, face, idx, nv);
        if (ps_fan_add(&fan, tris, (uint32_t)idx, err)) return -1;
    }
    return 0;
}

static int read_off(off_reader *r, const ps_decode_limits *lim, ps_pointset *out,
                    ps_tris *tris, ps_api_error *err) {
    long long nv, nf;
    int has_normals = 0;
    if (next_line(r, "the OFF keyword", err) || parse_variant(r, &has_normals, err) ||
        parse_counts(r, &nv, &nf, err) || check_counts(r, nv, nf, err) ||
        ps_decode_check_points((size_t)nv, lim, err))
        return -1;
    out->n = (size_t)nv;
    out->dim = 3;
    out->points = malloc(out->n * 3 * sizeof *out->points + 1);
    out->normals = has_normals ? malloc(out->n * 3 * sizeof *out->normals + 1) : NULL;
    if (!out->points || (has_normals && !out->normals) || ps_tris_reserve(tris, (size_t)nf, err))
        return ps_api_fail(err, 500, "out of memory");
    for (size_t i = 0; i < out->n; i++)
        if (read_vertex(r, i, has_normals, out, err)) return -1;
    for (size_t f = 0; f < (size_t)nf; f++)
        if (read_face(r, f, out->n, tris, err)) return -1;
    return 0;
}

int ps_decode_off(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err) {
    off_reader r;
    ps_tris tris = {0};
    memset(out, 0, sizeof *out);
    ps_lines_init(&r.lines, bytes, len);
    int failed = read_off(&r, lim, out, &tris, err);
    return ps_decode_finish_mesh(failed, &tris, out, lim, err);
}
