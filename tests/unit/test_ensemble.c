/*
 * test_ensemble.c: method auto's ensemble of draws (ensemble.h): when it
 * runs, the draws' assignment and the medoid, and end to end on a star
 * dense enough for three draws: its arms come out apart, every point is
 * answered consistently, and the answer is the same for any thread count
 * and for a rotated, scaled, moved and reordered copy, with progress that
 * never goes back and is never reported twice at once while draws run
 * side by side, phase times that are wall times, and a cancel that stops
 * draws in flight; repeated points count once.
 */
#include "ensemble.h"
#include "graph/reference_density.h"
#include "pointseg.h"
#include "progress_seen.h"
#include "result_checks.h"
#include "shapes.h"
#include "testlib.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define DENSE_STAR 2500.0   /* ps_shape_star density: about 128,000 points, 3 draws */
#define ONE_DRAW_STAR 800.0 /* about 41,000 points, one draw */
#define DRAWS 3           /* the assignment tests' draw count */

static void test_draws_only_when_each_keeps_the_reference(void) {
    ps_params p;
    ps_params_default(&p);
    size_t ref = PS_DENSITY_REFERENCE_POINTS;
    CHECK(ps_ensemble_draws(&p, ref) == 0);
    CHECK(ps_ensemble_draws(&p, ref + 1) == 1);
    CHECK(ps_ensemble_draws(&p, 3 * ref - 1) == 1);
    CHECK(ps_ensemble_draws(&p, 3 * ref) == 3);
    CHECK(ps_ensemble_draws(&p, 5 * ref - 1) == 3);
    CHECK(ps_ensemble_draws(&p, 5 * ref) == (PS_ENSEMBLE_MAX_DRAWS >= 5 ? 5 : 3));
    CHECK(ps_ensemble_draws(&p, 100 * ref) == PS_ENSEMBLE_MAX_DRAWS);
    p.method = PS_METHOD_PAPER;
    CHECK(ps_ensemble_draws(&p, 10 * ref) == 0);
}

/* A draw keeps the reference sampling until the draws cover the input. */
static void test_draw_points(void) {
    size_t ref = PS_DENSITY_REFERENCE_POINTS;
    size_t most = PS_ENSEMBLE_MAX_DRAWS;
    CHECK(ps_ensemble_draw_points(ref + 1) == ref);
    CHECK(ps_ensemble_draw_points(4 * ref) == ref);
    CHECK(ps_ensemble_draw_points(most * ref) == ref);
    CHECK(ps_ensemble_draw_points(10 * most * ref) == 10 * ref);
    CHECK(ps_ensemble_draw_points(10 * most * ref + 1) == 10 * ref + 1);
}

/* Each draw within 2% of size points, the rest in none. */
static void check_balanced(const uint8_t *draw_of, size_t n, size_t size) {
    size_t count[DRAWS] = {0}, none = 0;
    for (size_t i = 0; i < n; i++) {
        if (draw_of[i] == PS_ENSEMBLE_NONE) {
            none++;
            continue;
        }
        REQUIRE(draw_of[i] < DRAWS);
        count[draw_of[i]]++;
    }
    for (int j = 0; j < DRAWS; j++)
        CHECK_MSG(count[j] > 0.98 * size && count[j] < 1.02 * size,
                  "draw %d has %zu of %zu points, not about %zu", j, count[j], n, size);
    CHECK_MSG(none + 0.03 * n >= n - DRAWS * size && none <= n - DRAWS * size + 0.03 * n,
              "%zu of %zu points in no draw", none, n);
}

/* The keys of a rotated, scaled, moved and reversed copy are the same
 * (but for rounding on a handful of points), and so are the draws. */
