/* number_text.c: the number-to-text writers of number_text.h. */
#include "number_text.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

char *ps_put_int(char *p, int v) {
    char digits[PS_INT_TEXT_MAX];
    int len = 0;
    unsigned u = v < 0 ? 0u - (unsigned)v : (unsigned)v;
    do {
        digits[len++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0) *p++ = '-';
    while (len) *p++ = digits[--len];
    return p;
}

char *ps_put_double(char *p, double v) {
    if (!isfinite(v)) {
        memcpy(p, "null", 4);
        return p + 4;
    }
    char text[PS_DOUBLE_TEXT_MAX + 1];
    int len = snprintf(text, sizeof text, "%.9g", v);
    memcpy(p, text, (size_t)len);
    return p + len;
}
