/* openapi.c: builds the OpenAPI 3.1 document of the daemon from the parameter table. */
#include "openapi.h"

#include "params_table.h"
#include "pointseg.h"

#include <cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const problem_ref = "#/components/schemas/Problem";

static cJSON *ref(const char *target) {
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "$ref", target);
    return o;
}

static cJSON *choices_array(const char *const *choices) {
    cJSON *a = cJSON_CreateArray();
    for (; choices && *choices; choices++) cJSON_AddItemToArray(a, cJSON_CreateString(*choices));
    return a;
}

/* The default of parameter p as its schema's type has it (7, not "7"), as
 * strict code generators read it. */
static void add_default(cJSON *schema, const ps_param_spec *p) {
    if (p->type == PS_PT_INT || p->type == PS_PT_DOUBLE)
        cJSON_AddNumberToObject(schema, "default", strtod(p->default_text, NULL));
    else if (p->type == PS_PT_BOOL) cJSON_AddBoolToObject(schema, "default", !strcmp(p->default_text, "true"));
    else cJSON_AddStringToObject(schema, "default", p->default_text);
}

/* The schema of parameter p; description may be NULL. */
static cJSON *param_schema(const ps_param_spec *p, const char *description) {
    static const char *const types[] = {"integer", "number", "boolean", "string", "string"};
    cJSON *s = cJSON_CreateObject();
    cJSON_AddStringToObject(s, "type", types[p->type]);
    if (p->type == PS_PT_INT || p->type == PS_PT_DOUBLE) {
        cJSON_AddNumberToObject(s, "minimum", p->min);
        cJSON_AddNumberToObject(s, "maximum", p->max);
    }
    if (p->type == PS_PT_ENUM) cJSON_AddItemToObject(s, "enum", choices_array(p->choices));
    if (p->type == PS_PT_LIST) {
        char alternatives[200], pattern[512];
        ps_params_join_choices(p->choices, "|", alternatives, sizeof alternatives);
        snprintf(pattern, sizeof pattern, "^$|^(%s)(,(%s))*$", alternatives, alternatives);
        cJSON_AddStringToObject(s, "pattern", pattern);
    }
    if (description) cJSON_AddStringToObject(s, "description", description);
    add_default(s, p);
    return s;
}

static cJSON *query_parameters(void) {
    size_t n;
    const ps_param_spec *table = ps_param_table(&n);
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; i < n; i++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "name", table[i].name);
        cJSON_AddStringToObject(p, "in", "query");
        cJSON_AddBoolToObject(p, "required", 0);
        cJSON_AddStringToObject(p, "description", table[i].help);
        cJSON_AddItemToObject(p, "schema", param_schema(&table[i], table[i].type == PS_PT_LIST
                                                                       ? "comma-separated list"
                                                                       : NULL));
        cJSON_AddItemToArray(a, p);
    }
    return a;
}

static cJSON *params_object_schema(void) {
    size_t n;
    const ps_param_spec *table = ps_param_table(&n);
    cJSON *s = cJSON_CreateObject(), *props = cJSON_CreateObject();
    cJSON_AddStringToObject(s, "type", "object");
    for (size_t i = 0; i < n; i++) {
        cJSON_AddItemToObject(props, table[i].name, param_schema(&table[i], table[i].help));
    }
    cJSON_AddItemToObject(s, "properties", props);
    cJSON_AddBoolToObject(s, "additionalProperties", 0);
    return s;
}

static cJSON *media(cJSON *schema) {
    cJSON *m = cJSON_CreateObject();
    cJSON_AddItemToObject(m, "schema", schema);
    return m;
}

static cJSON *binary_schema(void) {
    cJSON *s = cJSON_CreateObject();
    cJSON_AddStringToObject(s, "type", "string");
    cJSON_AddStringToObject(s, "contentMediaType", "application/octet-stream");
    return s;
}

