/* test_memory_estimate.c: ps_segment_memory_estimate is an upper estimate
 * that is not wasteful: a child process segments a dumbbell a little
 * denser than the reference sampling (one draw), a 100,000-point one in
 * one run (method paper) and in three draws leaving points out (auto),
 * and a 250,000-point one in five draws covering it, and its peak RSS
 * (getrusage of the waited children) must lie between half the estimate
 * and the estimate; the estimate grows with n, k and the sample count,
 * and below the reference sampling covers a mesh segmented in fills up
 * to it.  Skipped under AddressSanitizer, whose shadow memory is no part
 * of the model. */
#include "graph/reference_density.h"
#include "pointseg.h"
#include "shapes.h"
#include "testlib.h"

#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#ifndef UNDER_ASAN
#define UNDER_ASAN 0
#endif

/* Peak RSS in bytes of a child segmenting pts, or 0 when it failed. */
static size_t child_peak_rss(const double *pts, size_t n, const ps_params *params) {
    pid_t pid = fork();
    if (pid == 0) {
        ps_params p = *params;
        ps_input in = {.points = pts, .n = n, .dim = 3};
        ps_result *r = NULL;
        _exit(ps_segment(&in, &p, NULL, &r, NULL) == PS_OK ? 0 : 1);
    }
    int status = 0;
    struct rusage ru;
    if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) ||
        getrusage(RUSAGE_CHILDREN, &ru) != 0)
        return 0;
    return (size_t)ru.ru_maxrss * 1024; /* the largest waited child; Linux: kilobytes */
}

/* A dumbbell of about `target` points segmented with method: the child's
 * peak RSS lies between half the estimate and the estimate. */
static void check_bounds_measured_peak(double target, ps_method method) {
    size_t n = 0;
    double *pts = ps_shape_dumbbell(100, &n, NULL);
    REQUIRE(pts && n > 0);
    double density = 100.0 * target / (double)n;
    free(pts);
    pts = ps_shape_dumbbell(density, &n, NULL);
    REQUIRE(pts && n > target / 2);
    ps_params p;
    ps_params_default(&p);
    p.method = method;
    size_t estimate = ps_segment_memory_estimate(n, 3, &p), measured = child_peak_rss(pts, n, &p);
    REQUIRE(measured > 0);
    CHECK_MSG(measured <= estimate && estimate <= 2 * measured,
              "%zu points: peak RSS %zu MB, estimate %zu MB", n, measured >> 20, estimate >> 20);
    free(pts);
}

static void test_estimate_bounds_measured_peak(void) {
    if (UNDER_ASAN) SKIP("under AddressSanitizer the peak RSS includes its shadow memory");
    check_bounds_measured_peak(PS_DENSITY_REFERENCE_POINTS * 1.2, PS_METHOD_AUTO);
    check_bounds_measured_peak(100000.0, PS_METHOD_PAPER);
}

/* 100,000 points are segmented in three draws of the reference sampling
 * (ensemble.h), the rest answered from the chosen one. */
static void test_estimate_bounds_peak_in_partial_draws(void) {
    if (UNDER_ASAN) SKIP("under AddressSanitizer the peak RSS includes its shadow memory");
    check_bounds_measured_peak(100000.0, PS_METHOD_AUTO);
}

/* 250,000 points are segmented in five draws covering them, which keep
 * less a point. */
static void test_estimate_bounds_peak_in_draws(void) {
    if (UNDER_ASAN) SKIP("under AddressSanitizer the peak RSS includes its shadow memory");
    check_bounds_measured_peak(250000.0, PS_METHOD_AUTO);
}

static void test_estimate_grows(void) {
    ps_params p, more_k, more_samples;
    ps_params_default(&p);
    more_k = more_samples = p;
    more_k.k = 14;
    more_samples.samples = 4000;
    size_t base = ps_segment_memory_estimate(1000000, 3, &p);
    CHECK(ps_segment_memory_estimate(2000000, 3, &p) > base);
    CHECK(ps_segment_memory_estimate(1000000, 3, &more_k) > base);
    CHECK(ps_segment_memory_estimate(1000000, 3, &more_samples) > base);
    CHECK(ps_segment_memory_estimate(1000000, 2, &p) > base); /* auto: a 3-D copy */
}

/* A small mesh may be segmented in fills up to the reference sampling:
 * below it the estimate is that of the fills, more than one run at the
 * reference, but with exact centrality (no fills). */
static void test_estimate_covers_the_fill(void) {
    ps_params p, exact;
    ps_params_default(&p);
    exact = p;
    exact.centrality = PS_CENTRALITY_EXACT;
    size_t ref = PS_DENSITY_REFERENCE_POINTS;
    CHECK(ps_segment_memory_estimate(100, 3, &p) == ps_segment_memory_estimate(ref - 1, 3, &p));
    CHECK(ps_segment_memory_estimate(100, 3, &p) > ps_segment_memory_estimate(ref, 3, &p));
    CHECK(ps_segment_memory_estimate(100, 3, &exact) < ps_segment_memory_estimate(ref, 3, &exact));
}

PS_TEST_MAIN(TEST(test_estimate_bounds_measured_peak),
             TEST(test_estimate_bounds_peak_in_partial_draws), TEST(test_estimate_bounds_peak_in_draws),
             TEST(test_estimate_grows),
             TEST(test_estimate_covers_the_fill))
