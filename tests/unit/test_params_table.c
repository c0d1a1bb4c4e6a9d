/* test_params_table.c: the parameter table (api/params_table.c): lookups in
 * both spellings, defaults that agree with ps_params_default, every value
 * type, the 400/422 errors with their messages, and joining choices. */
#include "params_table.h"
#include "testlib.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const all_names[] = {"method", "k", "centrality", "samples", "persistence",
                                        "ncut_threshold",
                                        "feature_threshold", "minima", "f2", "smooth_normals", "threads",
                                        "output", "include"};

static void test_table_lists_every_parameter(void) {
    size_t count = 0;
    const ps_param_spec *t = ps_param_table(&count);
    REQUIRE(t != NULL);
    CHECK(count == sizeof all_names / sizeof all_names[0]);
    for (size_t i = 0; i < count; i++) {
        CHECK_MSG(strcmp(t[i].name, all_names[i]) == 0, "entry %zu is %s", i, t[i].name);
        CHECK(t[i].help && strlen(t[i].help) > 10);
        CHECK(t[i].default_text != NULL);
        CHECK((t[i].type == PS_PT_ENUM || t[i].type == PS_PT_LIST) == (t[i].choices != NULL));
    }
}

static void test_find_both_spellings(void) {
    const ps_param_spec *a = ps_param_find("ncut_threshold");
    REQUIRE(a != NULL);
    CHECK(ps_param_find("ncut-threshold") == a);
    CHECK(strcmp(a->name, "ncut_threshold") == 0);
    CHECK(a->type == PS_PT_DOUBLE);
    CHECK(ps_param_find("feature-threshold") == ps_param_find("feature_threshold"));
    CHECK(ps_param_find("k")->type == PS_PT_INT);
    CHECK(ps_param_find("ncut") == NULL);
    CHECK(ps_param_find("ncut_threshold_") == NULL);
    CHECK(ps_param_find("") == NULL);
    CHECK(ps_param_find(NULL) == NULL);
    CHECK(ps_param_find("K") == NULL);
}

static int same_request_params(const ps_request_params *a, const ps_request_params *b) {
    return a->core.method == b->core.method && a->core.k == b->core.k && a->core.centrality == b->core.centrality &&
           a->core.samples == b->core.samples &&
           a->core.persistence == b->core.persistence &&
           a->core.ncut_threshold == b->core.ncut_threshold &&
           a->core.feature_threshold == b->core.feature_threshold &&
           a->core.use_minima == b->core.use_minima && a->core.use_f2 == b->core.use_f2 &&
           a->core.smooth_normals == b->core.smooth_normals &&
           a->core.threads == b->core.threads && a->output == b->output &&
           a->include == b->include;
}

/* Each default_text, set through the parser, gives ps_params_default. */
static void test_defaults_agree_with_core(void) {
    ps_request_params from_text, def;
    ps_api_error err;
    size_t count;
    const ps_param_spec *t = ps_param_table(&count);
    ps_request_params_default(&def);
    from_text = (ps_request_params){{PS_METHOD_PAPER, 64, PS_CENTRALITY_EXACT, 9, 0.7, 1.5, 0.9, 0, 1, 1, 3},
                                    PS_OUTPUT_PLY, 3};
    for (size_t i = 0; i < count; i++)
        CHECK_MSG(ps_request_param_set(&from_text, t[i].name, t[i].default_text, &err) == 0,
                  "default of %s: %s", t[i].name, err.message);
    CHECK(same_request_params(&from_text, &def));
    ps_request_params core_only = def;
    ps_params_default(&core_only.core);
    CHECK(same_request_params(&core_only, &def));
    CHECK(def.output == PS_OUTPUT_JSON);
    CHECK(def.include == 0);
    CHECK(strcmp(ps_param_find("k")->default_text, "7") == 0);
    CHECK(ps_param_find("k")->min == 1 && ps_param_find("k")->max == 64);
}

