/*
 * test_segment.c: ps_segment end to end on synthetic shapes with known
 * parts (a dumbbell, hands, stars, two balls, flat and bent sheets; clean,
 * noisy, scanned from one side, with stray points, in 2-D): the parts come
 * out in segments of their own and the result is self-consistent.  Shapes
 * without parts are test_segment_plain.c's, what must not change the
 * answer test_segment_invariance.c's, the interface test_segment_api.c's.
 */
#include "pointseg.h"
#include "random_bits.h"
#include "random_shapes.h"
#include "result_checks.h"
#include "shapes.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

static void test_dumbbell_two_spheres(void) {
    size_t n;
    int *part;
    double *pts = ps_shape_dumbbell(0, &n, &part);
    ps_check_shape_parts(pts, n, part, 1, 2, 0.9);
}

/* The segment holding most of the hand's palm (part 0) holds at least
 * min_purity of it and is no finger's (parts 1..5) majority segment. */
static void check_palm_apart(const ps_result *r, const int *part, double min_purity) {
    double palm_purity, finger_purity;
    int palm = ps_majority_label(r, part, 0, &palm_purity);
    CHECK_MSG(palm_purity >= min_purity, "palm: only %.2f of it in one segment", palm_purity);
    for (int finger = 1; finger <= 5; finger++)
        CHECK(ps_majority_label(r, part, finger, &finger_purity) != palm);
}

/* Segments a hand (part 0 the palm, 1..5 the fingers) with the defaults:
 * its fingers apart, each with finger_purity of it in one segment, and
 * its palm apart from them with palm_purity; frees pts and part. */
static void check_hand(double *pts, size_t n, int *part, double finger_purity,
                       double palm_purity) {
    REQUIRE(pts && part);
    ps_result *r = ps_segment_default(pts, n);
    REQUIRE(r);
    ps_check_result_consistent(r);
    ps_check_parts_separate(r, part, 1, 5, finger_purity);
    check_palm_apart(r, part, palm_purity);
    ps_result_free(r);
    free(pts);
    free(part);
}

/* The fingers come out whole and apart; the palm's far end is a maximum of
 * f of its own (like a wrist), so the palm may be two segments, but the
 * one holding most of it holds no finger. */
static void test_hand_five_fingers(void) {
    size_t n;
    int *part;
    double *pts = ps_shape_hand(0, &n, &part);
    check_hand(pts, n, part, 0.75, 0.45);
}

/* The star's six arms come out apart, each with at least `purity` of it in
 * one segment; the star is sampled at `density` (0: its default), every
 * coordinate is first jittered by up to `jitter` (a deterministic
 * pseudo-random sequence); smooth_normals as given.  Returns the normal
 * smoothing applied. */
static int check_star_arms(double density, double jitter, double purity, int smooth_normals) {
    size_t n;
    int *part;
    double *pts = ps_shape_star(density, &n, &part);
    uint64_t state = 88172645463325252ULL;
    for (size_t i = 0; pts && jitter > 0 && i < 3 * n; i++)
        pts[i] += jitter * (2.0 * ps_uniform_next(&state) - 1.0);
    ps_params p;
    ps_params_default(&p);
    p.smooth_normals = smooth_normals;
    return ps_check_parts_with(pts, n, part, 1, 6, purity, &p);
}

static void test_star_six_arms(void) { CHECK(check_star_arms(0, 0, 0.8, 1) == 0); }

/* A scan is never clean: jitter of 10% of an arm's radius (0.35), no
 * normals given; the default smooths the normals for it, and without
 * smoothing the arms come out as well. */
static void test_star_with_noise(void) {
    CHECK(check_star_arms(0, 0.035, 0.8, 1) > 0);
    CHECK(check_star_arms(0, 0.035, 0.8, 0) == 0);
}

/* About 100,000 points, 2.5 times the reference sampling whose normal scale
 * the crease steps use (normals_smooth.h): the normals are smoothed to it,
 * and the arms still come out whole and apart. */
static void test_star_dense(void) { CHECK(check_star_arms(1950, 0, 0.8, 0) == 0); }

/* 20%: the arms stay apart without smoothing (the crease split counts
 * only the strongest 45% of the points as crease points, crease_split.h;
 * before that cap an arm was cut in half, 0.47 of it in one segment) and
 * with it (normals_smooth.h), which says it smoothed.  The crease steps'
 * normals take no smoothing beyond the noise's own here
 * (ps_crease_scale_iterations, crease.h): with the crease scale's two
 * iterations on top, an arm was cut, 0.56 to 0.58 of it in one segment. */
static void test_star_with_heavy_noise(void) {
    CHECK(check_star_arms(0, 0.07, 0.7, 0) == 0);
    CHECK(check_star_arms(0, 0.07, 0.7, 1) > 0);
}

