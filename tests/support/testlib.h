/*
 * testlib.h: the project's small test harness.
 *
 * A test file lists its tests and ends with PS_TEST_MAIN:
 *
 *     static void test_dumbbell(void) { CHECK(x == 2); CHECK_NEAR(a, b, 1e-9); }
 *     PS_TEST_MAIN(TEST(test_dumbbell), TEST(test_other))
 *
 * Each test prints one line, "PASS file:name", "FAIL file:name: why" or
 * "SKIP file:name: why"; tests/run.sh counts those lines.  A failed CHECK
 * reports and goes on with the next statement; REQUIRE returns from the test.
 * Test binaries take an optional argument: a substring of the tests to run.
 */
#ifndef PS_TESTLIB_H
#define PS_TESTLIB_H

#include <stddef.h>

typedef struct ps_test_case {
    const char *name;
    void (*fn)(void);
} ps_test_case;

void ps_test_fail(const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
void ps_test_skip(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
int ps_test_main(const char *file, const ps_test_case *tests, size_t count,
                 int argc, char **argv);
/* ../shared/data beside the checkout (or $POINTSEG_SHARED); NULL if absent. */
const char *ps_test_shared_dir(void);

#define TEST(fn) {#fn, fn}
#define CHECK(cond) \
    do { if (!(cond)) ps_test_fail(__FILE__, __LINE__, "CHECK(%s)", #cond); } while (0)
#define REQUIRE(cond) \
    do { if (!(cond)) { ps_test_fail(__FILE__, __LINE__, "REQUIRE(%s)", #cond); return; } } while (0)
#define CHECK_MSG(cond, ...) \
    do { if (!(cond)) ps_test_fail(__FILE__, __LINE__, __VA_ARGS__); } while (0)
#define CHECK_NEAR(a, b, tol) \
    do { double a_ = (a), b_ = (b); \
         if (!(a_ - b_ <= (tol) && b_ - a_ <= (tol))) \
             ps_test_fail(__FILE__, __LINE__, "%s = %g, %s = %g, tolerance %g", \
                          #a, a_, #b, b_, (double)(tol)); } while (0)
#define SKIP(...) do { ps_test_skip(__VA_ARGS__); return; } while (0)

#define PS_TEST_MAIN(...) \
    int main(int argc, char **argv) { \
        static const ps_test_case tests_[] = {__VA_ARGS__}; \
        return ps_test_main(__FILE__, tests_, sizeof tests_ / sizeof tests_[0], argc, argv); \
    }

#endif
