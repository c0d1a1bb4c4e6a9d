/* test_select_parallel.c: ps_select_kth_parallel gives exactly the k-th
 * smallest that a sort gives, for ranks at both ends and in the middle,
 * on arrays above and below its bins' size limit, with many equal values,
 * with most values packed into one bin beside far outliers, and on a
 * constant array, for 1, 2 and 3 threads; the array is left unchanged. */
#include "random_bits.h"
#include "testlib.h"
#include "util/select_parallel.h"
#include "util/sort_util.h"

#include <stdlib.h>
#include <string.h>

static int compare_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Every rank of ranks[] against a sorted copy, for 1 to 3 threads. */
static void check_ranks(const double *x, size_t n) {
    double *sorted = malloc(n * sizeof *sorted), *copy = malloc(n * sizeof *copy);
    double *scratch = malloc(n * sizeof *scratch);
    CHECK(sorted && copy && scratch);
    if (sorted && copy && scratch) {
        memcpy(sorted, x, n * sizeof *sorted);
        memcpy(copy, x, n * sizeof *copy);
        qsort(sorted, n, sizeof *sorted, compare_double);
        size_t ranks[] = {0, 1, n / 3, n / 2, n - 2, n - 1};
        for (int threads = 1; threads <= 3; threads++)
            for (size_t r = 0; r < sizeof ranks / sizeof *ranks; r++) {
                double got = ps_select_kth_parallel(x, n, ranks[r], threads, scratch);
                CHECK_MSG(got == sorted[ranks[r]], "n %zu rank %zu threads %d: %g, want %g", n,
                          ranks[r], threads, got, sorted[ranks[r]]);
            }
        CHECK(memcmp(copy, x, n * sizeof *copy) == 0);
    }
    free(sorted), free(copy), free(scratch);
}

static void test_random_values(void) {
    size_t sizes[] = {10, 1000, 70000, 300001};
    uint64_t s = 7;
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
        double *x = malloc(sizes[i] * sizeof *x);
        for (size_t j = 0; x && j < sizes[i]; j++) x[j] = (double)(ps_random_bits(&s) >> 11) * 1e-9;
        if (x) check_ranks(x, sizes[i]);
        free(x);
    }
}

static void test_many_equal_values(void) {
    size_t n = 200000;
    uint64_t s = 3;
    double *x = malloc(n * sizeof *x);
    for (size_t j = 0; x && j < n; j++) x[j] = (double)(ps_random_bits(&s) % 17);
    if (x) check_ranks(x, n);
    free(x);
}

static void test_one_crowded_bin(void) {
    size_t n = 150000;
    uint64_t s = 11;
    double *x = malloc(n * sizeof *x);
    for (size_t j = 0; x && j < n; j++) x[j] = 1.0 + (double)(ps_random_bits(&s) % 1000) * 1e-12;
    if (x) x[5] = 1e9, x[n - 7] = -1e9; /* the range's ends, far from the crowd */
    if (x) check_ranks(x, n);
    free(x);
}

static void test_constant_array(void) {
    size_t n = 100000;
    double *x = malloc(n * sizeof *x), *scratch = malloc(n * sizeof *scratch);
    CHECK(x && scratch);
    for (size_t j = 0; x && j < n; j++) x[j] = 2.5;
    if (x && scratch) CHECK(ps_select_kth_parallel(x, n, n / 2, 2, scratch) == 2.5);
    free(x), free(scratch);
}

PS_TEST_MAIN(TEST(test_random_values), TEST(test_many_equal_values), TEST(test_one_crowded_bin),
             TEST(test_constant_array))
