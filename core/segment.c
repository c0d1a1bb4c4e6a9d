/*
 * segment.c: ps_segment, the three phases in order.
 *
 * Validates the input, fills a mesh's triangles with points up to the
 * reference sampling (method auto, surface_fill.h), removes duplicate
 * points, then runs features (kNN graph, centrality, flow to sinks),
 * hierarchy (normalized cuts over the supernodes) and refinement (small
 * features merge; with method auto in 3-D, boundaries then move onto
 * concave creases, boundary_cut.h, segments whose boundary is no crease
 * merge, crease_merge.h, convex unions merge, convex_merge.h, and nearly
 * flat segments merge into a neighbour, patch_merge.h), timing each phase,
 * reporting progress and honouring the cancel flag between steps.  The
 * result is assembled by result.c for the caller's points; duplicates get
 * their representative's answers.  An input denser than the reference
 * sampling several times over (method auto) goes to ensemble.h, which runs
 * the same phases (pipeline.h) on disjoint draws of it.
 */
#include "ensemble.h"
#include "features/centrality.h"
#include "features/crease.h"
#include "features/crease_split.h"
#include "features/f2_split.h"
#include "features/normals.h"
#include "features/normals_smooth.h"
#include "features/profile_split.h"
#include "features/supernodes.h"
#include "graph/dedup.h"
#include "graph/knn_graph.h"
#include "graph/outliers.h"
#include "graph/surface_fill.h"
#include "hierarchy/eigen.h"
#include "hierarchy/ncut.h"
#include "pipeline.h"
#include "pointseg.h"
#include "refine/boundary_cut.h"
#include "refine/convex_merge.h"
#include "refine/crease_merge.h"
#include "refine/patch_merge.h"
#include "refine/refine.h"
#include "result.h"
#include "util/control.h"
#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Progress within the knn phase after each of its steps ... */
#define KNN_GRAPH_DONE 0.45
#define KNN_OUTLIERS_DONE 0.55
#define KNN_NORMALS_DONE 0.9
#define KNN_STRENGTHS_DONE 0.95
/* ... within the supernodes phase ... */
#define SUPERNODES_BUILT 0.5
#define SUPERNODES_F2_DONE 0.6
/* ... and within the refine phase. */
#define REFINE_GROUPS_DONE 0.2
#define REFINE_CUT_DONE 0.7
#define REFINE_CREASE_MERGE_DONE 0.85

double ps_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}


static ps_status check_input(const ps_input *in, const ps_params *p, ps_error *err) {
    if (!in || !in->points || in->n == 0)
        return ps_fail(err, PS_ERR_INVALID, "no points");
    if (in->dim < 2 || in->dim > PS_MAX_DIM)
        return ps_fail(err, PS_ERR_INVALID, "dimension must be in [2, %d], got %d",
                       PS_MAX_DIM, in->dim);
    if (in->n > UINT32_MAX - 1)
        return ps_fail(err, PS_ERR_INVALID, "too many points (%zu)", in->n);
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
    for (size_t i = 0; in->faces && i < 3 * in->n_faces; i++)
        if (in->faces[i] >= in->n)
            return ps_fail(err, PS_ERR_INVALID, "face %zu refers to point %u, beyond the %zu points",
                           i / 3, in->faces[i], in->n);
    return ps_params_check(p, err);
}

/* pl->points: the distinct points of pl->dedup (the input itself when
 * they are every input point in input order); an earlier copy is freed. */
static ps_status distinct_points(ps_pipeline *pl, ps_error *err) {
    const ps_input *in = pl->in;
    size_t u = pl->dedup.n_unique;
    if (pl->points != in->points) free(pl->points);
    if (ps_dedup_is_identity(&pl->dedup, in->n)) {
        pl->points = (double *)in->points;
        return PS_OK;
    }
    pl->points = malloc(u * (size_t)in->dim * sizeof *pl->points);
    if (!pl->points) return ps_fail(err, PS_ERR_NOMEM, "out of memory (points)");
    for (size_t i = 0; i < u; i++)
        memcpy(pl->points + i * in->dim, in->points + (size_t)pl->dedup.first[i] * in->dim,
               (size_t)in->dim * sizeof *pl->points);
    return PS_OK;
}

