/*
 * params_table.c: the one table of request parameters (params_table.h) and
 * the parser that sets a ps_request_params field from text.  The CLI flags,
 * the query string and a JSON body's "params" all go through
 * ps_request_param_set, so names, ranges and messages agree everywhere.
 * A name may be spelled with '-' or '_' alike (ncut-threshold).
 */
#include "params_table.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Position of each parameter in the table. */
typedef enum param_id {
    P_METHOD,
    P_K,
    P_CENTRALITY,
    P_SAMPLES,
    P_PERSISTENCE,
    P_NCUT_THRESHOLD,
    P_FEATURE_THRESHOLD,
    P_MINIMA,
    P_F2,
    P_SMOOTH_NORMALS,
    P_THREADS,
    P_OUTPUT,
    P_INCLUDE,
    P_COUNT
} param_id;

/* Choice lists, in the order of their C enums / bits. */
static const char *const method_choices[] = {"auto", "paper", NULL};
static const char *const centrality_choices[] = {"auto", "exact", "approx", NULL};
static const char *const output_choices[] = {"json", "labels", "ply", NULL};
static const char *const include_choices[] = {"centrality", "point_supernode", NULL};

/* default_text mirrors ps_params_default (core/params.c); a unit test
 * checks that they agree. */
static const ps_param_spec table[P_COUNT] = {
    [P_METHOD] = {"method", PS_PT_ENUM, "auto", 0, 0, method_choices,
                  "auto (crease-aware: persistence, minima, crease split and merge, "
                  "convex unions and flat patches merged) "
                  "or paper (the published method)"},
    [P_K] = {"k", PS_PT_INT, "7", 1, 64, NULL,
             "neighbours per point in the kNN graph"},
    [P_CENTRALITY] = {"centrality", PS_PT_ENUM, "auto", 0, 0, centrality_choices,
                      "exact (Dijkstra from every point), approx (sampled), or auto by size"},
    [P_SAMPLES] = {"samples", PS_PT_INT, "0", 0, 100000, NULL,
                   "approx centrality sample count; 0 = ceil(sqrt(n)) of the points segmented, "
                   "at most 512; shared by the draws of an input split in draws "
                   "(method auto, over 26,667 points)"},
    [P_PERSISTENCE] = {"persistence", PS_PT_DOUBLE, "0.1", 0, 1, NULL,
                       "merge maxima less prominent than this fraction of f's range"},
    [P_NCUT_THRESHOLD] = {"ncut_threshold", PS_PT_DOUBLE, "0", 0, 2, NULL,
                          "stop bisecting when the normalized cut exceeds this; "
                          "0 = the method's own (auto: never, paper: 0.6)"},
    [P_FEATURE_THRESHOLD] = {"feature_threshold", PS_PT_DOUBLE, "0.1", 0, 1, NULL,
                             "merge segments whose feature size is below this fraction of f's range"},
    [P_MINIMA] = {"minima", PS_PT_BOOL, "true", 0, 1, NULL,
                  "central regions below the limbs' saddles go to the minima of f"},
    [P_F2] = {"f2", PS_PT_BOOL, "false", 0, 1, NULL,
              "split supernodes at the maxima of f2, the distance to their own sink"},
    [P_SMOOTH_NORMALS] = {"smooth_normals", PS_PT_BOOL, "true", 0, 1, NULL,
                          "smooth estimated normals as much as the scan's measured noise asks"},
    [P_THREADS] = {"threads", PS_PT_INT, "0", 0, 256, NULL,
                   "worker threads; 0 = all cores"},
    [P_OUTPUT] = {"output", PS_PT_ENUM, "json", 0, 0, output_choices,
                  "result format: json document, labels (one per line) or coloured ply"},
    [P_INCLUDE] = {"include", PS_PT_LIST, "", 0, 0, include_choices,
                   "extra per-point arrays in the json document"},
};

const ps_param_spec *ps_param_table(size_t *count) {
    if (count) *count = P_COUNT;
    return table;
}

/* Compares a name with '-' and '_' treated alike; len bounds `given`. */
static int same_name(const char *given, size_t len, const char *canonical) {
    size_t i = 0;
    for (; i < len && canonical[i]; i++) {
        char c = given[i] == '-' ? '_' : given[i];
        if (c != canonical[i]) return 0;
    }
    return i == len && canonical[i] == 0;
}

