/*
 * score.c: the Princeton Segmentation Benchmark's Rand Index error between
 * two labellings, and the majority rule that turns vertex labels into face
 * labels (see pointseg.h and the psb-dev README).
 *
 * 1 - RI = [sum_i C(a_i,2) + sum_j C(b_j,2) - 2 sum_ij C(n_ij,2)] / C(n,2),
 * with n_ij the contingency counts and a_i, b_j its row and column sums.
 * The counts come from sorting: the pair (a, b) packed into one 64-bit key
 * sorts by row then column, so runs of equal keys are the n_ij and runs of
 * equal high halves are the a_i; a sorted copy of b gives the b_j.  Label
 * values are never used as indices, so any int is fine.  The pairs joined
 * in a alone are sum_i C(a_i,2) - sum_ij C(n_ij,2), in b alone likewise.
 */
#include "pointseg.h"

#include <math.h>
#include <stdlib.h>

static uint64_t pairs_of(uint64_t count) { return count * (count - 1) / 2; }

static int compare_u64(const void *x, const void *y) {
    uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

static uint64_t pack_pair(int a, int b) {
    return ((uint64_t)(uint32_t)a << 32) | (uint64_t)(uint32_t)b;
}

/* sum over runs of equal (key >> shift) in sorted keys of C(run length, 2). */
static uint64_t pairs_in_runs(const uint64_t *keys, size_t n, int shift) {
    uint64_t total = 0;
    size_t start = 0;
    for (size_t i = 1; i <= n; i++) {
        if (i == n || (keys[i] >> shift) != (keys[start] >> shift)) {
            total += pairs_of(i - start);
            start = i;
        }
    }
    return total;
}

double ps_rand_index_parts(const int *a, const int *b, size_t n, double *a_only,
                           double *b_only) {
    if (a_only) *a_only = 0;
    if (b_only) *b_only = 0;
    if (n < 2) return 0.0;
    uint64_t *keys = malloc(n * sizeof *keys);
    if (!keys) {
        if (a_only) *a_only = NAN;
        if (b_only) *b_only = NAN;
        return NAN;
    }

    for (size_t i = 0; i < n; i++) keys[i] = pack_pair(a[i], b[i]);
    qsort(keys, n, sizeof *keys, compare_u64);
    uint64_t same_both = pairs_in_runs(keys, n, 0);
    uint64_t same_a = pairs_in_runs(keys, n, 32);

    for (size_t i = 0; i < n; i++) keys[i] = (uint32_t)b[i];
    qsort(keys, n, sizeof *keys, compare_u64);
    uint64_t same_b = pairs_in_runs(keys, n, 0);
    free(keys);

    double pairs = (double)pairs_of(n);
    if (a_only) *a_only = (double)(same_a - same_both) / pairs;
    if (b_only) *b_only = (double)(same_b - same_both) / pairs;
    return (double)(same_a + same_b - 2 * same_both) / pairs;
}

double ps_rand_index_error(const int *a, const int *b, size_t n) {
    return ps_rand_index_parts(a, b, n, NULL, NULL);
}

static int majority_of_three(int first, int second, int third) {
    if (first == second || first == third) return first;
    if (second == third) return second;
    return first;
}

void ps_face_labels_from_vertices(const int *vertex_labels,
                                  const uint32_t *faces, size_t n_faces,
                                  int *face_labels) {
    for (size_t f = 0; f < n_faces; f++) {
        const uint32_t *v = faces + 3 * f;
        face_labels[f] = majority_of_three(vertex_labels[v[0]], vertex_labels[v[1]],
                                           vertex_labels[v[2]]);
    }
}
