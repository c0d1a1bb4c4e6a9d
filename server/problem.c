/* problem.c: RFC 9457 problem+json documents. */
#include "problem.h"

#include <cJSON.h>
#include <string.h>

const char *ps_problem_title(int status) {
    switch (status) {
    case 400: return "Bad Request";
    case 401: return "Unauthorized";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 409: return "Conflict";
    case 413: return "Content Too Large";
    case 415: return "Unsupported Media Type";
    case 422: return "Unprocessable Content";
    case 503: return "Service Unavailable";
    default: return status >= 500 ? "Internal Server Error" : "Error";
    }
}

char *ps_problem_json(int status, const char *detail, size_t *len) {
    cJSON *doc = cJSON_CreateObject();
    if (!doc) return NULL;
    cJSON_AddStringToObject(doc, "type", "about:blank");
    cJSON_AddStringToObject(doc, "title", ps_problem_title(status));
    cJSON_AddNumberToObject(doc, "status", status);
    if (detail && *detail) cJSON_AddStringToObject(doc, "detail", detail);
    char *text = cJSON_PrintUnformatted(doc);
    cJSON_Delete(doc);
    if (text) *len = strlen(text);
    return text;
}
