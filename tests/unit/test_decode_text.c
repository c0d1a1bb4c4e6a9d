/* test_decode_text.c: OFF, OBJ and XYZ/CSV decoding, format detection,
 * ps_decode's checks and ps_read_file, with good and bad inputs (and a
 * byte order mark in front). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "decode.h"
#include "decode_check.h"
#include "testlib.h"

static int fails(const char *text, const ps_decode_limits *lim, int status, const char *needle) {
    return ps_check_decode_fails(ps_decode, text, strlen(text), lim, status, needle);
}

static void test_detect(void) {
    static const struct {
        const char *text;
        ps_format f;
    } cases[] = {
        {"ply\nformat ascii 1.0\n", PS_FORMAT_PLY}, {"ply\r\nformat", PS_FORMAT_PLY},
        {"plyx\n", PS_FORMAT_UNKNOWN},              {"  \n {\"points\": []}", PS_FORMAT_JSON},
        {"OFF\n1 0 0\n", PS_FORMAT_OFF},            {"# c\nNOFF 1 0 0\n", PS_FORMAT_OFF},
        {"COFF\n", PS_FORMAT_OFF},                  {"# c\nmtllib a\nv 1 2 3\n", PS_FORMAT_OBJ},
        {"1 2 3\nv 1 2 3\n", PS_FORMAT_XYZ},        {"x,y,z\n1,2,3\n", PS_FORMAT_XYZ},
        {"# c\n\n1;2\n", PS_FORMAT_XYZ},            {"hello world\n", PS_FORMAT_UNKNOWN},
        {"", PS_FORMAT_UNKNOWN},                    {"OFFICE 1 2\n", PS_FORMAT_UNKNOWN},
        {"# c\rOFF\r1 0 0\r", PS_FORMAT_OFF},      {"# c\rv 1 2 3\r", PS_FORMAT_OBJ},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        CHECK_MSG(ps_detect_format(cases[i].text, strlen(cases[i].text)) == cases[i].f,
                  "case %zu: %s", i, ps_format_name(ps_detect_format(cases[i].text,
                                                                     strlen(cases[i].text))));
    CHECK(!strcmp(ps_format_name(PS_FORMAT_OBJ), "obj"));
    CHECK(!strcmp(ps_format_name(PS_FORMAT_UNKNOWN), "unknown"));
}

static void test_off(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("OFF\n# a square and a triangle\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                    "2 2 2.5\n4 0 1 2 3\n3 1 4 2 255 0 0\n", &ps));
    CHECK(ps.n == 5 && ps.dim == 3 && ps.n_faces == 3 && !ps.normals);
    static const uint32_t want[] = {0, 1, 2, 0, 2, 3, 1, 4, 2};
    CHECK(ps.faces && !memcmp(ps.faces, want, sizeof want));
    CHECK_NEAR(ps.points[14], 2.5, 0);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("NOFF 2 0 0\n0 0 0 0 0 1\n1 0 0 0 1 0\n", &ps));
    CHECK(ps.n == 2 && ps.normals && ps.normals[2] == 1 && ps.normals[4] == 1 && !ps.faces);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("COFF\r\n1 0 0\r\n4 5 6 255 0 0 255\r\n", &ps));
    CHECK(ps.n == 1 && ps.points[2] == 6 && !ps.normals);
    ps_pointset_free(&ps);
}

static void test_off_errors(void) {
    CHECK(fails("4OFF\n1 0 0\n1 2 3 4\n", NULL, 422, "OFF variant \"4OFF\" is not supported"));
    CHECK(fails("OFF\n2 1 0\n0 0 0\n1 0 0\n3 0 1 2\n", NULL, 422,
                "line 5: face 0 refers to vertex 2 (the file has 2 vertices)"));
    CHECK(fails("OFF\n2 0 0\n0.0 0.0 0.0\n1 0\n", NULL, 400, "line 4: vertex 1 needs 3"));
    CHECK(fails("OFF\n2 0 0\n0 0 0\n1 nan 0\n", NULL, 422, "line 4: non-finite"));
    CHECK(fails("OFF\n99999999999 0 0\n0 0 0\n", NULL, 400,
                "vertex count 99999999999 exceeds the data"));
    CHECK(fails("OFF\n1 99999999 0\n0 0 0\n3 0 0 0\n", NULL, 400, "face count 99999999 exceeds"));
    CHECK(fails("OFF\n3 0 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n", NULL, 400,
                "the file ends before all vertices"));
    CHECK(fails("OFF\n-1 0 0\n", NULL, 400, "negative count"));
    CHECK(fails("OFF\nx y z\n", NULL, 400, "line 2: expected"));
    CHECK(fails("OFF\n0 0 0\n", NULL, 422, "no points"));
    ps_decode_limits lim = {2, 64};
    CHECK(fails("OFF\n3 0 0\n0 0 0\n1 0 0\n2 0 0\n", &lim, 413, "3 points exceed the limit of 2"));
}

static void test_obj(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("# cube corner\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0\n"
                    "vt 0 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nv 0 1 0\ns off\nf 1 2 3\n"
                    "f 1/1 3/1 4/1\nf -4/1/1 -3//1 -2/2/2 -1//3\nusemtl red\n", &ps));
    CHECK(ps.n == 4 && ps.dim == 3 && ps.n_faces == 4 && !ps.normals);
    static const uint32_t want[] = {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3};
    CHECK(ps.faces && !memcmp(ps.faces, want, sizeof want));
    CHECK(ps.points[4] == 0 && ps.points[6] == 1 && ps.points[7] == 1);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("v 0 0 0\nvn 1 0 0\nv 1 2 3\nvn 0 1 0\n", &ps));
    CHECK(ps.n == 2 && ps.normals && ps.normals[0] == 1 && ps.normals[4] == 1 && !ps.faces);
    ps_pointset_free(&ps);
}

static void test_obj_errors(void) {
    CHECK(fails("v 0 0 0\nv 1 0 0\nf 1 2 3\n", NULL, 422, "line 3: face refers to vertex 3"));
    CHECK(fails("v 0 0 0\nf -2 1 1\n", NULL, 422, "line 2: face refers to vertex -2"));
    CHECK(fails("v 0 0 0\nf 0 1 1\n", NULL, 400, "line 2: bad face vertex"));
    CHECK(fails("v 0 0 0\nv 1 0\n", NULL, 400, "line 2: expected 3 numbers"));
    CHECK(fails("v 0 0 0\nv 1 0 inf\n", NULL, 422, "line 2: non-finite number \"inf\""));
    CHECK(fails("v 0 0 0\nv 1 0 x\n", NULL, 400, "line 2: \"x\" is not a number"));
    ps_decode_limits lim = {1, 64};
    CHECK(fails("v 0 0 0\nv 1 0 0\n", &lim, 413, "2 points exceed the limit of 1"));
}

static void test_xyz(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("# scan\n1 2 3\n4\t5  6\r\n\n7 8 9 # last\n", &ps));
    CHECK(ps.n == 3 && ps.dim == 3 && !ps.normals && ps.points[8] == 9 && ps.points[4] == 5);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("x,y,z,nx,ny,nz\n1,2,3,0,0,1\n4, 5, 6, 1 ,0,0\n", &ps));
    CHECK(ps.n == 2 && ps.dim == 3 && ps.normals && ps.points[3] == 4 && ps.normals[3] == 1);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("1;2\n3;4\n-5e-1;6\n", &ps));
    CHECK(ps.n == 3 && ps.dim == 2 && ps.points[4] == -0.5);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("1 2 3 4\n5 6 7 8\n", &ps));
    CHECK(ps.n == 2 && ps.dim == 4 && ps.points[7] == 8);
    ps_pointset_free(&ps);
    /* old Mac line ends (a lone CR), mixed with CRLF and LF */
    REQUIRE(ps_check_decodes("# scan\r1 2 3\r4 5 6\r\n7 8 9\n10 11 12\r", &ps));
    CHECK(ps.n == 4 && ps.dim == 3 && ps.points[3] == 4 && ps.points[11] == 12);
    ps_pointset_free(&ps);
}