static void test_keys_invariant(void) {
    size_t n;
    double *pts = ps_shape_hand(400.0, &n, NULL);
    double *copy = malloc(3 * n * sizeof *copy);
    uint32_t *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    uint8_t *draw_a = malloc(n), *draw_b = malloc(n);
    REQUIRE(pts && copy && a && b && draw_a && draw_b);
    for (size_t i = 0; i < n; i++) memcpy(copy + 3 * i, pts + 3 * (n - 1 - i), 3 * sizeof *copy);
    const double t[3] = {-12.0, 3.5, 900.0};
    ps_shape_transform(copy, n, 0.2, 0.9, -0.4, 2.2, 37.0, t);
    ps_ensemble_keys(pts, n, 3, a);
    ps_ensemble_keys(copy, n, 3, b);
    size_t same = 0;
    for (size_t i = 0; i < n; i++) same += a[i] == b[n - 1 - i];
    CHECK_MSG(same + 5 >= n, "%zu of %zu keys kept", same, n);
    ps_ensemble_assign(a, n, n, DRAWS, n / DRAWS, draw_a);
    ps_ensemble_assign(b, n, n, DRAWS, n / DRAWS, draw_b);
    check_balanced(draw_a, n, n / DRAWS);
    same = 0;
    for (size_t i = 0; i < n; i++) same += draw_a[i] == draw_b[n - 1 - i];
    CHECK_MSG(same + 5 >= n, "%zu of %zu points kept their draw", same, n);
    size_t compared = 0;
    for (size_t i = 0; i < n; i++) compared += ps_ensemble_compared(a[i], n, 4096);
    CHECK_MSG(compared > 3700 && compared < 4500, "%zu points compared", compared);
    free(pts), free(copy), free(a), free(b), free(draw_a), free(draw_b);
}

/* A copy moved to georeferenced coordinates (a 2-metre scan in UTM
 * metres) keeps its keys but for the points whose rounded coordinates
 * cross a step (0.4% here; 27% when the centroid was summed as given). */
static void test_keys_georeferenced(void) {
    size_t n;
    double *pts = ps_shape_hand(400.0, &n, NULL);
    double *moved = malloc(3 * n * sizeof *moved);
    uint32_t *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    REQUIRE(pts && moved && a && b);
    const double offset[3] = {512345.678, 4123456.789, 312.5};
    for (size_t i = 0; i < 3 * n; i++) {
        pts[i] /= 200.0;
        moved[i] = pts[i] + offset[i % 3];
    }
    ps_ensemble_keys(pts, n, 3, a);
    ps_ensemble_keys(moved, n, 3, b);
    size_t same = 0;
    for (size_t i = 0; i < n; i++) same += a[i] == b[i];
    CHECK_MSG(same + n / 100 >= n, "%zu of %zu keys kept", same, n);
    free(pts), free(moved), free(a), free(b);
}

/* Draws that leave points out take their size each, the same points for
 * a reordered copy. */
static void test_assign_partial(void) {
    size_t n = 60000, size = n / 5;
    uint32_t *key = malloc(n * sizeof *key), *reversed = malloc(n * sizeof *reversed);
    uint8_t *draw_of = malloc(n), *draw_rev = malloc(n);
    REQUIRE(key && reversed && draw_of && draw_rev);
    for (size_t i = 0; i < n; i++) key[i] = reversed[n - 1 - i] = (uint32_t)(i * 17);
    ps_ensemble_assign(key, n, n, DRAWS, size, draw_of);
    ps_ensemble_assign(reversed, n, n, DRAWS, size, draw_rev);
    check_balanced(draw_of, n, size);
    size_t same = 0;
    for (size_t i = 0; i < n; i++) same += draw_of[i] == draw_rev[n - 1 - i];
    CHECK_MSG(same == n, "%zu of %zu points kept their draw", same, n);
    free(key), free(reversed), free(draw_of), free(draw_rev);
}

/* Every point as far from the centre: the draws still take their share,
 * covering the input or not. */
