/*
 * test_crease_split.c: the crease split (crease_split.h).  One supernode
 * covering the star of star_fixture.h splits along the six closed creases
 * where the arms meet the sphere into the seven true parts, each new
 * supernode represented by its largest f and keeping is_minimum; a sphere,
 * with no crease, stays one supernode; the answer is the same on every run;
 * noise that puts most points over the mean angular term does not shatter
 * the star (only the strongest points count as crease points); noise
 * alone, with no crease standing out of the median strength, splits
 * nothing.
 */
#include "features/crease_split.h"
#include "features/normals.h"
#include "shapes.h"
#include "star_fixture.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

/* One supernode holding every point; f = distance from the origin squared. */
static int whole_supernode(size_t n, const double *points, ps_supernodes *sn, double **f) {
    sn->m = 1;
    sn->sinks = malloc(sizeof *sn->sinks);
    sn->is_minimum = malloc(sizeof *sn->is_minimum);
    sn->sizes = malloc(sizeof *sn->sizes);
    sn->supernode_of = calloc(n, sizeof *sn->supernode_of);
    *f = malloc(n * sizeof **f);
    if (!sn->sinks || !sn->is_minimum || !sn->sizes || !sn->supernode_of || !*f) return 0;
    sn->sinks[0] = 0, sn->is_minimum[0] = 1, sn->sizes[0] = n;
    for (size_t p = 0; p < n; p++) {
        const double *x = points + 3 * p;
        (*f)[p] = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    }
    return 1;
}

/* The crease strengths of points, then the split of sn. */
static ps_status split(const ps_graph *g, const double *points, const double *normals,
                       const double *f, ps_supernodes *sn) {
    ps_error err = {0};
    ps_crease_points creases = {.strength = malloc(g->n * sizeof(double))};
    if (!creases.strength) return PS_ERR_NOMEM;
    ps_status st = ps_crease_strengths(g, points, normals, 1, &creases, &err);
    if (st == PS_OK) st = ps_crease_split(g, &creases, f, sn, &err);
    free(creases.strength);
    return st;
}

static ps_status split_star(const ps_star *s, ps_supernodes *sn, double **f) {
    if (!whole_supernode(s->n, s->points, sn, f)) return PS_ERR_NOMEM;
    return split(&s->graph, s->points, s->normals, *f, sn);
}

/* Fraction of points whose supernode's majority part is their own part. */
static double purity(const ps_star *s, const ps_supernodes *sn) {
    int *votes = calloc((size_t)sn->m * PS_STAR_PARTS, sizeof *votes);
    size_t agree = 0;
    for (size_t p = 0; votes && p < s->n; p++)
        votes[sn->supernode_of[p] * PS_STAR_PARTS + s->part[p]]++;
    for (size_t p = 0; votes && p < s->n; p++) {
        const int *row = votes + sn->supernode_of[p] * PS_STAR_PARTS;
        int best = 0;
        for (int k = 1; k < PS_STAR_PARTS; k++)
            if (row[k] > row[best]) best = k;
        agree += best == s->part[p];
    }
    free(votes);
    return (double)agree / (double)s->n;
}

static void test_star_splits_into_its_parts(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    ps_supernodes sn = {0};
    double *f = NULL;
    CHECK(split_star(&s, &sn, &f) == PS_OK);
    CHECK_MSG(sn.m == PS_STAR_PARTS, "%d supernodes", sn.m);
    double pure = purity(&s, &sn);
    CHECK_MSG(pure > 0.97, "purity %.3f", pure);
    size_t total = 0;
    for (int k = 0; k < sn.m; k++) {
        CHECK(sn.is_minimum[k] == 1);
        CHECK(sn.supernode_of[sn.sinks[k]] == k);
        total += sn.sizes[k];
    }
    CHECK(total == s.n);
    for (size_t p = 0; p < s.n; p++) CHECK(f[p] >= f[sn.sinks[sn.supernode_of[p]]]);
    ps_supernodes_free(&sn);
    free(f);
    ps_star_free(&s);
}