ps_status ps_pipeline_dedup(ps_pipeline *pl, ps_error *err) {
    const ps_input *in = pl->in;
    ps_status st = ps_dedup_build(in->points, in->n, in->dim, &pl->dedup, err);
    if (st != PS_OK) return st;
    size_t u = pl->dedup.n_unique;
    if (u < (size_t)pl->params.k + 1)
        return ps_fail(err, PS_ERR_INVALID,
                       "need at least k + 1 = %d distinct points, got %zu", pl->params.k + 1, u);
    if (u >= PS_DEDUP_MORTON_MIN) st = ps_dedup_morton(&pl->dedup, in->points, in->n, in->dim, err);
    return st == PS_OK ? distinct_points(pl, err) : st;
}

/* The crease split's and merge's normals (crease.h): on a clean surface
 * (noise at most PS_NOISE_FLOOR) the normals smoothed
 * PS_CREASE_SCALE_SMOOTHING more times, so that a crease must hold at that
 * scale; on a noisy one smoothing would turn the noise into blobs that
 * close loops, and they are the normals themselves. */
static ps_status crease_scale(ps_pipeline *pl, ps_error *err) {
    pl->crease_normals = pl->normals;
    if (!ps_noise_clean(pl->normals_report.noise)) return PS_OK;
    size_t u = pl->graph.n;
    pl->crease_normals = malloc(u * 3 * sizeof *pl->crease_normals);
    if (!pl->crease_normals) return ps_fail(err, PS_ERR_NOMEM, "out of memory (normals)");
    memcpy(pl->crease_normals, pl->normals, u * 3 * sizeof *pl->crease_normals);
    return ps_normals_smooth(&pl->graph, pl->crease_normals, PS_CREASE_SCALE_SMOOTHING,
                             pl->threads, err);
}

/* Normals (given, or PCA) of the distinct points, brought to the scale of
 * the reference sampling (normals_smooth.h) and kept for the boundary cut
 * and the patch merge; the crease scale's normals and strengths, kept for
 * the crease split and merge; then the crease metric, on the normals, and
 * the points' spacings (kept for the profile split) from the same pass. */
static ps_status crease_metric(ps_pipeline *pl, ps_error *err) {
    size_t u = pl->dedup.n_unique;
    double *given = NULL;
    pl->normals = malloc(u * 3 * sizeof *pl->normals);
    pl->creases.strength = malloc(u * sizeof *pl->creases.strength);
    pl->spacing = malloc(u * sizeof *pl->spacing);
    if (!pl->normals || !pl->creases.strength || !pl->spacing)
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (normals)");
    if (pl->in->normals) {
        given = malloc(u * 3 * sizeof *given);
        if (!given) return ps_fail(err, PS_ERR_NOMEM, "out of memory (normals)");
        for (size_t i = 0; i < u; i++)
            memcpy(given + 3 * i, pl->in->normals + 3 * (size_t)pl->dedup.first[i],
                   3 * sizeof *given);
    }
    ps_progress_span span = {pl->ctl, PS_PHASE_KNN, KNN_OUTLIERS_DONE, KNN_NORMALS_DONE};
    ps_normals_input in = {.graph = &pl->graph, .points = pl->points, .given = given,
                           .component = pl->component, .n_components = pl->n_components,
                           .smooth = pl->params.smooth_normals};
    ps_status st = ps_normals_build_tracked(&in, pl->threads, &span, pl->normals,
                                            &pl->normals_report, err);
    free(given); /* now, so that the smoothings below reuse its pages */
    if (st == PS_OK)
        st = ps_normals_smooth(&pl->graph, pl->normals, ps_density_iterations(u), pl->threads, err);
    if (st == PS_OK) st = crease_scale(pl, err);
    if (st == PS_OK)
        st = ps_crease_strengths(&pl->graph, pl->points, pl->crease_normals, pl->threads,
                                 &pl->creases, err);
    if (st == PS_OK) {
        ps_control_progress(pl->ctl, PS_PHASE_KNN, KNN_STRENGTHS_DONE);
        st = ps_crease_weights(&pl->graph, pl->points, pl->normals, pl->threads,
                               &pl->edge_scales, pl->spacing, err);
    }
    return st;
}