static int find_id(const char *name) {
    if (!name) return -1;
    for (int i = 0; i < P_COUNT; i++)
        if (same_name(name, strlen(name), table[i].name)) return i;
    return -1;
}

const ps_param_spec *ps_param_find(const char *name) {
    int id = find_id(name);
    return id < 0 ? NULL : &table[id];
}

void ps_request_params_default(ps_request_params *rp) {
    ps_params_default(&rp->core);
    rp->output = PS_OUTPUT_JSON;
    rp->include = 0;
}

/* ---- parsing text values ------------------------------------------------ */

/* Decimal notation and nothing else: [-]digits[.digits][e[+-]digits],
 * where either side of the point may be empty (".5", "5."), not both.  No
 * hexadecimal ("0x10"), no blanks or '+' in front, no "inf" or "nan". */
static int is_decimal(const char *p) {
    size_t whole = 0, fraction = 0, exponent = 0;
    if (*p == '-') p++;
    for (; isdigit((unsigned char)*p); p++) whole++;
    if (*p == '.')
        for (p++; isdigit((unsigned char)*p); p++) fraction++;
    if (!whole && !fraction) return 0;
    if (*p == 'e' || *p == 'E') {
        p++;
        if (*p == '+' || *p == '-') p++;
        for (; isdigit((unsigned char)*p); p++) exponent++;
        if (!exponent) return 0;
    }
    return *p == 0;
}

/* An integer, also written as an integral number ("1e+05", "7.0": what a
 * JSON number turned into text may look like); "7.5" is not one. */
static int parse_int(const char *text, long *out) {
    char *end;
    if (!is_decimal(text)) return 0;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (*end == 0 && errno != ERANGE) {
        *out = v;
        return 1;
    }
    double d = strtod(text, &end);
    if (!(fabs(d) < 1e15) || d != floor(d)) return 0;
    *out = (long)d;
    return 1;
}

static int parse_double(const char *text, double *out) {
    char *end;
    if (!is_decimal(text)) return 0;
    errno = 0;
    double v = strtod(text, &end);
    if (errno == ERANGE || !isfinite(v)) return 0;
    *out = v;
    return 1;
}

static int parse_bool(const char *text, int *out) {
    static const char *const yes[] = {"true", "1", "yes"};
    static const char *const no[] = {"false", "0", "no"};
    for (int i = 0; i < 3; i++) {
        if (strcasecmp(text, yes[i]) == 0) return *out = 1, 1;
        if (strcasecmp(text, no[i]) == 0) return *out = 0, 1;
    }
    return 0;
}

/* Index of `text` (first len bytes) in choices, '-' == '_'; -1 if absent. */
static int choice_index(const char *const *choices, const char *text, size_t len) {
    for (int i = 0; choices[i]; i++)
        if (same_name(text, len, choices[i])) return i;
    return -1;
}

/* Past the ' ' at p: spaces only (a value's text is one line), not the
 * tabs and newlines ps_skip_space of the decoders also passes. */
static const char *skip_spaces(const char *p) {
    while (*p == ' ') p++;
    return p;
}

/* "a,b" -> bit i set for choice i; spaces around items are ignored and an
 * empty text is the empty list. */
static int parse_list(const char *const *choices, const char *text, unsigned *bits) {
    *bits = 0;
    const char *p = skip_spaces(text);
    if (*p == 0) return 1;
    for (;;) {
        p = skip_spaces(p);
        size_t len = strcspn(p, ", ");
        int i = choice_index(choices, p, len);
        if (i < 0) return 0;
        *bits |= 1u << i;
        p = skip_spaces(p + len);
        if (*p == 0) return 1;
        if (*p != ',') return 0;
        p++;
    }
}

void ps_params_join_choices(const char *const *choices, const char *sep, char *buf,
                            size_t size) {
    size_t used = 0;
    buf[0] = 0;
    for (int i = 0; choices && choices[i]; i++) {
        const char *before = i ? sep : "";
        size_t before_len = strlen(before), len = strlen(choices[i]);
        if (used + before_len + len >= size) break;
        memcpy(buf + used, before, before_len);
        memcpy(buf + used + before_len, choices[i], len + 1);
        used += before_len + len;
    }
}

