/*
 * encode.c: ps_encode, the one place that maps a request's output format to
 * its encoder and media type (encode.h), for the daemon and the CLI alike.
 */
#include "encode.h"

const char *ps_encode_media_type(ps_output output) {
    switch (output) {
    case PS_OUTPUT_PLY: return "application/ply";
    case PS_OUTPUT_LABELS: return "text/plain; charset=utf-8";
    case PS_OUTPUT_JSON: break;
    }
    return "application/json";
}

char *ps_encode(const ps_pointset *in, const ps_result *r, const ps_request_params *rp,
                size_t *len, const char **media_type) {
    if (media_type) *media_type = ps_encode_media_type(rp->output);
    switch (rp->output) {
    case PS_OUTPUT_PLY: return ps_encode_ply(in, r, len);
    case PS_OUTPUT_LABELS: return ps_encode_labels(r, len);
    case PS_OUTPUT_JSON: break;
    }
    return ps_encode_json(in, r, rp->include, len);
}
