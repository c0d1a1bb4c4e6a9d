/* test_score.c: the Rand Index error and the face majority rule (score.c),
 * checked on hand-computed cases, against a brute-force pair count, and on
 * the PSB developer set's published "None" reference. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "pointseg.h"
#include "psb_data.h"
#include "random_bits.h"
#include "testlib.h"

static void test_identical_is_zero(void) {
    const int a[] = {0, 0, 1, 1, 2, 2, 2};
    CHECK(ps_rand_index_error(a, a, 7) == 0.0);
}

static void test_relabelled_is_zero(void) {
    const int a[] = {0, 0, 1, 1, 2, 2, 2};
    const int b[] = {7, 7, 2147483647, 2147483647, 3, 3, 3};
    CHECK(ps_rand_index_error(a, b, 7) == 0.0);
    CHECK(ps_rand_index_error(b, a, 7) == 0.0);
}

static void test_one_vs_all_separate_is_one(void) {
    const int one[] = {4, 4, 4, 4, 4, 4};
    const int separate[] = {0, 1, 2, 3, 4, 5};
    CHECK(ps_rand_index_error(one, separate, 6) == 1.0);
}

/* {0,0,1,1} vs {0,0,0,1}: of the 6 pairs, (1,3), (2,3) are together only in
 * the second and (3,4) only in the first: 3 disagreements, error 0.5. */
static void test_four_items_by_hand(void) {
    const int a[] = {0, 0, 1, 1};
    const int b[] = {0, 0, 0, 1};
    CHECK_NEAR(ps_rand_index_error(a, b, 4), 0.5, 1e-15);
    CHECK_NEAR(ps_rand_index_error(b, a, 4), 0.5, 1e-15);
}

/* {0,0,0,1,1} vs {5,5,6,6,6}: together in a 4, in b 4, in both 2: (4+4-4)/10. */
static void test_five_items_by_hand(void) {
    const int a[] = {0, 0, 0, 1, 1};
    const int b[] = {5, 5, 6, 6, 6};
    CHECK_NEAR(ps_rand_index_error(a, b, 5), 0.4, 1e-15);
}

static void test_fewer_than_two_items(void) {
    const int a[] = {3};
    CHECK(ps_rand_index_error(a, a, 1) == 0.0);
    CHECK(ps_rand_index_error(NULL, NULL, 0) == 0.0);
}

static double brute_force_error(const int *a, const int *b, size_t n) {
    size_t disagree = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            disagree += (a[i] == a[j]) != (b[i] == b[j]);
    return (double)disagree / ((double)n * (double)(n - 1) / 2);
}

static void test_matches_brute_force(void) {
    enum { N = 600 };
    static int a[N], b[N];
    uint64_t seed = 12345;
    for (int round = 0; round < 5; round++) {
        uint32_t ka = 1 + round * 3, kb = 2 + round * 7;
        for (int i = 0; i < N; i++) {
            a[i] = (int)(ps_random_bits(&seed) % ka) * 1000003;
            b[i] = (int)(ps_random_bits(&seed) % kb);
        }
        CHECK_NEAR(ps_rand_index_error(a, b, N), brute_force_error(a, b, N), 1e-12);
    }
}

/* The two parts by hand ({0,0,0,1,1} vs {5,5,6,6,6}: 2 pairs together in
 * a alone, 2 in b alone, of 10) and against a brute-force count; with
 * one label for all, every disagreement is a's. */
static void test_parts(void) {
    const int a[] = {0, 0, 0, 1, 1}, b[] = {5, 5, 6, 6, 6}, one[] = {7, 7, 7, 7, 7};
    double a_only, b_only;
    CHECK_NEAR(ps_rand_index_parts(a, b, 5, &a_only, &b_only), 0.4, 1e-15);
    CHECK_NEAR(a_only, 0.2, 1e-15);
    CHECK_NEAR(b_only, 0.2, 1e-15);
    CHECK_NEAR(ps_rand_index_parts(one, b, 5, &a_only, &b_only), 0.6, 1e-15);
    CHECK(b_only == 0.0 && a_only == ps_rand_index_error(one, b, 5));
    enum { N = 300 };
    static int x[N], y[N];
    uint64_t seed = 777;
    for (int i = 0; i < N; i++) {
        x[i] = (int)(ps_random_bits(&seed) % 4);
        y[i] = (int)(ps_random_bits(&seed) % 9);
    }
    size_t x_only = 0, y_only = 0;
    for (size_t i = 0; i < N; i++)
        for (size_t j = i + 1; j < N; j++) {
            x_only += x[i] == x[j] && y[i] != y[j];
            y_only += y[i] == y[j] && x[i] != x[j];
        }
    double pairs = N * (N - 1) / 2.0;
    ps_rand_index_parts(x, y, N, &a_only, &b_only);
    CHECK_NEAR(a_only, (double)x_only / pairs, 1e-12);
    CHECK_NEAR(b_only, (double)y_only / pairs, 1e-12);
}