static int bad_value(const ps_param_spec *s, const char *value, ps_api_error *err) {
    char choices[128];
    switch (s->type) {
    case PS_PT_INT:
        return ps_api_fail(err, 422, "parameter '%s' must be an integer in [%g, %g], got '%.100s'",
                           s->name, s->min, s->max, value);
    case PS_PT_DOUBLE:
        return ps_api_fail(err, 422, "parameter '%s' must be a number in [%g, %g], got '%.100s'",
                           s->name, s->min, s->max, value);
    case PS_PT_BOOL:
        return ps_api_fail(err, 422,
                           "parameter '%s' must be true or false (or 1/0, yes/no), got '%.100s'",
                           s->name, value);
    case PS_PT_ENUM:
        ps_params_join_choices(s->choices, ", ", choices, sizeof choices);
        return ps_api_fail(err, 422, "parameter '%s' must be one of %s, got '%.100s'", s->name,
                           choices, value);
    case PS_PT_LIST:
        ps_params_join_choices(s->choices, ", ", choices, sizeof choices);
        return ps_api_fail(err, 422,
                           "parameter '%s' must be a comma-separated list of %s, got '%.100s'",
                           s->name, choices, value);
    }
    return ps_api_fail(err, 500, "parameter '%s' has an unknown type", s->name);
}

/* ---- storing parsed values ---------------------------------------------- */

/* Stores an INT, DOUBLE or BOOL value already checked against the range. */
static void store_number(ps_request_params *rp, param_id id, double v) {
    switch (id) {
    case P_K: rp->core.k = (int)v; break;
    case P_SAMPLES: rp->core.samples = (int)v; break;
    case P_THREADS: rp->core.threads = (int)v; break;
    case P_PERSISTENCE: rp->core.persistence = v; break;
    case P_NCUT_THRESHOLD: rp->core.ncut_threshold = v; break;
    case P_FEATURE_THRESHOLD: rp->core.feature_threshold = v; break;
    case P_MINIMA: rp->core.use_minima = v != 0; break;
    case P_F2: rp->core.use_f2 = v != 0; break;
    case P_SMOOTH_NORMALS: rp->core.smooth_normals = v != 0; break;
    default: break;
    }
}

static void store_choice(ps_request_params *rp, param_id id, int index, unsigned bits) {
    switch (id) {
    case P_METHOD: rp->core.method = (ps_method)index; break;
    case P_CENTRALITY: rp->core.centrality = (ps_centrality_mode)index; break;
    case P_OUTPUT: rp->output = (ps_output)index; break;
    case P_INCLUDE: rp->include = bits; break;
    default: break;
    }
}

/* Parses value as spec s wants; on success stores it and returns 0. */
static int parse_and_store(ps_request_params *rp, param_id id, const char *value) {
    const ps_param_spec *s = &table[id];
    long iv;
    double dv;
    int bv;
    unsigned bits;
    switch (s->type) {
    case PS_PT_INT:
        if (!parse_int(value, &iv) || iv < s->min || iv > s->max) return -1;
        store_number(rp, id, (double)iv);
        return 0;
    case PS_PT_DOUBLE:
        if (!parse_double(value, &dv) || !(dv >= s->min && dv <= s->max)) return -1;
        store_number(rp, id, dv);
        return 0;
    case PS_PT_BOOL:
        if (!parse_bool(value, &bv)) return -1;
        store_number(rp, id, bv);
        return 0;
    case PS_PT_ENUM:
        bv = choice_index(s->choices, value, strlen(value));
        if (bv < 0) return -1;
        store_choice(rp, id, bv, 0);
        return 0;
    case PS_PT_LIST:
        if (!parse_list(s->choices, value, &bits)) return -1;
        store_choice(rp, id, 0, bits);
        return 0;
    }
    return -1;
}

int ps_request_param_set(ps_request_params *rp, const char *name, const char *value,
                         ps_api_error *err) {
    int id = find_id(name);
    if (id < 0) return ps_api_fail(err, 400, "unknown parameter '%.100s'", name ? name : "");
    if (!value) return ps_api_fail(err, 422, "parameter '%s' needs a value", table[id].name);
    if (parse_and_store(rp, (param_id)id, value) != 0) return bad_value(&table[id], value, err);
    return 0;
}
