/* test_decode_labels.c: labels files: one integer per line, signs, blank
 * lines and CRLF accepted; garbage, fractions and overflow refused with the
 * line number; the buffer need not end in a NUL. */
#include "decode.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

static void test_reads_integers(void) {
    const char text[] = "3\n-1\r\n\n+7\n  42  \n0";
    int *v = NULL;
    size_t n = 0;
    ps_api_error err;
    REQUIRE(ps_decode_labels(text, strlen(text), &v, &n, &err) == 0);
    REQUIRE(n == 5);
    CHECK(v[0] == 3 && v[1] == -1 && v[2] == 7 && v[3] == 42 && v[4] == 0);
    free(v);
    REQUIRE(ps_decode_labels("12", 1, &v, &n, &err) == 0); /* only "1" is given */
    CHECK(n == 1 && v[0] == 1);
    free(v);
    REQUIRE(ps_decode_labels("", 0, &v, &n, &err) == 0);
    CHECK(n == 0);
    free(v);
}

static void expect_error(const char *text, const char *where) {
    int *v = NULL;
    size_t n = 0;
    ps_api_error err = {0};
    CHECK_MSG(ps_decode_labels(text, strlen(text), &v, &n, &err) != 0, "accepted '%s'", text);
    CHECK(err.http_status == 400);
    CHECK_MSG(strstr(err.message, where) != NULL, "'%s' does not say %s", err.message, where);
}

static void test_refuses_garbage(void) {
    expect_error("1\n2\nx\n", "line 3");
    expect_error("1\n2.5\n", "line 2");
    expect_error("99999999999\n", "line 1");
    expect_error("-\n", "line 1");
}

PS_TEST_MAIN(TEST(test_reads_integers), TEST(test_refuses_garbage))