/* A UTF-8 byte order mark in front (what some editors write) is skipped
 * in every text format, and the first point is kept. */
static void test_byte_order_mark(void) {
    static const char *const texts[] = {
        "\xEF\xBB\xBF" "1 2 3\n4 5 6\n", "\xEF\xBB\xBF" "1,2,3\n4,5,6\n",
        "\xEF\xBB\xBF" "OFF\n2 0 0\n1 2 3\n4 5 6\n", "\xEF\xBB\xBF" "v 1 2 3\nv 4 5 6\n",
        "\xEF\xBB\xBF" "{\"points\": [[1,2,3],[4,5,6]]}"};
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        ps_pointset ps;
        REQUIRE(ps_check_decodes(texts[i], &ps));
        CHECK_MSG(ps.n == 2 && ps.points[0] == 1 && ps.points[5] == 6, "text %zu: %zu points", i, ps.n);
        ps_pointset_free(&ps);
    }
}

static void test_xyz_errors(void) {
    CHECK(fails("1 2 3\n4 5 6\n7 8\n", NULL, 400, "line 3: 2 columns, expected 3"));
    CHECK(fails("1 2 3\r4 5 6\r\n7 8\r", NULL, 400, "line 3: 2 columns, expected 3"));
    CHECK(fails("1 2 3\n4 5 six\n", NULL, 400, "line 2: \"six\" is not a number"));
    CHECK(fails("1 2 3\n4 5 nan\n", NULL, 422, "line 2: non-finite"));
    CHECK(fails("1\n2\n", NULL, 422, "line 1: 1 column"));
    CHECK(fails("1,2,3\n1,,2\n", NULL, 400, "line 2: empty field"));
    CHECK(fails("x y\na b\n", NULL, 400, "unrecognized format"));
    ps_decode_limits lim = {0, 3};
    CHECK(fails("1 2 3 4\n", &lim, 422, "dimension 4 is outside [2, 3]"));
    CHECK(fails("1 2 3 4 5 6 7\n", &lim, 422, "line 1: more than 6 columns"));
    lim.max_points = 1;
    CHECK(fails("1 2\n3 4\n", &lim, 413, "2 points exceed the limit of 1"));
}