/* One round of the outlier removal (outliers.h): stray points leave the
 * distinct points and the kNN graph (pruned, knn_graph.h, or where it
 * cannot be, built again on the rest), unless too few would remain.
 * round's share of the knn phase's progress: the search, then the graph.
 * *dropped out: how many left. */
static ps_status drop_outliers_once(ps_pipeline *pl, int round, size_t *dropped, ps_error *err) {
    size_t u = pl->dedup.n_unique, count = 0;
    double share = (KNN_OUTLIERS_DONE - KNN_GRAPH_DONE) / PS_OUTLIER_ROUNDS;
    ps_progress_span span = {pl->ctl, PS_PHASE_KNN, KNN_GRAPH_DONE + share * (round + 0.2),
                             KNN_GRAPH_DONE + share * (round + 1)};
    *dropped = 0;
    uint32_t *keep_for = malloc(u * sizeof *keep_for);
    if (!keep_for) return ps_fail(err, PS_ERR_NOMEM, "out of memory (outliers)");
    ps_status st = ps_outliers_find(&pl->graph, pl->threads, keep_for, &count, err);
    ps_control_progress(pl->ctl, PS_PHASE_KNN, span.lo);
    if (st == PS_OK && count > 0 && u - count >= (size_t)pl->params.k + 1) {
        int pruned = 0;
        st = ps_outliers_drop(&pl->dedup, pl->in->n, keep_for, err);
        if (st == PS_OK)
            st = ps_knn_graph_prune(&pl->graph, pl->knn_memo, pl->points, keep_for, pl->threads,
                                    &span, &pruned, err);
        if (st == PS_OK) st = distinct_points(pl, err);
        if (st == PS_OK && !pruned) {
            ps_knn_memo_free(pl->knn_memo);
            pl->knn_memo = NULL;
            ps_graph_free(&pl->graph);
            st = ps_knn_graph_build_tracked(pl->points, pl->dedup.n_unique, pl->in->dim,
                                            pl->params.k, pl->threads, &span, &pl->graph, err);
        }
        *dropped = count;
    }
    free(keep_for);
    return st;
}

/* Method auto: rounds of outlier removal until one finds none (a stray
 * point hidden by a farther one shows once that one is gone). */
static ps_status drop_outliers(ps_pipeline *pl, ps_error *err) {
    size_t dropped = 0;
    ps_status st = PS_OK;
    for (int round = 0; st == PS_OK && round < PS_OUTLIER_ROUNDS; round++) {
        st = drop_outliers_once(pl, round, &dropped, err);
        pl->n_outliers += dropped;
        if (!dropped) break;
    }
    return st;
}

static ps_status phase_knn(ps_pipeline *pl, ps_error *err) {
    ps_progress_span span = {pl->ctl, PS_PHASE_KNN, 0.0, KNN_GRAPH_DONE};
    int strays = pl->params.method == PS_METHOD_AUTO;
    ps_status st = ps_knn_graph_build_memo(pl->points, pl->dedup.n_unique, pl->in->dim,
                                           pl->params.k, pl->threads, &span, &pl->graph,
                                           strays ? &pl->knn_memo : NULL, err);
    if (st == PS_OK && strays) st = drop_outliers(pl, err);
    ps_knn_memo_free(pl->knn_memo);
    pl->knn_memo = NULL;
    if (st != PS_OK) return st;
    size_t u = pl->dedup.n_unique;
    pl->component = malloc(u * sizeof *pl->component);
    if (!pl->component) return ps_fail(err, PS_ERR_NOMEM, "out of memory (components)");
    pl->n_components = ps_graph_components(&pl->graph, pl->component);
    if (pl->params.method == PS_METHOD_AUTO && pl->in->dim == 3) return crease_metric(pl, err);
    return PS_OK;
}

