/*
 * test_segment_invariance.c: ps_segment's answer does not hang on what
 * should not matter: rotation, translation, uniform scaling (by a power
 * of two far from 1 too, exactly), the points' order, the thread count,
 * duplicated points, and (but for a few points) exact or approximate
 * centrality; scans far apart come out apart.
 */
#include "pointseg.h"
#include "result_checks.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void check_invariant(double angle, double scale) {
    size_t n;
    double *pts = ps_shape_hand(0, &n, NULL);
    ps_result *a = ps_segment_default(pts, n);
    const double t[3] = {3.5 * scale, -20.0 * scale, 7.25 * scale};
    ps_shape_transform(pts, n, 0.3, -0.5, 0.81, angle, scale, t);
    ps_result *b = ps_segment_default(pts, n);
    REQUIRE(a && b);
    CHECK_MSG(a->n_segments == b->n_segments, "segments %d vs %d (angle %g, scale %g)",
              a->n_segments, b->n_segments, angle, scale);
    double d = ps_moved_share(a, b->labels, n);
    CHECK_MSG(d <= 0.005, "%.4f of the points changed segment (angle %g, scale %g)", d, angle,
              scale);
    ps_result_free(a);
    ps_result_free(b);
    free(pts);
}

static void test_rotation_translation(void) { check_invariant(1.1, 1.0); }
static void test_scale_small(void) { check_invariant(0.0, 0.001); }
static void test_scale_large(void) { check_invariant(2.5, 1000.0); }

/* The hand scaled by each 2^exponents[i] comes out as it is (#n points,
 * labels and f of *ref), labels alike and f scaled exactly. */
static void check_power_of_two_scales(const double *pts, size_t n, const ps_params *p,
                                      const ps_result *ref, const int *exponents, int count) {
    double *scaled = malloc(n * 3 * sizeof *scaled);
    REQUIRE(scaled);
    for (int i = 0; i < count; i++) {
        for (size_t j = 0; j < 3 * n; j++) scaled[j] = ldexp(pts[j], exponents[i]);
        ps_result *r = ps_segment_with(scaled, n, p);
        REQUIRE(r);
        ps_check_result_consistent(r);
        size_t moved = 0, f_off = 0;
        for (size_t j = 0; j < n; j++) {
            moved += r->labels[j] != ref->labels[j];
            f_off += r->centrality[j] != ldexp(ref->centrality[j], exponents[i]);
        }
        CHECK_MSG(r->n_segments == ref->n_segments && moved == 0 && f_off == 0,
                  "%s, 2^%d: %d segments (%d unscaled), %zu labels and %zu f moved",
                  ps_method_name(p->method), exponents[i], r->n_segments, ref->n_segments, moved,
                  f_off);
        ps_result_free(r);
    }
    free(scaled);
}

/* Scaled by a power of two far from 1 the hand is segmented as it is:
 * at 2^-60 the PCA stopped at an absolute tolerance and labels moved, at
 * 2^-600 squared distances underflowed to 0 (239 segments), at 2^450
 * single-precision distances overflowed (input_scale.h). */
static void test_scale_extreme(void) {
    const int exponents[] = {-60, -600, 450};
    size_t n;
    double *pts = ps_shape_hand(0, &n, NULL);
    ps_params p;
    ps_params_default(&p);
    for (int method = 0; method < 2; method++) {
        p.method = method ? PS_METHOD_PAPER : PS_METHOD_AUTO;
        ps_result *ref = ps_segment_with(pts, n, &p);
        REQUIRE(ref && ref->n_segments > 1);
        check_power_of_two_scales(pts, n, &p, ref, exponents, 3);
        ps_result_free(ref);
    }
    free(pts);
}

/* A shape far from the origin is judged by its own extent: the hand
 * 2^-50 across at 2^-10 (where the PCA's absolute tolerance stops its
 * sweeps unless the points are scaled up), and 2^40 across at 2^80 (an
 * ordinary extent, not to be scaled down to a speck), come out as the
 * hand does but for the translation's rounding. */
