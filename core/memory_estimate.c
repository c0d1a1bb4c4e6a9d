/*
 * memory_estimate.c: ps_segment_memory_estimate (pointseg.h), a model of
 * ps_segment's peak memory fitted to measured peak RSS (tests/bench/
 * bench_scale.c prints the measured bytes per point to check it against):
 * arrays per point that grow with k (the kNN graph in CSR with its weights,
 * kept and scratch), the coordinates copied per dimension, and the
 * two-level centrality's table of cell-to-sample distances (a float per
 * sample for every cell of about CELL_POINTS points; the cell count stops
 * growing at PS_CELL_SCALE_POINTS, coarse_graph.h), over a fixed base; an
 * input split in draws, or a mesh segmented in fills (their pipelines side
 * by side), has per-point constants of its own, and the draws or fills
 * that run at the same time add their working memory; a pipeline small
 * enough for the boundary cut's pairs side by side adds its further
 * workers' scratch.
 */
#include "pointseg.h"

#include "ensemble.h"
#include "features/centrality.h"
#include "features/coarse_graph.h"
#include "graph/reference_density.h"
#include "graph/surface_fill.h"
#include "input_scale.h"
#include "refine/boundary_cut.h"
#include "util/parallel.h"

/* Fitted 2026-11-24 to the peaks of the horse sampled at 300,000 to 10M
 * points, k = 7, 14 and 28 (bench_scale and a progress probe of VmHWM):
 * at k = 7 the peak, table and base aside, is 291 to 325 bytes a point
 * without the input, at k = 28 647; these constants give 397 and 754,
 * about 1.15 (1M, k = 7) to 1.45 (10M) times the measured peak with the
 * input.  The peak is the boundary cut's (refine) or the centrality's. */
#define BASE_BYTES ((size_t)16 << 20) /* the process and small arrays: a run over
                                         25,000 points peaks at 18 MB in all */
#define BYTES_PER_POINT 230           /* labels, f, flow, normals, creases, ... */
#define BYTES_PER_NEIGHBOUR 17        /* per point and unit of k: graph, cut capacities */
#define BYTES_PER_COORDINATE 16       /* the distinct points and one working copy */
#define CELL_POINTS 15                /* points per centrality cell, low end */
/* An input split in draws (ensemble.h) keeps less a point: refitted
 * 2026-11-26 to the peaks of the horse sampled at 300,000 to 10M points,
 * k = 7 and 28 (bench_scale --k): without the input and the base, 183 to
 * 247 bytes a point at k = 7, 510 to 596 at k = 28; these constants give
 * 1.15 times the largest of each. */
#define DRAWS_BYTES_PER_POINT 102
#define DRAWS_BYTES_PER_NEIGHBOUR 19
/* Draws and fills run side by side, as many at once as the threads
 * (ensemble.c); each further one adds its working memory, and the heap
 * keeps what it freed of arrays under glibc's mmap threshold
 * (benchmarks.md, "What the allocator keeps").  Fitted 2026-11-28
 * to the peaks of the horse sampled at 100,000 to 10M points, k = 7 and
 * 28 (bench_scale, against the same code with one draw at a time): 375 +
 * 15 k bytes a point for the first SIDE_SMALL_POINTS of a draw (480 at
 * k = 7 measured on draws of 50,000 to 120,000 points), 100 + 2 k beyond
 * (the largest arrays are mapped and unmapped whole: 105 measured on a
 * draw of 2M). */
#define SIDE_SMALL_POINTS ((size_t)200000)
#define SIDE_BYTES_PER_POINT 375
#define SIDE_BYTES_PER_NEIGHBOUR 15
#define SIDE_LARGE_BYTES_PER_POINT 100
#define SIDE_LARGE_BYTES_PER_NEIGHBOUR 2
/* Each further worker of the boundary cut (boundary_cut.h), up to
 * PS_BOUNDARY_CUT_SIDE_BY_SIDE points a pipeline, holds per-point scratch
 * of its own; what it touches is its distances, band marks and search
 * stamps for every point (20 bytes) and the rest only over the largest
 * band. */
#define CUT_WORKER_BYTES_PER_POINT 48