static cJSON *request_body(void) {
    cJSON *b = cJSON_CreateObject(), *c = cJSON_CreateObject();
    cJSON_AddBoolToObject(b, "required", 1);
    cJSON_AddStringToObject(b, "description",
                            "the points: PLY (ascii or binary), OFF, OBJ or XYZ recognized from the "
                            "content (application/ply: PLY only; model/obj and chemical/x-xyz, the "
                            "types guessed from .obj and .xyz names, are read by content too), "
                            "a JSON document, or a form "
                            "with a `file` part; any of them may be sent with Content-Encoding: "
                            "gzip.  Bytes that are not what the type says are a 400");
    cJSON_AddItemToObject(c, "application/ply", media(binary_schema()));
    cJSON_AddItemToObject(c, "application/octet-stream", media(binary_schema()));
    cJSON_AddItemToObject(c, "text/plain", media(binary_schema()));
    cJSON_AddItemToObject(c, "model/obj", media(binary_schema()));
    cJSON_AddItemToObject(c, "chemical/x-xyz", media(binary_schema()));
    cJSON_AddItemToObject(c, "application/json", media(ref("#/components/schemas/PointsRequest")));
    cJSON *form = cJSON_CreateObject(), *props = params_object_schema();
    cJSON_AddItemToObject(cJSON_GetObjectItem(props, "properties"), "file", binary_schema());
    cJSON_AddItemToObject(props, "required", choices_array((const char *const[]){"file", NULL}));
    cJSON_AddItemToObject(form, "schema", props);
    cJSON_AddItemToObject(c, "multipart/form-data", form);
    cJSON_AddItemToObject(b, "content", c);
    return b;
}

static void add_problem(cJSON *responses, int status, const char *description) {
    char code[8];
    cJSON *r = cJSON_CreateObject(), *c = cJSON_CreateObject();
    snprintf(code, sizeof code, "%d", status);
    cJSON_AddStringToObject(r, "description", description);
    cJSON_AddItemToObject(c, "application/problem+json", media(ref(problem_ref)));
    cJSON_AddItemToObject(r, "content", c);
    if (cJSON_GetObjectItem(responses, code)) cJSON_ReplaceItemInObject(responses, code, r);
    else cJSON_AddItemToObject(responses, code, r);
}

/* An answer every route may give, unless the route describes its own. */
static void add_common_problem(cJSON *responses, int status, const char *description) {
    char code[8];
    snprintf(code, sizeof code, "%d", status);
    if (!cJSON_GetObjectItem(responses, code)) add_problem(responses, status, description);
}

static void add_response(cJSON *responses, const char *code, const char *description,
                         const char *media_type, cJSON *schema) {
    cJSON *r = cJSON_CreateObject();
    cJSON_AddStringToObject(r, "description", description);
    if (media_type) {
        cJSON *c = cJSON_CreateObject();
        cJSON_AddItemToObject(c, media_type, media(schema));
        cJSON_AddItemToObject(r, "content", c);
    }
    cJSON_AddItemToObject(responses, code, r);
}

static cJSON *operation(const char *summary, const char *id, cJSON *responses) {
    cJSON *op = cJSON_CreateObject();
    cJSON_AddStringToObject(op, "summary", summary);
    cJSON_AddStringToObject(op, "operationId", id);
    add_problem(responses, 401, "a bearer token is configured and missing or wrong");
    add_problem(responses, 405, "method not allowed (see the Allow header)");
    add_common_problem(responses, 400, "malformed request head: HTTP/1.1 without Host, conflicting "
                       "Content-Length headers, both Content-Length and Transfer-Encoding, an encoded NUL byte (%00) in the path, more than 64 "
                       "query parameters, a NUL byte in one");
    add_common_problem(responses, 414, "URL path longer than 255 bytes");
    add_common_problem(responses, 501, "a Transfer-Encoding other than chunked");
    add_common_problem(responses, 503, "over --max-connections: only /healthz, /readyz and /metrics "
                       "are served (see Retry-After)");
    cJSON_AddItemToObject(op, "responses", responses);
    return op;
}

