/*
 * test_crease_merge.c: the crease merge (crease_merge.h) on the star of
 * star_fixture.h.  Its true parts meet along concave creases and stay
 * apart; the same parts cut once more across smooth surface (the tip of
 * every arm, the sphere through its equator) merge back into exactly the
 * true parts, with one merge per extra piece recorded (smaller piece into
 * larger, feature size from f), leaves renamed to their survivor, and the
 * same answer on every run; but an arm cut halfway keeps its far half,
 * which protrudes (longer than its boundary is wide).  With its normals
 * turned inwards the star is a round room with six tunnels: cavities,
 * which merge into the room although they are long.  Creases no stronger
 * than the surface's noise keep nothing apart.  On three
 * hand-placed points, a concave bend counts against a merge only when it
 * runs across the boundary.
 */
#include "features/crease.h"
#include "hand_graph.h"
#include "refine/crease_merge.h"
#include "star_fixture.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N_PIECES (2 * PS_STAR_PARTS) /* piece k + PS_STAR_PARTS: far half of part k */

#define TIP_CUT 3.3  /* an arm's tip beyond this is shorter (0.55) than wide (0.7) */
#define HALF_CUT 2.3 /* an arm's far half beyond this is longer (1.55) than wide */

/* Each true part with its far piece (arm beyond arm_cut, sphere below z =
 * 0) apart. */
static void split_parts(const ps_star *s, double arm_cut, int *group) {
    for (size_t p = 0; p < s->n; p++) {
        const double *x = s->points + 3 * p;
        int part = s->part[p];
        int far = part == 0 ? x[2] < 0 : ps_star_along_arm(x, part) > arm_cut;
        group[p] = part + (far ? PS_STAR_PARTS : 0);
    }
}

/* The crease merge of the star's segments group, its creases measured on
 * the star; with noise > 0 the median strength is raised to noise times
 * the strongest point's strength over PS_CREASE_MERGE_NOISE, as if the
 * star were that noisy. */
static ps_status run_noisy_merge(const ps_star *s, const double *f, double noise, int *group,
                                 int *leaf, ps_merge **merges, int *n_merges) {
    ps_crease_points creases = {.strength = malloc(s->n * sizeof(double))};
    if (!creases.strength) return PS_ERR_NOMEM;
    ps_status st = ps_crease_strengths(&s->graph, s->points, s->normals, 1, &creases, NULL);
    double strongest = 0;
    for (size_t p = 0; p < s->n; p++) strongest = fmax(strongest, creases.strength[p]);
    free(creases.strength);
    if (st != PS_OK) return st;
    if (noise > 0) creases.median = noise * strongest / PS_CREASE_MERGE_NOISE;
    ps_star_merge_input in = {.f = f, .mean_angular = creases.mean,
                              .median_strength = creases.median, .n_groups = N_PIECES};
    return ps_star_merge(s, ps_crease_merge, &in, group, leaf, merges, n_merges);
}

static ps_status run_merge(const ps_star *s, const double *f, int *group, int *leaf,
                           ps_merge **merges, int *n_merges) {
    return run_noisy_merge(s, f, 0, group, leaf, merges, n_merges);
}

/* f = distance from the origin: feature sizes are easy to predict. */
static double *radius(const ps_star *s) {
    double *f = malloc(s->n * sizeof *f);
    for (size_t p = 0; f && p < s->n; p++) {
        const double *x = s->points + 3 * p;
        f[p] = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    }
    return f;
}

/* The star, f = distance from the origin, each point's segment and the
 * merge's outputs. */
typedef struct star_run {
    ps_star s;
    double *f;
    int *group; /* #n, the true parts until changed */
    int leaf[N_PIECES];
    ps_merge *merges;
    int n_merges;
} star_run;

static int star_run_init(star_run *r) {
    memset(r, 0, sizeof *r);
    if (!ps_star_build(&r->s)) return 0;
    r->f = radius(&r->s);
    r->group = malloc(r->s.n * sizeof *r->group);
    if (r->group) memcpy(r->group, r->s.part, r->s.n * sizeof *r->group);
    return r->f && r->group;
}

static ps_status star_run_merge(star_run *r) {
    return run_merge(&r->s, r->f, r->group, r->leaf, &r->merges, &r->n_merges);
}

static void star_run_free(star_run *r) {
    free(r->merges);
    free(r->group);
    free(r->f);
    ps_star_free(&r->s);
}

static void test_true_parts_stay_apart(void) {
    star_run r;
    REQUIRE(star_run_init(&r));
    CHECK(star_run_merge(&r) == PS_OK);
    CHECK_MSG(r.n_merges == 0, "%d merges", r.n_merges);
    CHECK(memcmp(r.group, r.s.part, r.s.n * sizeof *r.group) == 0);
    star_run_free(&r);
}

/* The star's true parts with f = 0, so that none protrudes: their
 * creases keep them apart, until the surface is so noisy that its median
 * strength times PS_CREASE_MERGE_NOISE passes its strongest crease; then
 * no edge stands out of the noise and the parts merge into one. */
