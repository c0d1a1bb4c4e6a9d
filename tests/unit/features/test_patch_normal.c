/* test_patch_normal.c: on a noisy cube, patch normals lie within a degree
 * of their face's normal where the kNN normals lean by several, also next
 * to an edge (they keep to their own face), and keep the kNN normals'
 * sign; rows not asked for are left alone. */
#include "features/normals.h"
#include "features/patch_normal.h"
#include "graph/knn_graph.h"
#include "random_bits.h"
#include "random_shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define SIDE 2.0
#define N 20000

/* The outward normal of the cube's face nearest to x; the distance to the
 * nearest edge of that face through *edge. */
static void face_normal(const double *x, double n[3], double *edge) {
    double best = INFINITY;
    int axis = 0, sign = 1;
    for (int a = 0; a < 3; a++)
        for (int s = 0; s < 2; s++) {
            double d = s ? SIDE - x[a] : x[a];
            if (d < best) best = d, axis = a, sign = s ? 1 : -1;
        }
    *edge = INFINITY;
    for (int a = 0; a < 3; a++)
        if (a != axis) *edge = fmin(*edge, fmin(x[a], SIDE - x[a]));
    n[0] = n[1] = n[2] = 0, n[axis] = sign;
}

static double degrees(const double *u, const double *v) {
    double c = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    return acos(fmax(-1, fmin(1, c))) * 180 / 3.14159265358979323846;
}

static void test_noisy_cube(void) {
    double *pts = ps_random_box(SIDE, SIDE, SIDE, N, 0x2545F4914F6CDD1DULL);
    double *knn = malloc(3 * N * sizeof *knn), *patch = malloc(3 * N * sizeof *patch);
    uint32_t *ids = malloc(N * sizeof *ids);
    int *comp = malloc(N * sizeof *comp);
    REQUIRE(pts && knn && patch && ids && comp);
    double sigma = sqrt(6 * SIDE * SIDE / N) / 6;
    uint64_t state = 99;
    for (size_t i = 0; i < 3 * N; i++) pts[i] += sigma * ps_gaussian_next(&state);
    ps_graph g;
    REQUIRE(ps_knn_graph_build(pts, N, 3, 7, 1, &g, NULL) == PS_OK);
    int nc = ps_graph_components(&g, comp);
    ps_normals_input in = {.graph = &g, .points = pts, .component = comp, .n_components = nc};
    REQUIRE(ps_normals_build(&in, knn, NULL, NULL) == PS_OK);
    size_t m = 0;
    for (uint32_t p = 0; p < N; p += 2) ids[m++] = p;
    for (size_t i = 0; i < 3 * N; i++) patch[i] = NAN;
    REQUIRE(ps_patch_normals(&g, pts, knn, ids, m, patch, NULL) == PS_OK);
    double err_knn[2] = {0, 0}, err_patch[2] = {0, 0};
    size_t count[2] = {0, 0}, flipped = 0, untouched = 0;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + 3 * ids[i];
        double truth[3], edge;
        face_normal(x, truth, &edge);
        if (edge < 0.05 || (edge > 0.15 && edge < 0.4)) continue;
        int near = edge <= 0.15;
        err_knn[near] += degrees(knn + 3 * ids[i], truth);
        err_patch[near] += degrees(patch + 3 * ids[i], truth);
        count[near]++;
        flipped += degrees(patch + 3 * ids[i], knn + 3 * ids[i]) > 90;
    }
    for (uint32_t p = 1; p < N; p += 2) untouched += isnan(patch[3 * p]);
    for (int near = 0; near < 2; near++) {
        err_knn[near] /= (double)count[near], err_patch[near] /= (double)count[near];
        printf("  %s: kNN normals %.2f degrees off, patch normals %.2f (%zu points)\n",
               near ? "0.05 to 0.15 from an edge" : "inside a face", err_knn[near],
               err_patch[near], count[near]);
    }
    CHECK(count[0] > 1000 && count[1] > 500);
    CHECK_MSG(err_patch[0] < 1.0 && err_patch[0] < err_knn[0] / 3, "inside: %.2f against %.2f",
              err_patch[0], err_knn[0]);
    CHECK_MSG(err_patch[1] < 2.0 && err_patch[1] < err_knn[1] / 2, "near an edge: %.2f against %.2f",
              err_patch[1], err_knn[1]);
    CHECK(flipped == 0);
    CHECK(untouched == N / 2);
    ps_graph_free(&g);
    free(pts), free(knn), free(patch), free(ids), free(comp);
}

PS_TEST_MAIN(TEST(test_noisy_cube))