static void test_sphere_stays_whole(void) {
    size_t n = 0;
    int *part = NULL;
    double *points = ps_shape_sphere(0, &n, &part);
    double *normals = malloc(n * 3 * sizeof *normals);
    int *component = calloc(n, sizeof *component);
    ps_graph g = {0};
    ps_error err = {0};
    REQUIRE(points && normals && component);
    REQUIRE(ps_knn_graph_build(points, n, 3, 7, 1, &g, &err) == PS_OK);
    ps_normals_input in = {.graph = &g, .points = points, .component = component,
                           .n_components = 1};
    REQUIRE(ps_normals_build(&in, normals, NULL, &err) == PS_OK);
    ps_supernodes sn = {0};
    double *f = NULL;
    REQUIRE(whole_supernode(n, points, &sn, &f));
    CHECK(split(&g, points, normals, f, &sn) == PS_OK);
    CHECK_MSG(sn.m == 1, "%d supernodes", sn.m);
    ps_supernodes_free(&sn);
    ps_graph_free(&g);
    free(f), free(component), free(normals), free(points), free(part);
}

static void test_deterministic(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    ps_supernodes a = {0}, b = {0};
    double *fa = NULL, *fb = NULL;
    CHECK(split_star(&s, &a, &fa) == PS_OK);
    CHECK(split_star(&s, &b, &fb) == PS_OK);
    CHECK(a.m == b.m);
    CHECK(memcmp(a.supernode_of, b.supernode_of, s.n * sizeof *a.supernode_of) == 0);
    CHECK(a.m == b.m && memcmp(a.sinks, b.sinks, (size_t)a.m * sizeof *a.sinks) == 0);
    ps_supernodes_free(&a);
    ps_supernodes_free(&b);
    free(fa), free(fb);
    ps_star_free(&s);
}

/* The star as one supernode with noise in its crease strengths: every
 * point raised to between 1 and 1.5 times the mean angular term, but, when
 * keep_creases, its crease points and one point in four; then split. */
static void split_noisy_star(const ps_star *s, int keep_creases, ps_supernodes *sn, double **f) {
    ps_crease_points creases = {.strength = malloc(s->n * sizeof(double))};
    REQUIRE(creases.strength && whole_supernode(s->n, s->points, sn, f));
    REQUIRE(ps_crease_strengths(&s->graph, s->points, s->normals, 1, &creases, NULL) == PS_OK);
    size_t raised = 0;
    for (size_t p = 0; p < s->n; p++) {
        if (keep_creases && (creases.strength[p] >= creases.mean || p % 4 == 0)) continue;
        creases.strength[p] = creases.mean * (1.0 + 0.5 * (double)(p % 97) / 97.0);
        raised++;
    }
    CHECK(raised > s->n / 2);
    ps_error err = {0};
    REQUIRE(ps_crease_median(s->n, &creases, &err) == PS_OK);
    CHECK(ps_crease_split(&s->graph, &creases, *f, sn, &err) == PS_OK);
    free(creases.strength);
}

/* Noise as the crease split sees it: the star's crease points keep their
 * strength, and 75% of the surface would pass the mean test.  Only the
 * strongest PS_CREASE_SPLIT_MAX_POINTS count, and the star still splits
 * into its seven parts. */
static void test_noise_does_not_shatter(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    ps_supernodes sn = {0};
    double *f = NULL;
    split_noisy_star(&s, 1, &sn, &f);
    CHECK_MSG(sn.m == PS_STAR_PARTS, "%d supernodes", sn.m);
    double pure = purity(&s, &sn);
    CHECK_MSG(pure > 0.95, "purity %.3f", pure);
    ps_supernodes_free(&sn);
    free(f);
    ps_star_free(&s);
}

/* Noise alone, as on a noisy sheet: no crease stands out of the median
 * (under the other two tests, the 45% strongest would be crease points,
 * scattered over the star).  Nothing is split. */
static void test_noise_alone_splits_nothing(void) {
    ps_star s;
    REQUIRE(ps_star_build(&s));
    ps_supernodes sn = {0};
    double *f = NULL;
    split_noisy_star(&s, 0, &sn, &f);
    CHECK_MSG(sn.m == 1, "%d supernodes", sn.m);
    ps_supernodes_free(&sn);
    free(f);
    ps_star_free(&s);
}

PS_TEST_MAIN(TEST(test_star_splits_into_its_parts), TEST(test_sphere_stays_whole),
             TEST(test_deterministic), TEST(test_noise_does_not_shatter),
             TEST(test_noise_alone_splits_nothing))
