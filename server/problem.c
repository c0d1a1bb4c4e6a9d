/* problem.c: RFC 9457 problem+json documents; the detail, which may echo
 * request bytes, is made valid UTF-8 first. */
#include "problem.h"

#include <cJSON.h>
#include <stdlib.h>
#include <string.h>

const char *ps_problem_title(int status) {
    switch (status) {
    case 400: return "Bad Request";
    case 401: return "Unauthorized";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 409: return "Conflict";
    case 413: return "Content Too Large";
    case 414: return "URI Too Long";
    case 415: return "Unsupported Media Type";
    case 422: return "Unprocessable Content";
    case 501: return "Not Implemented";
    case 503: return "Service Unavailable";
    default: return status >= 500 ? "Internal Server Error" : "Error";
    }
}

/* Length of the valid UTF-8 sequence at p (RFC 3629: no overlong forms,
 * no surrogates, nothing over U+10FFFF), or 0. */
static size_t utf8_sequence(const unsigned char *p) {
    size_t n;
    unsigned char lo = 0x80, hi = 0xBF;
    if (p[0] < 0x80) return 1;
    if (p[0] >= 0xC2 && p[0] <= 0xDF) n = 2;
    else if (p[0] >= 0xE0 && p[0] <= 0xEF) n = 3;
    else if (p[0] >= 0xF0 && p[0] <= 0xF4) n = 4;
    else return 0;
    if (p[0] == 0xE0) lo = 0xA0;
    if (p[0] == 0xED) hi = 0x9F;
    if (p[0] == 0xF0) lo = 0x90;
    if (p[0] == 0xF4) hi = 0x8F;
    if (p[1] < lo || p[1] > hi) return 0;
    for (size_t i = 2; i < n; i++)
        if ((p[i] & 0xC0) != 0x80) return 0;
    return n;
}

char *ps_problem_utf8(const char *text) {
    size_t len = strlen(text);
    char *out = malloc(3 * len + 1), *o = out;
    if (!out) return NULL;
    for (const unsigned char *p = (const unsigned char *)text; *p;) {
        size_t n = utf8_sequence(p);
        if (n) {
            memcpy(o, p, n);
            o += n;
            p += n;
        } else {
            memcpy(o, "\xEF\xBF\xBD", 3);
            o += 3;
            p++;
        }
    }
    *o = 0;
    return out;
}

char *ps_problem_json(int status, const char *detail, size_t *len) {
    cJSON *doc = cJSON_CreateObject();
    char *clean = detail ? ps_problem_utf8(detail) : NULL;
    if (!doc || (detail && !clean)) {
        cJSON_Delete(doc);
        free(clean);
        return NULL;
    }
    cJSON_AddStringToObject(doc, "type", "about:blank");
    cJSON_AddStringToObject(doc, "title", ps_problem_title(status));
    cJSON_AddNumberToObject(doc, "status", status);
    if (clean && *clean) cJSON_AddStringToObject(doc, "detail", clean);
    free(clean);
    char *text = cJSON_PrintUnformatted(doc);
    cJSON_Delete(doc);
    if (text) *len = strlen(text);
    return text;
}