static void test_set_every_type(void) {
    ps_request_params rp;
    ps_api_error err;
    ps_request_params_default(&rp);
    CHECK(ps_request_param_set(&rp, "k", "12", &err) == 0 && rp.core.k == 12);
    CHECK(ps_request_param_set(&rp, "samples", "100000", &err) == 0 && rp.core.samples == 100000);
    CHECK(ps_request_param_set(&rp, "threads", "0", &err) == 0 && rp.core.threads == 0);
    CHECK(ps_request_param_set(&rp, "samples", "1e+05", &err) == 0 && rp.core.samples == 100000);
    CHECK(ps_request_param_set(&rp, "k", "9.0", &err) == 0 && rp.core.k == 9);
    CHECK(ps_request_param_set(&rp, "k", "8.", &err) == 0 && rp.core.k == 8);
    CHECK(ps_request_param_set(&rp, "persistence", ".5", &err) == 0);
    CHECK_NEAR(rp.core.persistence, 0.5, 0);
    CHECK(ps_request_param_set(&rp, "persistence", "-.0", &err) == 0);
    CHECK_NEAR(rp.core.persistence, 0, 0);
    CHECK(ps_request_param_set(&rp, "ncut_threshold", "1.", &err) == 0);
    CHECK_NEAR(rp.core.ncut_threshold, 1, 0);
    CHECK(ps_request_param_set(&rp, "ncut-threshold", "0.25", &err) == 0);
    CHECK_NEAR(rp.core.ncut_threshold, 0.25, 0);
    CHECK(ps_request_param_set(&rp, "feature_threshold", "1e-2", &err) == 0);
    CHECK_NEAR(rp.core.feature_threshold, 0.01, 1e-15);
    CHECK(ps_request_param_set(&rp, "centrality", "exact", &err) == 0 &&
          rp.core.centrality == PS_CENTRALITY_EXACT);
    CHECK(ps_request_param_set(&rp, "centrality", "approx", &err) == 0 &&
          rp.core.centrality == PS_CENTRALITY_APPROX);
    CHECK(ps_request_param_set(&rp, "output", "ply", &err) == 0 && rp.output == PS_OUTPUT_PLY);
    CHECK(ps_request_param_set(&rp, "output", "labels", &err) == 0 &&
          rp.output == PS_OUTPUT_LABELS);
}

static void test_bool_spellings(void) {
    static const char *const yes[] = {"true", "1", "yes", "TRUE", "Yes"};
    static const char *const no[] = {"false", "0", "no", "False", "NO"};
    ps_request_params rp;
    ps_api_error err;
    ps_request_params_default(&rp);
    for (int i = 0; i < 5; i++) {
        CHECK(ps_request_param_set(&rp, "minima", yes[i], &err) == 0 && rp.core.use_minima == 1);
        CHECK(ps_request_param_set(&rp, "minima", no[i], &err) == 0 && rp.core.use_minima == 0);
        CHECK(ps_request_param_set(&rp, "f2", yes[i], &err) == 0 && rp.core.use_f2 == 1);
        CHECK(ps_request_param_set(&rp, "f2", no[i], &err) == 0 && rp.core.use_f2 == 0);
    }
}

static void test_include_list(void) {
    ps_request_params rp;
    ps_api_error err;
    ps_request_params_default(&rp);
    CHECK(ps_request_param_set(&rp, "include", "centrality", &err) == 0 &&
          rp.include == PS_INCLUDE_CENTRALITY);
    CHECK(ps_request_param_set(&rp, "include", "point_supernode,centrality", &err) == 0 &&
          rp.include == (PS_INCLUDE_CENTRALITY | PS_INCLUDE_POINT_SUPERNODE));
    CHECK(ps_request_param_set(&rp, "include", "point-supernode", &err) == 0 &&
          rp.include == PS_INCLUDE_POINT_SUPERNODE);
    CHECK(ps_request_param_set(&rp, "include", " centrality , point_supernode ", &err) == 0 &&
          rp.include == (PS_INCLUDE_CENTRALITY | PS_INCLUDE_POINT_SUPERNODE));
    CHECK(ps_request_param_set(&rp, "include", "", &err) == 0 && rp.include == 0);
}

/* Sets name=value expecting failure with status and exact message. */
static void expect_error(const char *name, const char *value, int status, const char *message) {
    ps_request_params rp, before;
    ps_api_error err = {0, ""};
    ps_request_params_default(&rp);
    before = rp;
    CHECK_MSG(ps_request_param_set(&rp, name, value, &err) == -1, "%s=%s accepted", name, value);
    CHECK_MSG(err.http_status == status, "%s=%s: status %d", name, value, err.http_status);
    CHECK_MSG(strcmp(err.message, message) == 0, "%s=%s: message '%s'", name, value, err.message);
    CHECK_MSG(same_request_params(&rp, &before), "%s=%s changed the params", name, value);
}

