/* test_decode_off.c: OFF records spread over several lines, CR-only and
 * mixed line ends, colours after wrapped records, and the errors of
 * truncated multi-line files (test_decode_text.c has the one-line cases). */
#include <string.h>

#include "decode.h"
#include "decode_check.h"
#include "testlib.h"

static int fails(const char *text, int status, const char *needle) {
    return ps_check_decode_fails(ps_decode, text, strlen(text), NULL, status, needle);
}

/* A decoded set has n points equal to want (#n by 3) and the triangles
 * tris (#n_tris by 3). */
static int has_mesh(const ps_pointset *ps, const double *want, size_t n, const uint32_t *tris,
                    size_t n_tris) {
    return ps->n == n && ps->dim == 3 && !memcmp(ps->points, want, n * 3 * sizeof *want) &&
           ps->n_faces == n_tris &&
           (!n_tris || !memcmp(ps->faces, tris, n_tris * 3 * sizeof *tris));
}

static const double square[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
static const uint32_t square_tris[] = {0, 1, 2, 0, 2, 3};

static void test_one_number_per_line(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("OFF\n4\n1\n0\n0\n0\n0\n1\n0\n0\n1\n1\n0\n0\n1\n0\n"
                             "4\n0\n1\n2\n3\n", &ps));
    CHECK(has_mesh(&ps, square, 4, square_tris, 2));
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("NOFF\n1 0 0\n1\n2\n3\n0\n0\n1\n", &ps));
    CHECK(ps.n == 1 && ps.points[2] == 3 && ps.normals && ps.normals[2] == 1);
    ps_pointset_free(&ps);
}

static void test_wrapped_face(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1\n  2 3\n", &ps));
    CHECK(has_mesh(&ps, square, 4, square_tris, 2));
    ps_pointset_free(&ps);
    /* A vertex split after x, and a face split after its count. */
    REQUIRE(ps_check_decodes("OFF\n4 1 0\n0\n0 0\n1 0 0\n1 1 0\n0 1 0\n4\n0 1 2 3\n", &ps));
    CHECK(has_mesh(&ps, square, 4, square_tris, 2));
    ps_pointset_free(&ps);
}

static void test_cr_line_ends(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("OFF\r4 1 0\r0 0 0\r1 0 0\r1 1 0\r0 1 0\r4 0 1 2 3\r", &ps));
    CHECK(has_mesh(&ps, square, 4, square_tris, 2));
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("OFF\r\n4 1 0\r\n0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n4 0 1 2 3",
                             &ps));
    CHECK(has_mesh(&ps, square, 4, square_tris, 2));
    ps_pointset_free(&ps);
    /* Mixed: CR, CRLF and LF in one file; CR CR is a blank line. */
    REQUIRE(ps_check_decodes("OFF\r\r4 1 0\r\n0 0 0\n1 0 0\r1 1 0\r\n\n0 1 0\r4 0 1 2 3\n",
                             &ps));
    CHECK(has_mesh(&ps, square, 4, square_tris, 2));
    ps_pointset_free(&ps);
}

static void test_cr_with_comments(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("OFF # a square\r# counts next\r4 1 0 # nv nf ne\r0 0 0\r"
                             "# between vertices\r1 0 0 # one\r1 # wrapped\r1 0\r0 1 0\r"
                             "4 0 1 # face\r# still the face\r2 3\r# the end", &ps));
    CHECK(has_mesh(&ps, square, 4, square_tris, 2));
    ps_pointset_free(&ps);
    /* Without automatic detection, a comment may come before the keyword. */
    ps_api_error err;
    const char text[] = "# first\rOFF\r1 0 0\r1 2 3\r";
    REQUIRE(ps_decode_off(text, sizeof text - 1, NULL, &ps, &err) == 0);
    CHECK(ps.n == 1 && ps.points[0] == 1 && ps.points[1] == 2 && ps.points[2] == 3);
    ps_pointset_free(&ps);
}

static void test_colours_skipped(void) {
    ps_pointset ps;
    static const double want[] = {0, 0, 0, 1, 2, 3, 4, 5, 6};
    static const uint32_t tris[] = {0, 1, 2};
    REQUIRE(ps_check_decodes("COFF\n3 1 0\n0 0 0 255 0 0 255\n1\n2 3 0 255 0 255\n"
                             "4 5\n6 0.5 0.5 0.5 1\n3 0\n1 2 255 255 255\n", &ps));
    CHECK(has_mesh(&ps, want, 3, tris, 1));
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("CNOFF\r1 0 0\r1 2 3 0 0 1 9 9 9\r", &ps));
    CHECK(ps.n == 1 && ps.points[2] == 3 && ps.normals[2] == 1);
    ps_pointset_free(&ps);
}

static void test_split_counts(void) {
    ps_pointset ps;
    REQUIRE(ps_check_decodes("OFF\n1\n0\n0\n7\n8\n9\n", &ps));
    CHECK(ps.n == 1 && ps.points[0] == 7 && ps.points[2] == 9 && ps.n_faces == 0);
    ps_pointset_free(&ps);
    REQUIRE(ps_check_decodes("OFF 1\n0 0\n7 8 9\n", &ps));
    CHECK(ps.n == 1 && ps.points[0] == 7 && ps.points[2] == 9);
    ps_pointset_free(&ps);
}

static void test_truncated(void) {
    CHECK(fails("OFF\n2 0 0\n0.0\n0.0\n0.0\n1.0\n0.0\n", 400,
                "line 6: vertex 1 needs 3 numbers (the file ends after 2)"));
    CHECK(fails("OFF\r4 1 0\r0 0 0\r1 0 0\r1 1 0\r0 1 0\r4 0 1\r2\r", 400,
                "line 7: face 0 needs 4 vertex indices (the file ends after 3)"));
    CHECK(fails("OFF\n2\n0\n", 400, "the file ends before the counts"));
    CHECK(fails("OFF\r3 0 0\r0.0 0.0 0.0\r1.0 0.0 0.0\r", 400,
                "line 5: the file ends before all vertices"));
    CHECK(fails("OFF\n3 0 0\n0.0 0.0 0.0\n1 0\n2.0 0.0 0.0\n", 400,
                "line 6: the file ends before all vertices"));
}

static void test_errors_name_lines(void) {
    CHECK(fails("OFF\r2 1 0\r0 0 0\r1 0 0\r3 0\r1 2\r", 422,
                "line 6: face 0 refers to vertex 2 (the file has 2 vertices)"));
    CHECK(fails("OFF\r\n2 0 0\r\n0 0 0\r\n1\r\nnan 0\r\n", 422, "line 5: non-finite"));
    CHECK(fails("OFF\r2 0 0\r0 0 0\r1\rx 0\r", 400, "line 5: \"x\" is not a number"));
    CHECK(fails("OFF\r1 1 0\r0 0 0\r3\r0 y\r", 400, "line 5: expected a vertex index"));
    CHECK(fails("OFF\r1\r99999999\r0\r0 0 0\r", 400, "face count 99999999 exceeds"));
    CHECK(fails("OFF\n1\n-1\n0\n0 0 0\n", 400, "negative count"));
}

PS_TEST_MAIN(TEST(test_one_number_per_line), TEST(test_wrapped_face), TEST(test_cr_line_ends),
             TEST(test_cr_with_comments), TEST(test_colours_skipped), TEST(test_split_counts),
             TEST(test_truncated), TEST(test_errors_name_lines))
