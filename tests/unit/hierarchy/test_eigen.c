/* test_eigen.c: the dense top-two eigensolver and the sign rule (eigen.h). */
#include "hierarchy/eigen.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>

static void test_known_3x3(void) {
    double a[9] = {4, 1, 0, 1, 4, 0, 0, 0, 2};
    double values[2], vectors[6];
    REQUIRE(ps_eigen_top2(a, 3, values, vectors, NULL) == PS_OK);
    CHECK_NEAR(values[0], 5, 1e-12);
    CHECK_NEAR(values[1], 3, 1e-12);
    ps_sign_normalize(vectors, 3);
    ps_sign_normalize(vectors + 3, 3);
    double r = sqrt(0.5);
    CHECK_NEAR(vectors[0], r, 1e-12);
    CHECK_NEAR(vectors[1], r, 1e-12);
    CHECK_NEAR(vectors[2], 0, 1e-12);
    /* (1,-1,0)/sqrt 2: both entries tie in magnitude, the first is made positive */
    CHECK_NEAR(vectors[3], r, 1e-12);
    CHECK_NEAR(vectors[4], -r, 1e-12);
    CHECK_NEAR(vectors[5], 0, 1e-12);
}

/* Path graph adjacency: eigenvalues 2 cos(pi j / (m+1)), vectors
 * sin(pi i j / (m+1)), i, j = 1..m; the top two are j = 1, 2. */
static void test_path_graph(void) {
    enum { M = 50 };
    double *a = calloc(M * M, sizeof *a), values[2], vectors[2 * M];
    REQUIRE(a);
    for (int i = 0; i + 1 < M; i++) a[i * M + i + 1] = a[(i + 1) * M + i] = 1;
    REQUIRE(ps_eigen_top2(a, M, values, vectors, NULL) == PS_OK);
    for (int j = 1; j <= 2; j++) {
        double *v = vectors + (j - 1) * M, norm = 0, dot = 0;
        CHECK_NEAR(values[j - 1], 2 * cos(acos(-1.0) * j / (M + 1)), 1e-12);
        for (int i = 0; i < M; i++) {
            double expected = sin(acos(-1.0) * (i + 1) * j / (M + 1));
            norm += expected * expected;
            dot += expected * v[i];
        }
        CHECK_NEAR(fabs(dot) / sqrt(norm), 1, 1e-10);
    }
    free(a);
}

static void test_sign_rule(void) {
    double v[3] = {0.1, -0.5, 0.3};
    ps_sign_normalize(v, 3);
    CHECK(v[0] == -0.1 && v[1] == 0.5 && v[2] == -0.3);
    double tie[2] = {-0.5, 0.5};
    ps_sign_normalize(tie, 2);
    CHECK(tie[0] == 0.5 && tie[1] == -0.5);
    double kept[2] = {0.5, -0.5};
    ps_sign_normalize(kept, 2);
    CHECK(kept[0] == 0.5 && kept[1] == -0.5);
    double zero[2] = {0, 0};
    ps_sign_normalize(zero, 2);
    CHECK(zero[0] == 0 && zero[1] == 0);
}

/* Whatever sign LAPACK returns, normalization gives one signed vector. */
static void test_sign_deterministic(void) {
    double a[9] = {2, -1, 0, -1, 2, -1, 0, -1, 2}, b[9], v1[6], v2[6], values[2];
    for (int i = 0; i < 9; i++) b[i] = a[i];
    REQUIRE(ps_eigen_top2(a, 3, values, v1, NULL) == PS_OK);
    REQUIRE(ps_eigen_top2(b, 3, values, v2, NULL) == PS_OK);
    for (int i = 0; i < 3; i++) v2[i] = -v2[i];
    ps_sign_normalize(v1, 3);
    ps_sign_normalize(v2, 3);
    for (int i = 0; i < 3; i++) CHECK(v1[i] == v2[i]);
    /* top vector (1, -sqrt 2, 1)/2: the middle, largest, is made positive */
    CHECK_NEAR(v1[0], -0.5, 1e-12);
    CHECK_NEAR(v1[1], sqrt(0.5), 1e-12);
    CHECK_NEAR(v1[2], -0.5, 1e-12);
}

static void test_too_small(void) {
    double a[1] = {1}, values[2], vectors[2];
    ps_error err = {0};
    CHECK(ps_eigen_top2(a, 1, values, vectors, &err) == PS_ERR_INVALID);
    CHECK(err.status == PS_ERR_INVALID);
}

PS_TEST_MAIN(TEST(test_known_3x3), TEST(test_path_graph), TEST(test_sign_rule),
             TEST(test_sign_deterministic), TEST(test_too_small))