static void test_unknown_name_is_400(void) {
    expect_error("x", "1", 400, "unknown parameter 'x'");
    expect_error("kk", "7", 400, "unknown parameter 'kk'");
    expect_error("", "7", 400, "unknown parameter ''");
}

static void test_bad_values_are_422(void) {
    const char *k_msg = "parameter 'k' must be an integer in [1, 64], got '%s'";
    static const char *const bad_k[] = {"abc", "0", "65", "7.5", "", "7x", "-1", "5e+02",
                                        "99999999999999999999999", "1e300", "inf", "0x10", "+8",
                                        " 8", "8 ", "0x1p3", "1e", ".",
                                        "-.", ".e1", "8.5."};
    char msg[256];
    for (size_t i = 0; i < sizeof bad_k / sizeof bad_k[0]; i++) {
        snprintf(msg, sizeof msg, k_msg, bad_k[i]);
        expect_error("k", bad_k[i], 422, msg);
    }
    expect_error("samples", "100001", 422,
                 "parameter 'samples' must be an integer in [0, 100000], got '100001'");
    expect_error("threads", "257", 422,
                 "parameter 'threads' must be an integer in [0, 256], got '257'");
    expect_error("ncut-threshold", "2.5", 422,
                 "parameter 'ncut_threshold' must be a number in [0, 2], got '2.5'");
    expect_error("ncut_threshold", "nan", 422,
                 "parameter 'ncut_threshold' must be a number in [0, 2], got 'nan'");
    expect_error("persistence", "0x1p-3", 422,
                 "parameter 'persistence' must be a number in [0, 1], got '0x1p-3'");
    expect_error("feature_threshold", "-0.1", 422,
                 "parameter 'feature_threshold' must be a number in [0, 1], got '-0.1'");
    expect_error("minima", "maybe", 422,
                 "parameter 'minima' must be true or false (or 1/0, yes/no), got 'maybe'");
    expect_error("centrality", "fast", 422,
                 "parameter 'centrality' must be one of auto, exact, approx, got 'fast'");
    expect_error("output", "xml", 422,
                 "parameter 'output' must be one of json, labels, ply, got 'xml'");
    expect_error("include", "labels", 422,
                 "parameter 'include' must be a comma-separated list of centrality, "
                 "point_supernode, got 'labels'");
    expect_error("include", "centrality,", 422,
                 "parameter 'include' must be a comma-separated list of centrality, "
                 "point_supernode, got 'centrality,'");
    expect_error("k", NULL, 422, "parameter 'k' needs a value");
}

static void test_long_value_is_clipped(void) {
    char value[1000];
    ps_request_params rp;
    ps_api_error err;
    memset(value, 'z', sizeof value - 1);
    value[sizeof value - 1] = 0;
    ps_request_params_default(&rp);
    CHECK(ps_request_param_set(&rp, "centrality", value, &err) == -1);
    CHECK(err.http_status == 422);
    CHECK(strlen(err.message) < sizeof err.message - 1);
}

static void test_join_choices(void) {
    static const char *const choices[] = {"auto", "exact", "approx", NULL};
    char buf[64];
    ps_params_join_choices(choices, ", ", buf, sizeof buf);
    CHECK(strcmp(buf, "auto, exact, approx") == 0);
    ps_params_join_choices(choices, "|", buf, sizeof buf);
    CHECK(strcmp(buf, "auto|exact|approx") == 0);
    ps_params_join_choices(choices, "|", buf, 11);
    CHECK_MSG(strcmp(buf, "auto|exact") == 0, "exact fit: '%s'", buf);
    ps_params_join_choices(choices, "|", buf, 10);
    CHECK_MSG(strcmp(buf, "auto") == 0, "no partial choice: '%s'", buf);
    ps_params_join_choices(choices, "|", buf, 4);
    CHECK(buf[0] == 0);
    ps_params_join_choices(NULL, "|", buf, sizeof buf);
    CHECK(buf[0] == 0);
}

PS_TEST_MAIN(TEST(test_table_lists_every_parameter), TEST(test_find_both_spellings),
             TEST(test_defaults_agree_with_core), TEST(test_set_every_type),
             TEST(test_bool_spellings), TEST(test_include_list), TEST(test_unknown_name_is_400),
             TEST(test_bad_values_are_422), TEST(test_long_value_is_clipped),
             TEST(test_join_choices))