/* The boundary cut's further workers on a pipeline of n points. */
static size_t cut_workers_bytes(size_t n, const ps_params *params) {
    int threads = ps_parallel_threads(params->threads);
    int extra = (threads < PS_BOUNDARY_CUT_WORKERS ? threads : PS_BOUNDARY_CUT_WORKERS) - 1;
    if (extra <= 0 || n > PS_BOUNDARY_CUT_SIDE_BY_SIDE) return 0;
    return (size_t)extra * n * CUT_WORKER_BYTES_PER_POINT;
}

/* The further pipelines of count (draws or fills) that run side by side,
 * each of n points. */
static size_t side_by_side_bytes(int count, size_t n, const ps_params *params) {
    int further = ps_ensemble_side_by_side(params->threads, count) - 1;
    if (further <= 0) return 0;
    size_t k = (size_t)params->k, small = n < SIDE_SMALL_POINTS ? n : SIDE_SMALL_POINTS;
    size_t one = small * (SIDE_BYTES_PER_POINT + SIDE_BYTES_PER_NEIGHBOUR * k) +
                 (n - small) * (SIDE_LARGE_BYTES_PER_POINT + SIDE_LARGE_BYTES_PER_NEIGHBOUR * k);
    return (size_t)further * one;
}

/* The two-level centrality's table for a pipeline of n points. */
static size_t table_bytes(size_t n, const ps_params *params) {
    int approx = params->centrality == PS_CENTRALITY_APPROX ||
                 (params->centrality == PS_CENTRALITY_AUTO && n > PS_EXACT_AUTO_LIMIT);
    if (!approx) return 0;
    size_t samples = params->samples > 0 ? (size_t)params->samples
                                         : (size_t)ps_centrality_default_samples(n);
    size_t cells = (n < PS_CELL_SCALE_POINTS ? n : PS_CELL_SCALE_POINTS) / CELL_POINTS;
    return cells * samples * sizeof(float);
}

/* The estimate for n points of dim coordinates run as given: fills below
 * the reference when fills is set, else one run or draws. */
static size_t estimate_of(size_t n, int dim, int fills, const ps_params *params) {
    if (fills) n = PS_ENSEMBLE_FILLS * (size_t)PS_DENSITY_REFERENCE_POINTS;
    int n_draws = fills ? PS_ENSEMBLE_FILLS : ps_ensemble_draws(params, n), draws = n_draws > 0;
    size_t per_pipeline = fills      ? PS_DENSITY_REFERENCE_POINTS
                          : n_draws ? ps_ensemble_draw_points(n)
                                    : n;
    size_t per_point = (draws ? DRAWS_BYTES_PER_POINT : BYTES_PER_POINT) +
                       (draws ? DRAWS_BYTES_PER_NEIGHBOUR : BYTES_PER_NEIGHBOUR) * (size_t)params->k +
                       BYTES_PER_COORDINATE * (size_t)dim;
    size_t table = fills ? PS_ENSEMBLE_FILLS * table_bytes(per_pipeline, params) : table_bytes(n, params);
    return BASE_BYTES + n * per_point + table + cut_workers_bytes(per_pipeline, params) +
           side_by_side_bytes(n_draws, per_pipeline, params);
}

size_t ps_segment_memory_estimate(const ps_input *in, const ps_params *params) {
    size_t n = in->n;
    int dim = in->dim;
    /* method auto segments 2-D points as a 3-D copy, and points of extreme
     * extent as a scaled copy (segment.c, input_scale.h) */
    int lift = params->method == PS_METHOD_AUTO && dim == 2;
    int scaled = in->points && ps_input_scale_exponent(in->points, n, dim, NULL) != 0;
    if (lift) dim = 3;
    size_t copied = lift || scaled ? n * (size_t)dim * sizeof(double) : 0;
    /* A mesh under the reference sampling is filled up to it; one over it
     * may be too, when its distinct points are fewer (an unwelded mesh
     * repeats each corner per triangle), and one too rough to fill runs on
     * its own: the larger of its own run and the fills.  A bare point set
     * is never filled. */
    size_t run = estimate_of(n, dim, 0, params);
    if (in->n_faces > 0 && ps_surface_fill_wanted(params, dim, 0)) {
        size_t filled = estimate_of(n, dim, 1, params);
        if (filled > run) run = filled;
    }
    return copied + run;
}
