/* intake.c: request bytes and text parameters -> point set and parameters. */
#include "intake.h"

#include "decode.h"
#include "pointseg.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Whether text p begins with media type name, ended by its end or one of
 * the characters of ends. */
static int names_type(const char *p, const char *name, const char *ends) {
    size_t n = strlen(name);
    return !strncasecmp(p, name, n) && (p[n] == 0 || strchr(ends, p[n]));
}

/* Whether header value ct (leading spaces skipped) names media type name. */
static int media_is(const char *ct, const char *name) {
    while (*ct == ' ') ct++;
    return names_type(ct, name, "; ");
}

ps_media ps_intake_media(const char *ct) {
    if (!ct || !*ct) return PS_MEDIA_POINTS;
    if (media_is(ct, "application/json")) return PS_MEDIA_JSON;
    if (media_is(ct, "multipart/form-data")) return PS_MEDIA_MULTIPART;
    if (media_is(ct, "application/ply")) return PS_MEDIA_PLY;
    if (media_is(ct, "application/octet-stream") || media_is(ct, "text/plain") ||
        media_is(ct, "model/obj") || media_is(ct, "chemical/x-xyz"))
        return PS_MEDIA_POINTS;
    return PS_MEDIA_UNSUPPORTED;
}

int ps_intake_is_form(const char *ct) {
    return ct && media_is(ct, "application/x-www-form-urlencoded");
}

int ps_intake_decode(const char *bytes, size_t len, ps_media media, size_t max_points,
                     ps_pointset *out, ps_api_error *err) {
    ps_decode_limits lim = {max_points, PS_MAX_DIM};
    memset(out, 0, sizeof *out);
    if (len == 0) return ps_api_fail(err, 400, "the request body is empty");
    if (media == PS_MEDIA_JSON) return ps_decode_json(bytes, len, &lim, out, err);
    if (media == PS_MEDIA_PLY && ps_detect_format(bytes, len) != PS_FORMAT_PLY)
        return ps_api_fail(err, 400, "not a PLY file: an application/ply body begins with the line \"ply\"");
    return ps_decode(bytes, len, &lim, out, err);
}

/* The q parameter of the Accept entry [entry, end); 1 when it has none. */
static double entry_quality(const char *entry, const char *end) {
    for (const char *p = entry; (p = memchr(p, ';', (size_t)(end - p)));) {
        p++;
        p += strspn(p, " \t");
        if ((*p == 'q' || *p == 'Q') && p[1] == '=') return strtod(p + 2, NULL);
    }
    return 1.0;
}

/* The quality the Accept header gives media type name by an entry naming
 * it (RFC 9110 12.5.1), or -1 when no entry does. */
static double accept_quality(const char *accept, const char *name) {
    for (const char *p = accept;; p++) {
        p += strspn(p, " \t");
        const char *end = p + strcspn(p, ",");
        if (names_type(p, name, " \t;,")) return entry_quality(p, end);
        if (!*end) return -1;
        p = end;
    }
}

/* PLY when Accept names application/ply with a quality over 0 and not
 * below JSON's. */
static int wants_ply(const char *accept) {
    double ply = accept ? accept_quality(accept, "application/ply") : -1;
    return ply > 0 && ply >= accept_quality(accept, "application/json");
}

/* The k-th text parameter of a request: the body's, then the extra pairs. */
static ps_text_param param_at(const ps_pointset *body, const ps_text_param *extra, size_t k) {
    size_t n_body = body ? body->n_params : 0;
    if (k < n_body) return (ps_text_param){body->params[k].name, body->params[k].value};
    return (ps_text_param){extra[k - n_body].name, extra[k - n_body].value ? extra[k - n_body].value : ""};
}

/* Whether a text parameter before the k-th names the parameter spec. */
static int given_before(const ps_pointset *body, const ps_text_param *extra, size_t k,
                        const ps_param_spec *spec) {
    for (size_t j = 0; spec && j < k; j++)
        if (ps_param_find(param_at(body, extra, j).name) == spec) return 1;
    return 0;
}

int ps_intake_params(const ps_pointset *body, const char *accept, const ps_text_param *extra,
                     size_t n_extra, ps_request_params *rp, ps_api_error *err) {
    size_t n = (body ? body->n_params : 0) + n_extra;
    ps_request_params_default(rp);
    if (wants_ply(accept)) rp->output = PS_OUTPUT_PLY;
    for (size_t k = 0; k < n; k++) {
        ps_text_param p = param_at(body, extra, k);
        const ps_param_spec *spec = ps_param_find(p.name);
        if (given_before(body, extra, k, spec))
            return ps_api_fail(err, 400, "parameter '%s' is given twice", spec->name);
        if (ps_request_param_set(rp, p.name, p.value, err)) return -1;
    }
    return 0;
}

int ps_intake_check_memory(const ps_pointset *ps, const ps_request_params *rp, size_t max_memory,
                           ps_api_error *err) {
    size_t coordinates = ps->n * (size_t)ps->dim * sizeof(double);
    ps_input in = ps_pointset_input(ps);
    size_t need = ps_segment_memory_estimate(&in, &rp->core) + coordinates +
                  (ps->normals ? coordinates : 0) + ps->n_faces * 3 * sizeof *ps->faces;
    if (need <= max_memory) return 0;
    return ps_api_fail(err, 413,
                       "%zu points need about %zu MiB by the service's estimate, over the limit of "
                       "%zu MiB (--max-memory)",
                       ps->n, need >> 20, max_memory >> 20);
}