static void test_face_majority(void) {
    const int vl[] = {5, 5, 9, 1, 2, 3, 4};
    const uint32_t faces[] = {0, 1, 2, /* 5 5 9 -> 5 */
                              2, 0, 1, /* 9 5 5 -> 5 */
                              0, 2, 1, /* 5 9 5 -> 5 */
                              3, 4, 5, /* 1 2 3 -> first, 1 */
                              5, 3, 4, /* 3 1 2 -> first, 3 */
                              6, 6, 6, /* 4 4 4 -> 4 */
                              2, 2, 0}; /* 9 9 5 -> 9 */
    int fl[7] = {0};
    ps_face_labels_from_vertices(vl, faces, 7, fl);
    const int expected[7] = {5, 5, 5, 1, 3, 4, 9};
    for (int f = 0; f < 7; f++) CHECK_MSG(fl[f] == expected[f], "face %d: %d, expected %d", f, fl[f], expected[f]);
}

/* Mean over the humans of model id of the error of labelling every vertex
 * the same; NAN when the model does not load. */
static double none_score_of_model(const char *dir, int id) {
    ps_pointset mesh;
    ps_psb_humans humans;
    if (ps_psb_load_mesh(dir, id, &mesh) != 0) return NAN;
    double score = NAN;
    int *same = calloc(mesh.n, sizeof *same);
    if (same && ps_psb_load_humans(dir, id, mesh.n_faces, &humans) == 0) {
        score = ps_psb_score(&mesh, same, &humans);
        ps_psb_humans_free(&humans);
    }
    free(same);
    ps_pointset_free(&mesh);
    return score;
}

/* People among themselves on model id (ps_psb_human_agreement); NAN when
 * the model does not load. */
static double people_of_model(const char *dir, int id) {
    ps_pointset mesh;
    ps_psb_humans humans;
    if (ps_psb_load_mesh(dir, id, &mesh) != 0) return NAN;
    double agreement = NAN;
    if (ps_psb_load_humans(dir, id, mesh.n_faces, &humans) == 0) {
        agreement = ps_psb_human_agreement(&humans);
        ps_psb_humans_free(&humans);
    }
    ps_pointset_free(&mesh);
    return agreement;
}

/* The mean of of_model over the models ids #n_ids of dir, each in (0, 1). */
static double mean_of_models(const char *dir, const int *ids, size_t n_ids,
                             double (*of_model)(const char *dir, int id)) {
    double total = 0;
    for (size_t m = 0; m < n_ids; m++) {
        double value = of_model(dir, ids[m]);
        CHECK_MSG(value > 0 && value < 1, "model %d: %g", ids[m], value);
        total += value;
    }
    return n_ids ? total / (double)n_ids : NAN;
}

/* The psb-dev README: labelling every vertex the same ("None") scores 0.6645
 * as the mean over the 38 models of the mean over their humans. */
static void test_psb_none_reference(void) {
    char dir[4096];
    if (!ps_test_shared_dir() || !ps_psb_find_dir(NULL, dir, sizeof dir))
        SKIP("PSB developer set not found (../shared/data/psb-dev or $POINTSEG_SHARED)");
    size_t n_ids = 0;
    int *ids = ps_psb_model_ids(dir, &n_ids);
    CHECK(n_ids == 38);
    CHECK_NEAR(mean_of_models(dir, ids, n_ids, none_score_of_model), 0.6645, 5e-5);
    free(ids);
}

/* The psb-dev README: each human segmentation against the other humans of
 * the same model scores 0.092 as the mean over the 38 models. */
static void test_psb_people_reference(void) {
    char dir[4096];
    if (!ps_test_shared_dir() || !ps_psb_find_dir(NULL, dir, sizeof dir))
        SKIP("PSB developer set not found (../shared/data/psb-dev or $POINTSEG_SHARED)");
    size_t n_ids = 0;
    int *ids = ps_psb_model_ids(dir, &n_ids);
    REQUIRE(n_ids == 38);
    CHECK_NEAR(mean_of_models(dir, ids, n_ids, people_of_model), 0.0919, 5e-4);
    free(ids);
}

/* One human segmentation has no one to agree with. */
static void test_people_need_two(void) {
    int labels[3] = {0, 0, 1}, *rows[1] = {labels};
    ps_psb_humans one = {.n_humans = 1, .n_faces = 3, .labels = rows};
    CHECK(isnan(ps_psb_human_agreement(&one)));
    int other[3] = {0, 1, 1}, *two_rows[2] = {labels, other};
    ps_psb_humans two = {.n_humans = 2, .n_faces = 3, .labels = two_rows};
    CHECK_NEAR(ps_psb_human_agreement(&two), 2.0 / 3.0, 1e-12);
}

PS_TEST_MAIN(TEST(test_identical_is_zero), TEST(test_relabelled_is_zero),
             TEST(test_one_vs_all_separate_is_one), TEST(test_four_items_by_hand),
             TEST(test_five_items_by_hand), TEST(test_fewer_than_two_items),
             TEST(test_matches_brute_force), TEST(test_parts), TEST(test_face_majority),
             TEST(test_psb_none_reference), TEST(test_psb_people_reference),
             TEST(test_people_need_two))