static void test_assign_tied_keys(void) {
    size_t n = 30000;
    uint32_t *key = malloc(n * sizeof *key);
    uint8_t *draw_of = malloc(n);
    REQUIRE(key && draw_of);
    for (size_t i = 0; i < n; i++) key[i] = 4000000000u;
    ps_ensemble_assign(key, n, n, DRAWS, n / DRAWS, draw_of);
    check_balanced(draw_of, n, n / DRAWS);
    ps_ensemble_assign(key, n, n, DRAWS, n / 4, draw_of);
    check_balanced(draw_of, n, n / 4);
    free(key), free(draw_of);
}

/* One labelling all in one part, one in halves, one in quarters: the
 * halves lie between the other two, unless a margin keeps the first. */
static void test_medoid_is_the_middle(void) {
    enum { S = 400 };
    int labels[3 * S];
    for (int t = 0; t < S; t++) {
        labels[t] = 0;
        labels[S + t] = t / (S / 2);
        labels[2 * S + t] = t / (S / 4);
    }
    CHECK(ps_ensemble_medoid(labels, 3, S, 0) == 1);
    CHECK(ps_ensemble_medoid(labels, 3, S, 0.4) == 1);   /* the first is 0.5 worse */
    CHECK(ps_ensemble_medoid(labels, 3, S, 0.6) == 0);   /* within the margin */
    for (int t = 0; t < S; t++) labels[S + t] = 0; /* two alike: the lower wins */
    CHECK(ps_ensemble_medoid(labels, 3, S, 0) == 0);
}

static ps_result *segment_star(const double *pts, size_t n, int threads, const ps_control *ctl) {
    ps_params p;
    ps_params_default(&p);
    p.threads = threads;
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_result *r = NULL;
    ps_error err = {0};
    ps_status st = ps_segment(&in, &p, ctl, &r, &err);
    CHECK_MSG(st == PS_OK, "ps_segment failed: %s", err.message);
    return r;
}

/* Every point answered and the result self-consistent, every sink one of
 * the n points. */
static void check_answers(const ps_result *r, size_t n) {
    REQUIRE(r->n_points == n);
    ps_check_result_consistent(r);
    for (int s = 0; s < r->n_supernodes; s++) CHECK(r->supernodes[s].sink < n);
}

/* A star of the given ps_shape_star density segmented in `draws` draws:
 * its arms come out apart, every point answered, the same answers for 1
 * and 2 threads. */
static void check_star_in_draws(double density, int draws) {
    size_t n;
    int *part;
    double *pts = ps_shape_star(density, &n, &part);
    REQUIRE(pts && part);
    REQUIRE(ps_ensemble_draws(&(ps_params){.method = PS_METHOD_AUTO}, n) == draws);
    ps_result *one = segment_star(pts, n, 1, NULL), *two = segment_star(pts, n, 2, NULL);
    REQUIRE(one && two);
    check_answers(one, n);
    ps_check_parts_separate(one, part, 1, 6, 0.8); /* each arm a segment of its own */
    CHECK(memcmp(one->labels, two->labels, n * sizeof *one->labels) == 0);
    CHECK(memcmp(one->centrality, two->centrality, n * sizeof *one->centrality) == 0);
    ps_result_free(one), ps_result_free(two);
    free(pts), free(part);
}

static void test_dense_star_in_draws(void) { check_star_in_draws(DENSE_STAR, 3); }

/* About 40,000 points: one draw of the reference sampling, the other
 * third of the points answered by their nearest in it. */
static void test_star_in_one_draw(void) { check_star_in_draws(ONE_DRAW_STAR, 1); }

/* Rotated, scaled, moved and reversed: the same partition, but for the
 * points the reversed order moves between draws' tie breaks (as the
 * single run's, test_segment_invariance.c's test_permutation). */
