/*
 * test_segment_api.c: ps_segment's interface: bad input (non-finite
 * normals too, and magnitudes too far apart to scale) fails cleanly with
 * a message, statuses and steps have names of their own, ncut_threshold 0
 * is the method's own, progress is reported (and moves within each phase)
 * and a run can be cancelled, steps are timed, and each merge names the
 * step that made it.
 */
#include "features/centrality.h"
#include "pointseg.h"
#include "progress_seen.h"
#include "random_shapes.h"
#include "result_checks.h"
#include "shapes.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ps_segment refuses in with a message that contains `names`. */
static void expect_input_invalid(const ps_input *in, const char *what, const char *names) {
    ps_result *r = (ps_result *)1;
    ps_error err = {0};
    ps_status st = ps_segment(in, NULL, NULL, &r, &err);
    CHECK_MSG(st == PS_ERR_INVALID, "%s: status %d", what, (int)st);
    CHECK(r == NULL);
    CHECK_MSG(strlen(err.message) > 0 && strstr(err.message, names), "%s: message \"%s\"", what,
              err.message);
}

static void expect_invalid(const double *pts, size_t n, int dim, const char *what) {
    ps_input in = {.points = pts, .n = n, .dim = dim};
    expect_input_invalid(&in, what, "");
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

/* A given normal with a NaN or infinite component is refused, as a
 * coordinate is (an infinite one became NaN in the normals and the hand
 * came out in one segment; a NaN one pointed along x). */
static void test_non_finite_normals_refused(void) {
    size_t n;
    double *pts = ps_shape_hand(0, &n, NULL);
    double *normals = malloc(n * 3 * sizeof *normals);
    REQUIRE(pts && normals);
    for (size_t i = 0; i < 3 * n; i++) normals[i] = i % 3 == 2;
    ps_input in = {.points = pts, .n = n, .dim = 3, .normals = normals};
    ps_result *r = NULL;
    ps_error err;
    REQUIRE(ps_segment(&in, NULL, NULL, &r, &err) == PS_OK);
    CHECK(r->n_segments > 1);
    ps_result_free(r);
    normals[3 * 40] = INFINITY;
    expect_input_invalid(&in, "infinite normal", "point 40 has a non-finite normal");
    normals[3 * 40] = NAN;
    expect_input_invalid(&in, "NaN normal", "point 40 has a non-finite normal");
    free(pts), free(normals);
}

/* A ball of extent 2^-600 is segmented as its copy scaled to about 1;
 * beside one point at 2^497 it cannot be (that point would pass the
 * ceiling, input_scale.h), and it was segmented as it was: the ball's
 * squared distances underflowed and it fell into 152 segments.  Now such
 * a point set is refused, naming why. */
static void test_unscalable_magnitudes_refused(void) {
    size_t n;
    double *ball = ps_shape_sphere(0, &n, NULL);
    double *pts = malloc(3 * (n + 1) * sizeof *pts);
    REQUIRE(ball && pts);
    for (size_t i = 0; i < 3 * n; i++) pts[i] = ldexp(ball[i], -600);
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_result *r = NULL;
    ps_error err;
    CHECK_MSG(ps_segment(&in, NULL, NULL, &r, &err) == PS_OK, "ps_segment: %s", err.message);
    ps_result_free(r);
    pts[3 * n] = ldexp(1, 497), pts[3 * n + 1] = pts[3 * n + 2] = 0;
    in.n = n + 1;
    expect_input_invalid(&in, "a ball of 2^-600 and a point at 2^497", "orders of magnitude");
    free(ball), free(pts);
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
    *a = ps_segment_with(pts, *n, p);
    p->method = PS_METHOD_PAPER;
    *paper = ps_segment_with(pts, *n, p);
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
    ps_result *paper_given = ps_segment_with(pts, n, &p);
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

/* Each merge names the step that made it: a ball's basins (no concave
 * edge) are joined by the crease merge, with method auto whole (5,000
 * points) or in a draw (60,000), and by the paper's feature merge with
 * method paper. */
static void test_merges_name_their_step(void) {
    const size_t counts[] = {5000, 60000};
    for (int i = 0; i < 2; i++) {
        double *pts = malloc(counts[i] * 3 * sizeof *pts);
        REQUIRE(pts);
        ps_random_ball(pts, counts[i], 0, 1.0, 0x2545F4914F6CDD1DULL + (unsigned)i);
        ps_params p;
        ps_params_default(&p);
        for (int method = 0; method < 2; method++) {
            p.method = method ? PS_METHOD_PAPER : PS_METHOD_AUTO;
            ps_result *r = ps_segment_with(pts, counts[i], &p);
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

PS_TEST_MAIN(TEST(test_bad_input), TEST(test_non_finite_normals_refused),
             TEST(test_unscalable_magnitudes_refused), TEST(test_status_names),
             TEST(test_ncut_threshold_method_default), TEST(test_progress_and_cancel),
             TEST(test_progress_moves_within_phases), TEST(test_steps_named_and_timed),
             TEST(test_merges_name_their_step))
