/*
 * test_segment.c: ps_segment end to end on synthetic shapes with known parts:
 * the parts come out, the answer survives rotation, translation, uniform
 * scaling, permutation and any thread count, the result is self-consistent,
 * and bad input fails cleanly.
 */
#include "features/centrality.h"
#include "pointseg.h"
#include "progress_seen.h"
#include "result_checks.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static ps_result *segment_with(const double *pts, size_t n, const ps_params *p) {
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_result *r = NULL;
    ps_error err = {0};
    ps_status st = ps_segment(&in, p, NULL, &r, &err);
    CHECK_MSG(st == PS_OK, "ps_segment failed: %s", err.message);
    return r;
}

static ps_result *segment_default(const double *pts, size_t n) {
    ps_params p;
    ps_params_default(&p);
    return segment_with(pts, n, &p);
}


/* Segments a synthetic shape with params p and checks that its parts
 * first..last come out apart; frees pts and part.  Returns the result's
 * normal_smoothing. */
static int check_parts_with(double *pts, size_t n, int *part, int first, int last,
                            double min_purity, const ps_params *p) {
    if (!pts || !part) {
        CHECK(pts && part);
        return -1;
    }
    ps_result *r = segment_with(pts, n, p);
    int smoothing = r ? r->normal_smoothing : -1;
    CHECK(r != NULL);
    if (r) {
        ps_check_result_consistent(r);
        ps_check_parts_separate(r, part, first, last, min_purity);
    }
    ps_result_free(r);
    free(pts);
    free(part);
    return smoothing;
}

/* The same with the defaults. */
static int check_shape_parts(double *pts, size_t n, int *part, int first, int last,
                             double min_purity) {
    ps_params p;
    ps_params_default(&p);
    return check_parts_with(pts, n, part, first, last, min_purity, &p);
}

