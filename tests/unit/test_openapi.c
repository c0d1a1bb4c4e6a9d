/* test_openapi.c: the OpenAPI document (api/openapi.c) as strict tools read
 * it: no object repeats a key (JSON allows parsers to refuse that, and
 * YAML-based linters do), it names a server and a licence, the probes need
 * no token, defaults have their parameter's type, every parameter schema
 * has one description, and a job's result is described in every output
 * format.  The full lint is
 * tests/integration/openapi_lint.sh (Redocly). */
#include "openapi.h"
#include "params_table.h"
#include "testlib.h"

#include <cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static cJSON *document(void) {
    size_t len = 0;
    char *text = ps_openapi_json(&len);
    cJSON *doc = text && len == strlen(text) ? cJSON_ParseWithLength(text, len) : NULL;
    free(text);
    return doc;
}

/* The first key that an object under node (node included) repeats, with
 * where; cJSON keeps repeated keys as separate children. */
static const char *repeated_key(const cJSON *node, const char **where) {
    for (const cJSON *c = node ? node->child : NULL; c; c = c->next) {
        if (cJSON_IsObject(node))
            for (const cJSON *d = c->next; d; d = d->next)
                if (!strcmp(c->string, d->string)) return *where = node->string, c->string;
        const char *inner = repeated_key(c, where);
        if (inner) return inner;
    }
    return NULL;
}

static void test_no_object_repeats_a_key(void) {
    cJSON *doc = document();
    REQUIRE(doc != NULL);
    const char *where = NULL, *key = repeated_key(doc, &where);
    CHECK_MSG(key == NULL, "key \"%s\" repeated in \"%s\"", key, where ? where : "(top)");
    cJSON_Delete(doc);
}

/* The checker itself finds a repeat, nested in an array. */
static void test_repeat_is_found(void) {
    cJSON *doc = cJSON_Parse("{\"a\": [{\"x\": 1}, {\"s\": {\"d\": 1, \"e\": 2, \"d\": 3}}]}");
    const char *where = NULL;
    REQUIRE(doc != NULL);
    const char *key = repeated_key(doc, &where);
    CHECK(key && !strcmp(key, "d") && where && !strcmp(where, "s"));
    cJSON_Delete(doc);
}

static void test_servers_and_license(void) {
    cJSON *doc = document();
    REQUIRE(doc != NULL);
    const cJSON *servers = cJSON_GetObjectItemCaseSensitive(doc, "servers");
    const cJSON *url = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(servers, 0), "url");
    CHECK(cJSON_IsString(url) && url->valuestring[0]);
    const cJSON *info = cJSON_GetObjectItemCaseSensitive(doc, "info");
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(info, "license"), "name");
    CHECK(cJSON_IsString(name) && name->valuestring[0]);
    cJSON_Delete(doc);
}

/* The probes (/healthz, /readyz) need no token: an empty security list and
 * no 401; any other route keeps the document's bearer scheme and its 401. */
static void test_probes_open_without_token(void) {
    cJSON *doc = document();
    REQUIRE(doc != NULL);
    const cJSON *path;
    cJSON_ArrayForEach(path, cJSON_GetObjectItemCaseSensitive(doc, "paths")) {
        const cJSON *get = cJSON_GetObjectItemCaseSensitive(path, "get");
        if (!get) continue;
        int probe = !strcmp(path->string, "/healthz") || !strcmp(path->string, "/readyz");
        const cJSON *security = cJSON_GetObjectItemCaseSensitive(get, "security");
        const cJSON *refused = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(get, "responses"), "401");
        CHECK_MSG(probe ? cJSON_IsArray(security) && !cJSON_GetArraySize(security) && !refused
                        : !security && refused,
                  "GET %s", path->string);
    }
    cJSON_Delete(doc);
}

/* The schema of the query parameter `name` among params, or NULL. */
static const cJSON *schema_named(const cJSON *params, const char *name) {
    const cJSON *p;
    cJSON_ArrayForEach(p, params) {
        const char *n = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(p, "name"));
        if (n && !strcmp(n, name)) return cJSON_GetObjectItemCaseSensitive(p, "schema");
    }
    return NULL;
}

