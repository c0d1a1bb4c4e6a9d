/*
 * decode_labels.c: a labels file (decode.h): whitespace-separated decimal
 * integers, in practice one per line (pointseg's --output labels, the
 * benchmark's .seg and .lab files).
 */
#include "decode.h"

#include <stdlib.h>
#include <string.h>

/* A labels file's separators: space, tab, \r and \n.  Unlike
 * ps_skip_space (decode_scan.h) not \v or \f, and the loop that skips them
 * counts the lines for its messages. */
static int is_label_separator(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

static int grow(int **v, size_t *room) {
    int *grown = realloc(*v, 2 * *room * sizeof **v);
    if (!grown) return -1;
    *v = grown;
    *room *= 2;
    return 0;
}

int ps_decode_labels(const char *bytes, size_t len, int **values, size_t *count,
                     ps_api_error *err) {
    const char *p = bytes, *end = bytes + len;
    size_t n = 0, room = 1024, line = 1;
    int *v = malloc(room * sizeof *v);
    while (v) {
        while (p < end && is_label_separator(*p)) line += *p++ == '\n';
        if (p == end) {
            *values = v;
            *count = n;
            return 0;
        }
        int negative = *p == '-';
        p += negative || *p == '+';
        long long x = 0;
        const char *digits = p;
        while (p < end && *p >= '0' && *p <= '9' && x <= 0x7fffffff) x = 10 * x + (*p++ - '0');
        if (p == digits || x > 0x7fffffff || (p < end && !is_label_separator(*p))) {
            free(v);
            return ps_api_fail(err, 400, "line %zu: expected an integer", line);
        }
        if (n == room && grow(&v, &room) != 0) break;
        v[n++] = (int)(negative ? -x : x);
    }
    free(v);
    return ps_api_fail(err, 500, "out of memory reading labels");
}
