/* test_crease.c: the convexity test and the crease metric: an edge across
 * a concave valley grows, one across a convex ridge of the same angle or a
 * flat one does not; an edge whose test is 0 but for rounding is convex
 * however it is turned; on the star the edges where the arms meet the centre
 * (a known concave crease) come out much longer than the rest; the
 * weights and strengths do not depend on the thread count; a flat grid
 * keeps its weights bit for bit; the median strength is the strengths'
 * middle. */
#include "features/crease.h"
#include "star_fixture.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Three separate unit edges: 0-1 across a valley, 2-3 across a ridge, 4-5
 * flat. */
static void test_valley_ridge_flat(void) {
    const double r = sqrt(0.5);
    const double pts[18] = {-0.5, 0, 0.5, 0.5, 0, 0.5, -0.5, 0, -0.5,
                            0.5,  0, -0.5, 0, 0, 0,     1,   0, 0};
    const double nrm[18] = {r, 0, r, -r, 0, r, -r, 0, r, r, 0, r, 0, 0, 1, 0, 0, 1};
    size_t off[7] = {0, 1, 2, 3, 4, 5, 6};
    uint32_t nbr[6] = {1, 0, 3, 2, 5, 4};
    double w[6] = {1, 1, 1, 1, 1, 1};
    ps_graph g = {6, off, nbr, w};
    REQUIRE(ps_crease_weights(&g, pts, nrm, 1, NULL, NULL, NULL) == PS_OK);
    CHECK(w[0] == w[1] && w[2] == w[3] && w[4] == w[5]);
    CHECK_MSG(w[0] > 1.5 * w[2], "valley %g, ridge %g", w[0], w[2]);
    CHECK_NEAR(w[2], w[4], 1e-12); /* convex edges weigh no more than flat */
    CHECK(w[4] > 0);
}

/* Mean length of edges crossing the arm/centre boundary over the mean of
 * the others, with the crease metric divided by the same ratio without. */
static void test_star_crease_edges_grow(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    ps_graph *g = &s.graph;
    double ratio[2];
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            REQUIRE(ps_crease_weights(g, s.points, s.normals, 0, NULL, NULL, NULL) == PS_OK);
        double cross = 0, rest = 0;
        size_t n_cross = 0, n_rest = 0;
        for (size_t p = 0; p < s.n; p++)
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
                int at_crease = s.part[p] != s.part[g->neighbors[e]];
                if (at_crease) cross += g->weights[e], n_cross++;
                else rest += g->weights[e], n_rest++;
            }
        REQUIRE(n_cross > 0 && n_rest > 0);
        ratio[pass] = (cross / (double)n_cross) / (rest / (double)n_rest);
    }
    CHECK_MSG(ratio[1] > 2 * ratio[0], "crease edges %.2fx the rest with the metric, %.2fx without",
              ratio[1], ratio[0]);
    ps_star_free(&s);
}

/* Weights, strengths and spacings are bit-identical on 1 and 3 threads, on
 * a star dense enough for several of crease.c's blocks of 4,096 points; a
 * spacing is the mean Euclidean length of the point's edges. */
static void test_same_for_any_threads(void) {
    ps_star s;
    REQUIRE(ps_star_build_dense(&s, 250));
    REQUIRE(s.n > 2 * 4096);
    size_t arcs = s.graph.offsets[s.n];
    double *base = malloc(arcs * sizeof *base), *weights[2], *strength[2], *spacing[2], mean[2];
    REQUIRE(base != NULL);
    memcpy(base, s.graph.weights, arcs * sizeof *base);
    int threads[2] = {1, 3};
    for (int t = 0; t < 2; t++) {
        weights[t] = malloc(arcs * sizeof *weights[t]);
        strength[t] = malloc(s.n * sizeof *strength[t]);
        spacing[t] = malloc(s.n * sizeof *spacing[t]);
        REQUIRE(weights[t] && strength[t] && spacing[t]);
        memcpy(s.graph.weights, base, arcs * sizeof *base);
        ps_crease_points cp = {.strength = strength[t]};
        REQUIRE(ps_crease_strengths(&s.graph, s.points, s.normals, threads[t], &cp, NULL) ==
                PS_OK);
        REQUIRE(ps_crease_weights(&s.graph, s.points, s.normals, threads[t], NULL, spacing[t],
                                  NULL) == PS_OK);
        memcpy(weights[t], s.graph.weights, arcs * sizeof *base);
        mean[t] = cp.mean;
    }
    CHECK(mean[0] > 0 && mean[0] == mean[1]);
    CHECK(memcmp(weights[0], weights[1], arcs * sizeof *base) == 0);
    CHECK(memcmp(strength[0], strength[1], s.n * sizeof *strength[0]) == 0);
    CHECK(memcmp(spacing[0], spacing[1], s.n * sizeof *spacing[0]) == 0);
    CHECK(memcmp(weights[0], base, arcs * sizeof *base) != 0);
    for (size_t p = 0; p < s.n; p += 97) {
        double sum = 0;
        for (size_t e = s.graph.offsets[p]; e < s.graph.offsets[p + 1]; e++) sum += base[e];
        CHECK(spacing[0][p] == sum / (double)(s.graph.offsets[p + 1] - s.graph.offsets[p]));
    }
    for (int t = 0; t < 2; t++) free(weights[t]), free(strength[t]), free(spacing[t]);
    free(base);
    ps_star_free(&s);
}

/* The median strength is the middle of the sorted strengths (the lower
 * middle for an even count, 0 for none), taken on a copy; on the star,
 * whose arms meet its centre in creases, it lies between them: at least
 * half the points at or under it, at least half at or over it. */
