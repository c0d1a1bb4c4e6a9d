/* test_supernodes.c: supernodes with and without minima on the star (its
 * centre becomes a minimum's supernode; the tracked build gives the same
 * and reports rising progress up to its span's end), and the f2 split (a
 * supernode whose far ends lie on two sides of its sink splits in two). */
#include "features/centrality.h"
#include "features/f2_split.h"
#include "features/supernodes.h"
#include "graph/knn_graph.h"
#include "progress_seen.h"
#include "shapes.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

typedef struct star_case {
    size_t n;
    double *pts;
    int *part;
    ps_graph g;
    int *comp;
    double *f;
} star_case;

static int star_setup(star_case *c) {
    c->pts = ps_shape_star(0, &c->n, &c->part);
    c->comp = malloc(c->n * sizeof *c->comp);
    c->f = malloc(c->n * sizeof *c->f);
    if (ps_knn_graph_build(c->pts, c->n, 3, 7, 2, &c->g, NULL) != PS_OK) return -1;
    int nc = ps_graph_components(&c->g, c->comp);
    ps_centrality_input in = {.graph = &c->g, .component = c->comp, .n_components = nc,
                              .mode = PS_CENTRALITY_APPROX, .threads = 2,
                              .coarse_min = PS_COARSE_MIN_POINTS};
    int used;
    return ps_centrality(&in, c->f, NULL, &used, NULL) == PS_OK ? nc : -1;
}

/* The supernodes input on c's star at persistence 0.1, on one thread,
 * without minima. */
static ps_supernodes_input star_input(const star_case *c, int n_components) {
    return (ps_supernodes_input){.graph = &c->g, .f = c->f, .component = c->comp,
                                 .n_components = n_components, .persistence = 0.1,
                                 .threads = 1};
}

static void star_free(star_case *c) {
    ps_graph_free(&c->g);
    free(c->pts), free(c->part), free(c->comp), free(c->f);
}

/* Fraction of supernode s's points in part `part`. */
static double share(const star_case *c, const ps_supernodes *sn, int s, int part) {
    size_t in = 0;
    for (size_t p = 0; p < c->n; p++) in += sn->supernode_of[p] == s && c->part[p] == part;
    return (double)in / (double)sn->sizes[s];
}

static void test_star_centre_is_a_minimum(void) {
    star_case c;
    int nc = star_setup(&c);
    REQUIRE(nc == 1);
    ps_supernodes plain, with_min;
    ps_supernodes_input in = star_input(&c, nc);
    double persistence = -1;
    REQUIRE(ps_supernodes_build(&in, &plain, &persistence, NULL) == PS_OK);
    in.use_minima = 1;
    REQUIRE(ps_supernodes_build(&in, &with_min, &persistence, NULL) == PS_OK);
    CHECK(persistence == 0.1);
    CHECK_MSG(plain.m == 6, "%d supernodes without minima", plain.m);
    int minima = 0;
    for (int s = 0; s < plain.m; s++) CHECK(!plain.is_minimum[s]);
    for (int s = 0; s < with_min.m; s++) {
        if (!with_min.is_minimum[s]) {
            CHECK(share(&c, &with_min, s, 0) < 0.25); /* an arm, not the centre */
            continue;
        }
        minima++;
        CHECK_MSG(share(&c, &with_min, s, 0) > 0.6, "minimum %d: %.2f centre", s,
                  share(&c, &with_min, s, 0));
    }
    CHECK(minima >= 1);
    size_t total = 0;
    for (int s = 0; s < with_min.m; s++) total += with_min.sizes[s];
    CHECK(total == c.n);
    ps_supernodes_free(&plain);
    ps_supernodes_free(&with_min);
    star_free(&c);
}

