/* test_normals.c: PCA normals on a sphere come out unit and outward, given
 * normals that point inward are flipped outward and made unit whatever
 * their length, a shifted, rotated copy
 * keeps its orientation (also when its most extreme point lies on a thin
 * fin, whose normal is sideways), a bowl with a rounded rim seen from
 * above (open, where the divergence vote alone turns it inside out) comes
 * out pointing at the viewer, PCA's normals and a scanner's given ones
 * alike, and the normals of a noisy sphere are
 * smoothed close to the true ones; the PCA's thread count changes no
 * byte, and the tracked build reports progress and stops when cancelled. */
#include "features/normals.h"
#include "features/normals_smooth.h"
#include "graph/knn_graph.h"
#include "progress_seen.h"
#include "random_bits.h"
#include "random_shapes.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Fraction of points whose normal points away from centre c. */
static double outward_share(const double *pts, const double *nrm, size_t n, const double c[3]) {
    size_t out = 0;
    for (size_t p = 0; p < n; p++) {
        double d = 0;
        for (int i = 0; i < 3; i++) d += (pts[3 * p + i] - c[i]) * nrm[3 * p + i];
        out += d > 0;
    }
    return (double)out / (double)n;
}

/* *out: the oriented normals (#n by 3, malloc'ed; not smoothed; NULL on
 * failure) of #n by 3 points over their kNN graph (k = 7): PCA's, or the
 * #n by 3 given ones when not NULL; *n_components (may be NULL): the
 * graph's components. */
static void oriented_normals(const double *pts, size_t n, const double *given, double **out,
                             int *n_components) {
    *out = NULL;
    ps_graph g;
    REQUIRE(ps_knn_graph_build(pts, n, 3, 7, 1, &g, NULL) == PS_OK);
    int *comp = malloc(n * sizeof *comp);
    double *nrm = malloc(n * 3 * sizeof *nrm);
    REQUIRE(comp && nrm);
    int nc = ps_graph_components(&g, comp);
    ps_normals_input in = {.graph = &g, .points = pts, .given = given, .component = comp,
                           .n_components = nc};
    REQUIRE(ps_normals_build(&in, nrm, NULL, NULL) == PS_OK);
    if (n_components) *n_components = nc;
    ps_graph_free(&g);
    free(comp);
    *out = nrm;
}

static void check_sphere(double shift, double angle) {
    size_t n;
    double *pts = ps_shape_sphere(0, &n, NULL);
    const double t[3] = {shift, -2 * shift, 0.5 * shift};
    ps_shape_transform(pts, n, 0.2, 0.9, -0.4, angle, 3.0, t);
    ps_graph g;
    REQUIRE(ps_knn_graph_build(pts, n, 3, 7, 1, &g, NULL) == PS_OK);
    int *comp = malloc(n * sizeof *comp);
    int nc = ps_graph_components(&g, comp);
    double *nrm = malloc(n * 3 * sizeof *nrm);
    ps_normals_report report = {-1, -1};
    ps_normals_input in = {.graph = &g, .points = pts, .component = comp, .n_components = nc,
                           .smooth = 1};
    REQUIRE(ps_normals_build(&in, nrm, &report, NULL) == PS_OK);
    CHECK(report.smoothing == 0); /* a clean sphere is left as PCA made it */
    CHECK(report.noise >= 0 && report.noise <= PS_NOISE_FLOOR); /* and measures clean */
    for (size_t p = 0; p < n; p++)
        CHECK_NEAR(sqrt(nrm[3 * p] * nrm[3 * p] + nrm[3 * p + 1] * nrm[3 * p + 1] +
                        nrm[3 * p + 2] * nrm[3 * p + 2]), 1.0, 1e-9);
    double share = outward_share(pts, nrm, n, t);
    CHECK_MSG(share > 0.99, "only %.3f outward (shift %g, angle %g)", share, shift, angle);
    ps_graph_free(&g);
    free(pts), free(comp), free(nrm);
}

static void test_pca_sphere_outward(void) { check_sphere(0, 0); }
static void test_pca_moved_sphere_outward(void) { check_sphere(40, 2.2); }

