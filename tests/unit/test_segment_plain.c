/*
 * test_segment_plain.c: ps_segment end to end on shapes without parts (a
 * ball, an egg, plain sheets, long boxes, noisy scans of a ball and a
 * sheet): each comes out as one segment.
 */
#include "pointseg.h"
#include "random_bits.h"
#include "random_shapes.h"
#include "result_checks.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>

/* A ball has no parts, however it is sampled: no concave edge, and f is
 * flat, its basins the sampling's noise (it came out in 8 to 20 segments). */
static void test_ball_is_one_part(void) {
    const size_t counts[] = {500, 5000, 20000};
    const double stretches[] = {1.0, 1.0, 1.6};
    for (int i = 0; i < 3; i++) {
        double *pts = malloc(counts[i] * 3 * sizeof *pts);
        REQUIRE(pts);
        ps_random_ball(pts, counts[i], 0, stretches[i], 88172645463325252ULL + (unsigned)i);
        ps_result *r = ps_segment_default(pts, counts[i]);
        REQUIRE(r);
        ps_check_result_consistent(r);
        CHECK_MSG(r->n_segments == 1, "%zu points, stretch %g: %d segments", counts[i],
                  stretches[i], r->n_segments);
        ps_result_free(r);
        free(pts);
    }
    size_t n;
    double *pts = ps_shape_sphere(1000.0, &n, NULL);
    REQUIRE(pts);
    const double t[3] = {-4.0, 2.0, 9.0};
    ps_shape_transform(pts, n, 0.2, 1.0, -0.4, 0.9, 37.0, t);
    ps_result *r = ps_segment_default(pts, n);
    REQUIRE(r);
    CHECK_MSG(r->n_segments == 1, "a stratified sphere of %zu points: %d segments", n,
              r->n_segments);
    ps_result_free(r);
    free(pts);
}

/* A square sheet, a disc and a hemisphere have no parts: their corners
 * and rims are f's maxima, but nothing sticks out (a square came out in
 * 5 segments, a disc and a cap in 3). */
static void test_plain_sheets_one_part(void) {
    const char *names[] = {"square", "disc", "hemisphere"};
    for (int kind = 0; kind < 3; kind++)
        ps_check_one_part(ps_plain_sheet(kind, 10000), 10000, names[kind]);
}

/* Long plain solids have no parts: a beam 12 by 1 by 1 and a board 24 by
 * 3 by 0.3 came out in 2 and 3 pieces across their length.  Each piece
 * sticks out of the next (crease_merge.h), and their union, convex, failed
 * the convex merge's test by a coin flip on the pairs that share a flat
 * side (convex_merge.h, PS_CONVEX_MERGE_TOLERANCE). */
static void test_long_solids_one_part(void) {
    const double sizes[2][3] = {{12, 1, 1}, {24, 3, 0.3}};
    const char *names[] = {"beam", "board"};
    const unsigned long long seed = 0x853C49E6748FEA9BULL;
    for (int s = 0; s < 2; s++)
        ps_check_one_part(ps_random_box(sizes[s][0], sizes[s][1], sizes[s][2], 40000, seed), 40000,
                          names[s]);
}

/* Noisy scans of plain solids stay one part: with noise of a sixth of
 * their point spacing the board here came out in 3 pieces (other samplings
 * split a beam in 3 and a cube in 2), the kNN normals leaning by several
 * degrees where the convex merge asks about one; it reads patch normals
 * (patch_normal.h). */
static void test_noisy_solids_one_part(void) {
    const double sizes[3][3] = {{12, 1, 1}, {24, 3, 0.3}, {2, 2, 2}};
    const char *names[] = {"noisy beam", "noisy board", "noisy cube"};
    const size_t n = 40000;
    uint64_t state = 0x5DEECE66DULL;
    for (int s = 0; s < 3; s++) {
        const double *d = sizes[s];
        double area = 2 * (d[0] * d[1] + d[0] * d[2] + d[1] * d[2]);
        double sigma = sqrt(area / (double)n) / 6;
        double *pts = ps_random_box(d[0], d[1], d[2], n, 0x853C49E6748FEA9BULL + (uint64_t)s);
        REQUIRE(pts);
        for (size_t i = 0; i < 3 * n; i++) pts[i] += sigma * ps_gaussian_next(&state);
        ps_check_one_part(pts, n, names[s]);
    }
}

/* Noisy scans of shapes without parts stay one part: a ball and a square
 * with noise of about half their point spacing (the noise made concave
 * edges everywhere, and they came out in 10 and 8 segments).  The
 * default smooths the estimated normals as the measured noise asks
 * (normals_smooth.h), and says so in the result. */
static void test_noisy_plain_shapes_one_part(void) {
    const size_t n = 10000;
    double *ball = malloc(n * 3 * sizeof *ball), *square = ps_plain_sheet(0, n);
    REQUIRE(ball && square);
    ps_random_ball(ball, n, 0, 1.0, 0x9E3779B97F4A7C15ULL);
    uint64_t state = 7;
    for (size_t i = 0; i < n; i++) { /* spacings about 0.035 and 0.02 */
        for (int d = 0; d < 3; d++) ball[3 * i + d] += 0.02 * ps_gaussian_next(&state);
        square[3 * i + 2] += 0.01 * ps_gaussian_next(&state);
    }
    double *shapes[] = {ball, square};
    const char *names[] = {"ball", "square"};
    for (int s = 0; s < 2; s++) {
        ps_result *r = ps_segment_default(shapes[s], n);
        REQUIRE(r);
        CHECK_MSG(r->normal_smoothing > 0, "%s: normals not smoothed", names[s]);
        CHECK_MSG(r->n_segments == 1, "%s: %d segments", names[s], r->n_segments);
        ps_result_free(r);
    }
    free(ball);
    free(square);
}

PS_TEST_MAIN(TEST(test_ball_is_one_part), TEST(test_plain_sheets_one_part),
             TEST(test_long_solids_one_part), TEST(test_noisy_solids_one_part),
             TEST(test_noisy_plain_shapes_one_part))