static ps_status phase_centrality(ps_pipeline *pl, ps_error *err) {
    size_t u = pl->dedup.n_unique;
    ps_params *p = &pl->params;
    if (p->centrality == PS_CENTRALITY_AUTO)
        p->centrality = u <= PS_EXACT_AUTO_LIMIT ? PS_CENTRALITY_EXACT : PS_CENTRALITY_APPROX;
    if (p->centrality == PS_CENTRALITY_APPROX && p->samples == 0)
        p->samples = ps_centrality_default_samples(u);
    pl->f = malloc(u * sizeof *pl->f);
    if (!pl->f) return ps_fail(err, PS_ERR_NOMEM, "out of memory (centrality)");
    int used = 0;
    ps_status st = ps_centrality_borrowing(&pl->graph, pl->component, pl->n_components,
                                           p->centrality, p->samples, pl->threads, pl->ctl,
                                           pl->f, NULL, &used, err);
    if (st == PS_OK && p->centrality == PS_CENTRALITY_APPROX) p->samples = used;
    return st;
}

static ps_status phase_supernodes(ps_pipeline *pl, ps_error *err) {
    ps_params *p = &pl->params;
    ps_progress_span span = {pl->ctl, PS_PHASE_SUPERNODES, 0.0, SUPERNODES_BUILT};
    ps_status st = ps_supernodes_build_tracked(&pl->graph, pl->f, pl->component,
                                               pl->n_components, &p->persistence,
                                               p->use_minima, pl->threads, &span, &pl->sn, err);
    if (st == PS_OK && p->use_f2)
        st = ps_f2_split(&pl->graph, pl->f, p->persistence, &pl->sn, err);
    if (st == PS_OK) ps_control_progress(pl->ctl, PS_PHASE_SUPERNODES, SUPERNODES_F2_DONE);
    if (st == PS_OK && pl->normals)
        st = ps_crease_split(&pl->graph, &pl->creases, pl->f, &pl->sn, err);
    if (st == PS_OK && pl->normals && pl->in->dim == 3)
        st = ps_profile_split(&pl->graph, pl->points, pl->f, pl->spacing, &pl->sn, err);
    free(pl->spacing); /* read by the profile split alone */
    pl->spacing = NULL;
    return st;
}

static ps_status phase_hierarchy(ps_pipeline *pl, ps_error *err) {
    ps_supernode_graph sg = {
        .m = pl->sn.m,
        .sinks = pl->sn.sinks,
        .sizes = pl->sn.sizes,
        .supernode_of = pl->sn.supernode_of,
        .component = pl->component,
    };
    return ps_ncut_hierarchy(&pl->graph, &sg, pl->params.ncut_threshold, pl->threads, pl->ctl,
                             &pl->tree, &pl->n_tree, err);
}

/* group_of_point from the refined groups of the hierarchy leaves. */
static ps_status point_groups(ps_pipeline *pl, ps_error *err) {
    size_t u = pl->dedup.n_unique;
    int *group_of_supernode = malloc((size_t)(pl->sn.m ? pl->sn.m : 1) * sizeof(int));
    pl->group_of_point = malloc(u * sizeof *pl->group_of_point);
    if (!group_of_supernode || !pl->group_of_point) {
        free(group_of_supernode);
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (refine)");
    }
    for (int t = 0; t < pl->n_tree; t++) {
        const ps_tree_node *node = &pl->tree[t];
        if (node->children[0] >= 0) continue;
        for (int j = 0; j < node->n_supernodes; j++)
            group_of_supernode[node->supernodes[j]] = pl->group_of_leaf[t];
    }
    for (size_t i = 0; i < u; i++)
        pl->group_of_point[i] = group_of_supernode[pl->sn.supernode_of[i]];
    free(group_of_supernode);
    return PS_OK;
}

static ps_status boundary_cut(ps_pipeline *pl, ps_error *err) {
    ps_progress_span span = {pl->ctl, PS_PHASE_REFINE, REFINE_GROUPS_DONE, REFINE_CUT_DONE};
    ps_boundary_cut_input bc = {
        .graph = &pl->graph,
        .points = pl->points,
        .normals = pl->normals,
        .scales = pl->edge_scales,
        .n_groups = pl->n_tree,
        .n_supernodes = pl->sn.m,
        .sinks = pl->sn.sinks,
        .span = &span,
        .threads = pl->threads,
    };
    return ps_boundary_cut(&bc, pl->group_of_point, pl->sn.supernode_of, err);
}