static void test_tracked_two_threads_same_and_progress(void) {
    star_case c;
    int nc = star_setup(&c);
    REQUIRE(nc == 1);
    ps_supernodes plain, tracked;
    ps_supernodes_input in = star_input(&c, nc);
    in.use_minima = 1;
    double persistence, again;
    ps_progress_seen seen = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &seen};
    ps_progress_span span = {&ctl, PS_PHASE_SUPERNODES, 0.0, 0.5};
    REQUIRE(ps_supernodes_build(&in, &plain, &persistence, NULL) == PS_OK);
    in.threads = 2;
    REQUIRE(ps_supernodes_build_tracked(&in, &span, &tracked, &again, NULL) == PS_OK);
    REQUIRE(tracked.m == plain.m);
    CHECK(memcmp(tracked.supernode_of, plain.supernode_of, c.n * sizeof(int)) == 0);
    CHECK(memcmp(tracked.sinks, plain.sinks, (size_t)plain.m * sizeof(uint32_t)) == 0);
    CHECK_MSG(seen.inside[PS_PHASE_SUPERNODES] >= 3 && !seen.went_back &&
                  seen.last[PS_PHASE_SUPERNODES] == 0.5,
              "%d fractions inside, last %g", seen.inside[PS_PHASE_SUPERNODES],
              seen.last[PS_PHASE_SUPERNODES]);
    ps_supernodes_free(&plain);
    ps_supernodes_free(&tracked);
    star_free(&c);
}

/* One supernode covering a path 0..40 with its representative at 16: f2
 * peaks at both ends (16 and 24 away; both basins above the minimum basin
 * size), so it splits in two; a persistence of 1 (the shorter end's 16 is
 * under the range 24) keeps it whole. */
static void test_f2_splits_two_ends(void) {
    enum { N = 41, REP = 16 };
    static size_t off[N + 1];
    static uint32_t nbr[2 * N];
    static double w[2 * N];
    size_t e = 0;
    for (size_t p = 0; p < N; p++) {
        off[p] = e;
        if (p > 0) nbr[e] = (uint32_t)(p - 1), w[e++] = 1;
        if (p + 1 < N) nbr[e] = (uint32_t)(p + 1), w[e++] = 1;
    }
    off[N] = e;
    ps_graph g = {N, off, nbr, w};
    double f[N];
    for (int p = 0; p < N; p++) f[p] = 100 - (p - REP) * (p - REP) * 0.1;
    for (int pass = 0; pass < 2; pass++) {
        ps_supernodes sn = {1, malloc(sizeof(uint32_t)), calloc(1, sizeof(int)),
                            malloc(sizeof(size_t)), calloc(N, sizeof(int))};
        sn.sinks[0] = REP, sn.sizes[0] = N;
        double persistence = pass == 0 ? 0.1 : 1.0;
        REQUIRE(ps_f2_split(&g, f, persistence, &sn, NULL) == PS_OK);
        if (pass == 0) {
            REQUIRE(sn.m == 2);
            CHECK(sn.supernode_of[0] != sn.supernode_of[N - 1]);
            CHECK(sn.sizes[0] + sn.sizes[1] == N);
            CHECK(sn.sizes[0] >= 16 && sn.sizes[1] >= 16);
        } else {
            CHECK(sn.m == 1 && sn.sinks[0] == REP);
        }
        ps_supernodes_free(&sn);
    }
}

/* A sawtooth f on a long path has 3,100 sharp peaks, each basin 20 points:
 * the persistence is raised until the supernodes fit the dense hierarchy,
 * and reported. */
static void test_supernode_cap(void) {
    enum { N = 62001 };
    size_t *off = malloc((N + 1) * sizeof *off);
    uint32_t *nbr = malloc(2 * N * sizeof *nbr);
    double *w = malloc(2 * N * sizeof *w), *f = malloc(N * sizeof *f);
    int *comp = calloc(N, sizeof *comp);
    size_t e = 0;
    for (size_t p = 0; p < N; p++) {
        off[p] = e;
        if (p > 0) nbr[e] = (uint32_t)(p - 1), w[e++] = 1;
        if (p + 1 < N) nbr[e] = (uint32_t)(p + 1), w[e++] = 1;
        f[p] = (double)(p % 20) + (double)p * 1e-6;
    }
    off[N] = e;
    ps_graph g = {N, off, nbr, w};
    ps_supernodes sn;
    ps_supernodes_input in = {.graph = &g, .f = f, .component = comp, .n_components = 1,
                              .threads = 1}; /* persistence 0, without minima */
    double persistence = 0;
    REQUIRE(ps_supernodes_build(&in, &sn, &persistence, NULL) == PS_OK);
    CHECK_MSG(sn.m <= PS_MAX_SUPERNODES, "%d supernodes", sn.m);
    CHECK(persistence > 0.5);
    ps_supernodes_free(&sn);
    free(off), free(nbr), free(w), free(f), free(comp);
}

PS_TEST_MAIN(TEST(test_star_centre_is_a_minimum), TEST(test_tracked_two_threads_same_and_progress),
             TEST(test_f2_splits_two_ends),
             TEST(test_supernode_cap))