/* The unit sphere and a flat fin of zero thickness in the plane y = 0
 * sticking out along +x to x = 2.5: the point of largest x is on the fin's
 * edge, where the normal is sideways.  *n_sphere: the sphere's points,
 * which come first. */
static double *sphere_with_fin(size_t *n, size_t *n_sphere) {
    double *sphere = ps_shape_sphere(0, n_sphere, NULL);
    const double step = 0.06;
    const int columns = 26, rows = 11;
    *n = *n_sphere + (size_t)(columns * rows);
    double *pts = realloc(sphere, *n * 3 * sizeof *pts);
    if (!pts) return free(sphere), NULL;
    double *fin = pts + 3 * *n_sphere;
    for (int i = 0; i < columns; i++)
        for (int j = 0; j < rows; j++, fin += 3)
            fin[0] = 1.0 + step * i, fin[1] = 0, fin[2] = step * (j - rows / 2);
    return pts;
}

static void test_fin_does_not_decide_the_sign(void) {
    for (int turn = 0; turn < 6; turn++) {
        size_t n, n_sphere;
        double *pts = sphere_with_fin(&n, &n_sphere);
        REQUIRE(pts);
        const double t[3] = {1, 2, 3}, angle = 0.3 + 0.6 * turn;
        ps_shape_transform(pts, n, 0.3, 0.5, 0.81, angle, 2.0, t);
        double *nrm;
        oriented_normals(pts, n, NULL, &nrm, NULL);
        REQUIRE(nrm);
        double share = outward_share(pts, nrm, n_sphere, t);
        CHECK_MSG(share > 0.99, "angle %g: only %.3f of the sphere outward", angle, share);
        free(pts), free(nrm);
    }
}

/* Given normals that point inward are flipped outward and made unit,
 * whatever their length: also one whose squared length overflows (1e300)
 * or underflows (1e-200), which came out zero and (1, 0, 0). */
static void test_given_inward_flipped(void) {
    const double lengths[] = {2, 1e300, 1e-200};
    size_t n;
    double *pts = ps_shape_sphere(0, &n, NULL);
    double *inward = malloc(n * 3 * sizeof *inward), *nrm = malloc(n * 3 * sizeof *nrm);
    ps_graph g;
    REQUIRE(ps_knn_graph_build(pts, n, 3, 7, 1, &g, NULL) == PS_OK);
    int *comp = calloc(n, sizeof *comp);
    for (int l = 0; l < 3; l++) {
        for (size_t i = 0; i < 3 * n; i++) inward[i] = -lengths[l] * pts[i];
        ps_normals_report report = {-1, -1};
        ps_normals_input in = {.graph = &g, .points = pts, .given = inward, .component = comp,
                               .n_components = 1, .smooth = 1};
        REQUIRE(ps_normals_build(&in, nrm, &report, NULL) == PS_OK);
        CHECK(report.smoothing == 0 && report.noise == 0); /* given normals: nothing measured */
        const double c[3] = {0, 0, 0};
        CHECK(outward_share(pts, nrm, n, c) == 1.0);
        size_t off = 0; /* the given direction, made unit and outward */
        for (size_t p = 0; p < n; p++)
            off += fabs(nrm[3 * p] * pts[3 * p] + nrm[3 * p + 1] * pts[3 * p + 1] +
                        nrm[3 * p + 2] * pts[3 * p + 2] - 1.0) > 1e-6;
        CHECK_MSG(off == 0, "length %g: %zu of %zu normals not the given direction", lengths[l],
                  off, n);
    }
    ps_graph_free(&g);
    free(pts), free(inward), free(nrm), free(comp);
}

/* Mean angle (radians) between the normals and the directions from the
 * origin to the clean points. */
static double mean_error(const double *clean, const double *nrm, size_t n) {
    double sum = 0;
    for (size_t p = 0; p < n; p++) {
        const double *x = clean + 3 * p;
        double c = (x[0] * nrm[3 * p] + x[1] * nrm[3 * p + 1] + x[2] * nrm[3 * p + 2]) /
                   sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        sum += acos(fmin(1, fmax(-1, c)));
    }
    return sum / (double)n;
}