/* The merges' input over the given normals (the crease merge and the
 * convex merge read the crease scale's, the patch merge the raw ones),
 * with the boundary edges they pass on. */
static ps_merge_input merge_input(const ps_pipeline *pl, const double *normals,
                                  ps_edge_list *boundary) {
    return (ps_merge_input){.graph = &pl->graph, .points = pl->points, .normals = normals,
                            .f = pl->f, .mean_angular = pl->creases.mean,
                            .n_groups = pl->n_tree, .threads = pl->threads,
                            .boundary = boundary};
}

/* The merges after the boundary cut (method auto, 3-D), in order; each
 * looks for boundaries only among the edges the one before found (merges
 * only join segments). */
static ps_status merge_segments(ps_pipeline *pl, ps_error *err) {
    ps_edge_list boundary = {0};
    ps_merge_input crease = merge_input(pl, pl->crease_normals, &boundary);
    ps_merge_input raw = merge_input(pl, pl->normals, &boundary);
    ps_status st = ps_crease_merge(&crease, pl->group_of_point, pl->group_of_leaf, &pl->merges,
                                   &pl->n_merges, err);
    if (st == PS_OK) ps_control_progress(pl->ctl, PS_PHASE_REFINE, REFINE_CREASE_MERGE_DONE);
    if (st == PS_OK)
        st = ps_convex_merge(&crease, pl->group_of_point, pl->group_of_leaf, &pl->merges,
                             &pl->n_merges, err);
    if (st == PS_OK)
        st = ps_patch_merge(&raw, pl->group_of_point, pl->group_of_leaf, &pl->merges,
                            &pl->n_merges, err);
    free(boundary.ends);
    return st;
}

static ps_status phase_refine(ps_pipeline *pl, ps_error *err) {
    pl->group_of_leaf = malloc((size_t)pl->n_tree * sizeof *pl->group_of_leaf);
    if (!pl->group_of_leaf) return ps_fail(err, PS_ERR_NOMEM, "out of memory (refine)");
    ps_refine_input in = {.graph = &pl->graph, .f = pl->f, .supernode_of = pl->sn.supernode_of,
                          .is_minimum = pl->sn.is_minimum, .component = pl->component,
                          .tree = pl->tree, .n_tree = pl->n_tree,
                          .feature_threshold = pl->params.feature_threshold};
    ps_status st = ps_refine(&in, pl->group_of_leaf, &pl->merges, &pl->n_merges, err);
    if (st == PS_OK) st = point_groups(pl, err);
    if (st == PS_OK) ps_control_progress(pl->ctl, PS_PHASE_REFINE, REFINE_GROUPS_DONE);
    if (st == PS_OK && pl->normals) st = boundary_cut(pl, err);
    if (st == PS_OK) ps_control_progress(pl->ctl, PS_PHASE_REFINE, REFINE_CUT_DONE);
    if (st == PS_OK && pl->normals) st = merge_segments(pl, err);
    return st;
}

typedef ps_status (*phase_fn)(ps_pipeline *pl, ps_error *err);

ps_status ps_pipeline_phase(ps_pipeline *pl, ps_phase ph, ps_error *err) {
    static const phase_fn phases[PS_PHASE_COUNT] = {phase_knn, phase_centrality,
                                                    phase_supernodes, phase_hierarchy,
                                                    phase_refine};
    if (ps_control_cancelled(pl->ctl)) return ps_fail(err, PS_ERR_CANCELLED, "cancelled");
    double start = ps_now_ms();
    ps_control_progress(pl->ctl, ph, 0.0);
    ps_status st = phases[ph](pl, err);
    if (st != PS_OK) return st;
    ps_control_progress(pl->ctl, ph, 1.0);
    pl->timings.ms[ph] = ps_now_ms() - start;
    return PS_OK;
}

