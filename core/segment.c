/*
 * segment.c: ps_segment, the method as a list of steps (steps[] below, in
 * the order docs/method.md describes them), each a call into pipeline.c.
 *
 * ps_segment validates the input and the parameters (method auto takes 2-D
 * points as the plane z = 0 in 3-D), scales points of extreme magnitude by
 * a power of two (input_scale.h; refused when their magnitudes lie too far
 * apart for that), removes duplicate points, then runs the
 * five phases (ps_phase, pointseg.h) one after the other, each its steps in
 * the table's order: those of every method (the paper's: kNN graph,
 * centrality, flow to sinks, normalized cuts, feature-size merge), those of
 * method auto, and those of auto in 3-D, which read normals (crease-aware).
 * It times each step and phase, reports progress after each step and
 * honours the cancel flag between steps.  The result is assembled by
 * result.c for the caller's points; duplicates get their representative's
 * answers.  With method auto a mesh under the reference sampling
 * (reference_density.h) and an input denser than it go to ensemble.h, which
 * runs the same phases on fills of the mesh's triangles (surface_fill.h) or
 * on draws of the input, and answers from the one the others agree with
 * most.
 */
#include "ensemble.h"
#include "graph/surface_fill.h"
#include "hierarchy/eigen.h"
#include "input_scale.h"
#include "pipeline.h"
#include "pointseg.h"
#include "segment.h"
#include "util/control.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>

/* When a step runs. */
typedef enum step_when {
    EVERY_METHOD,   /* paper and auto */
    AUTO,           /* method auto */
    CREASE_AWARE,   /* method auto in 3-D: the steps that read normals */
    F2_ASKED,       /* ps_params.use_f2 */
} step_when;

typedef struct step {
    const char *name;           /* ps_step_name: the timings' and docs' */
    ps_phase phase;
    step_when when;
    double done;                /* the phase's progress once it has run */
    ps_pipeline_step_fn *run;   /* pipeline.c */
} step;

/* The method, step by step (docs/method.md, in the same order), indexed
 * by ps_step. */
static const step steps[PS_STEP_COUNT] = {
    [PS_STEP_KNN_GRAPH] = {"knn_graph", PS_PHASE_KNN, EVERY_METHOD, 0.45, ps_pipeline_knn_graph},
    [PS_STEP_OUTLIERS] = {"outliers", PS_PHASE_KNN, AUTO, 0.55, ps_pipeline_outliers},
    [PS_STEP_COMPONENTS] = {"components", PS_PHASE_KNN, EVERY_METHOD, 0.55,
                            ps_pipeline_components},
    [PS_STEP_NORMALS] = {"normals", PS_PHASE_KNN, CREASE_AWARE, 0.9, ps_pipeline_normals},
    [PS_STEP_CREASE_METRIC] = {"crease_metric", PS_PHASE_KNN, CREASE_AWARE, 1.0,
                               ps_pipeline_crease_metric},
    [PS_STEP_CENTRALITY] = {"centrality", PS_PHASE_CENTRALITY, EVERY_METHOD, 1.0,
                            ps_pipeline_centrality},
    [PS_STEP_SUPERNODES] = {"supernodes", PS_PHASE_SUPERNODES, EVERY_METHOD, 0.5,
                            ps_pipeline_supernodes},
    [PS_STEP_F2_SPLIT] = {"f2_split", PS_PHASE_SUPERNODES, F2_ASKED, 0.6, ps_pipeline_f2_split},
    [PS_STEP_CREASE_SPLIT] = {"crease_split", PS_PHASE_SUPERNODES, CREASE_AWARE, 0.8,
                              ps_pipeline_crease_split},
    [PS_STEP_PROFILE_SPLIT] = {"profile_split", PS_PHASE_SUPERNODES, CREASE_AWARE, 1.0,
                               ps_pipeline_profile_split},
    [PS_STEP_NCUT] = {"ncut", PS_PHASE_HIERARCHY, EVERY_METHOD, 1.0, ps_pipeline_ncut},
    [PS_STEP_FEATURE_MERGE] = {"feature_merge", PS_PHASE_REFINE, EVERY_METHOD, 0.2,
                               ps_pipeline_feature_merge},
    [PS_STEP_BOUNDARY_CUT] = {"boundary_cut", PS_PHASE_REFINE, CREASE_AWARE, 0.7,
                              ps_pipeline_boundary_cut},
    [PS_STEP_CREASE_MERGE] = {"crease_merge", PS_PHASE_REFINE, CREASE_AWARE, 0.85,
                              ps_pipeline_crease_merge},
    [PS_STEP_CONVEX_MERGE] = {"convex_merge", PS_PHASE_REFINE, CREASE_AWARE, 0.95,
                              ps_pipeline_convex_merge},
    [PS_STEP_PATCH_MERGE] = {"patch_merge", PS_PHASE_REFINE, CREASE_AWARE, 1.0,
                             ps_pipeline_patch_merge},
};

