/* test_sort_util.c: the shared qsort / bsearch comparison (sort_util.h),
 * including values whose difference overflows an int; the radix sort
 * against qsort on keys over the full range, with ties, and on keys that
 * share their high bytes; the grouping of items by label, with an empty
 * group; and the selection of the k-th smallest value against a sort, with
 * ties. */
#include "random_bits.h"
#include "testlib.h"
#include "util/sort_util.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static void test_compare_u32_orders_full_range(void) {
    uint32_t v[6] = {UINT32_MAX, 0, 7, 0x80000000u, 7, 1};
    static const uint32_t sorted[6] = {0, 1, 7, 7, 0x80000000u, UINT32_MAX};
    qsort(v, 6, sizeof *v, ps_compare_u32);
    for (int i = 0; i < 6; i++) CHECK_MSG(v[i] == sorted[i], "v[%d] = %u", i, (unsigned)v[i]);
    uint32_t a = 0, b = UINT32_MAX;
    CHECK(ps_compare_u32(&a, &b) == -1 && ps_compare_u32(&b, &a) == 1);
    CHECK(ps_compare_u32(&a, &a) == 0);
    uint32_t key = 0x80000000u, missing = 2;
    const uint32_t *hit = bsearch(&key, v, 6, sizeof *v, ps_compare_u32);
    CHECK(hit == &v[4]);
    CHECK(bsearch(&missing, v, 6, sizeof *v, ps_compare_u32) == NULL);
}

static int compare_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void test_select_kth_matches_sort(void) {
    enum { N = 101 };
    double values[N], sorted[N], work[N];
    unsigned state = 12345;
    for (int i = 0; i < N; i++) {
        state = state * 1103515245u + 12345u;
        values[i] = (double)((state >> 16) % 40); /* many ties */
    }
    memcpy(sorted, values, sizeof values);
    qsort(sorted, N, sizeof *sorted, compare_double);
    for (size_t k = 0; k < N; k++) {
        memcpy(work, values, sizeof values);
        CHECK_MSG(ps_select_kth(work, N, k) == sorted[k], "k = %zu", k);
    }
    double one = 3.5;
    CHECK(ps_select_kth(&one, 1, 0) == 3.5);
}

/* ps_sort_u32 on n keys drawn with mask (full range, or sharing high
 * bytes), against qsort. */
static void check_radix(size_t n, uint32_t mask) {
    uint32_t *keys = malloc((n ? n : 1) * sizeof *keys), *expect = malloc((n ? n : 1) * sizeof *keys);
    uint32_t *scratch = malloc((n ? n : 1) * sizeof *keys);
    REQUIRE(keys && expect && scratch);
    uint64_t state = 88172645463325252ull;
    for (size_t i = 0; i < n; i++) {
        keys[i] = (uint32_t)(ps_random_bits(&state) >> 20) & mask;
    }
    if (n > 2) keys[0] = UINT32_MAX & mask, keys[1] = 0;
    memcpy(expect, keys, n * sizeof *keys);
    qsort(expect, n, sizeof *expect, ps_compare_u32);
    ps_sort_u32(keys, n, scratch);
    CHECK_MSG(n == 0 || memcmp(keys, expect, n * sizeof *keys) == 0, "n %zu mask %x", n,
              (unsigned)mask);
    free(keys), free(expect), free(scratch);
}

static void test_radix_sort_matches_qsort(void) {
    static const size_t sizes[] = {0, 1, 2, 3, 255, 1000, 100000};
    static const uint32_t masks[] = {UINT32_MAX, 0xFFFFu, 0xF0F0u, 7u};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
        for (size_t m = 0; m < sizeof masks / sizeof *masks; m++) check_radix(sizes[i], masks[m]);
}

/* ps_order_by_u32: keys in increasing order, ties (mask 7: many) in
 * increasing index. */
static void test_order_by_key_stable(void) {
    enum { N = 20000 };
    uint32_t *keys = malloc(N * sizeof *keys), *order = malloc(N * sizeof *order);
    uint32_t *scratch = malloc(N * sizeof *scratch);
    REQUIRE(keys && order && scratch);
    static const uint32_t masks[] = {UINT32_MAX, 0xFF00FFu, 7u};
    for (size_t m = 0; m < sizeof masks / sizeof *masks; m++) {
        uint64_t state = 88172645463325252ull;
        for (size_t i = 0; i < N; i++) {
            keys[i] = (uint32_t)(ps_random_bits(&state) >> 20) & masks[m];
        }
        ps_order_by_u32(keys, N, order, scratch);
        int seen_ok = 1;
        for (size_t i = 1; i < N; i++) {
            uint32_t a = order[i - 1], b = order[i];
            if (keys[a] > keys[b] || (keys[a] == keys[b] && a >= b)) seen_ok = 0;
        }
        CHECK_MSG(seen_ok, "mask %x", (unsigned)masks[m]);
    }
    ps_order_by_u32(keys, 1, order, scratch);
    CHECK(order[0] == 0);
    free(keys), free(order), free(scratch);
}

/* Items grouped by label, each group in index order; group 2 is empty. */
static void test_group_by_label(void) {
    static const uint32_t label[8] = {3, 0, 3, 1, 0, 3, 1, 0};
    static const uint32_t want_members[8] = {1, 4, 7, 3, 6, 0, 2, 5};
    static const size_t want_first[5] = {0, 3, 5, 5, 8};
    size_t first[5];
    uint32_t members[8];
    ps_group_by_label(label, 8, 4, first, members);
    CHECK(memcmp(first, want_first, sizeof first) == 0);
    CHECK(memcmp(members, want_members, sizeof members) == 0);
    ps_group_by_label(label, 0, 4, first, members);
    for (int g = 0; g <= 4; g++) CHECK(first[g] == 0);
}

PS_TEST_MAIN(TEST(test_compare_u32_orders_full_range), TEST(test_select_kth_matches_sort),
             TEST(test_radix_sort_matches_qsort), TEST(test_order_by_key_stable),
             TEST(test_group_by_label))
