/* test_morton.c: the Morton order is a permutation, sorts points on a line
 * by position, follows the Z curve on a 2 by 2 grid, ties go by index, and
 * on many points with ties it is the order of a comparison sort. */
#include "random_bits.h"
#include "testlib.h"
#include "util/morton.h"

#include <stdlib.h>

static void test_line_sorted(void) {
    enum { N = 1000 };
    double *p = malloc(N * 3 * sizeof *p);
    uint32_t *order = malloc(N * sizeof *order);
    REQUIRE(p && order);
    for (size_t i = 0; i < N; i++) {
        size_t x = (i * 7919) % N; /* a shuffle of 0..N-1 */
        p[3 * i] = (double)x, p[3 * i + 1] = 5.0, p[3 * i + 2] = -1.0;
    }
    REQUIRE(ps_morton_order(p, N, 3, order) == PS_OK);
    unsigned char seen[N] = {0};
    for (size_t i = 0; i < N; i++) {
        REQUIRE(order[i] < N);
        seen[order[i]]++;
        if (i > 0) CHECK(p[3 * order[i]] > p[3 * order[i - 1]]);
    }
    for (size_t i = 0; i < N; i++) CHECK(seen[i] == 1);
    free(p), free(order);
}

static void test_z_curve_2d_and_ties(void) {
    const double p[] = {1, 1, 0, 1, 1, 0, 0, 0, 0, 0};
    uint32_t order[5];
    REQUIRE(ps_morton_order(p, 5, 2, order) == PS_OK);
    const uint32_t want[5] = {3, 4, 2, 1, 0}; /* (0,0) twice by index, (1,0), (0,1), (1,1) */
    for (int i = 0; i < 5; i++) CHECK_MSG(order[i] == want[i], "order[%d] = %u", i, order[i]);
}

/* The Z-order key of a point on an integer grid of side 1 << 21 (the
 * bounding box below spans it exactly), bit by bit. */
static uint64_t reference_code(const double *x) {
    uint64_t code = 0;
    for (int bit = 0; bit < 21; bit++)
        for (int a = 0; a < 3; a++)
            code |= (uint64_t)(((uint64_t)x[a] >> bit) & 1u) << (3 * bit + a);
    return code;
}

typedef struct ref_key {
    uint64_t code;
    uint32_t index;
} ref_key;

static int compare_ref(const void *pa, const void *pb) {
    const ref_key *a = pa, *b = pb;
    if (a->code != b->code) return a->code < b->code ? -1 : 1;
    return (a->index > b->index) - (a->index < b->index);
}

/* 200,000 points on the grid, a quarter of them repeats of earlier ones,
 * and the two corners that fix the bounding box: the order must be the
 * comparison sort's by (code, index), digit for digit of the radix sort. */
static void test_matches_comparison_sort(void) {
    enum { N = 200000 };
    const double side = (double)((1u << 21) - 1);
    double *p = malloc(N * 3 * sizeof *p);
    uint32_t *order = malloc(N * sizeof *order);
    ref_key *ref = malloc(N * sizeof *ref);
    REQUIRE(p && order && ref);
    uint64_t s = 88172645463325252ULL;
    for (size_t i = 0; i < N; i++)
        for (int a = 0; a < 3; a++) {
            uint64_t bits = ps_random_bits(&s);
            p[3 * i + a] = i >= 2 && i % 4 == 3 ? p[3 * (i / 2) + a] : (double)(bits % (1u << 21));
        }
    for (int a = 0; a < 3; a++) p[a] = 0.0, p[3 + a] = side;
    REQUIRE(ps_morton_order(p, N, 3, order) == PS_OK);
    for (size_t i = 0; i < N; i++) ref[i] = (ref_key){reference_code(p + 3 * i), (uint32_t)i};
    qsort(ref, N, sizeof *ref, compare_ref);
    size_t wrong = 0;
    for (size_t i = 0; i < N; i++) wrong += order[i] != ref[i].index;
    CHECK_MSG(wrong == 0, "%zu of %d positions differ from the comparison sort", wrong, N);
    free(p), free(order), free(ref);
}

PS_TEST_MAIN(TEST(test_line_sorted), TEST(test_z_curve_2d_and_ties),
             TEST(test_matches_comparison_sort))