static void test_median_strength(void) {
    double strength[6] = {5, 1, 4, 2, 3, 0.5};
    ps_crease_points cp = {.strength = strength};
    REQUIRE(ps_crease_median(5, &cp, NULL) == PS_OK);
    CHECK(cp.median == 3);
    REQUIRE(ps_crease_median(6, &cp, NULL) == PS_OK);
    CHECK(cp.median == 2);
    CHECK(strength[0] == 5 && strength[5] == 0.5);
    REQUIRE(ps_crease_median(0, &cp, NULL) == PS_OK);
    CHECK(cp.median == 0);
    ps_star s;
    REQUIRE(ps_star_build(&s));
    ps_crease_points star = {.strength = malloc(s.n * sizeof(double))};
    REQUIRE(star.strength);
    REQUIRE(ps_crease_strengths(&s.graph, s.points, s.normals, 1, &star, NULL) == PS_OK);
    size_t under = 0, over = 0;
    for (size_t p = 0; p < s.n; p++) under += star.strength[p] <= star.median,
                                       over += star.strength[p] >= star.median;
    CHECK(2 * under >= s.n && 2 * over >= s.n);
    CHECK(star.median < star.mean);
    free(star.strength);
    ps_star_free(&s);
}

/* Rotates v by angle a about z, then b about x. */
static void turn(const double *v, double a, double b, double *out) {
    double x = cos(a) * v[0] - sin(a) * v[1], y = sin(a) * v[0] + cos(a) * v[1];
    out[0] = x, out[1] = cos(b) * y - sin(b) * v[2], out[2] = sin(b) * y + cos(b) * v[2];
}

/* Two points side by side on the two faces of a thin slab: normals
 * opposite, the edge across them perpendicular, so (n_q - n_p) . (q - p)
 * is 0 but for rounding.  Turned many ways, the edge is never concave (its
 * sign used to follow the rounding); a valley as gentle as 1e-6 still is. */
static void test_slab_sign_is_no_rounding(void) {
    const double p0[3] = {0, 0, 0}, q0[3] = {1, 0, 0}, up[3] = {0, 0, 1}, down[3] = {0, 0, -1};
    const double lean = 1e-6, in_l[3] = {lean, 0, 1}, in_r[3] = {-lean, 0, 1};
    int concave = 0, valleys = 0;
    for (int i = 0; i < 200; i++) {
        double a = 0.1 + 0.37 * i, b = 0.2 + 0.53 * i, p[3], q[3], np[3], nq[3], nl[3], nr[3];
        turn(p0, a, b, p), turn(q0, a, b, q), turn(up, a, b, np), turn(down, a, b, nq);
        concave += ps_crease_angular(p, np, q, nq, 0.0) > 0;
        turn(in_l, a, b, nl), turn(in_r, a, b, nr);
        valleys += ps_crease_angular(p, nl, q, nr, 0.0) > 0;
    }
    CHECK_MSG(concave == 0, "%d of 200 turned slab edges concave", concave);
    CHECK_MSG(valleys == 200, "%d of 200 turned gentle valleys concave", valleys);
}

/* A 40 by 40 grid in a tilted plane, every normal the plane's: no crease
 * anywhere, and the weights stay the kNN graph's lengths bit for bit. */
static void test_flat_keeps_lengths(void) {
    enum { SIDE = 40, N = SIDE * SIDE };
    static double points[3 * N], normals[3 * N];
    const double r = sqrt(0.5);
    for (int i = 0; i < N; i++) {
        double x = 0.1 * (i % SIDE) + 0.003 * (i % 7), y = 0.1 * (i / SIDE);
        points[3 * i] = x, points[3 * i + 1] = r * y, points[3 * i + 2] = r * y;
        normals[3 * i] = 0, normals[3 * i + 1] = -r, normals[3 * i + 2] = r;
    }
    ps_graph g = {0};
    REQUIRE(ps_knn_graph_build(points, N, 3, 7, 1, &g, NULL) == PS_OK);
    size_t arcs = g.offsets[N];
    double *lengths = malloc(arcs * sizeof *lengths);
    REQUIRE(lengths != NULL);
    memcpy(lengths, g.weights, arcs * sizeof *lengths);
    ps_edge_scales scales;
    REQUIRE(ps_crease_weights(&g, points, normals, 2, &scales, NULL, NULL) == PS_OK);
    CHECK(scales.mean_concave < PS_CREASE_FLAT);
    CHECK(memcmp(lengths, g.weights, arcs * sizeof *lengths) == 0);
    free(lengths);
    ps_graph_free(&g);
}

/* The crease scale counts the smoothing against noise: clean normals
 * take all of it, normals smoothed once against noise the rest, twice or
 * more none; noisy normals left unsmoothed none. */
static void test_crease_scale_counts_noise_smoothing(void) {
    CHECK(ps_crease_scale_iterations(0, 0) == PS_CREASE_SCALE_SMOOTHING);
    CHECK(ps_crease_scale_iterations(1, 0) == 0);
    CHECK(ps_crease_scale_iterations(1, 1) == PS_CREASE_SCALE_SMOOTHING - 1);
    CHECK(ps_crease_scale_iterations(1, PS_CREASE_SCALE_SMOOTHING) == 0);
    CHECK(ps_crease_scale_iterations(1, 8) == 0);
}

PS_TEST_MAIN(TEST(test_valley_ridge_flat), TEST(test_slab_sign_is_no_rounding),
             TEST(test_star_crease_edges_grow),
             TEST(test_same_for_any_threads), TEST(test_flat_keeps_lengths),
             TEST(test_crease_scale_counts_noise_smoothing), TEST(test_median_strength))
