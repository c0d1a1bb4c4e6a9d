/* decode_off.c: OFF meshes (also COFF, NOFF, CNOFF): "OFF", counts
 * "nv nf [ne]", nv vertex records "x y z [nx ny nz] [colour...]", nf face
 * records "k i1 .. ik [colour...]" fan-triangulated.
 *
 * Tokens are separated by white space; a line ends at LF, CR or CRLF, and
 * '#' starts a comment to the end of its line.  Every record (the counts, a
 * vertex, a face) starts on a new line.  A record whose line holds all its
 * numbers ends with that line: further tokens on it (colours) are skipped.
 * A record that is incomplete on its line continues on the next lines (one
 * number per line, wrapped face lines), and ends with the line that
 * completes it, whose further tokens are skipped the same way.  So two
 * records never share a line, and colours are only recognized after the
 * last number of a record, on the same line.  The counts follow "OFF" on
 * its line or start on the next; "ne" may be left out when nv and nf are on
 * one line, and is required when they are on different lines (else it
 * could not be told from the first vertex's x). */
#include "decode.h"

#include <stdlib.h>
#include <string.h>

#include "decode_scan.h"
#include "decode_util.h"

typedef struct off_reader {
    const char *p, *end; /* the bytes not read yet */
    size_t line;         /* the line p is on, from 1 */
} off_reader;

static const char counts_syntax[] = "\"vertex_count face_count edge_count\"";

/* White space within a line (ps_is_blank without CR, which ends a line). */
static int is_inline_blank(char ch) { return ch != '\r' && ps_is_blank(ch); }

/* Moves past the rest of the line and its LF, CR or CRLF.  Returns 0 when
 * the data ends first. */
static int skip_line(off_reader *r) {
    r->p = ps_line_end(r->p, r->end);
    if (r->p == r->end) return 0;
    r->p = ps_past_line_end(r->p, r->end);
    r->line++;
    return 1;
}

/* The next token [*s, *t) on the current line, moving past it; 0 when the
 * line has no more (its end or a '#' comment). */
static int line_token(off_reader *r, const char **s, const char **t) {
    while (r->p < r->end && is_inline_blank(*r->p)) r->p++;
    if (r->p == r->end || ps_is_line_end(*r->p) || *r->p == '#') return 0;
    *s = r->p;
    *t = r->p = ps_token_end(r->p, r->end, NULL);
    return 1;
}

/* The next token on this line or a later one (past blank and comment
 * lines); 0 when the data ends first. */
static int data_token(off_reader *r, const char **s, const char **t) {
    while (!line_token(r, s, t))
        if (!skip_line(r)) return 0;
    return 1;
}

static int ends_before(const off_reader *r, const char *what, ps_api_error *err) {
    return ps_api_fail(err, 400, "line %zu: the file ends before %s", r->line, what);
}

/* Parses the token [s, t) of the current line as an integer. */
static int token_integer(const off_reader *r, const char *s, const char *t, const char *what,
                         long long *v, ps_api_error *err) {
    if (ps_parse_integer(s, (size_t)(t - s), v))
        return ps_api_fail(err, 400, "line %zu: expected %s", r->line, what);
    return 0;
}

/* The next token, which the counts need, as an integer. */
static int count_token(off_reader *r, long long *v, ps_api_error *err) {
    const char *s, *t;
    if (!data_token(r, &s, &t)) return ends_before(r, "the counts", err);
    return token_integer(r, s, t, counts_syntax, v, err);
}

static int parse_variant(off_reader *r, int *has_normals, ps_api_error *err) {
    const char *s, *t;
    if (!data_token(r, &s, &t)) return ends_before(r, "the OFF keyword", err);
    size_t n = (size_t)(t - s);
    static const char *const known[] = {"OFF", "COFF", "NOFF", "CNOFF", "NCOFF"};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (n == strlen(known[i]) && !memcmp(s, known[i], n)) {
            *has_normals = memchr(s, 'N', n) != NULL;
            return 0;
        }
    char shown[41];
    ps_preview(s, n, shown, sizeof shown);
    return ps_api_fail(err, 422, "line %zu: OFF variant \"%s\" is not supported (OFF, COFF, "
                       "NOFF and CNOFF are)", r->line, shown);
}

/* "nv nf [ne]" after "OFF" on its line or from the next data line on; ne
 * is read (and required) only when nv and nf are on different lines. */
static int parse_counts(off_reader *r, long long *nv, long long *nf, ps_api_error *err) {
    long long ne;
    if (count_token(r, nv, err)) return -1;
    size_t nv_line = r->line;
    if (count_token(r, nf, err) || (r->line != nv_line && count_token(r, &ne, err))) return -1;
    if (*nv < 0 || *nf < 0) return ps_api_fail(err, 400, "line %zu: negative count", r->line);
    skip_line(r);
    return 0;
}

/* 400 when the counts cannot fit in the bytes left (a vertex takes at least
 * 6 bytes, a face 2), checked before allocating. */
static int check_counts(const off_reader *r, long long nv, long long nf, ps_api_error *err) {
    unsigned long long remain = (unsigned long long)(r->end - r->p) + 1;
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
    const int need = has_normals ? 6 : 3;
    size_t first_line = r->line;
    for (int k = 0; k < need; k++) {
        const char *s, *t;
        double *dst = k < 3 ? &out->points[3 * i + (size_t)k]
                            : &out->normals[3 * i + (size_t)k - 3];
        if (!data_token(r, &s, &t)) {
            if (k == 0) return ends_before(r, "all vertices", err);
            return ps_api_fail(err, 400, "line %zu: vertex %zu needs %d numbers (the file ends "
                               "after %d)", first_line, i, need, k);
        }
        if (k == 0) first_line = r->line;
        if (ps_field_number(s, t, r->line, dst, err)) return -1;
    }
    skip_line(r);
    return 0;
}

static int read_face(off_reader *r, size_t face, size_t nv, ps_tris *tris, ps_api_error *err) {
    const char *s, *t;
    long long k, idx;
    ps_fan fan = {0};
    if (!data_token(r, &s, &t)) return ends_before(r, "all faces", err);
    size_t first_line = r->line;
    if (token_integer(r, s, t, "a face's vertex count", &k, err)) return -1;
    for (long long j = 0; j < k; j++) {
        if (!data_token(r, &s, &t))
            return ps_api_fail(err, 400, "line %zu: face %zu needs %lld vertex indices (the "
                               "file ends after %lld)", first_line, face, k, j);
        if (token_integer(r, s, t, "a vertex index", &idx, err)) return -1;
        if (idx < 0 || (unsigned long long)idx >= nv)
            return ps_api_fail(err, 422, "line %zu: face %zu refers to vertex %lld (the file "
                               "has %zu vertices)", r->line, face, idx, nv);
        if (ps_fan_add(&fan, tris, (uint32_t)idx, err)) return -1;
    }
    skip_line(r);
    return 0;
}

static int read_off(off_reader *r, const ps_decode_limits *lim, ps_pointset *out,
                    ps_tris *tris, ps_api_error *err) {
    long long nv, nf;
    int has_normals = 0;
    if (parse_variant(r, &has_normals, err) || parse_counts(r, &nv, &nf, err) ||
        check_counts(r, nv, nf, err) || ps_decode_check_points((size_t)nv, lim, err))
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
    off_reader r = {bytes, bytes + len, 1};
    ps_tris tris = {0};
    memset(out, 0, sizeof *out);
    int failed = read_off(&r, lim, out, &tris, err);
    return ps_decode_finish_mesh(failed, &tris, out, lim, err);
}