static void test_dense_star_rotated_and_reordered(void) {
    size_t n;
    double *pts = ps_shape_star(DENSE_STAR, &n, NULL);
    double *copy = malloc(3 * n * sizeof *copy);
    REQUIRE(pts && copy);
    for (size_t i = 0; i < n; i++) memcpy(copy + 3 * i, pts + 3 * (n - 1 - i), 3 * sizeof *copy);
    const double t[3] = {250.0, -40.0, 7.0};
    ps_shape_transform(copy, n, 0.3, -0.5, 0.81, 1.1, 100.0, t);
    ps_result *a = segment_star(pts, n, 0, NULL), *b = segment_star(copy, n, 0, NULL);
    REQUIRE(a && b);
    CHECK_MSG(a->n_segments == b->n_segments, "%d segments, the copy %d", a->n_segments, b->n_segments);
    int *b_in_a_order = malloc(n * sizeof *b_in_a_order);
    REQUIRE(b_in_a_order);
    for (size_t i = 0; i < n; i++) b_in_a_order[i] = b->labels[n - 1 - i];
    double moved = ps_moved_share(a, b_in_a_order, n);
    CHECK_MSG(moved <= 0.005, "%.4f of the points changed segment", moved);
    ps_result_free(a), ps_result_free(b);
    free(pts), free(copy), free(b_in_a_order);
}

/* A star of about 2,000 points given COPIES times over (40,000 points,
 * over the reference sampling, but 2,000 distinct ones): one run, as
 * the star given once, each copy answered as its point. */
#define COPIES 20
static void test_repeated_points_segmented_as_their_distinct_ones(void) {
    size_t n;
    double *pts = ps_shape_star(40.0, &n, NULL);
    REQUIRE(pts && n * COPIES > PS_DENSITY_REFERENCE_POINTS);
    double *repeated = malloc(COPIES * 3 * n * sizeof *repeated);
    REQUIRE(repeated);
    for (int c = 0; c < COPIES; c++) memcpy(repeated + (size_t)c * 3 * n, pts, 3 * n * sizeof *pts);
    ps_result *once = segment_star(pts, n, 0, NULL), *many = segment_star(repeated, COPIES * n, 0, NULL);
    REQUIRE(once && many);
    check_answers(many, COPIES * n);
    CHECK(many->n_segments == once->n_segments);
    for (int c = 0; c < COPIES; c++)
        CHECK_MSG(memcmp(many->labels + (size_t)c * n, once->labels, n * sizeof *once->labels) == 0,
                  "copy %d labelled otherwise than the star given once", c);
    ps_result_free(once), ps_result_free(many);
    free(pts), free(repeated);
}

/* Ten points repeated 5,000 times each: enough distinct points for the
 * kNN graph (k + 1 = 8), though a draw of the reference sampling by their
 * keys would hold only some of them (it failed with "got 6"). */
static void test_few_points_repeated(void) {
    enum { LOCATIONS = 10, EACH = 5000 };
    size_t n = (size_t)LOCATIONS * EACH;
    double *pts = malloc(3 * n * sizeof *pts);
    REQUIRE(pts);
    for (size_t i = 0; i < n; i++) {
        size_t at = i % LOCATIONS;
        pts[3 * i] = (double)at, pts[3 * i + 1] = (double)(at * at % 7), pts[3 * i + 2] = (double)(at % 3);
    }
    ps_result *r = segment_star(pts, n, 0, NULL);
    REQUIRE(r);
    check_answers(r, n);
    for (size_t i = LOCATIONS; i < n; i++)
        CHECK_MSG(r->labels[i] == r->labels[i % LOCATIONS], "point %zu: label %d, its first copy %d",
                  i, r->labels[i], r->labels[i % LOCATIONS]);
    ps_result_free(r);
    free(pts);
}

/* Progress within every phase, never backwards across the draws; a raised
 * cancel flag stops the run. */
