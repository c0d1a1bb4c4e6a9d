/*
 * select_parallel.c: the k-th smallest by bins (select_parallel.h).
 *
 * The array is cut into CHUNKS fixed chunks (so the bins' counts do not
 * depend on the thread count); each pass is a ps_parallel_for over them.
 * An array under SMALL values is copied and selected in one go.
 */
#include "util/select_parallel.h"

#include "util/parallel.h"
#include "util/sort_util.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define CHUNKS 16
#define SMALL 65536

typedef struct select_job {
    const double *x;
    size_t n;
    double lo, scale;     /* bin of v: (v - lo) * scale, below PS_SELECT_BINS */
    double min[CHUNKS], max[CHUNKS];
    uint32_t *counts;     /* CHUNKS by PS_SELECT_BINS */
    size_t bin;           /* the bin holding rank k */
    size_t offset[CHUNKS];/* where each chunk's values of that bin go in out */
    double *out;
} select_job;

static size_t chunk_begin(const select_job *j, size_t c) { return j->n * c / CHUNKS; }

static size_t bin_of(const select_job *j, double v) {
    size_t b = (size_t)((v - j->lo) * j->scale);
    return b < PS_SELECT_BINS ? b : PS_SELECT_BINS - 1;
}

static void range_task(void *ctx, size_t begin, size_t end, int worker) {
    select_job *j = ctx;
    (void)worker;
    for (size_t c = begin; c < end; c++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = chunk_begin(j, c); i < chunk_begin(j, c + 1); i++) {
            if (j->x[i] < lo) lo = j->x[i];
            if (j->x[i] > hi) hi = j->x[i];
        }
        j->min[c] = lo, j->max[c] = hi;
    }
}

static void count_task(void *ctx, size_t begin, size_t end, int worker) {
    select_job *j = ctx;
    (void)worker;
    for (size_t c = begin; c < end; c++) {
        uint32_t *counts = j->counts + c * PS_SELECT_BINS;
        for (size_t i = chunk_begin(j, c); i < chunk_begin(j, c + 1); i++)
            counts[bin_of(j, j->x[i])]++;
    }
}

static void gather_task(void *ctx, size_t begin, size_t end, int worker) {
    select_job *j = ctx;
    (void)worker;
    for (size_t c = begin; c < end; c++) {
        double *out = j->out + j->offset[c];
        for (size_t i = chunk_begin(j, c); i < chunk_begin(j, c + 1); i++)
            if (bin_of(j, j->x[i]) == j->bin) *out++ = j->x[i];
    }
}

/* The bin holding rank *k, and *k made the rank within it; the chunks'
 * offsets for its values.  Returns the bin's count. */
static size_t find_bin(select_job *j, size_t *k) {
    size_t below = 0;
    for (size_t b = 0; b < PS_SELECT_BINS; b++) {
        size_t in_bin = 0;
        for (size_t c = 0; c < CHUNKS; c++) in_bin += j->counts[c * PS_SELECT_BINS + b];
        if (*k < below + in_bin) {
            j->bin = b;
            *k -= below;
            size_t at = 0;
            for (size_t c = 0; c < CHUNKS; c++) {
                j->offset[c] = at;
                at += j->counts[c * PS_SELECT_BINS + b];
            }
            return in_bin;
        }
        below += in_bin;
    }
    return 0; /* not reached: k < n */
}

double ps_select_kth_parallel(const double *x, size_t n, size_t k, int threads,
                              double *scratch) {
    threads = ps_parallel_threads(threads);
    if (n < SMALL) {
        memcpy(scratch, x, n * sizeof *scratch);
        return ps_select_kth(scratch, n, k);
    }
    select_job j = {.x = x, .n = n, .out = scratch};
    ps_parallel_for(threads, CHUNKS, 1, range_task, &j);
    double lo = j.min[0], hi = j.max[0];
    for (size_t c = 1; c < CHUNKS; c++) lo = fmin(lo, j.min[c]), hi = fmax(hi, j.max[c]);
    if (lo == hi) return lo;
    j.lo = lo, j.scale = PS_SELECT_BINS / (hi - lo);
    j.counts = calloc((size_t)CHUNKS * PS_SELECT_BINS, sizeof *j.counts);
    if (!j.counts) return NAN;
    ps_parallel_for(threads, CHUNKS, 1, count_task, &j);
    size_t in_bin = find_bin(&j, &k);
    free(j.counts);
    ps_parallel_for(threads, CHUNKS, 1, gather_task, &j);
    return ps_select_kth(scratch, in_bin, k);
}
