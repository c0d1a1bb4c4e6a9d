/* test_memory_estimate.c: ps_segment_memory_estimate is an upper estimate
 * that is not wasteful: a child process segments a dumbbell a little
 * denser than the reference sampling (one draw), a 100,000-point one in
 * one run (method paper) and in three draws leaving points out (auto),
 * a 250,000-point one in five draws covering it, and an unwelded sphere
 * mesh over the reference whose distinct points are under it (filled),
 * and its peak RSS (wait4's usage of that child) must lie between half
 * the estimate and the estimate; the estimate grows with n, k and the
 * sample count, and below the reference sampling covers a mesh segmented
 * in fills up to it but a bare point set's one run.  Skipped under AddressSanitizer, whose shadow memory
 * is no part of the model. */
#define _DEFAULT_SOURCE /* wait4 */
#include "graph/reference_density.h"
#include "pointseg.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
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

/* Peak RSS in bytes of a child segmenting in, or 0 when it failed. */
static size_t child_peak_rss(const ps_input *in, const ps_params *params) {
    pid_t pid = fork();
    if (pid == 0) {
        ps_params p = *params;
        ps_result *r = NULL;
        _exit(ps_segment(in, &p, NULL, &r, NULL) == PS_OK ? 0 : 1);
    }
    int status = 0;
    struct rusage ru;
    if (pid < 0 || wait4(pid, &status, 0, &ru) != pid || !WIFEXITED(status) || WEXITSTATUS(status))
        return 0;
    return (size_t)ru.ru_maxrss * 1024; /* Linux: kilobytes */
}

/* The child's peak RSS segmenting in with method lies between half the
 * estimate and the estimate. */
