/* decode_ply_header.c: parsing the text header of a PLY file, and reading
 * one binary value in the file's byte order (decode_ply_header.h). */
#include "decode_ply_header.h"

#include <string.h>

#include "decode_scan.h"

enum { MAX_WORDS = 6 };

typedef struct header_line {
    size_t number;
    int n_words;
    const char *word[MAX_WORDS];
    size_t word_len[MAX_WORDS];
} header_line;

static const struct {
    const char *name;
    ps_ply_type type;
} type_names[] = {
    {"char", PS_PLY_INT8},     {"int8", PS_PLY_INT8},       {"uchar", PS_PLY_UINT8},
    {"uint8", PS_PLY_UINT8},   {"short", PS_PLY_INT16},     {"int16", PS_PLY_INT16},
    {"ushort", PS_PLY_UINT16}, {"uint16", PS_PLY_UINT16},   {"int", PS_PLY_INT32},
    {"int32", PS_PLY_INT32},   {"uint", PS_PLY_UINT32},     {"uint32", PS_PLY_UINT32},
    {"float", PS_PLY_FLOAT32}, {"float32", PS_PLY_FLOAT32}, {"double", PS_PLY_FLOAT64},
    {"float64", PS_PLY_FLOAT64},
};

size_t ps_ply_type_size(ps_ply_type t) {
    switch (t) {
    case PS_PLY_INT8: case PS_PLY_UINT8: return 1;
    case PS_PLY_INT16: case PS_PLY_UINT16: return 2;
    case PS_PLY_INT32: case PS_PLY_UINT32: case PS_PLY_FLOAT32: return 4;
    case PS_PLY_FLOAT64: return 8;
    }
    return 1;
}

static int word_is(const header_line *l, int i, const char *s) {
    return i < l->n_words && l->word_len[i] == strlen(s) && !memcmp(l->word[i], s, l->word_len[i]);
}

static int parse_type(const header_line *l, int i, ps_ply_type *t) {
    for (size_t k = 0; k < sizeof type_names / sizeof type_names[0]; k++)
        if (word_is(l, i, type_names[k].name)) {
            *t = type_names[k].type;
            return 0;
        }
    return -1;
}

static void copy_name(char *dst, const header_line *l, int i) {
    size_t n = l->word_len[i] < PS_PLY_NAME_MAX - 1 ? l->word_len[i] : PS_PLY_NAME_MAX - 1;
    memcpy(dst, l->word[i], n);
    dst[n] = 0;
}

static void split_words(header_line *l, const char *s, const char *e) {
    l->n_words = 0;
    while (s < e && l->n_words < MAX_WORDS) {
        const char *t = ps_token_end(s, e, NULL);
        l->word[l->n_words] = s;
        l->word_len[l->n_words++] = (size_t)(t - s);
        s = ps_skip_blanks(t, e);
    }
}

static int parse_format(const header_line *l, ps_ply_header *h, ps_api_error *err) {
    if (word_is(l, 1, "ascii")) h->format = PS_PLY_ASCII;
    else if (word_is(l, 1, "binary_little_endian")) h->format = PS_PLY_BINARY_LE;
    else if (word_is(l, 1, "binary_big_endian")) h->format = PS_PLY_BINARY_BE;
    else return ps_api_fail(err, 400, "PLY header line %zu: unknown format", l->number);
    return 0;
}

static int parse_count(const header_line *l, uint64_t *count) {
    if (l->n_words != 3 || l->word_len[2] > 20) return -1;
    uint64_t c = 0;
    for (size_t i = 0; i < l->word_len[2]; i++) {
        char d = l->word[2][i];
        if (d < '0' || d > '9') return -1;
        if (c > (UINT64_MAX - (uint64_t)(d - '0')) / 10) return -1;
        c = c * 10 + (uint64_t)(d - '0');
    }
    *count = c;
    return 0;
}

static int parse_element(const header_line *l, ps_ply_header *h, ps_api_error *err) {
    if (h->n_elements == PS_PLY_MAX_ELEMENTS)
        return ps_api_fail(err, 400, "PLY header line %zu: more than %d elements", l->number,
                           PS_PLY_MAX_ELEMENTS);
    ps_ply_element *e = &h->elements[h->n_elements];
    if (parse_count(l, &e->count))
        return ps_api_fail(err, 400, "PLY header line %zu: expected \"element NAME COUNT\"",
                           l->number);
    copy_name(e->name, l, 1);
    e->first_property = h->n_properties;
    e->n_properties = 0;
    h->n_elements++;
    return 0;
}

static int parse_property(const header_line *l, ps_ply_header *h, ps_api_error *err) {
    if (h->n_elements == 0)
        return ps_api_fail(err, 400, "PLY header line %zu: property before any element",
                           l->number);
    if (h->n_properties == PS_PLY_MAX_PROPERTIES)
        return ps_api_fail(err, 400, "PLY header line %zu: more than %d properties", l->number,
                           PS_PLY_MAX_PROPERTIES);
    ps_ply_property *p = &h->properties[h->n_properties];
    int list = word_is(l, 1, "list");
    p->is_list = list;
    p->count_type = PS_PLY_UINT8;
    int ok = list ? l->n_words == 5 && !parse_type(l, 2, &p->count_type) &&
                        !parse_type(l, 3, &p->type)
                  : l->n_words == 3 && !parse_type(l, 1, &p->type);
    if (!ok)
        return ps_api_fail(err, 400,
                           "PLY header line %zu: expected \"property TYPE NAME\" or "
                           "\"property list TYPE TYPE NAME\" with a PLY type",
                           l->number);
    copy_name(p->name, l, l->n_words - 1);
    h->n_properties++;
    h->elements[h->n_elements - 1].n_properties++;
    return 0;
}

