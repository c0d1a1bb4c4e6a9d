/*
 * test_nearest.c: ps_nearest_query finds each query's nearest point, as a
 * scan of every point does, the same for any thread count.
 */
#include "graph/nearest.h"
#include "random_bits.h"
#include "testlib.h"

#include <stdlib.h>

static double squared(const double *a, const double *b) {
    double d = 0;
    for (int c = 0; c < 3; c++) d += (a[c] - b[c]) * (a[c] - b[c]);
    return d;
}

static void test_nearest_as_a_scan(void) {
    enum { N = 3000, Q = 2500 };
    uint64_t s = 88172645463325252ULL;
    double *pts = malloc(3 * N * sizeof *pts), *q = malloc(3 * Q * sizeof *q);
    uint32_t *one = malloc(Q * sizeof *one), *two = malloc(Q * sizeof *two);
    REQUIRE(pts && q && one && two);
    for (int i = 0; i < 3 * N; i++) pts[i] = ps_uniform_next(&s);
    for (int i = 0; i < 3 * Q; i++) q[i] = 1.2 * ps_uniform_next(&s) - 0.1;
    ps_nearest_index *index = ps_nearest_build(pts, N, 3);
    REQUIRE(index);
    ps_error err;
    CHECK(ps_nearest_query(index, q, Q, 1, one, &err) == PS_OK);
    CHECK(ps_nearest_query(index, q, Q, 2, two, &err) == PS_OK);
    for (int t = 0; t < Q; t++) {
        REQUIRE(one[t] < N);
        CHECK(one[t] == two[t]);
        double best = squared(q + 3 * t, pts + 3 * (size_t)one[t]);
        for (int i = 0; i < N; i++)
            CHECK_MSG(squared(q + 3 * t, pts + 3 * i) >= best, "query %d: point %d is nearer", t, i);
    }
    CHECK(ps_nearest_query(index, q, 0, 2, one, &err) == PS_OK);
    ps_nearest_free(index);
    free(pts), free(q), free(one), free(two);
}

PS_TEST_MAIN(TEST(test_nearest_as_a_scan))
