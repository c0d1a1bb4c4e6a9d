/*
 * encode_labels.c: a ps_result as text, one segment label per line in input
 * order (encode.h) -- the format PSB-style scripts and `pointseg score` read.
 */
#include "encode.h"
#include "number_text.h"

#include <stdlib.h>

char *ps_encode_labels(const ps_result *r, size_t *len) {
    size_t n = r->labels ? r->n_points : 0;
    char *text = malloc(n * (PS_INT_TEXT_MAX + 1) + 1);
    if (!text) return NULL;
    char *p = text;
    for (size_t i = 0; i < n; i++) {
        p = ps_put_int(p, r->labels[i]);
        *p++ = '\n';
    }
    *p = 0;
    if (len) *len = (size_t)(p - text);
    return text;
}
