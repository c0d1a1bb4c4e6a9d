/* decode_json.c: the JSON request body: {"points": [[x,y,z], ...]} or
 * {"points": [x,y,z, ...], "dimension": 3}, optional "normals" of the same
 * shape and "params": {name: number | string | boolean | [string, ...]}.
 * Any other top-level key is a 400 naming it. */
#include "decode.h"

#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "decode_scan.h"
#include "decode_util.h"

typedef struct json_body {
    const cJSON *points, *normals, *dimension, *params;
} json_body;

/* One of the body's known keys, or 400 naming an unknown or repeated one. */
static int sort_keys(const cJSON *root, json_body *b, ps_api_error *err) {
    memset(b, 0, sizeof *b);
    for (const cJSON *c = root->child; c; c = c->next) {
        const cJSON **slot = !strcmp(c->string, "points")      ? &b->points
                             : !strcmp(c->string, "normals")   ? &b->normals
                             : !strcmp(c->string, "dimension") ? &b->dimension
                             : !strcmp(c->string, "params")    ? &b->params
                                                               : NULL;
        char shown[41];
        ps_preview(c->string, strlen(c->string), shown, sizeof shown);
        if (!slot)
            return ps_api_fail(err, 400, "unknown key \"%s\" (expected points, normals, "
                               "dimension, params)", shown);
        if (*slot) return ps_api_fail(err, 400, "key \"%s\" appears twice", shown);
        *slot = c;
    }
    if (!b->points) return ps_api_fail(err, 400, "missing \"points\"");
    return 0;
}

static int read_dimension(const cJSON *item, const ps_decode_limits *lim, int *dim,
                          ps_api_error *err) {
    *dim = 0;
    if (!item) return 0;
    double d = item->valuedouble;
    if (!cJSON_IsNumber(item) || d != floor(d) || fabs(d) > 1e9)
        return ps_api_fail(err, 400, "\"dimension\" must be a small integer");
    if (ps_decode_check_dim((long long)d, lim, err)) return -1;
    *dim = (int)d;
    return 0;
}

static int read_rows(const cJSON *arr, const char *what, int dim, double *dst,
                     ps_api_error *err) {
    size_t i = 0;
    for (const cJSON *row = arr->child; row; row = row->next, i++) {
        if (!cJSON_IsArray(row) || cJSON_GetArraySize(row) != dim)
            return ps_api_fail(err, 400, "%s[%zu] must be an array of %d numbers", what, i, dim);
        int k = 0;
        for (const cJSON *v = row->child; v; v = v->next, k++) {
            if (!cJSON_IsNumber(v))
                return ps_api_fail(err, 400, "%s[%zu][%d] is not a number", what, i, k);
            dst[i * (size_t)dim + (size_t)k] = v->valuedouble;
        }
    }
    return 0;
}

static int read_flat(const cJSON *arr, const char *what, double *dst, ps_api_error *err) {
    size_t i = 0;
    for (const cJSON *v = arr->child; v; v = v->next, i++) {
        if (!cJSON_IsNumber(v)) return ps_api_fail(err, 400, "%s[%zu] is not a number", what, i);
        dst[i] = v->valuedouble;
    }
    return 0;
}

/* Reads "points" or "normals" (nested rows, or flat with *dim given) into a
 * new #n by *dim array; *dim is set from the rows when 0. */
static int read_matrix(const cJSON *arr, const char *what, const ps_decode_limits *lim,
                       size_t *n, int *dim, double **data, ps_api_error *err) {
    if (!cJSON_IsArray(arr)) return ps_api_fail(err, 400, "\"%s\" must be an array", what);
    size_t size = (size_t)cJSON_GetArraySize(arr);
    int nested = size > 0 && cJSON_IsArray(arr->child);
    if (nested && *dim && cJSON_GetArraySize(arr->child) != *dim)
        return ps_api_fail(err, 422, "%s[0] has %d values, expected %d", what,
                           cJSON_GetArraySize(arr->child), *dim);
    if (nested && !*dim && ps_decode_check_dim(cJSON_GetArraySize(arr->child), lim, err))
        return -1;
    if (nested && !*dim) *dim = cJSON_GetArraySize(arr->child);
    if (!nested && size > 0 && !*dim)
        return ps_api_fail(err, 400, "flat \"%s\" needs \"dimension\"", what);
    if (!nested && *dim && size % (size_t)*dim)
        return ps_api_fail(err, 422, "\"%s\" has %zu numbers, not a multiple of dimension %d",
                           what, size, *dim);
    *n = nested || !*dim ? size : size / (size_t)*dim;
    if (ps_decode_check_points(*n, lim, err)) return -1;
    *data = malloc(*n * (size_t)(*dim > 0 ? *dim : 1) * sizeof **data + 1);
    if (!*data) return ps_api_fail(err, 500, "out of memory");
    return nested ? read_rows(arr, what, *dim, *data, err) : read_flat(arr, what, *data, err);
}