/* The unit sphere with every coordinate jittered by up to half the mean
 * kNN edge length: asked to smooth, its normals still point outward,
 * within 8 degrees on average of the true ones (5.2 here); not asked, they
 * are k-PCA's (14.0 degrees off) and no smoothing is reported. */
static void test_noisy_sphere_smoothed(void) {
    size_t n;
    double *clean = ps_shape_sphere(0, &n, NULL), *pts = malloc(n * 3 * sizeof *pts);
    ps_graph g;
    REQUIRE(pts && ps_knn_graph_build(clean, n, 3, 7, 1, &g, NULL) == PS_OK);
    double spacing = 0;
    for (size_t e = 0; e < g.offsets[n]; e++) spacing += g.weights[e] / (double)g.offsets[n];
    ps_graph_free(&g);
    uint64_t state = 88172645463325252ULL;
    for (size_t i = 0; i < 3 * n; i++)
        pts[i] = clean[i] + 0.5 * spacing * (2.0 * ps_uniform_next(&state) - 1);
    REQUIRE(ps_knn_graph_build(pts, n, 3, 7, 1, &g, NULL) == PS_OK);
    int *comp = calloc(n, sizeof *comp);
    double *nrm = malloc(n * 3 * sizeof *nrm);
    REQUIRE(comp && nrm);
    const double c[3] = {0, 0, 0};
    for (int smooth = 0; smooth <= 1; smooth++) {
        ps_normals_report report = {-1, -1};
        ps_normals_input in = {.graph = &g, .points = pts, .component = comp, .n_components = 1,
                               .smooth = smooth};
        REQUIRE(ps_normals_build(&in, nrm, &report, NULL) == PS_OK);
        int smoothing = report.smoothing;
        CHECK(report.noise > PS_NOISE_FLOOR); /* measured noisy either way */
        CHECK(outward_share(pts, nrm, n, c) > 0.99);
        double error = mean_error(clean, nrm, n) * 180 / 3.14159265358979;
        CHECK_MSG(smooth ? smoothing > 0 && error < 8 : smoothing == 0 && error > 10,
                  "smooth %d: %d iterations, mean normal error %.1f degrees", smooth, smoothing,
                  error);
    }
    ps_graph_free(&g);
    free(clean), free(pts), free(comp), free(nrm);
}

/* What a scanner above a bowl sees: the inside of a hemisphere of radius 1
 * opening upwards (a Fibonacci lattice, z < 0) and the upper half of its
 * rim, a tube of radius RIM round the circle of radius 1 + RIM at z = 0.
 * truth #n by 3: the outward normals (out of the bowl's wall, towards the
 * viewer).  The bowl's centroid lies above its bottom, so the outward
 * normals have sum n . (x - centroid) < 0: the divergence vote alone
 * would flip them (normals_outward.h). */
#define RIM 0.12
#define PI 3.14159265358979323846
static double *bowl_seen_from_above(size_t *n, double **truth) {
    const size_t lattice = 16000, around = 250, across = 13;
    double *pts = malloc((lattice / 2 + around * across) * 3 * sizeof *pts);
    double *nrm = malloc((lattice / 2 + around * across) * 3 * sizeof *nrm);
    size_t k = 0;
    for (size_t i = 0; pts && nrm && i < lattice; i++) {
        double z = 1 - (2 * (double)i + 1) / (double)lattice, r = sqrt(1 - z * z);
        double phi = 2.39996322972865332 * (double)i;
        if (z >= 0) continue;
        double p[3] = {r * cos(phi), r * sin(phi), z};
        for (int d = 0; d < 3; d++) pts[3 * k + d] = p[d], nrm[3 * k + d] = -p[d];
        k++;
    }
    for (size_t i = 0; pts && nrm && i < around; i++)
        for (size_t j = 0; j < across; j++) {
            double u = 2 * PI * (double)i / (double)around, v = PI * ((double)j + 0.5) / (double)across;
            double out[3] = {-cos(v) * cos(u), -cos(v) * sin(u), sin(v)};
            for (int d = 0; d < 3; d++) nrm[3 * k + d] = out[d];
            pts[3 * k] = (1 + RIM) * cos(u) + RIM * out[0];
            pts[3 * k + 1] = (1 + RIM) * sin(u) + RIM * out[1];
            pts[3 * k + 2] = RIM * out[2];
            k++;
        }
    *n = k, *truth = nrm;
    return pts;
}