static void test_scale_far_from_origin(void) {
    const int scale_exponents[] = {-50, 40};
    const double offsets[][3] = {{0x1p-10, 0x1p-10, 0x1p-10}, {0x1p80, 0x1p80, 0x1p80}};
    size_t n;
    double *pts = ps_shape_hand(0, &n, NULL), *moved_pts = malloc(n * 3 * sizeof *moved_pts);
    REQUIRE(pts && moved_pts);
    ps_result *ref = ps_segment_default(pts, n);
    REQUIRE(ref && ref->n_segments > 1);
    for (int c = 0; c < 2; c++) {
        for (size_t j = 0; j < 3 * n; j++)
            moved_pts[j] = ldexp(pts[j], scale_exponents[c]) + offsets[c][j % 3];
        ps_result *r = ps_segment_default(moved_pts, n);
        REQUIRE(r);
        double moved = ps_moved_share(ref, r->labels, n);
        CHECK_MSG(r->n_segments == ref->n_segments && moved <= 0.01,
                  "2^%d across, far from the origin: %d segments (%d), %.4f of the labels moved",
                  scale_exponents[c], r->n_segments, ref->n_segments, moved);
        ps_result_free(r);
    }
    ps_result_free(ref);
    free(moved_pts);
    free(pts);
}

static void test_permutation(void) {
    size_t n;
    double *pts = ps_shape_star(0, &n, NULL);
    double *perm_pts = malloc(n * 3 * sizeof *perm_pts);
    size_t *perm = malloc(n * sizeof *perm);
    for (size_t i = 0; i < n; i++) perm[i] = i;
    unsigned s = 12345;
    for (size_t i = n - 1; i > 0; i--) {
        s = s * 1103515245u + 12345u;
        size_t j = (s >> 8) % (i + 1), tmp = perm[i];
        perm[i] = perm[j], perm[j] = tmp;
    }
    for (size_t i = 0; i < n; i++) memcpy(perm_pts + 3 * i, pts + 3 * perm[i], 3 * sizeof(double));
    ps_result *a = ps_segment_default(pts, n), *b = ps_segment_default(perm_pts, n);
    REQUIRE(a && b);
    int *b_in_a_order = malloc(n * sizeof *b_in_a_order);
    for (size_t i = 0; i < n; i++) b_in_a_order[perm[i]] = b->labels[i];
    CHECK(a->n_segments == b->n_segments);
    double d = ps_moved_share(a, b_in_a_order, n);
    CHECK_MSG(d <= 0.005, "%.4f of the points changed segment", d);
    free(b_in_a_order);
    ps_result_free(a);
    ps_result_free(b);
    free(perm);
    free(perm_pts);
    free(pts);
}

static void check_same_for_threads(ps_centrality_mode mode) {
    size_t n;
    double *pts = ps_shape_hand(0, &n, NULL);
    ps_params p;
    ps_params_default(&p);
    p.centrality = mode;
    p.threads = 1;
    ps_result *one = ps_segment_with(pts, n, &p);
    for (int threads = 2; threads <= 3; threads++) {
        p.threads = threads;
        ps_result *many = ps_segment_with(pts, n, &p);
        REQUIRE(one && many);
        CHECK(memcmp(one->labels, many->labels, n * sizeof *one->labels) == 0);
        CHECK(memcmp(one->centrality, many->centrality, n * sizeof(double)) == 0);
        ps_result_free(many);
    }
    ps_result_free(one);
    free(pts);
}

/* At most 10% of the n points in another label between exact and approx
 * (best overlap of each exact label). */
static void check_overlap(const char *what, size_t shape, int *exact, int n_exact,
                          const int *approx, size_t n) {
    ps_result as_labels;
    memset(&as_labels, 0, sizeof as_labels);
    as_labels.labels = exact;
    as_labels.n_segments = n_exact;
    double d = ps_moved_share(&as_labels, approx, n);
    CHECK_MSG(d <= 0.10, "shape %zu: %.3f of the points in another of the %s", shape, d, what);
}