const char *ps_step_name(ps_step id) {
    return id >= 0 && id < PS_STEP_COUNT ? steps[id].name : "unknown";
}

ps_phase ps_step_phase(ps_step id) {
    return id >= 0 && id < PS_STEP_COUNT ? steps[id].phase : PS_PHASE_COUNT;
}

/* The crease-aware steps read normals, which need a surface in 3-D. */
static int crease_aware(const ps_pipeline *pl) {
    return pl->params.method == PS_METHOD_AUTO && pl->in->dim == 3;
}

static int wanted(const ps_pipeline *pl, step_when when) {
    switch (when) {
    case AUTO: return pl->params.method == PS_METHOD_AUTO;
    case CREASE_AWARE: return crease_aware(pl);
    case F2_ASKED: return pl->params.use_f2;
    default: return 1;
    }
}

/* The merges from index first on were made by step id. */
static void name_merges(ps_pipeline *pl, int first, ps_step id) {
    for (int m = first; m < pl->n_merges; m++) pl->merges[m].step = id;
}

ps_status ps_segment_phase(ps_pipeline *pl, ps_phase ph, ps_error *err) {
    double start = ps_now_ms(), at = 0.0;
    if (ps_control_cancelled(pl->ctl)) return ps_fail(err, PS_ERR_CANCELLED, "cancelled");
    ps_control_progress(pl->ctl, ph, 0.0);
    for (int i = 0; i < PS_STEP_COUNT; i++) {
        const step *s = &steps[i];
        if (s->phase != ph || !wanted(pl, s->when)) continue;
        if (ps_control_cancelled(pl->ctl)) return ps_fail(err, PS_ERR_CANCELLED, "cancelled");
        ps_progress_span span = {pl->ctl, ph, at, s->done};
        double step_start = ps_now_ms();
        int merges_before = pl->n_merges;
        ps_status st = s->run(pl, &span, err);
        if (st != PS_OK) return st;
        name_merges(pl, merges_before, (ps_step)i);
        pl->timings.step_ms[i] = ps_now_ms() - step_start;
        ps_control_progress(pl->ctl, ph, s->done);
        at = s->done;
    }
    ps_control_progress(pl->ctl, ph, 1.0);
    pl->timings.ms[ph] = ps_now_ms() - start;
    return PS_OK;
}

/* Every coordinate finite and within PS_MAX_COORDINATE, every given
 * normal's component finite. */
static ps_status check_values(const ps_input *in, ps_error *err) {
    size_t count = in->n * (size_t)in->dim;
    for (size_t i = 0; i < count; i++) {
        if (!isfinite(in->points[i]))
            return ps_fail(err, PS_ERR_INVALID, "point %zu has a non-finite coordinate",
                           i / (size_t)in->dim);
        if (fabs(in->points[i]) > PS_MAX_COORDINATE)
            return ps_fail(err, PS_ERR_INVALID,
                           "point %zu has a coordinate beyond +-%g (squared distances "
                           "would overflow)", i / (size_t)in->dim, PS_MAX_COORDINATE);
    }
    for (size_t i = 0; in->normals && i < count; i++)
        if (!isfinite(in->normals[i]))
            return ps_fail(err, PS_ERR_INVALID, "point %zu has a non-finite normal",
                           i / (size_t)in->dim);
    return PS_OK;
}

static ps_status check_input(const ps_input *in, const ps_params *p, ps_error *err) {
    if (!in || !in->points || in->n == 0)
        return ps_fail(err, PS_ERR_INVALID, "no points");
    if (in->dim < 2 || in->dim > PS_MAX_DIM)
        return ps_fail(err, PS_ERR_INVALID, "dimension must be in [2, %d], got %d",
                       PS_MAX_DIM, in->dim);
    if (in->n > UINT32_MAX - 1)
        return ps_fail(err, PS_ERR_INVALID, "too many points (%zu)", in->n);
    ps_status st = check_values(in, err);
    if (st != PS_OK) return st;
    for (size_t i = 0; in->faces && i < 3 * in->n_faces; i++)
        if (in->faces[i] >= in->n)
            return ps_fail(err, PS_ERR_INVALID, "face %zu refers to point %u, beyond the %zu points",
                           i / 3, in->faces[i], in->n);
    return ps_params_check(p, err);
}