static void test_creases_stand_out_of_the_noise(void) {
    const double noise[2] = {0, 1.01};
    const int expected[2] = {0, PS_STAR_PARTS - 1};
    star_run r;
    REQUIRE(star_run_init(&r));
    for (int i = 0; i < 2; i++) {
        memcpy(r.group, r.s.part, r.s.n * sizeof *r.group);
        free(r.merges);
        CHECK(run_noisy_merge(&r.s, NULL, noise[i], r.group, r.leaf, &r.merges, &r.n_merges) ==
              PS_OK);
        CHECK_MSG(r.n_merges == expected[i], "noise %g: %d merges", noise[i], r.n_merges);
    }
    star_run_free(&r);
}

static void test_smooth_cuts_merge_back(void) {
    star_run r;
    REQUIRE(star_run_init(&r));
    split_parts(&r.s, TIP_CUT, r.group);
    CHECK(star_run_merge(&r) == PS_OK);
    CHECK_MSG(r.n_merges == PS_STAR_PARTS, "%d merges", r.n_merges);
    /* every part is one group again, and no two parts share one */
    int group_of_part[PS_STAR_PARTS];
    for (int k = 0; k < PS_STAR_PARTS; k++) group_of_part[k] = -1;
    size_t wrong = 0;
    for (size_t p = 0; p < r.s.n; p++) {
        int k = r.s.part[p];
        if (group_of_part[k] < 0) group_of_part[k] = r.group[p];
        wrong += r.group[p] != group_of_part[k];
    }
    CHECK_MSG(wrong == 0, "%zu points off their part's group", wrong);
    for (int a = 0; a < PS_STAR_PARTS; a++)
        for (int b = a + 1; b < PS_STAR_PARTS; b++) CHECK(group_of_part[a] != group_of_part[b]);
    for (int i = 0; i < r.n_merges; i++) {
        CHECK(r.merges[i].segment != r.merges[i].into);
        CHECK(r.merges[i].feature_size > 0);
        CHECK(r.leaf[r.merges[i].segment] == r.leaf[r.merges[i].into]);
    }
    star_run_free(&r);
}

static void test_protruding_half_stays(void) {
    star_run r;
    REQUIRE(star_run_init(&r));
    int *cut = malloc(r.s.n * sizeof *cut);
    REQUIRE(cut);
    split_parts(&r.s, HALF_CUT, r.group);
    memcpy(cut, r.group, r.s.n * sizeof *cut);
    CHECK(star_run_merge(&r) == PS_OK);
    CHECK_MSG(r.n_merges == 1, "%d merges", r.n_merges); /* the two hemispheres only */
    size_t moved = 0;
    for (size_t p = 0; p < r.s.n; p++)
        if (r.s.part[p] != 0) moved += r.group[p] != cut[p];
    CHECK_MSG(moved == 0, "%zu arm points changed segment", moved);
    free(cut);
    star_run_free(&r);
}

static void test_tunnels_merge(void) {
    star_run r;
    REQUIRE(star_run_init(&r));
    for (size_t i = 0; i < 3 * r.s.n; i++) r.s.normals[i] = -r.s.normals[i];
    CHECK(star_run_merge(&r) == PS_OK);
    CHECK_MSG(r.n_merges == PS_STAR_PARTS - 1, "%d merges", r.n_merges);
    size_t apart = 0;
    for (size_t p = 0; p < r.s.n; p++) apart += r.group[p] != r.group[0];
    CHECK_MSG(apart == 0, "%zu points outside the room's segment", apart);
    for (int i = 0; i < r.n_merges; i++) CHECK(r.merges[i].into == 0 && r.merges[i].segment > 0);
    star_run_free(&r);
}

/* Whether the n merges of a and b are the same, field by field (since
 * ps_merge has a step after its double, memcmp would read padding). */
static int same_merges(const ps_merge *a, const ps_merge *b, int n) {
    for (int i = 0; i < n; i++)
        if (a[i].segment != b[i].segment || a[i].into != b[i].into ||
            a[i].feature_size != b[i].feature_size || a[i].step != b[i].step)
            return 0;
    return 1;
}

static void test_deterministic(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    double *f = radius(&s);
    int *first = malloc(s.n * sizeof *first), *again = malloc(s.n * sizeof *again);
    int leaf[N_PIECES], leaf_again[N_PIECES];
    REQUIRE(f && first && again);
    split_parts(&s, HALF_CUT, first);
    split_parts(&s, HALF_CUT, again);
    ps_merge *m1, *m2;
    int n1, n2;
    CHECK(run_merge(&s, f, first, leaf, &m1, &n1) == PS_OK);
    CHECK(run_merge(&s, f, again, leaf_again, &m2, &n2) == PS_OK);
    CHECK(memcmp(first, again, s.n * sizeof *first) == 0);
    CHECK(memcmp(leaf, leaf_again, sizeof leaf) == 0);
    CHECK(n1 == n2 && same_merges(m1, m2, n1));
    free(m1);
    free(m2);
    free(first);
    free(again);
    free(f);
    ps_star_free(&s);
}

