/* test_mesh_seen.c: what the benchmarks' scans see of a mesh (mesh_seen.h),
 * on a closed 2 by 1.5 by 1 box: six views see all of it and nothing
 * inside; the front view (from the high end of the shortest axis, z) sees
 * the top and hides the bottom and the sides below their rim; samples of
 * the seen part lie on it and repeat for the same seed. */
#include "mesh_seen.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SAMPLES 20000
#define RIM 0.01 /* the depth slack of two pixels (2 / PS_SEEN_PIXELS) and some */

/* The box [0, 2] x [0, 1.5] x [0, 1], its six sides as twelve triangles. */
static ps_pointset box(double *points, uint32_t *faces) {
    for (int c = 0; c < 8; c++) {
        points[3 * c] = c & 1 ? 2 : 0;
        points[3 * c + 1] = c & 2 ? 1.5 : 0;
        points[3 * c + 2] = c & 4 ? 1 : 0;
    }
    static const uint32_t sides[36] = {0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6,  /* z = 0, 1 */
                                       0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6,  /* y = 0, 1.5 */
                                       0, 2, 6, 0, 6, 4, 1, 3, 7, 1, 7, 5}; /* x = 0, 2 */
    memcpy(faces, sides, sizeof sides);
    return (ps_pointset){.points = points, .n = 8, .dim = 3, .faces = faces, .n_faces = 12};
}

static void test_six_views_see_the_outside_only(void) {
    double corners[24];
    uint32_t faces[36];
    ps_pointset mesh = box(corners, faces);
    ps_seen *six = ps_seen_build(&mesh, PS_SEEN_SIX);
    REQUIRE(six);
    unsigned char seen[8];
    ps_seen_flags(six, corners, 8, seen);
    int all = 1;
    for (int c = 0; c < 8; c++) all &= seen[c];
    CHECK(all);
    double *samples = NULL;
    REQUIRE(ps_seen_sample(six, SAMPLES, 3, &samples) == 0);
    free(samples);
    const double inside[6] = {1, 0.75, 0.5, 0.2, 0.2, 0.2};
    ps_seen_flags(six, inside, 2, seen);
    CHECK(!seen[0] && !seen[1]);
    ps_seen_free(six);
}

static void test_front_view_sees_the_top(void) {
    double corners[24];
    uint32_t faces[36];
    ps_pointset mesh = box(corners, faces);
    unsigned front = ps_mesh_front_view(&mesh);
    CHECK_MSG(front == 1u << 4, "front view bit %u", front);
    const double probes[12] = {1, 0.75, 1, 1, 0.75, 0, 0, 0.75, 0.5, 1, 0, 0.5};
    ps_seen *view = ps_seen_build(&mesh, front);
    REQUIRE(view);
    unsigned char seen[4];
    ps_seen_flags(view, probes, 4, seen);
    CHECK_MSG(seen[0] && !seen[1] && !seen[2] && !seen[3], "top %d bottom %d sides %d %d",
              seen[0], seen[1], seen[2], seen[3]);
    double *a = NULL, *b = NULL;
    REQUIRE(ps_seen_sample(view, SAMPLES, 5, &a) == 0);
    REQUIRE(ps_seen_sample(view, SAMPLES, 5, &b) == 0);
    CHECK(memcmp(a, b, 3 * SAMPLES * sizeof *a) == 0);
    int on_top = 1;
    for (size_t i = 0; i < SAMPLES; i++) on_top &= a[3 * i + 2] > 1 - RIM;
    CHECK(on_top);
    free(a), free(b);
    ps_seen_free(view);
}

static void test_no_faces(void) {
    double corners[24];
    uint32_t faces[36];
    ps_pointset mesh = box(corners, faces);
    mesh.n_faces = 0;
    ps_seen *six = ps_seen_build(&mesh, PS_SEEN_SIX);
    REQUIRE(six);
    double *out = corners;
    CHECK(ps_seen_sample(six, 10, 1, &out) == -1 && out == NULL);
    ps_seen_free(six);
}

PS_TEST_MAIN(TEST(test_six_views_see_the_outside_only), TEST(test_front_view_sees_the_top),
             TEST(test_no_faces))
