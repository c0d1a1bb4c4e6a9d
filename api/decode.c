/* decode.c: recognizing a format from the bytes, dispatching to its
 * decoder, and reading a whole file (decode.h). */
#include "decode.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "decode_scan.h"
#include "decode_util.h"

static int starts_with(const char *s, const char *e, const char *prefix) {
    size_t n = strlen(prefix);
    return (size_t)(e - s) >= n && !memcmp(s, prefix, n);
}

/* OFF, NOFF, COFF and the other [C][N][4][n]OFF variants (the decoder
 * rejects the ones it does not handle, with a message). */
static int is_off_token(const char *s, const char *e) {
    if (e - s < 3 || memcmp(e - 3, "OFF", 3)) return 0;
    for (const char *p = s; p < e - 3; p++)
        if (!*p || !strchr("STCN4n", *p)) return 0;
    return 1;
}

static int first_token_is_off(const char *bytes, size_t len) {
    ps_lines lines;
    const char *s, *e;
    ps_lines_init(&lines, bytes, len);
    if (!ps_lines_next_data(&lines, &s, &e)) return 0;
    return is_off_token(s, ps_token_end(s, e, NULL));
}

/* 1 when [s, e) is one or more numbers separated by blanks, ',' or ';'. */
static int is_number_line(const char *s, const char *e) {
    if (s >= e) return 0;
    while (s < e) {
        const char *t = ps_token_end(s, e, ",;");
        double v;
        if (ps_parse_double(s, (size_t)(t - s), &v)) return 0;
        s = ps_skip_blanks(t, e);
        if (s < e && (*s == ',' || *s == ';')) s = ps_skip_blanks(s + 1, e);
    }
    return 1;
}

static int looks_like_obj(const char *bytes, size_t len) {
    ps_lines lines;
    const char *s, *e;
    ps_lines_init(&lines, bytes, len);
    while (ps_lines_next_data(&lines, &s, &e)) {
        if (starts_with(s, e, "v ") || starts_with(s, e, "v\t")) return 1;
        if (is_number_line(s, e)) return 0;
    }
    return 0;
}

/* The first data line is numbers, or a header line followed by numbers. */
static int looks_like_xyz(const char *bytes, size_t len) {
    ps_lines lines;
    const char *s, *e;
    ps_lines_init(&lines, bytes, len);
    if (!ps_lines_next_data(&lines, &s, &e)) return 0;
    if (is_number_line(s, e)) return 1;
    return ps_lines_next_data(&lines, &s, &e) && is_number_line(s, e);
}

ps_format ps_detect_format(const char *bytes, size_t len) {
    const char *end = bytes + len;
    if (starts_with(bytes, end, "ply\n") || starts_with(bytes, end, "ply\r\n"))
        return PS_FORMAT_PLY;
    const char *p = bytes;
    while (p < end && (ps_is_blank(*p) || *p == '\n')) p++;
    if (p < end && *p == '{') return PS_FORMAT_JSON;
    if (first_token_is_off(bytes, len)) return PS_FORMAT_OFF;
    if (looks_like_obj(bytes, len)) return PS_FORMAT_OBJ;
    if (looks_like_xyz(bytes, len)) return PS_FORMAT_XYZ;
    return PS_FORMAT_UNKNOWN;
}

const char *ps_format_name(ps_format f) {
    switch (f) {
    case PS_FORMAT_UNKNOWN: return "unknown";
    case PS_FORMAT_PLY: return "ply";
    case PS_FORMAT_OFF: return "off";
    case PS_FORMAT_OBJ: return "obj";
    case PS_FORMAT_XYZ: return "xyz";
    case PS_FORMAT_JSON: return "json";
    }
    return "unknown";
}

static int is_blank_input(const char *bytes, size_t len) {
    for (size_t i = 0; i < len; i++)
        if (!ps_is_blank(bytes[i]) && bytes[i] != '\n') return 0;
    return 1;
}

int ps_decode(const char *bytes, size_t len, const ps_decode_limits *lim,
              ps_pointset *out, ps_api_error *err) {
    memset(out, 0, sizeof *out);
    bytes = ps_skip_bom(bytes, &len);
    if (is_blank_input(bytes, len)) return ps_api_fail(err, 400, "empty input");
    ps_format f = ps_detect_format(bytes, len);
    switch (f) {
    case PS_FORMAT_PLY: return ps_decode_ply(bytes, len, lim, out, err);
    case PS_FORMAT_JSON: return ps_decode_json(bytes, len, lim, out, err);
    case PS_FORMAT_OFF: return ps_decode_off(bytes, len, lim, out, err);
    case PS_FORMAT_OBJ: return ps_decode_obj(bytes, len, lim, out, err);
    case PS_FORMAT_XYZ: return ps_decode_xyz(bytes, len, lim, out, err);
    case PS_FORMAT_UNKNOWN: break;
    }
    return ps_api_fail(err, 400, "unrecognized format (expected PLY, OFF, OBJ, XYZ/CSV or JSON)");
}

static int read_stream(FILE *in, const char *path, char **bytes, size_t *len,
                       ps_api_error *err) {
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n, in);
        if (n < cap) break;
        char *bigger = cap <= SIZE_MAX / 2 ? realloc(buf, cap * 2) : NULL;
        if (!bigger) free(buf);
        buf = bigger;
        cap *= 2;
    }
    if (!buf) return ps_api_fail(err, 413, "%s: too large to hold in memory", path);
    if (ferror(in)) {
        free(buf);
        return ps_api_fail(err, 400, "%s: read error", path);
    }
    *bytes = buf;
    *len = n;
    return 0;
}

int ps_read_file(const char *path, char **bytes, size_t *len, ps_api_error *err) {
    *bytes = NULL;
    *len = 0;
    if (!strcmp(path, "-")) return read_stream(stdin, "stdin", bytes, len, err);
    FILE *in = fopen(path, "rb");
    if (!in) return ps_api_fail(err, 400, "cannot open %s: %s", path, strerror(errno));
    int rc = read_stream(in, path, bytes, len, err);
    fclose(in);
    return rc;
}
