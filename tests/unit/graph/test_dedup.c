/* test_dedup.c: coincident points collapse onto their lowest index, distinct
 * points keep their order, the maps agree with a brute-force check, and
 * the Morton renumbering keeps the maps consistent and puts the points in
 * Morton order. */
#include "graph/dedup.h"
#include "testlib.h"

#include <stdlib.h>
#include <string.h>

static void test_small_example(void) {
    const double p[] = {1, 2, 0, 0, 1, 2, 3, 3, 0, 0, 1, 2};
    ps_dedup d;
    REQUIRE(ps_dedup_build(p, 6, 2, &d, NULL) == PS_OK);
    CHECK(d.n_unique == 3);
    const uint32_t unique_of[] = {0, 1, 0, 2, 1, 0};
    const uint32_t first[] = {0, 1, 3};
    CHECK(memcmp(d.unique_of, unique_of, sizeof unique_of) == 0);
    CHECK(memcmp(d.first, first, sizeof first) == 0);
    ps_dedup_free(&d);
    CHECK(d.first == NULL && d.unique_of == NULL);
}

static void test_all_distinct_and_empty(void) {
    const double p[] = {3, 2, 1, 0, -1, -2};
    ps_dedup d;
    REQUIRE(ps_dedup_build(p, 6, 1, &d, NULL) == PS_OK);
    CHECK(d.n_unique == 6);
    for (size_t i = 0; i < 6; i++) CHECK(d.unique_of[i] == i && d.first[i] == i);
    ps_dedup_free(&d);
    REQUIRE(ps_dedup_build(p, 0, 3, &d, NULL) == PS_OK);
    CHECK(d.n_unique == 0);
    ps_dedup_free(&d);
}

/* Many repeats on a coarse lattice, checked against pairwise comparison. */
static void test_against_brute_force(void) {
    enum { N = 2000, DIM = 3 };
    double *p = malloc(N * DIM * sizeof *p);
    REQUIRE(p);
    unsigned s = 12345;
    for (size_t i = 0; i < N * DIM; i++) {
        s = s * 1103515245u + 12345u;
        p[i] = (double)((s >> 16) % 5) * 0.5;
    }
    ps_dedup d;
    REQUIRE(ps_dedup_build(p, N, DIM, &d, NULL) == PS_OK);
    size_t count = 0;
    for (size_t i = 0; i < N; i++) {
        size_t lowest = i;
        for (size_t j = 0; j < i && lowest == i; j++)
            if (memcmp(&p[i * DIM], &p[j * DIM], DIM * sizeof *p) == 0) lowest = j;
        if (lowest == i) {
            CHECK(d.unique_of[i] == count && d.first[count] == i);
            count++;
        } else {
            CHECK(d.unique_of[i] == d.unique_of[lowest]);
        }
    }
    CHECK(d.n_unique == count);
    CHECK(count > 100 && count < N);
    for (size_t u = 1; u < d.n_unique; u++) CHECK(d.first[u] > d.first[u - 1]);
    ps_dedup_free(&d);
    free(p);
}

static void test_rejects_null(void) {
    ps_dedup d;
    ps_error err = {0};
    CHECK(ps_dedup_build(NULL, 3, 3, &d, &err) == PS_ERR_INVALID);
    CHECK(err.status == PS_ERR_INVALID);
}

/* 2,000 points on a line in shuffled order, every fourth a repeat: after
 * ps_dedup_morton each input point still maps to a distinct point with its
 * coordinates, first[] still names the lowest input index of each, and the
 * distinct points run along the line (their Morton order). */
static void test_morton_renumbering(void) {
    enum { N = 2000 };
    double *p = malloc(N * 3 * sizeof *p);
    REQUIRE(p);
    for (size_t i = 0; i < N; i++) {
        double x = (double)((i * 7919) % N);
        if (i % 4 == 3) x = p[3 * (i / 2)];
        p[3 * i] = x, p[3 * i + 1] = 1.0, p[3 * i + 2] = 2.0;
    }
    ps_dedup d;
    REQUIRE(ps_dedup_build(p, N, 3, &d, NULL) == PS_OK);
    CHECK(ps_dedup_is_identity(&d, N) == 0);
    size_t u = d.n_unique;
    REQUIRE(ps_dedup_morton(&d, p, N, 3, NULL) == PS_OK);
    CHECK(d.n_unique == u);
    for (size_t i = 0; i < N; i++) {
        size_t first = d.first[d.unique_of[i]];
        CHECK_MSG(p[3 * first] == p[3 * i] && first <= i, "point %zu -> first %zu", i, first);
    }
    for (size_t k = 1; k < u; k++)
        CHECK_MSG(p[3 * d.first[k]] > p[3 * d.first[k - 1]], "distinct point %zu out of order", k);
    ps_dedup_free(&d);
    const double line[] = {0, 0, 1, 0, 2, 0};
    REQUIRE(ps_dedup_build(line, 3, 2, &d, NULL) == PS_OK);
    CHECK(ps_dedup_is_identity(&d, 3) == 1);
    ps_dedup_free(&d);
    free(p);
}

/* -0 and +0 are the same coordinate, as == says, wherever they fall. */
static void test_signed_zeros_coincide(void) {
    const double p[] = {0.0, 1.0, -0.0, 1.0, 2.0, -0.0, 2.0, 0.0, -0.0, -0.0};
    ps_dedup d;
    REQUIRE(ps_dedup_build(p, 5, 2, &d, NULL) == PS_OK);
    CHECK(d.n_unique == 3);
    CHECK(d.unique_of[0] == 0 && d.unique_of[1] == 0 && d.unique_of[2] == 1 &&
          d.unique_of[3] == 1 && d.unique_of[4] == 2);
    CHECK(d.first[0] == 0 && d.first[1] == 2 && d.first[2] == 4);
    ps_dedup_free(&d);
}

PS_TEST_MAIN(TEST(test_signed_zeros_coincide), TEST(test_small_example), TEST(test_all_distinct_and_empty),
             TEST(test_against_brute_force), TEST(test_rejects_null), TEST(test_morton_renumbering))