static void test_dense_star_progress_and_cancel(void) {
    size_t n;
    double *pts = ps_shape_star(DENSE_STAR, &n, NULL);
    REQUIRE(pts);
    ps_progress_seen m = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &m};
    ps_result *r = segment_star(pts, n, 0, &ctl);
    CHECK(r != NULL);
    for (int p = 0; p < PS_PHASE_COUNT; p++)
        CHECK_MSG(m.inside[p] >= DRAWS - 1, "%s: %d fractions inside (0, 1)",
                  ps_phase_name(p), m.inside[p]);
    CHECK(!m.went_back);
    ps_result_free(r);
    volatile int cancel = 1;
    ctl.cancel = &cancel;
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_error err;
    r = NULL;
    CHECK(ps_segment(&in, NULL, &ctl, &r, &err) == PS_ERR_CANCELLED);
    CHECK(r == NULL);
    free(pts);
}

/* A progress callback that notes whether two calls ever overlapped (it
 * holds a flag for a moment each time), and raises the probe's cancel flag
 * once the centrality phase is past cancel_at (never when it is over 1). */
typedef struct overlap_probe {
    atomic_int busy, overlapped, calls;
    double cancel_at;
    volatile int cancel;
} overlap_probe;

static void probe_progress(void *user, ps_phase phase, double fraction) {
    overlap_probe *o = user;
    if (atomic_exchange(&o->busy, 1)) atomic_store(&o->overlapped, 1);
    nanosleep(&(struct timespec){0, 20000}, NULL);
    atomic_fetch_add(&o->calls, 1);
    if (phase == PS_PHASE_CENTRALITY && fraction > o->cancel_at) ps_cancel_raise(&o->cancel);
    atomic_store(&o->busy, 0);
}

/* Two threads run the three draws two at a time: the caller's callback is
 * still called by one thread at a time, and the phases' times are wall
 * times that add up to no more than the run's. */
static void test_draws_side_by_side(void) {
    size_t n;
    double *pts = ps_shape_star(DENSE_STAR, &n, NULL);
    REQUIRE(pts);
    overlap_probe o = {.cancel_at = 2.0};
    ps_control ctl = {.progress = probe_progress, .user = &o};
    ps_result *r = segment_star(pts, n, 2, &ctl);
    REQUIRE(r);
    CHECK(atomic_load(&o.calls) > 0);
    CHECK_MSG(!atomic_load(&o.overlapped), "the progress callback ran twice at once");
    double phases = 0;
    for (int p = 0; p < PS_PHASE_COUNT; p++) phases += r->timings.ms[p];
    CHECK_MSG(phases <= r->timings.total_ms + 1.0, "phases %.1f ms in a run of %.1f ms", phases,
              r->timings.total_ms);
    ps_result_free(r);
    free(pts);
}

/* A cancel raised while the draws' centrality runs side by side stops
 * the run with nothing returned. */
static void test_cancel_while_draws_run(void) {
    size_t n;
    double *pts = ps_shape_star(DENSE_STAR, &n, NULL);
    REQUIRE(pts);
    overlap_probe o = {.cancel_at = 0.3};
    ps_control ctl = {.progress = probe_progress, .user = &o, .cancel = &o.cancel};
    ps_params p;
    ps_params_default(&p);
    p.threads = 2;
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_result *r = NULL;
    ps_error err;
    CHECK(ps_segment(&in, &p, &ctl, &r, &err) == PS_ERR_CANCELLED);
    CHECK(r == NULL);
    CHECK(o.cancel == 1);
    free(pts);
}

PS_TEST_MAIN(TEST(test_draws_only_when_each_keeps_the_reference), TEST(test_draw_points),
             TEST(test_keys_invariant), TEST(test_keys_georeferenced),
             TEST(test_assign_partial), TEST(test_assign_tied_keys), TEST(test_medoid_is_the_middle),
             TEST(test_star_in_one_draw), TEST(test_dense_star_in_draws), TEST(test_dense_star_rotated_and_reordered),
             TEST(test_dense_star_progress_and_cancel), TEST(test_draws_side_by_side),
             TEST(test_cancel_while_draws_run),
             TEST(test_repeated_points_segmented_as_their_distinct_ones), TEST(test_few_points_repeated))