/* p (segment 0) at the origin, q (segment 1) at (1, 0, 0): the boundary
 * edge runs along x.  r (segment 0) one unit from p along `toward`, with
 * the edge p-r a concave bend (normals tilted towards each other); q's
 * normal is p's, so p-q itself is flat.  Returns how many merges. */
static int merges_with_bend(const double toward[3]) {
    const double s = 0.6, c = 0.8;
    double points[9] = {0, 0, 0, 1, 0, 0, toward[0], toward[1], toward[2]};
    double normals[9] = {s * toward[0],  s * toward[1],  c, s * toward[0], s * toward[1], c,
                         -s * toward[0], -s * toward[1], c};
    const int edges[2][2] = {{0, 1}, {0, 2}};
    ps_hand_graph h;
    ps_hand_graph_edges(&h, 3, edges, 2, 1.0);
    double f[3] = {0, 1, 0};
    double bend = ps_crease_angular(points, normals, points + 6, normals + 6, 0.0);
    ps_merge_input in = {.graph = &h.g, .points = points, .normals = normals, .f = f,
                         .mean_angular = bend / 2, .n_groups = 2};
    int group[3] = {0, 1, 0}, leaf[2] = {0, 1}, n_merges = 0;
    ps_merge *merges = NULL;
    ps_error err = {0};
    CHECK(bend > 0);
    CHECK(ps_crease_merge(&in, group, leaf, &merges, &n_merges, &err) == PS_OK);
    free(merges);
    return n_merges;
}

static void test_bend_across_boundary_keeps_apart(void) {
    const double behind[3] = {-1, 0, 0}; /* the crease runs across the boundary line */
    CHECK(merges_with_bend(behind) == 0);
}

static void test_bend_along_boundary_merges(void) {
    const double beside[3] = {0, -1, 0}; /* a fillet the boundary crosses */
    CHECK(merges_with_bend(beside) == 1);
}

/* A flat plus sign on a grid of unit spacing: the centre |u|, |v| <= 1
 * (segment 0, 9 points) and four arms 3 wide from 2 to 5 out (segments 1
 * to 4, 12 points each), f = max(|u|, |v|), normals all up: no creases.
 * The centre is the smallest segment, but it is the core; each arm sticks
 * out (feature size 3, boundary width 1.6), so nothing merges.  Judged by
 * the smaller segment alone, the centre (feature size 1) merged into an
 * arm. */
static void test_plus_centre_smaller_than_arms(void) {
    double points[3 * 57], normals[3 * 57], f[57];
    int group[57], at[11][11], edges[120][2], n = 0, n_edges = 0;
    for (int u = -5; u <= 5; u++)
        for (int v = -5; v <= 5; v++) {
            at[u + 5][v + 5] = -1;
            if (abs(u) > 1 && abs(v) > 1) continue;
            points[3 * n] = u, points[3 * n + 1] = v, points[3 * n + 2] = 0;
            normals[3 * n] = normals[3 * n + 1] = 0, normals[3 * n + 2] = 1;
            f[n] = abs(u) > abs(v) ? abs(u) : abs(v);
            group[n] = abs(u) <= 1 && abs(v) <= 1 ? 0 : u > 1 ? 1 : u < -1 ? 2 : v > 1 ? 3 : 4;
            at[u + 5][v + 5] = n++;
        }
    for (int u = 0; u < 11; u++)
        for (int v = 0; v < 11; v++) {
            if (at[u][v] < 0) continue;
            if (u + 1 < 11 && at[u + 1][v] >= 0)
                edges[n_edges][0] = at[u][v], edges[n_edges++][1] = at[u + 1][v];
            if (v + 1 < 11 && at[u][v + 1] >= 0)
                edges[n_edges][0] = at[u][v], edges[n_edges++][1] = at[u][v + 1];
        }
    REQUIRE(n == 57);
    ps_hand_graph h;
    ps_hand_graph_edges(&h, (size_t)n, (const int(*)[2])edges, n_edges, 1.0);
    ps_merge_input in = {.graph = &h.g, .points = points, .normals = normals, .f = f,
                         .mean_angular = 0, .n_groups = 5, .threads = 1};
    int leaf[5] = {0, 1, 2, 3, 4}, n_merges = 0;
    ps_merge *merges = NULL;
    ps_error err = {0};
    CHECK(ps_crease_merge(&in, group, leaf, &merges, &n_merges, &err) == PS_OK);
    CHECK_MSG(n_merges == 0, "%d merges", n_merges);
    free(merges);
}

PS_TEST_MAIN(TEST(test_true_parts_stay_apart), TEST(test_smooth_cuts_merge_back),
             TEST(test_protruding_half_stays), TEST(test_tunnels_merge), TEST(test_deterministic),
             TEST(test_bend_across_boundary_keeps_apart), TEST(test_bend_along_boundary_merges),
             TEST(test_plus_centre_smaller_than_arms), TEST(test_creases_stand_out_of_the_noise))