/* The bowl, turned and moved: (nearly) every normal points out of its
 * wall, PCA's and the scanner's own (given, pointing at it) alike. */
static void test_open_bowl_points_at_viewer(void) {
    size_t n;
    double *truth, *pts = bowl_seen_from_above(&n, &truth);
    REQUIRE(pts && truth);
    const double shift[3] = {5, -3, 2}, none[3] = {0, 0, 0};
    ps_shape_transform(pts, n, 2.0 / 3, -2.0 / 3, 1.0 / 3, 2.0, 4.0, shift);
    ps_shape_transform(truth, n, 2.0 / 3, -2.0 / 3, 1.0 / 3, 2.0, 1.0, none);
    for (int given = 0; given < 2; given++) {
        int nc;
        double *nrm;
        oriented_normals(pts, n, given ? truth : NULL, &nrm, &nc);
        REQUIRE(nrm);
        CHECK(nc == 1);
        size_t agree = 0;
        for (size_t p = 0; p < n; p++)
            agree += nrm[3 * p] * truth[3 * p] + nrm[3 * p + 1] * truth[3 * p + 1] +
                         nrm[3 * p + 2] * truth[3 * p + 2] > 0;
        CHECK_MSG(agree > 0.99 * (double)n, "given %d: %zu of %zu normals point out", given,
                  agree, n);
        free(nrm);
    }
    free(pts), free(truth);
}

/* The PCA on 1 or 3 threads gives the same bytes; progress rises through
 * the span to its end; a raised cancel flag stops the build. */
static void test_threads_identical_with_progress(void) {
    size_t n;
    double *pts = ps_shape_star(400.0, &n, NULL);
    ps_graph g;
    REQUIRE(pts && ps_knn_graph_build(pts, n, 3, 7, 1, &g, NULL) == PS_OK);
    int *comp = malloc(n * sizeof *comp);
    double *one = malloc(n * 3 * sizeof *one), *three = malloc(n * 3 * sizeof *three);
    REQUIRE(comp && one && three);
    int nc = ps_graph_components(&g, comp);
    ps_progress_seen seen = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &seen};
    ps_progress_span span = {&ctl, PS_PHASE_KNN, 0.5, 0.9};
    ps_normals_input in = {.graph = &g, .points = pts, .component = comp, .n_components = nc,
                           .smooth = 1};
    REQUIRE(ps_normals_build(&in, one, NULL, NULL) == PS_OK);
    REQUIRE(ps_normals_build_tracked(&in, 3, &span, three, NULL, NULL) == PS_OK);
    CHECK(memcmp(one, three, n * 3 * sizeof *one) == 0);
    CHECK_MSG(seen.calls[PS_PHASE_KNN] >= 2 && !seen.went_back && seen.last[PS_PHASE_KNN] == 0.9,
              "%d calls, last %g", seen.calls[PS_PHASE_KNN], seen.last[PS_PHASE_KNN]);
    volatile int cancel = 1;
    ctl.cancel = &cancel;
    ps_error err = {0};
    CHECK(ps_normals_build_tracked(&in, 2, &span, three, NULL, &err) == PS_ERR_CANCELLED);
    ps_graph_free(&g);
    free(pts), free(comp), free(one), free(three);
}

PS_TEST_MAIN(TEST(test_pca_sphere_outward), TEST(test_pca_moved_sphere_outward),
             TEST(test_fin_does_not_decide_the_sign),
             TEST(test_given_inward_flipped), TEST(test_open_bowl_points_at_viewer),
             TEST(test_noisy_sphere_smoothed),
             TEST(test_threads_identical_with_progress))