#define SHARED_QUEUE_DOWN "the shared job queue (pointsegd --redis) is unreachable (see Retry-After)"
#define JOB_ROUTE_503 "over --max-connections, or " SHARED_QUEUE_DOWN

/* The 200 answer holding a segmentation, in the format output= asked for. */
static void add_segmentation(cJSON *responses, const char *description) {
    cJSON *c = cJSON_CreateObject(), *ok = cJSON_CreateObject();
    cJSON_AddStringToObject(ok, "description", description);
    cJSON_AddItemToObject(c, "application/json", media(ref("#/components/schemas/Segmentation")));
    cJSON_AddItemToObject(c, "application/ply", media(binary_schema()));
    cJSON_AddItemToObject(c, "text/plain", media(binary_schema()));
    cJSON_AddItemToObject(ok, "content", c);
    cJSON_AddItemToObject(responses, "200", ok);
}

static cJSON *segment_responses(int async) {
    cJSON *r = cJSON_CreateObject();
    if (async) {
        add_response(r, "202", "queued; Location names the job", "application/json",
                     ref("#/components/schemas/JobAccepted"));
    } else {
        add_segmentation(r, "the segmentation (output=json, labels or ply)");
    }
    add_problem(r, 400, "malformed body (bytes in no known format, not PLY for application/ply, "
                        "not JSON for application/json) or request head, unknown parameter, a "
                        "parameter given twice (query string, form fields and JSON params together "
                        "give each once), two multipart file parts, a NUL byte in a parameter");
    add_problem(r, 413, "body, inflated body, point count or the job's memory estimate over the limit");
    add_problem(r, 415, "a Content-Type or Content-Encoding the service does not take");
    add_problem(r, 422, "well-formed but unusable input, or a parameter out of range");
    add_problem(r, 503, async ? "queue full, shutting down, over --max-connections, or " SHARED_QUEUE_DOWN
                              : "queue full, shutting down, or over --max-connections (see Retry-After)");
    return r;
}

static cJSON *segment_op(const char *summary, const char *id, int async) {
    cJSON *op = operation(summary, id, segment_responses(async));
    cJSON_AddItemToObject(op, "parameters", query_parameters());
    cJSON_AddItemToObject(op, "requestBody", request_body());
    return op;
}

static cJSON *job_id_parameter(void) {
    cJSON *a = cJSON_CreateArray(), *p = cJSON_CreateObject(), *s = cJSON_CreateObject();
    cJSON_AddStringToObject(p, "name", "id");
    cJSON_AddStringToObject(p, "in", "path");
    cJSON_AddBoolToObject(p, "required", 1);
    cJSON_AddStringToObject(s, "type", "string");
    cJSON_AddItemToObject(p, "schema", s);
    cJSON_AddItemToArray(a, p);
    return a;
}

static cJSON *simple_get(const char *summary, const char *id, const char *media_type, cJSON *schema) {
    cJSON *r = cJSON_CreateObject(), *path = cJSON_CreateObject();
    add_response(r, "200", summary, media_type, schema);
    cJSON_AddItemToObject(path, "get", operation(summary, id, r));
    return path;
}

/* A probe's path: open without the token (no security, no 401). */
static cJSON *open_to_probes(cJSON *path) {
    cJSON *get = cJSON_GetObjectItem(path, "get");
    cJSON_DeleteItemFromObject(cJSON_GetObjectItem(get, "responses"), "401");
    cJSON_AddItemToObject(get, "security", cJSON_CreateArray());
    return path;
}

static cJSON *type_schema(const char *type) {
    cJSON *s = cJSON_CreateObject();
    cJSON_AddStringToObject(s, "type", type);
    return s;
}