static void test_decode_checks(void) {
    CHECK(fails("", NULL, 400, "empty input"));
    CHECK(fails(" \n\t\n", NULL, 400, "empty input"));
    CHECK(fails("\x01\x02garbage", NULL, 400, "unrecognized format"));
    CHECK(fails("# only a comment\n", NULL, 400, "unrecognized format"));
    ps_pointset ps;
    ps_api_error err;
    CHECK(ps_decode_off("1 2\n", 4, NULL, &ps, &err) == -1 && err.http_status == 422 &&
          strstr(err.message, "OFF") != NULL);
}

static void test_not_nul_terminated(void) {
    char buf[16];
    memcpy(buf, "1 2\n3 4.5", 9);
    memset(buf + 9, '7', sizeof buf - 9);
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode(buf, 9, NULL, &ps, &err) == 0);
    CHECK(ps.n == 2 && ps.points[3] == 4.5);
    ps_pointset_free(&ps);
}

static void test_read_file(void) {
    char path[] = "/tmp/ps_decode_testXXXXXX";
    int fd = mkstemp(path);
    REQUIRE(fd >= 0);
    static const char text[] = "1 2 3\n4 5 6\n";
    CHECK(write(fd, text, sizeof text - 1) == (ssize_t)(sizeof text - 1));
    close(fd);
    char *bytes;
    size_t len;
    ps_api_error err;
    REQUIRE(ps_read_file(path, &bytes, &len, &err) == 0);
    CHECK(len == sizeof text - 1 && !memcmp(bytes, text, len));
    free(bytes);
    unlink(path);
    CHECK(ps_read_file(path, &bytes, &len, &err) == -1 && err.http_status == 400 &&
          strstr(err.message, path));
}

static void test_psb_off(void) {
    ps_pointset ps;
    int decoded = ps_decode_shared_file("psb-dev/off/1.off", &ps, NULL);
    if (decoded == 0) return; /* skipped */
    REQUIRE(decoded == 1);
    CHECK(ps.n == 4706 && ps.n_faces == 9408 && ps.dim == 3);
    ps_pointset_free(&ps);
}

PS_TEST_MAIN(TEST(test_detect), TEST(test_off), TEST(test_off_errors), TEST(test_obj),
             TEST(test_obj_errors), TEST(test_xyz), TEST(test_byte_order_mark), TEST(test_xyz_errors),
             TEST(test_decode_checks), TEST(test_not_nul_terminated), TEST(test_read_file),
             TEST(test_psb_off))