static char *number_text(double v) {
    char buf[40];
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, sizeof buf, "%.*g", prec, v);
        if (strtod(buf, NULL) == v) break;
    }
    return strdup(buf);
}

/* An array of strings joined with ','; NULL if an item is not a string. */
static char *joined_strings(const cJSON *arr) {
    size_t total = 1;
    for (const cJSON *c = arr->child; c; c = c->next) {
        if (!cJSON_IsString(c)) return NULL;
        total += strlen(c->valuestring) + 1;
    }
    char *out = malloc(total);
    if (!out) return NULL;
    out[0] = 0;
    for (const cJSON *c = arr->child; c; c = c->next) {
        if (c != arr->child) strcat(out, ",");
        strcat(out, c->valuestring);
    }
    return out;
}

static char *param_text(const cJSON *v) {
    if (cJSON_IsNumber(v)) return number_text(v->valuedouble);
    if (cJSON_IsString(v)) return strdup(v->valuestring);
    if (cJSON_IsBool(v)) return strdup(cJSON_IsTrue(v) ? "true" : "false");
    if (cJSON_IsArray(v)) return joined_strings(v);
    return NULL;
}

static int read_params(const cJSON *obj, ps_pointset *out, ps_api_error *err) {
    if (!obj) return 0;
    if (!cJSON_IsObject(obj)) return ps_api_fail(err, 400, "\"params\" must be an object");
    size_t count = (size_t)cJSON_GetArraySize(obj);
    out->params = calloc(count + 1, sizeof *out->params);
    if (!out->params) return ps_api_fail(err, 500, "out of memory");
    for (const cJSON *c = obj->child; c; c = c->next) {
        ps_param_pair *p = &out->params[out->n_params];
        char shown[41];
        ps_preview(c->string, strlen(c->string), shown, sizeof shown);
        p->name = strdup(c->string);
        p->value = param_text(c);
        out->n_params++;
        if (!p->name || !p->value)
            return ps_api_fail(err, 400, "params.%s must be a number, string, boolean or "
                               "array of strings", shown);
    }
    return 0;
}

static int read_body(const cJSON *root, const ps_decode_limits *lim, ps_pointset *out,
                     ps_api_error *err) {
    json_body b;
    size_t n_normals = 0;
    if (!cJSON_IsObject(root)) return ps_api_fail(err, 400, "the JSON body must be an object");
    if (sort_keys(root, &b, err) || read_dimension(b.dimension, lim, &out->dim, err) ||
        read_matrix(b.points, "points", lim, &out->n, &out->dim, &out->points, err))
        return -1;
    if (b.normals) {
        int dim = out->dim;
        if (read_matrix(b.normals, "normals", lim, &n_normals, &dim, &out->normals, err))
            return -1;
        if (n_normals != out->n)
            return ps_api_fail(err, 422, "%zu normals for %zu points", n_normals, out->n);
    }
    return read_params(b.params, out, err);
}

int ps_decode_json(const char *bytes, size_t len, const ps_decode_limits *lim,
                   ps_pointset *out, ps_api_error *err) {
    const char *stop = NULL;
    memset(out, 0, sizeof *out);
    bytes = ps_skip_bom(bytes, &len);
    cJSON *root = cJSON_ParseWithLengthOpts(bytes, len, &stop, 0);
    size_t at = stop && stop >= bytes ? (size_t)(stop - bytes) : 0;
    if (!root) return ps_api_fail(err, 400, "malformed JSON at byte offset %zu", at);
    const char *rest = ps_skip_space(stop, bytes + len);
    if (rest != bytes + len) {
        cJSON_Delete(root);
        return ps_api_fail(err, 400, "unexpected data after the JSON value at byte offset %zu",
                           (size_t)(rest - bytes));
    }
    int rc = read_body(root, lim, out, err);
    cJSON_Delete(root);
    if (rc) {
        ps_pointset_free(out);
        return -1;
    }
    return ps_decode_finish(out, lim, "point", err);
}