/* A line without a known keyword: listed in h->skipped, or refused when
 * too many were (a file that is no PLY but starts with "ply"). */
static int skip_line(const header_line *l, const char *s, const char *e, ps_ply_header *h,
                     ps_api_error *err) {
    char shown[PS_PLY_PREVIEW_MAX];
    if (h->n_skipped == PS_PLY_MAX_SKIPPED || word_is(l, 0, "end_header")) {
        ps_preview(l->word[0], l->word_len[0], shown, sizeof shown);
        return ps_api_fail(err, 400, "PLY header line %zu: unknown keyword \"%s\"%s", l->number, shown,
                           word_is(l, 0, "end_header") ? "" : " (too many lines without a keyword)");
    }
    ps_ply_skipped *k = &h->skipped[h->n_skipped++];
    k->line = l->number;
    ps_preview(s, (size_t)(e - s), k->preview, sizeof k->preview);
    return 0;
}

static int parse_line(const header_line *l, const char *s, const char *e, ps_ply_header *h,
                      int *done, ps_api_error *err) {
    if (l->n_words == 0 || word_is(l, 0, "comment") || word_is(l, 0, "obj_info")) return 0;
    if (word_is(l, 0, "format")) return parse_format(l, h, err);
    if (word_is(l, 0, "element")) return parse_element(l, h, err);
    if (word_is(l, 0, "property")) return parse_property(l, h, err);
    if (word_is(l, 0, "end_header") && l->n_words == 1) {
        *done = 1;
        return 0;
    }
    return skip_line(l, s, e, h, err);
}

int ps_ply_parse_header(const char *bytes, size_t len, ps_ply_header *h, ps_api_error *err) {
    ps_lines lines;
    const char *s, *e;
    header_line l;
    int done = 0, have_format = 0;
    memset(h, 0, sizeof *h);
    ps_lines_init(&lines, bytes, len);
    if (!ps_lines_next(&lines, &s, &e) || e - s != 3 || memcmp(s, "ply", 3))
        return ps_api_fail(err, 400, "PLY header line 1: expected \"ply\"");
    while (!done && ps_lines_next(&lines, &s, &e)) {
        l.number = lines.line;
        split_words(&l, s, e);
        have_format |= word_is(&l, 0, "format");
        if (parse_line(&l, s, e, h, &done, err)) return -1;
    }
    if (!done) return ps_api_fail(err, 400, "PLY header has no end_header line");
    if (!have_format) return ps_api_fail(err, 400, "PLY header has no format line");
    h->data_offset = (size_t)(lines.pos - bytes);
    return 0;
}

const ps_ply_element *ps_ply_find_element(const ps_ply_header *h, const char *name) {
    for (int i = 0; i < h->n_elements; i++)
        if (!strcmp(h->elements[i].name, name)) return &h->elements[i];
    return NULL;
}

const ps_ply_property *ps_ply_property_of(const ps_ply_header *h, const ps_ply_element *e,
                                          int i) {
    return &h->properties[e->first_property + i];
}

int ps_ply_find_scalar(const ps_ply_header *h, const ps_ply_element *e, const char *name) {
    for (int i = 0; i < e->n_properties; i++) {
        const ps_ply_property *p = ps_ply_property_of(h, e, i);
        if (!p->is_list && !strcmp(p->name, name)) return i;
    }
    return -1;
}

size_t ps_ply_scalar_offset(const ps_ply_header *h, const ps_ply_element *e, int i) {
    size_t offset = 0;
    for (int k = 0; k < i; k++) offset += ps_ply_type_size(ps_ply_property_of(h, e, k)->type);
    return offset;
}

int ps_ply_needs_swap(ps_ply_format f) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    return f == PS_PLY_BINARY_LE;
#else
    return f == PS_PLY_BINARY_BE;
#endif
}

static uint16_t load16(const char *p, int swap) {
    uint16_t v;
    memcpy(&v, p, sizeof v);
    return swap ? __builtin_bswap16(v) : v;
}

static uint32_t load32(const char *p, int swap) {
    uint32_t v;
    memcpy(&v, p, sizeof v);
    return swap ? __builtin_bswap32(v) : v;
}

static uint64_t load64(const char *p, int swap) {
    uint64_t v;
    memcpy(&v, p, sizeof v);
    return swap ? __builtin_bswap64(v) : v;
}

double ps_ply_load_binary(const char *at, ps_ply_type t, int swap) {
    switch (t) {
    case PS_PLY_INT8: return (int8_t)*at;
    case PS_PLY_UINT8: return (uint8_t)*at;
    case PS_PLY_INT16: return (int16_t)load16(at, swap);
    case PS_PLY_UINT16: return load16(at, swap);
    case PS_PLY_INT32: return (int32_t)load32(at, swap);
    case PS_PLY_UINT32: return load32(at, swap);
    case PS_PLY_FLOAT32: {
        uint32_t bits = load32(at, swap);
        float f;
        memcpy(&f, &bits, sizeof f);
        return f;
    }
    case PS_PLY_FLOAT64: {
        uint64_t bits = load64(at, swap);
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    }
    return 0;
}
