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

/* Exact powers of ten up to 1e22; beyond, within an ulp. */
static double power_of_ten(int e) {
    static const double exact[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                   1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    return e <= 22 ? exact[e] : exact[22] * exact[e - 22];
}

/* a * 10^(8 - e): a's nine leading digits before the point, when e is its
 * decimal exponent. */
static double nine_digits(double a, int e) {
    return e <= 8 ? a * power_of_ten(8 - e) : a / power_of_ten(e - 8);
}

/* Writes the `len` significant digits `digits` (no trailing zeros) of a
 * value with decimal exponent e the way %g does. */
static char *put_g(char *p, const char *digits, int len, int e) {
    if (e < -4 || e >= 9) {
        *p++ = digits[0];
        if (len > 1) {
            *p++ = '.';
            memcpy(p, digits + 1, (size_t)len - 1);
            p += len - 1;
        }
        *p++ = 'e';
        *p++ = e < 0 ? '-' : '+';
        if (e > -10 && e < 10) *p++ = '0';
        return ps_put_int(p, e < 0 ? -e : e);
    }
    if (e < 0) {
        *p++ = '0';
        *p++ = '.';
        for (int z = -1; z > e; z--) *p++ = '0';
        memcpy(p, digits, (size_t)len);
        return p + len;
    }
    int whole = len > e + 1 ? e + 1 : len;
    memcpy(p, digits, (size_t)whole);
    p += whole;
    for (int z = whole; z <= e; z++) *p++ = '0';
    if (len > whole) {
        *p++ = '.';
        memcpy(p, digits + whole, (size_t)(len - whole));
        p += len - whole;
    }
    return p;
}

/* %.9g of a finite a with 1e-30 <= |a| < 1e30, without snprintf: the
 * digits come from one scaling and rounding, so the last digit may differ
 * from printf's in rare half-way cases (the value is still within one unit
 * of the ninth digit). */
static char *put_moderate(char *p, double v) {
    double a = fabs(v);
    int e = (int)floor(log10(a));
    double scaled = nine_digits(a, e);
    if (scaled < 1e8 - 0.5) scaled = nine_digits(a, --e);
    if (scaled >= 1e9 - 0.5) scaled = nine_digits(a, ++e);
    unsigned long m = (unsigned long)(scaled + 0.5);
    char digits[9];
    for (int i = 8; i >= 0; i--, m /= 10) digits[i] = (char)('0' + m % 10);
    int len = 9;
    while (len > 1 && digits[len - 1] == '0') len--;
    if (v < 0) *p++ = '-';
    return put_g(p, digits, len, e);
}

char *ps_put_double(char *p, double v) {
    if (!isfinite(v)) {
        memcpy(p, "null", 4);
        return p + 4;
    }
    if (v == 0) {
        *p++ = '0';
        return p;
    }
    if (fabs(v) >= 1e-30 && fabs(v) < 1e30) return put_moderate(p, v);
    char text[PS_DOUBLE_TEXT_MAX + 1];
    int len = snprintf(text, sizeof text, "%.9g", v);
    memcpy(p, text, (size_t)len);
    return p + len;
}