/* Every parameter's default has its schema's type (a number for integer
 * and number, a boolean for boolean), and is the table's default. */
static void test_defaults_typed(void) {
    cJSON *doc = document();
    REQUIRE(doc != NULL);
    const cJSON *segment = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(doc, "paths"), "/segment"), "post");
    const cJSON *params = cJSON_GetObjectItemCaseSensitive(segment, "parameters");
    size_t n;
    const ps_param_spec *table = ps_param_table(&n);
    for (size_t i = 0; i < n; i++) {
        const cJSON *schema = schema_named(params, table[i].name);
        const char *type = cJSON_GetStringValue(cJSON_GetObjectItemCaseSensitive(schema, "type"));
        const cJSON *d = cJSON_GetObjectItemCaseSensitive(schema, "default");
        CHECK_MSG(type && d, "%s: no schema with a type and a default", table[i].name);
        if (!type || !d) continue;
        int ok = !strcmp(type, "boolean") ? cJSON_IsBool(d) && cJSON_IsTrue(d) == !strcmp(table[i].default_text, "true")
                 : !strcmp(type, "integer") || !strcmp(type, "number")
                     ? cJSON_IsNumber(d) && d->valuedouble == strtod(table[i].default_text, NULL)
                     : cJSON_IsString(d) && !strcmp(d->valuestring, table[i].default_text);
        CHECK_MSG(ok, "%s: default of type %s", table[i].name, type);
    }
    cJSON_Delete(doc);
}

/* The multipart form's schema: each parameter with its help as description. */
static void test_form_fields_described_by_their_help(void) {
    cJSON *doc = document();
    REQUIRE(doc != NULL);
    const cJSON *form = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(
            cJSON_GetObjectItemCaseSensitive(
                cJSON_GetObjectItemCaseSensitive(
                    cJSON_GetObjectItemCaseSensitive(
                        cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(doc, "paths"), "/segment"),
                        "post"),
                    "requestBody"),
                "content"),
            "multipart/form-data"),
        "schema");
    const cJSON *props = cJSON_GetObjectItemCaseSensitive(form, "properties");
    size_t n;
    const ps_param_spec *table = ps_param_table(&n);
    REQUIRE(props != NULL);
    for (size_t i = 0; i < n; i++) {
        const cJSON *d = cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(props, table[i].name),
                                                          "description");
        CHECK_MSG(cJSON_IsString(d) && !strcmp(d->valuestring, table[i].help), "%s: %s", table[i].name,
                  cJSON_IsString(d) ? d->valuestring : "(no description)");
    }
    cJSON_Delete(doc);
}

/* The media types of a path's 200 answer to method, joined by ' '. */
static void answer_types(const cJSON *doc, const char *path, const char *method, char *out, size_t cap) {
    const cJSON *content = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(
            cJSON_GetObjectItemCaseSensitive(
                cJSON_GetObjectItemCaseSensitive(
                    cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(doc, "paths"), path),
                    method),
                "responses"),
            "200"),
        "content");
    const cJSON *type;
    out[0] = 0;
    cJSON_ArrayForEach(type, content) {
        size_t used = strlen(out);
        snprintf(out + used, cap - used, "%s%s", used ? " " : "", type->string);
    }
}

/* A job's result comes in the output format the job asked for, as a
 * synchronous answer does: labels as text/plain, ply as application/ply. */
static void test_job_result_in_every_output_format(void) {
    cJSON *doc = document();
    REQUIRE(doc != NULL);
    char segment[128], result[128];
    answer_types(doc, "/segment", "post", segment, sizeof segment);
    answer_types(doc, "/jobs/{id}/result", "get", result, sizeof result);
    CHECK_MSG(!strcmp(segment, "application/json application/ply text/plain"), "/segment: %s", segment);
    CHECK_MSG(!strcmp(result, segment), "/jobs/{id}/result: %s, /segment: %s", result, segment);
    cJSON_Delete(doc);
}

PS_TEST_MAIN(TEST(test_no_object_repeats_a_key), TEST(test_repeat_is_found), TEST(test_servers_and_license),
             TEST(test_probes_open_without_token), TEST(test_defaults_typed),
             TEST(test_form_fields_described_by_their_help),
             TEST(test_job_result_in_every_output_format))