/* A scan from one side: only the hand's upper half (z > 0), every part
 * open underneath.  The palm stays a segment of its own, apart from every
 * finger: its normals all point up-ish (flatness 0.86, near the patch
 * merge's 0.9, patch_merge.h), and a patch larger than its neighbours
 * would stay anyway. */
static void test_hand_scanned_from_one_side(void) {
    size_t n, kept = 0;
    int *part;
    double *pts = ps_shape_hand(0, &n, &part);
    REQUIRE(pts && part);
    for (size_t i = 0; i < n; i++) {
        if (pts[3 * i + 2] <= 0) continue;
        memmove(pts + 3 * kept, pts + 3 * i, 3 * sizeof *pts);
        part[kept++] = part[i];
    }
    ps_result *r = ps_segment_default(pts, kept);
    REQUIRE(r);
    ps_check_result_consistent(r);
    check_palm_apart(r, part, 0.9);
    ps_result_free(r);
    free(pts);
    free(part);
}

/* Ten stray points between the star's arms, at least 2 away from any (a
 * scanner's outliers, outliers.h): they are left out, each takes a star
 * point's label, and the star's own labels are those of the clean star,
 * point for point. */
static void test_stray_points_left_out(void) {
    size_t n;
    int *part;
    double *pts = ps_shape_star(0, &n, &part);
    REQUIRE(pts && part);
    double *noisy = malloc((n + 10) * 3 * sizeof *noisy);
    REQUIRE(noisy);
    memcpy(noisy, pts, n * 3 * sizeof *pts);
    static const double strays[10][3] = {{2, 2, 2},  {2, 2, -2},  {2, -2, 2},  {2, -2, -2},
                                         {-2, 2, 2}, {-2, 2, -2}, {-2, -2, 2}, {-2, -2, -2},
                                         {2.5, 2.5, 0}, {0, -2.5, -2.5}};
    memcpy(noisy + 3 * n, strays, sizeof strays);
    ps_result *clean = ps_segment_default(pts, n), *r = ps_segment_default(noisy, n + 10);
    REQUIRE(clean && r);
    CHECK_MSG(r->n_outliers == 10, "%zu outliers", r->n_outliers);
    CHECK(clean->n_outliers == 0);
    CHECK(r->n_segments == clean->n_segments);
    CHECK(memcmp(r->labels, clean->labels, n * sizeof *r->labels) == 0);
    for (size_t i = n; i < n + 10; i++) CHECK(r->labels[i] >= 0 && r->labels[i] < r->n_segments);
    ps_check_result_consistent(r);
    ps_result_free(clean), ps_result_free(r);
    free(pts), free(part), free(noisy);
}

/* The same star with its strays on 1, 2 and 3 threads: the stray points
 * leave the kNN graph (knn_graph.h's prune) and the labels are the same. */
static void test_threads_with_strays(void) {
    size_t n;
    double *pts = ps_shape_star(0, &n, NULL);
    REQUIRE(pts);
    double *noisy = realloc(pts, (n + 4) * 3 * sizeof *noisy);
    REQUIRE(noisy);
    static const double strays[4][3] = {{2, 2, 2}, {-2, 2, -2}, {2, -2.5, 0}, {0, 2.5, -2.5}};
    memcpy(noisy + 3 * n, strays, sizeof strays);
    n += 4;
    ps_params p;
    ps_params_default(&p);
    p.threads = 1;
    ps_result *one = ps_segment_with(noisy, n, &p);
    REQUIRE(one);
    CHECK(one->n_outliers == 4);
    for (int threads = 2; threads <= 3; threads++) {
        p.threads = threads;
        ps_result *many = ps_segment_with(noisy, n, &p);
        REQUIRE(many);
        CHECK(many->n_outliers == 4);
        CHECK(memcmp(one->labels, many->labels, n * sizeof *one->labels) == 0);
        ps_result_free(many);
    }
    ps_result_free(one);
    free(noisy);
}

/* A flat surface has no creases: the crease steps leave it alone and the
 * fingers still come out apart (they used to merge into one segment). */
static void test_flat_hand_in_3d(void) {
    size_t n;
    int *part;
    double *pts = ps_flat_hand(&n, &part);
    ps_check_shape_parts(pts, n, part, 1, 5, 0.7);
}

/* Two balls apart are two parts, each whole. */
static void test_two_balls_two_parts(void) {
    const size_t big = 10000, small = 5000;
    double *pts = malloc((big + small) * 3 * sizeof *pts);
    int *part = malloc((big + small) * sizeof *part);
    REQUIRE(pts && part);
    ps_random_ball(pts, big, 0, 1.0, 2463534242ULL);
    ps_random_ball(pts + 3 * big, small, 4.0, 1.0, 1181783497276652981ULL);
    for (size_t k = 0; k < big + small; k++) part[k] = k >= big;
    ps_result *r = ps_segment_default(pts, big + small);
    REQUIRE(r);
    CHECK_MSG(r->n_segments == 2, "%d segments", r->n_segments);
    ps_check_parts_separate(r, part, 0, 1, 1.0);
    ps_result_free(r);
    free(pts);
    free(part);
}