/* Exact and approximate centrality give the same answer on small shapes:
 * the same number of segments, and at most 10% of the points elsewhere in
 * the segments and in the supernodes.  The supernodes' number is not
 * compared: the crease split leaves pieces of a few points (3 to 70 on the
 * dumbbell) whose number moves with the saddle levels, and the merges fold
 * them into the same segments. */
static void test_exact_approx_agree(void) {
    double *(*const shapes[])(double, size_t *, int **) = {ps_shape_star, ps_shape_dumbbell};
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
        size_t n;
        double *pts = shapes[k](0, &n, NULL);
        ps_params p;
        ps_params_default(&p);
        p.centrality = PS_CENTRALITY_EXACT;
        ps_result *exact = ps_segment_with(pts, n, &p);
        p.centrality = PS_CENTRALITY_APPROX;
        ps_result *approx = ps_segment_with(pts, n, &p);
        REQUIRE(exact && approx);
        CHECK_MSG(exact->n_segments == approx->n_segments, "shape %zu: %d vs %d segments", k,
                  exact->n_segments, approx->n_segments);
        check_overlap("segments", k, exact->labels, exact->n_segments, approx->labels, n);
        check_overlap("supernodes", k, exact->point_supernode, exact->n_supernodes,
                      approx->point_supernode, n);
        ps_result_free(exact);
        ps_result_free(approx);
        free(pts);
    }
}

static void test_threads_exact(void) { check_same_for_threads(PS_CENTRALITY_EXACT); }
static void test_threads_approx(void) { check_same_for_threads(PS_CENTRALITY_APPROX); }

static void test_duplicates_share_labels(void) {
    size_t n;
    double *pts = ps_shape_dumbbell(0, &n, NULL);
    size_t m = n + n / 2;
    double *dup = malloc(m * 3 * sizeof *dup);
    memcpy(dup, pts, n * 3 * sizeof *dup);
    for (size_t i = n; i < m; i++) memcpy(dup + 3 * i, pts + 3 * ((i - n) * 2), 3 * sizeof *dup);
    ps_result *a = ps_segment_default(pts, n), *b = ps_segment_default(dup, m);
    REQUIRE(a && b);
    ps_check_result_consistent(b);
    for (size_t i = n; i < m; i++) CHECK(b->labels[i] == b->labels[(i - n) * 2]);
    CHECK(a->n_segments == b->n_segments);
    ps_result_free(a);
    ps_result_free(b);
    free(dup);
    free(pts);
}

static void test_disconnected_scans(void) {
    size_t n;
    double *sphere = ps_shape_sphere(0, &n, NULL);
    double *two = malloc(2 * n * 3 * sizeof *two);
    memcpy(two, sphere, n * 3 * sizeof *two);
    for (size_t i = 0; i < n; i++) {
        two[3 * (n + i)] = sphere[3 * i] + 50;
        two[3 * (n + i) + 1] = sphere[3 * i + 1];
        two[3 * (n + i) + 2] = sphere[3 * i + 2];
    }
    ps_result *r = ps_segment_default(two, 2 * n);
    REQUIRE(r);
    ps_check_result_consistent(r);
    CHECK(r->n_components == 2);
    CHECK_MSG(r->n_segments == 2, "%d segments", r->n_segments); /* each ball whole */
    int *side = calloc((size_t)r->n_segments, sizeof *side); /* bit 1: first, 2: second */
    for (size_t i = 0; i < 2 * n; i++) side[r->labels[i]] |= i < n ? 1 : 2;
    for (int s = 0; s < r->n_segments; s++) CHECK_MSG(side[s] != 3, "segment %d spans both", s);
    free(side);
    ps_result_free(r);
    free(two);
    free(sphere);
}

PS_TEST_MAIN(TEST(test_rotation_translation), TEST(test_scale_small), TEST(test_scale_large),
             TEST(test_scale_extreme), TEST(test_scale_far_from_origin),
             TEST(test_permutation), TEST(test_exact_approx_agree), TEST(test_threads_exact),
             TEST(test_threads_approx), TEST(test_duplicates_share_labels),
             TEST(test_disconnected_scans))