static cJSON *job_path(void) {
    cJSON *path = cJSON_CreateObject(), *r = cJSON_CreateObject(), *d = cJSON_CreateObject();
    add_response(r, "200", "the job's status and progress", "application/json", ref("#/components/schemas/JobStatus"));
    add_problem(r, 404, "no such job (or it expired)");
    add_problem(r, 503, JOB_ROUTE_503);
    cJSON_AddItemToObject(path, "get", operation("status of a job", "getJob", r));
    add_response(d, "202", "cancellation requested; the job's status", "application/json", ref("#/components/schemas/JobStatus"));
    add_problem(d, 404, "no such job");
    add_problem(d, 503, JOB_ROUTE_503);
    cJSON_AddItemToObject(path, "delete", operation("cancel a job", "cancelJob", d));
    cJSON_AddItemToObject(path, "parameters", job_id_parameter());
    return path;
}

static cJSON *result_path(void) {
    cJSON *path = cJSON_CreateObject(), *r = cJSON_CreateObject();
    add_segmentation(r, "the segmentation, in the job's output format (json, labels or ply)");
    add_problem(r, 404, "no such job");
    add_problem(r, 409, "the job is not done (queued, running or cancelled)");
    add_problem(r, 422, "the job failed: its input was unusable");
    add_problem(r, 500, "the job failed: an internal error, or it lost its worker 3 times");
    add_problem(r, 503, JOB_ROUTE_503);
    cJSON_AddItemToObject(path, "get", operation("result of a finished job", "getJobResult", r));
    cJSON_AddItemToObject(path, "parameters", job_id_parameter());
    return path;
}

static cJSON *paths(void) {
    cJSON *p = cJSON_CreateObject(), *seg = cJSON_CreateObject(), *jobs = cJSON_CreateObject();
    cJSON_AddItemToObject(seg, "post", segment_op("segment a point set and wait for the result", "segment", 0));
    cJSON_AddItemToObject(p, "/segment", seg);
    cJSON_AddItemToObject(jobs, "post", segment_op("queue a segmentation job", "submitJob", 1));
    cJSON_AddItemToObject(p, "/jobs", jobs);
    cJSON_AddItemToObject(p, "/jobs/{id}", job_path());
    cJSON_AddItemToObject(p, "/jobs/{id}/result", result_path());
    cJSON_AddItemToObject(p, "/healthz", open_to_probes(simple_get("the daemon is alive", "healthz", "application/json",
                                                                   type_schema("object"))));
    cJSON *ready = simple_get("ready: the queue is not full and the shared job queue (--redis) answers",
                              "readyz", "application/json", type_schema("object"));
    add_problem(cJSON_GetObjectItem(cJSON_GetObjectItem(ready, "get"), "responses"), 503,
                "queue full, shutting down, or " SHARED_QUEUE_DOWN);
    cJSON_AddItemToObject(p, "/readyz", open_to_probes(ready));
    cJSON_AddItemToObject(p, "/metrics", simple_get("Prometheus metrics", "metrics", "text/plain", type_schema("string")));
    cJSON_AddItemToObject(p, "/openapi.json", simple_get("this document", "openapi", "application/json", type_schema("object")));
    cJSON_AddItemToObject(p, "/version", simple_get("versions", "version", "application/json", type_schema("object")));
    cJSON_AddItemToObject(p, "/", simple_get("the web viewer (static files)", "static", "text/html", type_schema("string")));
    return p;
}

static cJSON *object_schema(const char *const *names, const char *const *types, const char *const *required) {
    cJSON *s = type_schema("object"), *props = cJSON_CreateObject();
    for (; *names; names++, types++) cJSON_AddItemToObject(props, *names, type_schema(*types));
    cJSON_AddItemToObject(s, "properties", props);
    if (required) cJSON_AddItemToObject(s, "required", choices_array(required));
    return s;
}