static void check_bounds(const ps_input *in, ps_method method) {
    ps_params p;
    ps_params_default(&p);
    p.method = method;
    size_t estimate = ps_segment_memory_estimate(in, &p), measured = child_peak_rss(in, &p);
    REQUIRE(measured > 0);
    CHECK_MSG(measured <= estimate && estimate <= 2 * measured,
              "%zu points: peak RSS %zu MB, estimate %zu MB", in->n, measured >> 20, estimate >> 20);
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
    check_bounds(&(ps_input){.points = pts, .n = n, .dim = 3}, method);
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

/* The corners of an unwelded UV sphere (rings x segments distinct
 * points), each triangle with its own three copies: #P = #F * 3. */
static double *unwelded_sphere(int rings, int segments, size_t *n, uint32_t **faces,
                               size_t *n_faces) {
    *n_faces = 2 * (size_t)(rings - 1) * (size_t)segments;
    *n = 3 * *n_faces;
    double *pts = malloc(3 * *n * sizeof *pts);
    *faces = malloc(*n * sizeof **faces);
    if (!pts || !*faces) return free(pts), free(*faces), NULL;
    size_t p = 0;
    for (int i = 0; i + 1 < rings; i++)
        for (int j = 0; j < segments; j++) {
            const int corner[6][2] = {{i, j},     {i + 1, j},     {i + 1, j + 1},
                                      {i, j},     {i + 1, j + 1}, {i, j + 1}};
            for (int c = 0; c < 6; c++, p++) {
                double theta = M_PI * (corner[c][0] + 0.5) / rings,
                       phi = 2 * M_PI * (corner[c][1] % segments) / segments;
                pts[3 * p] = sin(theta) * cos(phi), pts[3 * p + 1] = sin(theta) * sin(phi);
                pts[3 * p + 2] = cos(theta);
                (*faces)[p] = (uint32_t)p;
            }
        }
    return pts;
}

/* An unwelded mesh over the reference sampling whose distinct points are
 * under it is deduplicated and filled three times: the estimate covers
 * the fills, not only the one run its point count would take. */
static void test_estimate_bounds_peak_of_unwelded_mesh(void) {
    if (UNDER_ASAN) SKIP("under AddressSanitizer the peak RSS includes its shadow memory");
    size_t n, n_faces;
    uint32_t *faces;
    double *pts = unwelded_sphere(40, 120, &n, &faces, &n_faces);
    REQUIRE(pts && n > PS_DENSITY_REFERENCE_POINTS);
    ps_input in = {.points = pts, .n = n, .dim = 3, .faces = faces, .n_faces = n_faces};
    check_bounds(&in, PS_METHOD_AUTO);
    ps_params p;
    ps_params_default(&p);
    ps_input bare = {.n = n, .dim = 3};
    CHECK(ps_segment_memory_estimate(&in, &p) > ps_segment_memory_estimate(&bare, &p));
    free(pts);
    free(faces);
}

/* The estimate for n points of dim coordinates without faces. */
static size_t bare_estimate(size_t n, int dim, const ps_params *p) {
    return ps_segment_memory_estimate(&(ps_input){.n = n, .dim = dim}, p);
}

static void test_estimate_grows(void) {
    ps_params p, more_k, more_samples;
    ps_params_default(&p);
    more_k = more_samples = p;
    more_k.k = 14;
    more_samples.samples = 4000;
    size_t base = bare_estimate(1000000, 3, &p);
    CHECK(bare_estimate(2000000, 3, &p) > base);
    CHECK(bare_estimate(1000000, 3, &more_k) > base);
    CHECK(bare_estimate(1000000, 3, &more_samples) > base);
    CHECK(bare_estimate(1000000, 2, &p) > base); /* auto: a 3-D copy */
}

/* The estimate for a mesh of n points of dim coordinates (the estimate
 * reads the face count, not the faces). */
static size_t mesh_estimate(size_t n, int dim, const ps_params *p) {
    return ps_segment_memory_estimate(&(ps_input){.n = n, .dim = dim, .n_faces = n}, p);
}

/* A small mesh may be segmented in fills up to the reference sampling:
 * below it the estimate is that of the fills, more than one run at the
 * reference, but with exact centrality (no fills); a bare point set is
 * never filled. */
static void test_estimate_covers_the_fill(void) {
    ps_params p, exact;
    ps_params_default(&p);
    exact = p;
    exact.centrality = PS_CENTRALITY_EXACT;
    size_t ref = PS_DENSITY_REFERENCE_POINTS;
    CHECK(mesh_estimate(100, 3, &p) == mesh_estimate(ref - 1, 3, &p));
    CHECK(mesh_estimate(100, 3, &p) > bare_estimate(ref, 3, &p));
    CHECK(mesh_estimate(100, 3, &exact) < bare_estimate(ref, 3, &exact));
    CHECK(bare_estimate(ref - 1, 3, &p) < bare_estimate(ref, 3, &p));
    CHECK(bare_estimate(ref - 1, 3, &p) < mesh_estimate(ref - 1, 3, &p));
}

/* A bare point set under the reference sampling runs once, unfilled: its
 * estimate bounds that run's peak without being twice it. */
static void test_estimate_bounds_peak_of_small_bare_set(void) {
    if (UNDER_ASAN) SKIP("under AddressSanitizer the peak RSS includes its shadow memory");
    check_bounds_measured_peak(PS_DENSITY_REFERENCE_POINTS * 0.75, PS_METHOD_AUTO);
}

/* Points of extreme extent are segmented as a scaled copy (input_scale.h):
 * the estimate counts it when it is given the points. */
static void test_estimate_counts_the_scaled_copy(void) {
    enum { N = 50000 };
    double *pts = malloc(3 * N * sizeof *pts);
    REQUIRE(pts);
    for (size_t i = 0; i < 3 * N; i++) pts[i] = (double)((i * 7919) % 1000) / 1000.0;
    ps_params p;
    ps_params_default(&p);
    ps_input in = {.points = pts, .n = N, .dim = 3};
    size_t ordinary = ps_segment_memory_estimate(&in, &p);
    CHECK(ordinary == bare_estimate(N, 3, &p));
    for (size_t i = 0; i < 3 * N; i++) pts[i] *= 0x1p-40;
    CHECK(ps_segment_memory_estimate(&in, &p) == ordinary + 3 * N * sizeof(double));
    free(pts);
}

PS_TEST_MAIN(TEST(test_estimate_bounds_measured_peak),
             TEST(test_estimate_bounds_peak_in_partial_draws), TEST(test_estimate_bounds_peak_in_draws),
             TEST(test_estimate_bounds_peak_of_unwelded_mesh), TEST(test_estimate_grows),
             TEST(test_estimate_covers_the_fill), TEST(test_estimate_bounds_peak_of_small_bare_set),
             TEST(test_estimate_counts_the_scaled_copy))
