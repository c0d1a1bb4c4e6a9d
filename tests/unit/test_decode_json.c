/* test_decode_json.c: the JSON request body decoder: nested and flat
 * points, normals, params as text, and malformed or unusable bodies. */
#include <stdio.h>
#include <string.h>

#include "decode.h"
#include "decode_check.h"
#include "testlib.h"

static int fails(const char *text, const ps_decode_limits *lim, int status, const char *needle) {
    return ps_check_decode_fails(ps_decode_json, text, strlen(text), lim, status, needle);
}

static const char *param(const ps_pointset *ps, const char *name) {
    for (size_t i = 0; i < ps->n_params; i++)
        if (!strcmp(ps->params[i].name, name)) return ps->params[i].value;
    return "(absent)";
}

static void test_nested_points_and_normals(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes(" {\"points\": [[0, 1, 2], [3, 4, 5.5]],\n"
                    "  \"normals\": [[0, 0, 1], [1, 0, 0]]}", &ps));
    CHECK(ps.n == 2 && ps.dim == 3 && ps.points[5] == 5.5 && ps.points[1] == 1);
    CHECK(ps.normals && ps.normals[2] == 1 && ps.normals[3] == 1);
    CHECK(ps.n_params == 0 && !ps.faces);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("{\"points\": [[0, 1], [2, 3], [4, 5]], \"dimension\": 2}", &ps));
    CHECK(ps.n == 3 && ps.dim == 2 && ps.points[5] == 5);
    ps_pointset_free(&ps);
}

static void test_flat_points(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("{\"dimension\": 3, \"points\": [0, 1, 2, 3, 4, 5],"
                    " \"normals\": [0, 0, 1, 0, 1, 0]}", &ps));
    CHECK(ps.n == 2 && ps.dim == 3 && ps.points[3] == 3 && ps.normals && ps.normals[4] == 1);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("{\"points\": [1, 2, 3, 4], \"dimension\": 4}", &ps));
    CHECK(ps.n == 1 && ps.dim == 4);
    ps_pointset_free(&ps);
}

static void test_params(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("{\"points\": [[0, 0], [1, 1]], \"params\": {\"k\": 7, \"ncut_threshold\":"
                    " 0.1, \"x\": 0.25, \"big\": 1e300, \"centrality\": \"approx\", \"use_f2\":"
                    " true, \"use_minima\": false, \"include\": [\"centrality\", \"point_"
                    "supernode\"], \"none\": []}}", &ps));
    CHECK(ps.n_params == 9);
    CHECK(!strcmp(param(&ps, "k"), "7"));
    CHECK(!strcmp(param(&ps, "ncut_threshold"), "0.1"));
    CHECK(!strcmp(param(&ps, "x"), "0.25"));
    CHECK(!strcmp(param(&ps, "big"), "1e+300"));
    CHECK(!strcmp(param(&ps, "centrality"), "approx"));
    CHECK(!strcmp(param(&ps, "use_f2"), "true"));
    CHECK(!strcmp(param(&ps, "use_minima"), "false"));
    CHECK(!strcmp(param(&ps, "include"), "centrality,point_supernode"));
    CHECK(!strcmp(param(&ps, "none"), ""));
    ps_pointset_free(&ps);
    CHECK(ps.params == NULL && ps.n_params == 0);
}

static void test_bad_bodies(void) {
    CHECK(fails("{\"points\": [[0, 0]], \"prams\": {}}", NULL, 400, "unknown key \"prams\""));
    CHECK(fails("{\"points\": [[0, 0]], \"points\": [[1, 1]]}", NULL, 400, "appears twice"));
    CHECK(fails("{\"points\": [[0, 0], [1, 1]", NULL, 400, "malformed JSON at byte offset"));
    CHECK(fails("{\"points\": [[0, 0], [1, 1]]} x", NULL, 400, "after the JSON value at byte "
                "offset 29"));
    CHECK(fails("{\"points\": [[0, 0] [1, 1]]}", NULL, 400, "malformed JSON at byte offset 19"));
    CHECK(fails("[1, 2]", NULL, 400, "must be an object"));
    CHECK(fails("{}", NULL, 400, "missing \"points\""));
    CHECK(fails("{\"points\": 3}", NULL, 400, "\"points\" must be an array"));
    CHECK(fails("{\"points\": [0, 1, 2]}", NULL, 400, "flat \"points\" needs \"dimension\""));
    CHECK(fails("{\"points\": [0, 1, 2], \"dimension\": 2}", NULL, 422, "not a multiple"));
    CHECK(fails("{\"points\": [0, 1], \"dimension\": 1.5}", NULL, 400, "\"dimension\" must be"));
    CHECK(fails("{\"points\": [[0, 1], [2]]}", NULL, 400, "points[1] must be an array of 2"));
    CHECK(fails("{\"points\": [[0, 1], [2, \"3\"]]}", NULL, 400, "points[1][1] is not a number"));
    CHECK(fails("{\"points\": [0, \"1\"], \"dimension\": 2}", NULL, 400, "points[1] is not"));
    CHECK(fails("{\"points\": [[0, 1, 2]], \"dimension\": 2}", NULL, 422,
                "points[0] has 3 values, expected 2"));
    CHECK(fails("{\"points\": [[0], [1]]}", NULL, 422, "dimension 1 is outside"));
    CHECK(fails("{\"points\": []}", NULL, 422, "no points"));
    CHECK(fails("{\"points\": [[0, 1], [1e999, 0]]}", NULL, 422,
                "point 1 has a non-finite coordinate"));
    CHECK(fails("{\"points\": [[0, 1]], \"normals\": [[0, 1], [1, 0]]}", NULL, 422,
                "2 normals for 1 points"));
    CHECK(fails("{\"points\": [[0, 1]], \"params\": []}", NULL, 400, "must be an object"));
    CHECK(fails("{\"points\": [[0, 1]], \"params\": {\"k\": null}}", NULL, 400, "params.k must"));
    CHECK(fails("{\"points\": [[0, 1]], \"params\": {\"i\": [1]}}", NULL, 400, "params.i must"));
    ps_decode_limits lim = {1, 64};
    CHECK(fails("{\"points\": [[0, 1], [1, 2]]}", &lim, 413, "2 points exceed the limit of 1"));
}

static void test_not_nul_terminated(void) {
    char buf[64];
    const char *text = "{\"points\": [[1, 2], [3, 4]]}";
    size_t len = strlen(text);
    memcpy(buf, text, len);
    memset(buf + len, ']', sizeof buf - len);
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode(buf, len, NULL, &ps, &err) == 0);
    CHECK(ps.n == 2 && ps.points[3] == 4);
    ps_pointset_free(&ps);
    CHECK(ps_decode_json(buf, len - 1, NULL, &ps, &err) == -1 && err.http_status == 400);
}

PS_TEST_MAIN(TEST(test_nested_points_and_normals), TEST(test_flat_points), TEST(test_params),
             TEST(test_bad_bodies), TEST(test_not_nul_terminated))
