/*
 * test_normals_smooth.c: the noise estimate's median, the iterations it
 * asks for, and the smoothing itself on a hand-made graph (normals_smooth.h).
 */
#include "hand_graph.h"
#include "normals_smooth.h"
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
    CHECK(ps_normals_smooth(&h.g, normals, 0, NULL) == PS_OK);
    CHECK(memcmp(normals, before, sizeof normals) == 0);
    CHECK(ps_normals_smooth(&h.g, normals, 1, NULL) == PS_OK);
    for (int p = 0; p < 3; p++)
        CHECK_NEAR(normals[3 * p] * normals[3 * p] + normals[3 * p + 1] * normals[3 * p + 1] +
                       normals[3 * p + 2] * normals[3 * p + 2], 1.0, 1e-12);
    CHECK(normals[5] > before[5]);             /* the tilted one turned up */
    CHECK_NEAR(normals[3], s / sqrt(s * s + (2 + s) * (2 + s)), 1e-12);
    CHECK(normals[0] > 0 && normals[6] > 0);   /* the ends lean towards it */
}

PS_TEST_MAIN(TEST(test_median), TEST(test_iterations), TEST(test_smooth_path))