void ps_pipeline_shed(ps_pipeline *pl) {
    ps_graph_free(&pl->graph);
    free(pl->component);
    if (pl->crease_normals != pl->normals) free(pl->crease_normals);
    free(pl->normals);
    free(pl->creases.strength);
    free(pl->spacing);
    pl->component = NULL;
    pl->crease_normals = pl->normals = pl->creases.strength = pl->spacing = NULL;
}

void ps_pipeline_free(ps_pipeline *pl) {
    if (pl->points != pl->in->points) free(pl->points);
    ps_dedup_free(&pl->dedup);
    ps_pipeline_shed(pl);
    free(pl->f);
    ps_supernodes_free(&pl->sn);
    ps_tree_free(pl->tree, pl->n_tree);
    free(pl->group_of_leaf);
    free(pl->group_of_point);
    free(pl->merges);
}

ps_result_parts ps_pipeline_parts(const ps_pipeline *pl) {
    return (ps_result_parts){
        .n_input = pl->n_input,
        .host_of_added = pl->host_of_added,
        .n_filled = pl->in->n - pl->n_input,
        .dim = pl->in->dim,
        .n_unique = pl->dedup.n_unique,
        .unique_of = pl->dedup.unique_of,
        .first_of = pl->dedup.first,
        .f = pl->f,
        .n_components = pl->n_components,
        .normal_smoothing = pl->normals_report.smoothing,
        .n_outliers = pl->n_outliers,
        .n_supernodes = pl->sn.m,
        .sinks = pl->sn.sinks,
        .is_minimum = pl->sn.is_minimum,
        .supernode_of = pl->sn.supernode_of,
        .tree = pl->tree,
        .n_tree = pl->n_tree,
        .group_of_leaf = pl->group_of_leaf,
        .group_of_point = pl->group_of_point,
        .merges = pl->merges,
        .n_merges = pl->n_merges,
    };
}

/* Every phase on the whole input, and the result for the caller's points. */
static ps_status segment_whole(ps_pipeline *pl, ps_result **out, ps_error *err) {
    ps_status st = ps_pipeline_dedup(pl, err);
    for (int ph = 0; st == PS_OK && ph < PS_PHASE_COUNT; ph++)
        st = ps_pipeline_phase(pl, (ps_phase)ph, err);
    if (st == PS_OK) {
        ps_result_parts parts = ps_pipeline_parts(pl);
        st = ps_result_build(&parts, &pl->params, out, err);
        /* the tree moved into the result */
        if (st == PS_OK) pl->tree = NULL, pl->n_tree = 0;
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

/* A mesh's triangles filled up to the reference sampling where the
 * parameters want it (surface_fill.h); pl->in becomes *filled, the input
 * points first. */
static ps_status fill_surface(ps_pipeline *pl, ps_surface_fill *fill, ps_input *filled,
                              ps_error *err) {
    const ps_input *in = pl->in;
    pl->n_input = in->n;
    if (!ps_surface_fill_wanted(&pl->params, in->dim, in->n)) return PS_OK;
    ps_status st = ps_surface_fill_build(in, PS_DENSITY_REFERENCE_POINTS, fill, err);
    if (st != PS_OK || !fill->n_added) return st;
    filled->points = fill->points, filled->normals = fill->normals;
    filled->n = in->n + fill->n_added;
    pl->in = filled;
    pl->host_of_added = fill->host;
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
    ps_surface_fill fill = {0};
    ps_input filled = *in;
    st = fill_surface(&pl, &fill, &filled, err);
    if (st != PS_OK) return st;
    pl.points = (double *)pl.in->points;
    pl.threads = ps_parallel_threads(pl.params.threads);
    int draws = ps_ensemble_draws(&pl.params, pl.in->n);
    st = draws > 1 ? ps_ensemble_segment(&pl, draws, out, err) : segment_whole(&pl, out, err);
    ps_pipeline_free(&pl);
    ps_surface_fill_free(&fill);
    if (st == PS_OK) {
        (*out)->timings = pl.timings;
        (*out)->timings.total_ms = ps_now_ms() - start;
    }
    return st;
}
