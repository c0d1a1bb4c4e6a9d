/*
 * test_normals_smooth.c: the noise estimate's median, the iterations it
 * asks for, the iterations a density asks for, and the smoothing itself
 * (whole and fractional iterations, any thread count) on a hand-made graph
 * (normals_smooth.h).
 */
#include "features/normals_smooth.h"
#include "hand_graph.h"
#include "testlib.h"

#include <math.h>
#include <string.h>

static void test_median(void) {
    ps_noise_estimate e;
    memset(&e, 0, sizeof e);
    CHECK(ps_noise_median(&e) == 0);
    const double ratios[] = {0.30, 0.02, 0.18, 5.0, 0.19};
    for (int i = 0; i < 5; i++) ps_noise_add(&e, ratios[i]);
    CHECK_NEAR(ps_noise_median(&e), 0.19, 1.0 / PS_NOISE_BINS); /* of 0.02 0.18 0.19 0.30 5 */
    CHECK(e.counts[PS_NOISE_BINS - 1] == 1); /* 5.0 lands in the last bin */
}

static void test_iterations(void) {
    CHECK(ps_noise_iterations(0) == 0);
    CHECK(ps_noise_iterations(PS_NOISE_FLOOR) == 0);
    CHECK(ps_noise_iterations(NAN) == 0);
    CHECK(ps_noise_iterations(PS_NOISE_FLOOR + 2 * PS_NOISE_STEP) == 2);
    CHECK(ps_noise_iterations(PS_NOISE_FLOOR + 3.4 * PS_NOISE_STEP) == 3);
    CHECK(ps_noise_iterations(1.0) == PS_SMOOTH_MAX);
    CHECK(ps_noise_clean(0) && ps_noise_clean(PS_NOISE_FLOOR) && ps_noise_clean(NAN));
    CHECK(!ps_noise_clean(PS_NOISE_FLOOR + PS_NOISE_STEP) && !ps_noise_clean(1.0));
}

/* A path 0 - 1 - 2 whose middle normal is tilted: one iteration pulls it
 * back towards its neighbours and keeps every normal unit; zero iterations
 * leave the normals as they were. */
static void test_smooth_path(void) {
    ps_hand_graph h;
    ps_hand_graph_path(&h, 3, 1.0, 0);
    const double s = sqrt(0.5);
    double normals[9] = {0, 0, 1, s, 0, s, 0, 0, 1}, before[9];
    memcpy(before, normals, sizeof normals);
    CHECK(ps_normals_smooth(&h.g, normals, 0, 1, NULL) == PS_OK);
    CHECK(memcmp(normals, before, sizeof normals) == 0);
    CHECK(ps_normals_smooth(&h.g, normals, 1, 1, NULL) == PS_OK);
    for (int p = 0; p < 3; p++)
        CHECK_NEAR(normals[3 * p] * normals[3 * p] + normals[3 * p + 1] * normals[3 * p + 1] +
                       normals[3 * p + 2] * normals[3 * p + 2], 1.0, 1e-12);
    CHECK(normals[5] > before[5]);             /* the tilted one turned up */
    CHECK_NEAR(normals[3], s / sqrt(s * s + (2 + s) * (2 + s)), 1e-12);
    CHECK(normals[0] > 0 && normals[6] > 0);   /* the ends lean towards it */
}

static void test_density_iterations(void) {
    CHECK(ps_density_iterations(0) == 0);
    CHECK(ps_density_iterations(PS_DENSITY_REFERENCE_POINTS) == 0);
    CHECK_NEAR(ps_density_iterations(2 * PS_DENSITY_REFERENCE_POINTS), 1.0, 1e-12);
    CHECK_NEAR(ps_density_iterations(3 * PS_DENSITY_REFERENCE_POINTS), 2.0, 1e-12);
    /* 2.5 times the reference, rounded down to whole points */
    CHECK_NEAR(ps_density_iterations(5 * PS_DENSITY_REFERENCE_POINTS / 2), 1.5, 1e-4);
    CHECK(ps_density_iterations(100 * (size_t)PS_DENSITY_REFERENCE_POINTS) == PS_SMOOTH_MAX);
}

/* The middle normal of a path after `iterations`, its first being tilted. */
static double middle_up_after(double iterations) {
    ps_hand_graph h;
    ps_hand_graph_path(&h, 3, 1.0, 0);
    const double s = sqrt(0.5);
    double normals[9] = {0, 0, 1, s, 0, s, 0, 0, 1};
    CHECK(ps_normals_smooth(&h.g, normals, iterations, 1, NULL) == PS_OK);
    CHECK_NEAR(normals[3] * normals[3] + normals[4] * normals[4] + normals[5] * normals[5], 1.0,
               1e-12);
    return normals[5];
}

/* A fractional iteration lands strictly between the whole ones around it
 * (the middle normal first turns up, then follows its neighbours, which
 * lean towards it), and a sliver of one changes next to nothing. */
static void test_fractional_iteration(void) {
    double none = middle_up_after(0), one = middle_up_after(1), two = middle_up_after(2);
    double half = middle_up_after(0.5), one_half = middle_up_after(1.5);
    CHECK(none < half && half < one);
    CHECK(two < one_half && one_half < one);
    CHECK_NEAR(middle_up_after(1 + 1e-9), one, 1e-8);
}

/* The same normals from one thread and from three, bit for bit, on a
 * path long enough to be split between them. */
static void test_threads_agree(void) {
    ps_hand_graph h;
    ps_hand_graph_path(&h, PS_HAND_GRAPH_MAX_V, 1.0, 0);
    double one[3 * PS_HAND_GRAPH_MAX_V], three[3 * PS_HAND_GRAPH_MAX_V];
    for (int p = 0; p < PS_HAND_GRAPH_MAX_V; p++) {
        double a = 0.7 * p;
        one[3 * p] = cos(a), one[3 * p + 1] = sin(a), one[3 * p + 2] = 0;
    }
    memcpy(three, one, sizeof one);
    CHECK(ps_normals_smooth(&h.g, one, 2.5, 1, NULL) == PS_OK);
    CHECK(ps_normals_smooth(&h.g, three, 2.5, 3, NULL) == PS_OK);
    CHECK(memcmp(one, three, sizeof one) == 0);
}

PS_TEST_MAIN(TEST(test_median), TEST(test_iterations), TEST(test_smooth_path),
             TEST(test_density_iterations), TEST(test_fractional_iteration),
             TEST(test_threads_agree))