static cJSON *components(void) {
    cJSON *c = cJSON_CreateObject(), *s = cJSON_CreateObject();
    cJSON_AddItemToObject(s, "Problem", object_schema(
        (const char *const[]){"type", "title", "status", "detail", NULL},
        (const char *const[]){"string", "string", "integer", "string"},
        (const char *const[]){"type", "title", "status", NULL}));
    cJSON_AddItemToObject(s, "JobAccepted", object_schema(
        (const char *const[]){"id", "status", NULL}, (const char *const[]){"string", "string"},
        (const char *const[]){"id", "status", NULL}));
    cJSON *status = object_schema(
        (const char *const[]){"id", "status", "progress", "points", "created", "started", "finished", "error", NULL},
        (const char *const[]){"string", "string", "object", "integer", "string", "string", "string", "object"},
        (const char *const[]){"id", "status", NULL});
    cJSON_AddItemToObject(cJSON_GetObjectItem(cJSON_GetObjectItem(status, "properties"), "status"), "enum",
                          choices_array((const char *const[]){"queued", "running", "done", "failed", "cancelled", NULL}));
    cJSON_AddItemToObject(s, "JobStatus", status);
    cJSON *points = object_schema((const char *const[]){"points", "dimension", "params", NULL},
                                  (const char *const[]){"array", "integer", "object"},
                                  (const char *const[]){"points", NULL});
    cJSON_ReplaceItemInObject(cJSON_GetObjectItem(points, "properties"), "params", params_object_schema());
    cJSON_AddItemToObject(s, "PointsRequest", points);
    cJSON *seg = type_schema("object");
    cJSON_AddStringToObject(seg, "description", "the document of `pointseg --output json` (see the README); "
                            "`warnings` lists what the reader tolerated in the input");
    cJSON_AddItemToObject(s, "Segmentation", seg);
    cJSON_AddItemToObject(c, "schemas", s);
    cJSON *sec = cJSON_CreateObject(), *bearer = type_schema("http");
    cJSON_AddStringToObject(bearer, "scheme", "bearer");
    cJSON_AddItemToObject(sec, "bearer", bearer);
    cJSON_AddItemToObject(c, "securitySchemes", sec);
    return c;
}

char *ps_openapi_json(size_t *len) {
    cJSON *doc = cJSON_CreateObject(), *info = cJSON_CreateObject();
    cJSON_AddStringToObject(doc, "openapi", "3.1.0");
    cJSON_AddStringToObject(info, "title", "pointsegd");
    cJSON_AddStringToObject(info, "version", PS_VERSION);
    cJSON_AddStringToObject(info, "description", "Segments point-sampled surfaces into parts "
                            "(Yamazaki et al., Segmenting Point Sets). Errors are RFC 9457 problem+json, "
                            "but for libmicrohttpd's own HTML answers to a request it cannot parse "
                            "(400, 413, 414, 431, 505).");
    cJSON *license = cJSON_AddObjectToObject(info, "license");
    cJSON_AddStringToObject(license, "name", "MIT");
    cJSON_AddStringToObject(license, "identifier", "MIT");
    cJSON_AddItemToObject(doc, "info", info);
    cJSON *servers = cJSON_AddArrayToObject(doc, "servers"), *here = cJSON_CreateObject();
    cJSON_AddStringToObject(here, "url", "/");
    cJSON_AddStringToObject(here, "description", "the pointsegd that serves this document");
    cJSON_AddItemToArray(servers, here);
    cJSON_AddItemToObject(doc, "paths", paths());
    cJSON_AddItemToObject(doc, "components", components());
    cJSON *security = cJSON_CreateArray(), *req = cJSON_CreateObject();
    cJSON_AddItemToObject(req, "bearer", cJSON_CreateArray());
    cJSON_AddItemToArray(security, req);
    cJSON_AddItemToArray(security, cJSON_CreateObject());
    cJSON_AddItemToObject(doc, "security", security);
    char *text = cJSON_PrintUnformatted(doc);
    cJSON_Delete(doc);
    if (text) *len = strlen(text);
    return text;
}