/* The bent sheet keeps its four arms: on a surface without creases what
 * protrudes stays.  With arms reaching 4 each arm is larger than the
 * centre; the centre, holding the least f, is the core, and the arm
 * beside it is the part judged (crease_merge.h). */
static void test_bent_sheet_keeps_its_arms(void) {
    const double reaches[] = {3.0, 4.0};
    for (int i = 0; i < 2; i++) {
        size_t n;
        int *part;
        double *pts = ps_bent_plus(reaches[i], &n, &part);
        ps_check_shape_parts(pts, n, part, 1, 4, 0.7);
    }
}

/* A flat hand scanned with noise across its plane of a quarter of its
 * point spacing keeps its palm apart from its fingers and its fingers
 * apart from each other.  It came out as one segment: the noise creased
 * every boundary, so the crease merge merged none, and the patch merge,
 * for which every piece of a flat hand is flat, folded them all into the
 * palm.  Now a crease must stand out of the noise (PS_CREASE_MERGE_NOISE
 * times the median crease strength) and a flat piece that sticks out
 * stays; a finger may still come out in two pieces.  With normals
 * precise to a degree (patch_normal.h) every union of its pieces is
 * "convex", flat in each other's tangent planes: the convex merge asks
 * for depth (PS_CONVEX_MERGE_DEPTH), or it merged the fingers again. */
static void test_noisy_flat_hand_keeps_its_fingers(void) {
    size_t n;
    int *part;
    double *pts = ps_flat_hand(&n, &part);
    REQUIRE(pts && part);
    uint64_t state = 1;
    for (size_t i = 0; i < n; i++) pts[3 * i + 2] += 0.008 * ps_gaussian_next(&state);
    check_hand(pts, n, part, 0.4, 0.9);
}

/* 2-D points are segmented as the plane z = 0 in 3-D (method auto): the
 * same labels as the flat 3-D copy, the caller's dimension in the result,
 * a square one part (its corners came out as 4 more) and a flat hand's
 * fingers apart. */
static void test_2d_points_as_a_flat_surface(void) {
    size_t n;
    int *part;
    double *flat = ps_flat_hand(&n, &part);
    REQUIRE(flat && part);
    double *plane = malloc(n * 2 * sizeof *plane);
    REQUIRE(plane);
    for (size_t i = 0; i < n; i++) plane[2 * i] = flat[3 * i], plane[2 * i + 1] = flat[3 * i + 1];
    ps_params p;
    ps_params_default(&p);
    ps_input in = {.points = plane, .n = n, .dim = 2};
    ps_result *r = NULL, *r3 = ps_segment_default(flat, n);
    ps_error err = {0};
    REQUIRE(ps_segment(&in, &p, NULL, &r, &err) == PS_OK && r3);
    CHECK(r->dim == 2 && r3->dim == 3);
    CHECK(r->n_segments == r3->n_segments &&
          memcmp(r->labels, r3->labels, n * sizeof *r->labels) == 0);
    ps_check_parts_separate(r, part, 1, 5, 0.7);
    ps_result_free(r), ps_result_free(r3);
    double *square = ps_plain_sheet(0, 10000);
    REQUIRE(square);
    for (size_t i = 0; i < 10000; i++)
        square[2 * i] = square[3 * i], square[2 * i + 1] = square[3 * i + 1];
    in = (ps_input){.points = square, .n = 10000, .dim = 2};
    REQUIRE(ps_segment(&in, &p, NULL, &r, &err) == PS_OK);
    CHECK_MSG(r->n_segments == 1, "a 2-D square: %d segments", r->n_segments);
    ps_result_free(r);
    free(square), free(plane), free(flat), free(part);
}

PS_TEST_MAIN(TEST(test_dumbbell_two_spheres), TEST(test_hand_five_fingers),
             TEST(test_hand_scanned_from_one_side), TEST(test_stray_points_left_out),
             TEST(test_threads_with_strays), TEST(test_star_six_arms),
             TEST(test_star_with_noise), TEST(test_star_dense),
             TEST(test_star_with_heavy_noise), TEST(test_flat_hand_in_3d),
             TEST(test_two_balls_two_parts), TEST(test_bent_sheet_keeps_its_arms),
             TEST(test_noisy_flat_hand_keeps_its_fingers),
             TEST(test_2d_points_as_a_flat_surface))
