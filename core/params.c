/* params.c: defaults, range checks and names of the core's parameters and
 * status codes (pointseg.h).  The api's parameter table mirrors these. */
#include "pointseg.h"

#include <stdarg.h>
#include <stdio.h>

ps_status ps_fail(ps_error *err, ps_status status, const char *fmt, ...) {
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
        err->status = status;
    }
    return status;
}

const char *ps_status_name(ps_status status) {
    switch (status) {
    case PS_OK: return "ok";
    case PS_ERR_INVALID: return "invalid input";
    case PS_ERR_NOMEM: return "out of memory";
    case PS_ERR_CANCELLED: return "cancelled";
    case PS_ERR_INTERNAL: return "internal error";
    }
    return "unknown status";
}

void ps_params_default(ps_params *p) {
    *p = (ps_params){
        .method = PS_METHOD_AUTO,
        .k = 7,
        .centrality = PS_CENTRALITY_AUTO,
        .samples = 0,
        .persistence = 0.1,
        .ncut_threshold = 0,
        .feature_threshold = 0.1,
        .use_minima = 1,
        .use_f2 = 0,
        .smooth_normals = 1,
        .threads = 0,
    };
}

ps_status ps_params_check(const ps_params *p, ps_error *err) {
    if (p->method < PS_METHOD_AUTO || p->method > PS_METHOD_PAPER)
        return ps_fail(err, PS_ERR_INVALID, "unknown method %d", (int)p->method);
    if (p->k < 1 || p->k > PS_MAX_K)
        return ps_fail(err, PS_ERR_INVALID, "k must be in [1, %d], got %d", PS_MAX_K, p->k);
    if (p->centrality < PS_CENTRALITY_AUTO || p->centrality > PS_CENTRALITY_APPROX)
        return ps_fail(err, PS_ERR_INVALID, "unknown centrality mode %d", (int)p->centrality);
    if (p->samples < 0 || p->samples > 100000)
        return ps_fail(err, PS_ERR_INVALID, "samples must be in [0, 100000], got %d", p->samples);
    if (!(p->persistence >= 0 && p->persistence <= 1))
        return ps_fail(err, PS_ERR_INVALID, "persistence must be in [0, 1], got %g",
                       p->persistence);
    if (!(p->ncut_threshold >= 0 && p->ncut_threshold <= 2))
        return ps_fail(err, PS_ERR_INVALID, "ncut_threshold must be in [0, 2], got %g",
                       p->ncut_threshold);
    if (!(p->feature_threshold >= 0 && p->feature_threshold <= 1))
        return ps_fail(err, PS_ERR_INVALID, "feature_threshold must be in [0, 1], got %g",
                       p->feature_threshold);
    if (p->threads < 0 || p->threads > 256)
        return ps_fail(err, PS_ERR_INVALID, "threads must be in [0, 256], got %d", p->threads);
    return PS_OK;
}

const char *ps_centrality_name(ps_centrality_mode mode) {
    switch (mode) {
    case PS_CENTRALITY_AUTO: return "auto";
    case PS_CENTRALITY_EXACT: return "exact";
    case PS_CENTRALITY_APPROX: return "approx";
    }
    return "unknown";
}

const char *ps_method_name(ps_method method) {
    return method == PS_METHOD_PAPER ? "paper" : method == PS_METHOD_AUTO ? "auto" : "unknown";
}

const char *ps_phase_name(ps_phase phase) {
    static const char *const names[PS_PHASE_COUNT] = {"knn", "centrality", "supernodes",
                                                      "hierarchy", "refine"};
    return phase >= 0 && phase < PS_PHASE_COUNT ? names[phase] : "unknown";
}
