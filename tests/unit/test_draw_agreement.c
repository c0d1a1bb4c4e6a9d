/* test_draw_agreement.c: the draws' agreement of bench_quality --seeds
 * (tests/support/draw_agreement.c) on hand-computed cases: the mean Rand
 * index error over the draws' pairs and the medoid, the first among
 * equals, wherever the odd draw stands. */
#include "draw_agreement.h"
#include "testlib.h"

static const int split_even[] = {0, 0, 1, 1};
static const int split_even_renamed[] = {5, 5, 3, 3};
static const int split_odd[] = {0, 0, 0, 1}; /* 0.5 from the others (test_score.c) */

static void test_identical_draws_agree(void) {
    const int *draws[] = {split_even, split_even_renamed};
    ps_draw_agreement a = ps_draws_agree(draws, 2, 4);
    CHECK(a.disagreement == 0.0);
    CHECK(a.medoid == 0);
}

/* Pairs: 0 (the two even splits), 0.5 and 0.5: mean 1/3; the even splits
 * are each 0.5 from the others, the odd one 1.0. */
static void test_odd_draw_is_no_medoid(void) {
    const int *last[] = {split_even, split_even_renamed, split_odd};
    const int *first[] = {split_odd, split_even_renamed, split_even};
    ps_draw_agreement a = ps_draws_agree(last, 3, 4), b = ps_draws_agree(first, 3, 4);
    CHECK_NEAR(a.disagreement, 1.0 / 3.0, 1e-15);
    CHECK_NEAR(b.disagreement, 1.0 / 3.0, 1e-15);
    CHECK_MSG(a.medoid == 0, "medoid %d", a.medoid);
    CHECK_MSG(b.medoid == 1, "medoid %d", b.medoid);
}

int main(int argc, char **argv) {
    static const ps_test_case tests[] = {TEST(test_identical_draws_agree),
                                         TEST(test_odd_draw_is_no_medoid)};
    return ps_test_main(__FILE__, tests, sizeof tests / sizeof tests[0], argc, argv);
}