static void test_dumbbell_two_spheres(void) {
    size_t n;
    int *part;
    double *pts = ps_shape_dumbbell(0, &n, &part);
    check_shape_parts(pts, n, part, 1, 2, 0.9);
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
    ps_result *r = segment_default(pts, n);
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
    unsigned long long state = 88172645463325252ULL;
    for (size_t i = 0; pts && jitter > 0 && i < 3 * n; i++) {
        state ^= state << 13, state ^= state >> 7, state ^= state << 17;
        pts[i] += jitter * (2.0 * (double)(state >> 11) / 9007199254740992.0 - 1.0);
    }
    ps_params p;
    ps_params_default(&p);
    p.smooth_normals = smooth_normals;
    return check_parts_with(pts, n, part, 1, 6, purity, &p);
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

/* The next of a xorshift sequence, uniform in [0, 1). */
static double uniform_next(unsigned long long *state) {
    *state ^= *state << 13, *state ^= *state >> 7, *state ^= *state << 17;
    return (double)(*state >> 11) / 9007199254740992.0;
}

/* A flat hand in the plane z = 0: a unit disc (part 0) and five strips
 * (parts 1..5) fanning out from it, sampled uniformly. */
static double *flat_hand(size_t *n, int **part) {
    const size_t palm = 3000, finger = 500, total = palm + 5 * finger;
    double *pts = malloc(total * 3 * sizeof *pts);
    *part = malloc(total * sizeof **part);
    unsigned long long state = 2463534242ULL;
    size_t k = 0;
    while (pts && *part && k < total) {
        double u[2];
        for (int j = 0; j < 2; j++) u[j] = uniform_next(&state);
        int which = k < palm ? 0 : 1 + (int)((k - palm) / finger);
        double x = 2 * u[0] - 1, y = 2 * u[1] - 1;
        if (which == 0 && x * x + y * y > 1) continue;
        if (which > 0) {
            double a = 3.14159265358979 * (0.15 + 0.175 * (which - 1));
            double t = 0.9 + 1.7 * u[0], w = 0.24 * u[1] - 0.12;
            x = t * cos(a) - w * sin(a), y = t * sin(a) + w * cos(a);
        }
        pts[3 * k] = x, pts[3 * k + 1] = y, pts[3 * k + 2] = 0;
        (*part)[k++] = which;
    }
    *n = total;
    return pts;
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
    ps_result *r = segment_default(pts, kept);
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
    ps_result *clean = segment_default(pts, n), *r = segment_default(noisy, n + 10);
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
    ps_result *one = segment_with(noisy, n, &p);
    REQUIRE(one);
    CHECK(one->n_outliers == 4);
    for (int threads = 2; threads <= 3; threads++) {
        p.threads = threads;
        ps_result *many = segment_with(noisy, n, &p);
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
    double *pts = flat_hand(&n, &part);
    check_shape_parts(pts, n, part, 1, 5, 0.7);
}

/* n points drawn at random on a unit sphere centred at (cx, 0, 0), its z
 * stretched by `stretch` (an egg above 1), written to pts #n by 3. */
static void random_ball(double *pts, size_t n, double cx, double stretch,
                        unsigned long long seed) {
    for (size_t k = 0; k < n; k++) {
        double z = 2 * uniform_next(&seed) - 1, a = 6.283185307179586 * uniform_next(&seed);
        double r = sqrt(1 - z * z);
        pts[3 * k] = cx + r * cos(a), pts[3 * k + 1] = r * sin(a), pts[3 * k + 2] = stretch * z;
    }
}

/* Each merge names the step that made it: a ball's basins (no concave
 * edge) are joined by the crease merge, with method auto whole (5,000
 * points) or in a draw (60,000), and by the paper's feature merge with
 * method paper. */
static void test_merges_name_their_step(void) {
    const size_t counts[] = {5000, 60000};
    for (int i = 0; i < 2; i++) {
        double *pts = malloc(counts[i] * 3 * sizeof *pts);
        REQUIRE(pts);
        random_ball(pts, counts[i], 0, 1.0, 0x2545F4914F6CDD1DULL + (unsigned)i);
        ps_params p;
        ps_params_default(&p);
        for (int method = 0; method < 2; method++) {
            p.method = method ? PS_METHOD_PAPER : PS_METHOD_AUTO;
            ps_result *r = segment_with(pts, counts[i], &p);
            REQUIRE(r);
            ps_check_result_consistent(r);
            ps_step expected = method ? PS_STEP_FEATURE_MERGE : PS_STEP_CREASE_MERGE;
            int named = 0;
            for (int m = 0; m < r->n_merges; m++) named += r->merges[m].step == expected;
            CHECK_MSG(r->n_merges > 0 && named > 0, "%zu points, %s: %d merges, %d by %s",
                      counts[i], ps_method_name(p.method), r->n_merges, named,
                      ps_step_name(expected));
            ps_result_free(r);
        }
        free(pts);
    }
}

/* A ball has no parts, however it is sampled: no concave edge, and f is
 * flat, its basins the sampling's noise (it came out in 8 to 20 segments). */
static void test_ball_is_one_part(void) {
    const size_t counts[] = {500, 5000, 20000};
    const double stretches[] = {1.0, 1.0, 1.6};
    for (int i = 0; i < 3; i++) {
        double *pts = malloc(counts[i] * 3 * sizeof *pts);
        REQUIRE(pts);
        random_ball(pts, counts[i], 0, stretches[i], 88172645463325252ULL + (unsigned)i);
        ps_result *r = segment_default(pts, counts[i]);
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
    ps_result *r = segment_default(pts, n);
    REQUIRE(r);
    CHECK_MSG(r->n_segments == 1, "a stratified sphere of %zu points: %d segments", n,
              r->n_segments);
    ps_result_free(r);
    free(pts);
}

/* Two balls apart are two parts, each whole. */
static void test_two_balls_two_parts(void) {
    const size_t big = 10000, small = 5000;
    double *pts = malloc((big + small) * 3 * sizeof *pts);
    int *part = malloc((big + small) * sizeof *part);
    REQUIRE(pts && part);
    random_ball(pts, big, 0, 1.0, 2463534242ULL);
    random_ball(pts + 3 * big, small, 4.0, 1.0, 1181783497276652981ULL);
    for (size_t k = 0; k < big + small; k++) part[k] = k >= big;
    ps_result *r = segment_default(pts, big + small);
    REQUIRE(r);
    CHECK_MSG(r->n_segments == 2, "%d segments", r->n_segments);
    ps_check_parts_separate(r, part, 0, 1, 1.0);
    ps_result_free(r);
    free(pts);
    free(part);
}

/* A plus-shaped sheet (arms 2 wide reaching `reach` from the centre) bent
 * round a cylinder of radius 3: an open surface with no concave edge,
 * whose parts are its outline's.  Part 0 the centre square, 1..4 the
 * arms. */
static double *bent_plus(double reach, size_t *n, int **part) {
    const size_t total = 20000;
    double *pts = malloc(total * 3 * sizeof *pts);
    *part = malloc(total * sizeof **part);
    unsigned long long state = 0x9E3779B97F4A7C15ULL;
    size_t k = 0;
    while (pts && *part && k < total) {
        double u = reach * (2 * uniform_next(&state) - 1);
        double v = reach * (2 * uniform_next(&state) - 1);
        if (fabs(u) >= 1 && fabs(v) >= 1) continue;
        int arm = fabs(u) < 1 && fabs(v) < 1 ? 0 : fabs(u) >= 1 ? (u > 0 ? 1 : 2) : (v > 0 ? 3 : 4);
        pts[3 * k] = 3 * sin(u / 3), pts[3 * k + 1] = v, pts[3 * k + 2] = 3 * cos(u / 3);
        (*part)[k++] = arm;
    }
    *n = total;
    return pts;
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
        double *pts = bent_plus(reaches[i], &n, &part);
        check_shape_parts(pts, n, part, 1, 4, 0.7);
    }
}

/* n points drawn at random on a sheet without parts, by `kind`: 0 a
 * square, 1 a disc, 2 a hemisphere (a cap, open at its rim). */
static double *plain_sheet(int kind, size_t n) {
    double *pts = malloc(n * 3 * sizeof *pts);
    unsigned long long state = 0x2545F4914F6CDD1DULL + (unsigned)kind;
    for (size_t k = 0; pts && k < n;) {
        double x = 2 * uniform_next(&state) - 1, y = 2 * uniform_next(&state) - 1;
        double r2 = x * x + y * y;
        if (kind > 0 && r2 >= 1) continue;
        double z = 0;
        if (kind == 2) { /* the disc lifted onto the cap, area-preserving (Lambert) */
            double s = sqrt(2 - r2);
            x *= s, y *= s, z = 1 - r2;
        }
        pts[3 * k] = x, pts[3 * k + 1] = y, pts[3 * k + 2] = z, k++;
    }
    return pts;
}

/* A square sheet, a disc and a hemisphere have no parts: their corners
 * and rims are f's maxima, but nothing sticks out (a square came out in
 * 5 segments, a disc and a cap in 3). */
/* Checks that the default makes one segment of the #n by 3 points (and
 * frees them). */
static void check_one_part(double *pts, size_t n, const char *name) {
    REQUIRE(pts);
    ps_result *r = segment_default(pts, n);
    REQUIRE(r);
    CHECK_MSG(r->n_segments == 1, "%s: %d segments", name, r->n_segments);
    ps_result_free(r);
    free(pts);
}

static void test_plain_sheets_one_part(void) {
    const char *names[] = {"square", "disc", "hemisphere"};
    for (int kind = 0; kind < 3; kind++)
        check_one_part(plain_sheet(kind, 10000), 10000, names[kind]);
}

/* n points drawn at random, uniform by area, on the closed surface of an
 * a by b by c box (its six sides). */
static double *random_box(double a, double b, double c, size_t n, unsigned long long seed) {
    double *pts = malloc(n * 3 * sizeof *pts);
    const double side[3] = {a * b, a * c, b * c}, total = 2 * (side[0] + side[1] + side[2]);
    for (size_t k = 0; pts && k < n; k++) {
        double pick = total * uniform_next(&seed), u = uniform_next(&seed), v = uniform_next(&seed);
        int face = 0;
        while (face < 5 && pick > side[face / 2]) pick -= side[face / 2], face++;
        double far = face % 2 ? 1 : 0, *p = pts + 3 * k;
        if (face < 2) p[0] = u * a, p[1] = v * b, p[2] = far * c;
        else if (face < 4) p[0] = u * a, p[1] = far * b, p[2] = v * c;
        else p[0] = far * a, p[1] = u * b, p[2] = v * c;
    }
    return pts;
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
        check_one_part(random_box(sizes[s][0], sizes[s][1], sizes[s][2], 40000, seed), 40000,
                       names[s]);
}

/* A standard normal number (Box-Muller over uniform_next). */
static double gaussian_next(unsigned long long *state) {
    double u = 1 - uniform_next(state); /* in (0, 1] */
    return sqrt(-2 * log(u)) * cos(6.283185307179586 * uniform_next(state));
}

/* Noisy scans of shapes without parts stay one part: a ball and a square
 * with noise of about half their point spacing (the noise made concave
 * edges everywhere, and they came out in 10 and 8 segments).  The
 * default smooths the estimated normals as the measured noise asks
 * (normals_smooth.h), and says so in the result. */
static void test_noisy_plain_shapes_one_part(void) {
    const size_t n = 10000;
    double *ball = malloc(n * 3 * sizeof *ball), *square = plain_sheet(0, n);
    REQUIRE(ball && square);
    random_ball(ball, n, 0, 1.0, 0x9E3779B97F4A7C15ULL);
    unsigned long long state = 7;
    for (size_t i = 0; i < n; i++) { /* spacings about 0.035 and 0.02 */
        for (int d = 0; d < 3; d++) ball[3 * i + d] += 0.02 * gaussian_next(&state);
        square[3 * i + 2] += 0.01 * gaussian_next(&state);
    }
    double *shapes[] = {ball, square};
    const char *names[] = {"ball", "square"};
    for (int s = 0; s < 2; s++) {
        ps_result *r = segment_default(shapes[s], n);
        REQUIRE(r);
        CHECK_MSG(r->normal_smoothing > 0, "%s: normals not smoothed", names[s]);
        CHECK_MSG(r->n_segments == 1, "%s: %d segments", names[s], r->n_segments);
        ps_result_free(r);
    }
    free(ball);
    free(square);
}

/* A flat hand scanned with noise across its plane of a quarter of its
 * point spacing keeps its palm apart from its fingers and its fingers
 * apart from each other.  It came out as one segment: the noise creased
 * every boundary, so the crease merge merged none, and the patch merge,
 * for which every piece of a flat hand is flat, folded them all into the
 * palm.  Now a crease must stand out of the noise (PS_CREASE_MERGE_NOISE
 * times the median crease strength) and a flat piece that sticks out
 * stays; a finger may still come out in two pieces. */
static void test_noisy_flat_hand_keeps_its_fingers(void) {
    size_t n;
    int *part;
    double *pts = flat_hand(&n, &part);
    REQUIRE(pts && part);
    unsigned long long state = 1;
    for (size_t i = 0; i < n; i++) pts[3 * i + 2] += 0.008 * gaussian_next(&state);
    check_hand(pts, n, part, 0.4, 0.9);
}

/* 2-D points are segmented as the plane z = 0 in 3-D (method auto): the
 * same labels as the flat 3-D copy, the caller's dimension in the result,
 * a square one part (its corners came out as 4 more) and a flat hand's
 * fingers apart. */
static void test_2d_points_as_a_flat_surface(void) {
    size_t n;
    int *part;
    double *flat = flat_hand(&n, &part);
    REQUIRE(flat && part);
    double *plane = malloc(n * 2 * sizeof *plane);
    REQUIRE(plane);
    for (size_t i = 0; i < n; i++) plane[2 * i] = flat[3 * i], plane[2 * i + 1] = flat[3 * i + 1];
    ps_params p;
    ps_params_default(&p);
    ps_input in = {.points = plane, .n = n, .dim = 2};
    ps_result *r = NULL, *r3 = segment_default(flat, n);
    ps_error err = {0};
    REQUIRE(ps_segment(&in, &p, NULL, &r, &err) == PS_OK && r3);
    CHECK(r->dim == 2 && r3->dim == 3);
    CHECK(r->n_segments == r3->n_segments &&
          memcmp(r->labels, r3->labels, n * sizeof *r->labels) == 0);
    ps_check_parts_separate(r, part, 1, 5, 0.7);
    ps_result_free(r), ps_result_free(r3);
    double *square = plain_sheet(0, 10000);
    REQUIRE(square);
    for (size_t i = 0; i < 10000; i++)
        square[2 * i] = square[3 * i], square[2 * i + 1] = square[3 * i + 1];
    in = (ps_input){.points = square, .n = 10000, .dim = 2};
    REQUIRE(ps_segment(&in, &p, NULL, &r, &err) == PS_OK);
    CHECK_MSG(r->n_segments == 1, "a 2-D square: %d segments", r->n_segments);
    ps_result_free(r);
    free(square), free(plane), free(flat), free(part);
}

/* Fraction of points whose label differs from b's after mapping each label
 * of a to the label of b most of its points carry. */
static double disagreement(const ps_result *a, const int *labels_b, size_t n) {
    int na = a->n_segments, nb = 0;
    for (size_t i = 0; i < n; i++)
        if (labels_b[i] + 1 > nb) nb = labels_b[i] + 1;
    int *table = calloc((size_t)na * (size_t)nb, sizeof *table);
    for (size_t i = 0; i < n; i++) table[a->labels[i] * nb + labels_b[i]]++;
    size_t agree = 0;
    for (int s = 0; s < na; s++) {
        int best = 0;
        for (int t = 0; t < nb; t++)
            if (table[s * nb + t] > best) best = table[s * nb + t];
        agree += (size_t)best;
    }
    free(table);
    return 1.0 - (double)agree / (double)n;
}

static void check_invariant(double angle, double scale) {
    size_t n;
    double *pts = ps_shape_hand(0, &n, NULL);
    ps_result *a = segment_default(pts, n);
    const double t[3] = {3.5 * scale, -20.0 * scale, 7.25 * scale};
    ps_shape_transform(pts, n, 0.3, -0.5, 0.81, angle, scale, t);
    ps_result *b = segment_default(pts, n);
    REQUIRE(a && b);
    CHECK_MSG(a->n_segments == b->n_segments, "segments %d vs %d (angle %g, scale %g)",
              a->n_segments, b->n_segments, angle, scale);
    double d = disagreement(a, b->labels, n);
    CHECK_MSG(d <= 0.005, "%.4f of the points changed segment (angle %g, scale %g)", d, angle,
              scale);
    ps_result_free(a);
    ps_result_free(b);
    free(pts);
}

static void test_rotation_translation(void) { check_invariant(1.1, 1.0); }
static void test_scale_small(void) { check_invariant(0.0, 0.001); }
static void test_scale_large(void) { check_invariant(2.5, 1000.0); }

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
    ps_result *a = segment_default(pts, n), *b = segment_default(perm_pts, n);
    REQUIRE(a && b);
    int *b_in_a_order = malloc(n * sizeof *b_in_a_order);
    for (size_t i = 0; i < n; i++) b_in_a_order[perm[i]] = b->labels[i];
    CHECK(a->n_segments == b->n_segments);
    double d = disagreement(a, b_in_a_order, n);
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
    ps_result *one = segment_with(pts, n, &p);
    for (int threads = 2; threads <= 3; threads++) {
        p.threads = threads;
        ps_result *many = segment_with(pts, n, &p);
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
    double d = disagreement(&as_labels, approx, n);
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
        ps_result *exact = segment_with(pts, n, &p);
        p.centrality = PS_CENTRALITY_APPROX;
        ps_result *approx = segment_with(pts, n, &p);
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
    ps_result *a = segment_default(pts, n), *b = segment_default(dup, m);
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
    ps_result *r = segment_default(two, 2 * n);
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

static void expect_invalid(const double *pts, size_t n, int dim, const char *what) {
    ps_input in = {.points = pts, .n = n, .dim = dim};
    ps_result *r = (ps_result *)1;
    ps_error err = {0};
    ps_status st = ps_segment(&in, NULL, NULL, &r, &err);
    CHECK_MSG(st == PS_ERR_INVALID, "%s: status %d", what, (int)st);
    CHECK(r == NULL);
    CHECK_MSG(strlen(err.message) > 0, "%s: no message", what);
}

static void test_bad_input(void) {
    double pts[3 * 20];
    for (int i = 0; i < 60; i++) pts[i] = (double)(i % 7) + i * 0.01;
    expect_invalid(NULL, 0, 3, "empty");
    expect_invalid(pts, 1, 3, "one point");
    expect_invalid(pts, 7, 3, "fewer than k+1");
    expect_invalid(pts, 10, 1, "dimension 1");
    double equal[3 * 20];
    for (int i = 0; i < 60; i++) equal[i] = 1.5;
    expect_invalid(equal, 20, 3, "all equal");
    pts[17] = NAN;
    expect_invalid(pts, 20, 3, "NaN");
    pts[17] = INFINITY;
    expect_invalid(pts, 20, 3, "Inf");
    pts[17] = 1.5e297; /* finite, but its square is not */
    expect_invalid(pts, 20, 3, "huge coordinate");
}

/* Every status has its own name, for messages. */
static void test_status_names(void) {
    const ps_status all[] = {PS_OK, PS_ERR_INVALID, PS_ERR_NOMEM, PS_ERR_CANCELLED,
                             PS_ERR_INTERNAL};
    const int n = (int)(sizeof all / sizeof all[0]);
    for (int i = 0; i < n; i++) {
        CHECK(strcmp(ps_status_name(all[i]), "unknown status") != 0);
        for (int j = 0; j < i; j++) CHECK(strcmp(ps_status_name(all[i]), ps_status_name(all[j])));
    }
    CHECK(strcmp(ps_status_name(PS_OK), "ok") == 0);
    CHECK(strcmp(ps_status_name(PS_ERR_NOMEM), "out of memory") == 0);
}

static int progress_calls, last_phase;
static void on_progress(void *user, ps_phase phase, double fraction) {
    (void)user;
    CHECK(fraction >= 0 && fraction <= 1);
    CHECK((int)phase >= last_phase);
    last_phase = (int)phase;
    progress_calls++;
}

/* The hand segmented with the default parameters (*a) and with method
 * paper (*paper, its parameters left in *p); the points. */
static double *hand_both_methods(size_t *n, ps_params *p, ps_result **a, ps_result **paper) {
    double *pts = ps_shape_hand(0, n, NULL);
    ps_params_default(p);
    *a = segment_with(pts, *n, p);
    p->method = PS_METHOD_PAPER;
    *paper = segment_with(pts, *n, p);
    return pts;
}

/* ncut_threshold 0 is the method's own: auto bisects down to single
 * supernodes, paper stops at PS_NCUT_PAPER exactly as when that is given. */
static void test_ncut_threshold_method_default(void) {
    size_t n;
    ps_params p;
    ps_result *a, *paper;
    double *pts = hand_both_methods(&n, &p, &a, &paper);
    p.ncut_threshold = PS_NCUT_PAPER;
    ps_result *paper_given = segment_with(pts, n, &p);
    REQUIRE(a && paper && paper_given);
    CHECK(a->params.ncut_threshold == PS_NCUT_NEVER_STOP);
    for (int t = 0; t < a->n_tree_nodes; t++)
        if (a->tree[t].children[0] < 0) CHECK(a->tree[t].n_supernodes == 1);
    CHECK(paper->params.ncut_threshold == PS_NCUT_PAPER);
    CHECK(paper->n_tree_nodes == paper_given->n_tree_nodes);
    CHECK(paper->n_tree_nodes < 2 * paper->n_supernodes - 1);
    CHECK(memcmp(paper->labels, paper_given->labels, n * sizeof *paper->labels) == 0);
    ps_result_free(a);
    ps_result_free(paper);
    ps_result_free(paper_given);
    free(pts);
}

static void test_progress_and_cancel(void) {
    size_t n;
    double *pts = ps_shape_sphere(0, &n, NULL);
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_control ctl = {.progress = on_progress};
    ps_result *r = NULL;
    ps_error err;
    last_phase = 0;
    CHECK(ps_segment(&in, NULL, &ctl, &r, &err) == PS_OK);
    CHECK(progress_calls >= 2 * PS_PHASE_COUNT);
    CHECK(last_phase == PS_PHASE_REFINE);
    ps_result_free(r);
    volatile int cancel = 1;
    ctl.cancel = &cancel;
    CHECK(ps_segment(&in, NULL, &ctl, &r, &err) == PS_ERR_CANCELLED);
    CHECK(r == NULL);
    free(pts);
}

/* A scan big enough for the two-level centrality: every phase reports
 * progress more than once between its start (0) and end (1), never
 * backwards, so a long job shows motion within each phase. */
static void test_progress_moves_within_phases(void) {
    size_t n;
    double *pts = ps_shape_star(780.0, &n, NULL);
    REQUIRE(pts && n > PS_COARSE_MIN_POINTS);
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_progress_seen m = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &m};
    ps_result *r = NULL;
    ps_error err;
    CHECK(ps_segment(&in, NULL, &ctl, &r, &err) == PS_OK);
    for (int p = 0; p < PS_PHASE_COUNT; p++)
        CHECK_MSG(m.inside[p] >= 2, "%s: %d fractions inside (0, 1)", ps_phase_name(p),
                  m.inside[p]);
    CHECK(!m.went_back);
    ps_result_free(r);
    free(pts);
}

/* The steps in the order they run, each with a name of its own, phases
 * nondecreasing; a run times the steps its method calls for and only
 * those (auto in 3-D: the crease-aware ones; paper: the paper's), and a
 * phase's steps take no longer than the phase. */
static void test_steps_named_and_timed(void) {
    for (int s = 0; s < PS_STEP_COUNT; s++) {
        CHECK(strcmp(ps_step_name((ps_step)s), "unknown") != 0);
        for (int t = 0; t < s; t++)
            CHECK(strcmp(ps_step_name((ps_step)s), ps_step_name((ps_step)t)) != 0);
        if (s > 0) CHECK(ps_step_phase((ps_step)s) >= ps_step_phase((ps_step)(s - 1)));
    }
    CHECK(ps_step_phase(PS_STEP_BOUNDARY_CUT) == PS_PHASE_REFINE);
    size_t n;
    ps_params p;
    ps_result *a, *paper;
    double *pts = hand_both_methods(&n, &p, &a, &paper);
    REQUIRE(a && paper);
    CHECK(a->timings.step_ms[PS_STEP_BOUNDARY_CUT] > 0 && a->timings.step_ms[PS_STEP_NORMALS] > 0);
    CHECK(a->timings.step_ms[PS_STEP_PATCH_MERGE] > 0 && a->timings.step_ms[PS_STEP_F2_SPLIT] == 0);
    CHECK(paper->timings.step_ms[PS_STEP_KNN_GRAPH] > 0);
    CHECK(paper->timings.step_ms[PS_STEP_NCUT] > 0);
    CHECK(paper->timings.step_ms[PS_STEP_OUTLIERS] == 0);
    CHECK(paper->timings.step_ms[PS_STEP_CREASE_SPLIT] == 0);
    CHECK(paper->timings.step_ms[PS_STEP_BOUNDARY_CUT] == 0);
    for (int ph = 0; ph < PS_PHASE_COUNT; ph++) {
        double sum = 0;
        for (int s = 0; s < PS_STEP_COUNT; s++)
            if ((int)ps_step_phase((ps_step)s) == ph) sum += a->timings.step_ms[s];
        CHECK_MSG(sum <= a->timings.ms[ph] + 1e-9, "phase %d: steps %g ms, phase %g ms", ph, sum,
                  a->timings.ms[ph]);
    }
    ps_result_free(a);
    ps_result_free(paper);
    free(pts);
}

PS_TEST_MAIN(TEST(test_dumbbell_two_spheres), TEST(test_hand_five_fingers),
             TEST(test_hand_scanned_from_one_side), TEST(test_stray_points_left_out), TEST(test_threads_with_strays), TEST(test_star_six_arms), TEST(test_star_with_noise), TEST(test_star_dense), TEST(test_star_with_heavy_noise), TEST(test_flat_hand_in_3d), TEST(test_ball_is_one_part), TEST(test_merges_name_their_step), TEST(test_two_balls_two_parts), TEST(test_bent_sheet_keeps_its_arms), TEST(test_plain_sheets_one_part), TEST(test_long_solids_one_part), TEST(test_noisy_plain_shapes_one_part),
             TEST(test_noisy_flat_hand_keeps_its_fingers), TEST(test_2d_points_as_a_flat_surface),
             TEST(test_rotation_translation), TEST(test_scale_small),
             TEST(test_scale_large), TEST(test_permutation), TEST(test_exact_approx_agree),
             TEST(test_threads_exact),
             TEST(test_threads_approx), TEST(test_duplicates_share_labels),
             TEST(test_disconnected_scans), TEST(test_bad_input), TEST(test_status_names),
             TEST(test_ncut_threshold_method_default), TEST(test_progress_and_cancel),
             TEST(test_progress_moves_within_phases), TEST(test_steps_named_and_timed))
