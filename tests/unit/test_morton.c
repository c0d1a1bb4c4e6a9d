/* test_morton.c: the Morton order is a permutation, sorts points on a line
 * by position, follows the Z curve on a 2 by 2 grid, and ties go by index. */
#include "morton.h"
#include "testlib.h"

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

PS_TEST_MAIN(TEST(test_line_sorted), TEST(test_z_curve_2d_and_ties))
