/* decode_scan.c: lines, tokens and bounded number parsing over text that is
 * not NUL-terminated (decode_scan.h). */
#include "decode_scan.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { NUMBER_MAX = 127 };

void ps_lines_init(ps_lines *c, const char *bytes, size_t len) {
    c->pos = bytes;
    c->end = bytes + len;
    c->line = 0;
}

int ps_is_blank(char ch) {
    return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\v' || ch == '\f';
}

const char *ps_skip_blanks(const char *p, const char *end) {
    while (p < end && ps_is_blank(*p)) p++;
    return p;
}

const char *ps_skip_space(const char *p, const char *end) {
    while (p < end && (ps_is_blank(*p) || *p == '\n')) p++;
    return p;
}

int ps_is_line_end(char ch) { return ch == '\n' || ch == '\r'; }

const char *ps_line_end(const char *p, const char *end) {
    while (p < end && !ps_is_line_end(*p)) p++;
    return p;
}

const char *ps_past_line_end(const char *p, const char *end) {
    if (p < end && *p == '\r') p++;
    if (p < end && *p == '\n') p++;
    return p;
}

int ps_lines_next(ps_lines *c, const char **start, const char **stop) {
    if (c->pos >= c->end) return 0;
    const char *line_end = ps_line_end(c->pos, c->end);
    const char *s = ps_skip_blanks(c->pos, line_end);
    const char *e = line_end;
    while (e > s && ps_is_blank(e[-1])) e--;
    c->pos = ps_past_line_end(line_end, c->end);
    c->line++;
    *start = s;
    *stop = e;
    return 1;
}

int ps_lines_next_data(ps_lines *c, const char **start, const char **stop) {
    while (ps_lines_next(c, start, stop))
        if (*start < *stop && **start != '#') return 1;
    return 0;
}

const char *ps_token_end(const char *p, const char *end, const char *seps) {
    while (p < end && !ps_is_blank(*p) && *p != '\n' && !(seps && *p && strchr(seps, *p)))
        p++;
    return p;
}

int ps_parse_double(const char *s, size_t n, double *out) {
    char buf[NUMBER_MAX + 1];
    if (n == 0 || n > NUMBER_MAX) return -1;
    memcpy(buf, s, n);
    buf[n] = 0;
    if (ps_is_blank(buf[0])) return -1;
    char *stop;
    *out = strtod(buf, &stop);
    return stop == buf + n ? 0 : -1;
}

int ps_parse_integer(const char *s, size_t n, long long *out) {
    char buf[NUMBER_MAX + 1];
    if (n == 0 || n > NUMBER_MAX) return -1;
    memcpy(buf, s, n);
    buf[n] = 0;
    size_t digits = (buf[0] == '-' || buf[0] == '+') ? 1 : 0;
    if (digits == n) return -1;
    for (size_t i = digits; i < n; i++)
        if (buf[i] < '0' || buf[i] > '9') return -1;
    char *stop;
    errno = 0;
    *out = strtoll(buf, &stop, 10);
    return errno == ERANGE || stop != buf + n ? -1 : 0;
}

int ps_next_field(const char **p, const char *end, const char *seps, const char **s,
                  const char **t) {
    const char *q = ps_skip_blanks(*p, end);
    if (q == end || *q == '#') return 0;
    if (seps && strchr(seps, *q)) return -1;
    *s = q;
    *t = ps_token_end(q, end, seps);
    q = ps_skip_blanks(*t, end);
    if (seps && q < end && strchr(seps, *q)) q++;
    *p = q;
    return 1;
}

void ps_preview(const char *s, size_t n, char *out, size_t out_size) {
    size_t k = n < out_size - 1 ? n : out_size - 1;
    for (size_t i = 0; i < k; i++) out[i] = (s[i] >= 32 && s[i] < 127) ? s[i] : '?';
    out[k] = 0;
}

/* The failure of ps_field_number: the message quotes a preview of [s, t). */
static int field_number_fail(const char *s, const char *t, size_t line, int non_finite,
                             ps_api_error *err) {
    char shown[41];
    ps_preview(s, (size_t)(t - s), shown, sizeof shown);
    if (non_finite)
        return ps_api_fail(err, 422, "line %zu: non-finite number \"%s\"", line, shown);
    return ps_api_fail(err, 400, "line %zu: \"%s\" is not a number", line, shown);
}

int ps_field_number(const char *s, const char *t, size_t line, double *v, ps_api_error *err) {
    if (ps_parse_double(s, (size_t)(t - s), v)) return field_number_fail(s, t, line, 0, err);
    if (!isfinite(*v)) return field_number_fail(s, t, line, 1, err);
    return 0;
}
