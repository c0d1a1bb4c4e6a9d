/*
 * params_table.h: the one table of request parameters.  The CLI's flags, the
 * daemon's query string and JSON "params", and the OpenAPI document all read
 * it, so a parameter is added in one place.  Core parameters (ps_params) and
 * request options (output format, extra arrays) live side by side.
 */
#ifndef PS_PARAMS_TABLE_H
#define PS_PARAMS_TABLE_H

#include "api_error.h"
#include "pointseg.h"

typedef enum ps_param_type { PS_PT_INT, PS_PT_DOUBLE, PS_PT_BOOL, PS_PT_ENUM, PS_PT_LIST } ps_param_type;

typedef struct ps_param_spec {
    const char *name;            /* "k", "centrality", ... */
    ps_param_type type;
    const char *default_text;    /* as shown in help and OpenAPI */
    double min, max;             /* numeric range (inclusive) */
    const char *const *choices;  /* ENUM/LIST: NULL-terminated */
    const char *help;            /* one line */
} ps_param_spec;

enum { PS_INCLUDE_CENTRALITY = 1, PS_INCLUDE_POINT_SUPERNODE = 2 };
typedef enum ps_output { PS_OUTPUT_JSON = 0, PS_OUTPUT_LABELS, PS_OUTPUT_PLY } ps_output;

/* A request's parameters: the core's, plus what to send back. */
typedef struct ps_request_params {
    ps_params core;
    ps_output output;
    unsigned include;    /* PS_INCLUDE_* bits */
} ps_request_params;

const ps_param_spec *ps_param_table(size_t *count);
const ps_param_spec *ps_param_find(const char *name);
void ps_request_params_default(ps_request_params *rp);

/* Joins the NULL-terminated choices (may be NULL: none) with sep between
 * them into buf (#size bytes, size >= 1): "auto, exact" or "auto|exact".
 * Stops before a choice that would not fit with its NUL, so the text never
 * ends inside a choice.  buf is always NUL-terminated. */
void ps_params_join_choices(const char *const *choices, const char *sep, char *buf,
                            size_t size);

/* Sets one parameter from text.  Unknown name: 400 naming it; bad value or
 * out of range: 422 naming the parameter and its range/choices. */
int ps_request_param_set(ps_request_params *rp, const char *name, const char *value,
                         ps_api_error *err);

#endif