/* Every phase on the whole input, and the result for the caller's points. */
static ps_status segment_whole(ps_pipeline *pl, ps_result **out, ps_error *err) {
    ps_status st = ps_pipeline_distinct(pl, err);
    for (int ph = 0; st == PS_OK && ph < PS_PHASE_COUNT; ph++)
        st = ps_segment_phase(pl, (ps_phase)ph, err);
    if (st == PS_OK) {
        ps_result_parts parts = ps_pipeline_parts(pl);
        st = ps_pipeline_result(pl, &parts, out, err);
    }
    return st;
}

/* The method's presets: paper has no persistence, minima or f2; an
 * ncut_threshold of 0 becomes the method's own. */
static void apply_method(ps_params *p) {
    int paper = p->method == PS_METHOD_PAPER;
    if (paper) p->persistence = 0, p->use_minima = p->use_f2 = 0;
    if (p->ncut_threshold == 0) p->ncut_threshold = paper ? PS_NCUT_PAPER : PS_NCUT_NEVER_STOP;
}

/* A mesh under the reference sampling in fills of it where the
 * parameters want them (surface_fill.h, ensemble.h); else the input as
 * given, whole or in draws.  Both count distinct points: a few points
 * repeated many times are a small input, not a dense one, and a mesh
 * whose triangles each have copies of their own vertices is as sparse as
 * the same mesh welded. */
static ps_status segment_input(ps_pipeline *pl, ps_result **out, ps_error *err) {
    const ps_input *in = pl->in;
    ps_status st = ps_dedup_build(in->points, in->n, in->dim, &pl->dedup, err);
    if (st != PS_OK) return st;
    size_t distinct = pl->dedup.n_unique;
    if (in->faces && in->n_faces && ps_surface_fill_wanted(&pl->params, in->dim, distinct)) {
        int filled = 0;
        st = ps_ensemble_fill(pl, PS_ENSEMBLE_FILLS, &filled, out, err);
        if (st != PS_OK || filled) return st;
    }
    int draws = ps_ensemble_draws(&pl->params, distinct);
    if (!draws) return segment_whole(pl, out, err);
    ps_dedup_free(&pl->dedup); /* each draw finds its own; only the count is needed */
    return ps_ensemble_segment(pl, draws, distinct, out, err);
}

/* *work: in with a malloc'ed copy of its points (the caller frees
 * work->points), every coordinate times 2^e (input_scale.h).  With lift,
 * a 2-D point set becomes the flat surface it is in 3-D (z = 0), so that
 * method auto's surface steps judge it as they judge a plane: a square or
 * a disc one part, a silhouette's limbs apart; 2-D normals, an
 * outline's, are dropped. */
static ps_status copy_input(const ps_input *in, int lift, int e, ps_input *work, ps_error *err) {
    int dim = lift ? 3 : in->dim;
    double *points = malloc(in->n * (size_t)dim * sizeof *points);
    if (!points) return ps_fail(err, PS_ERR_NOMEM, "out of memory (a copy of the points)");
    for (size_t i = 0; i < in->n; i++)
        for (int d = 0; d < dim; d++)
            points[i * (size_t)dim + d] =
                d < in->dim ? ldexp(in->points[i * (size_t)in->dim + d], e) : 0;
    *work = *in;
    work->points = points, work->dim = dim;
    if (lift) work->normals = NULL;
    return PS_OK;
}

ps_status ps_segment(const ps_input *in, const ps_params *params, const ps_control *ctl,
                     ps_result **out, ps_error *err) {
    double start = ps_now_ms();
    *out = NULL;
    ps_eigen_setup();
    ps_pipeline pl = {.in = in, .ctl = ctl};
    if (params) pl.params = *params;
    else ps_params_default(&pl.params);
    apply_method(&pl.params);
    ps_status st = check_input(in, &pl.params, err);
    if (st != PS_OK) return st;
    ps_input work;
    int lift = pl.params.method == PS_METHOD_AUTO && in->dim == 2, short_of;
    int e = ps_input_scale_exponent(in->points, in->n, in->dim, &short_of);
    if (short_of)
        return ps_fail(err, PS_ERR_INVALID,
                       "the points span too many orders of magnitude: their typical extent "
                       "cannot be scaled up to about 1 without a coordinate passing 2^%d",
                       PS_SCALE_CEILING_EXPONENT);
    if (lift || e != 0) {
        st = copy_input(in, lift, e, &work, err);
        if (st != PS_OK) return st;
        pl.in = &work;
    }
    pl.n_input = in->n;
    pl.points = (double *)pl.in->points;
    pl.threads = ps_parallel_threads(pl.params.threads);
    st = segment_input(&pl, out, err);
    ps_pipeline_free(&pl);
    if (pl.in == &work) free((double *)work.points);
    if (st == PS_OK) {
        ps_result_unscale(*out, e);
        (*out)->dim = in->dim;
        (*out)->timings = pl.timings;
        (*out)->timings.total_ms = ps_now_ms() - start;
    }
    return st;
}
