/*
 * pipeline.c: the steps of the method (pipeline.h) on one pipeline's state,
 * each a call of its module with what the steps before it left: the
 * distinct points, the kNN graph and what auto adds to it (stray points
 * out, normals, the crease metric), centrality, supernodes and their
 * splits, the hierarchy, and the merges and the cut of refinement.
 * Which steps run, in what order, is segment.c's table.
 */
#include "pipeline.h"

#include "features/centrality.h"
#include "features/crease_split.h"
#include "features/f2_split.h"
#include "features/normals_smooth.h"
#include "features/profile_split.h"
#include "graph/outliers.h"
#include "hierarchy/ncut.h"
#include "refine/boundary_cut.h"
#include "refine/convex_merge.h"
#include "refine/crease_merge.h"
#include "refine/patch_merge.h"
#include "refine/refine.h"
#include "util/control.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

double ps_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
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
    return st == PS_OK ? ps_pipeline_distinct(pl, err) : st;
}

ps_status ps_pipeline_distinct(ps_pipeline *pl, ps_error *err) {
    const ps_input *in = pl->in;
    ps_status st = PS_OK;
    size_t u = pl->dedup.n_unique;
    if (u < (size_t)pl->params.k + 1)
        return ps_fail(err, PS_ERR_INVALID,
                       "need at least k + 1 = %d distinct points, got %zu", pl->params.k + 1, u);
    if (u >= PS_DEDUP_MORTON_MIN) st = ps_dedup_morton(&pl->dedup, in->points, in->n, in->dim, err);
    return st == PS_OK ? distinct_points(pl, err) : st;
}

/* ---- knn phase ------------------------------------------------------------ */

/* The kNN graph's build on the distinct points, progress over span. */
static ps_knn_graph_input knn_input(const ps_pipeline *pl, const ps_progress_span *span) {
    return (ps_knn_graph_input){.points = pl->points, .n = pl->dedup.n_unique,
                                .dim = pl->in->dim, .k = pl->params.k, .threads = pl->threads,
                                .span = span};
}

/* With method auto the build keeps its search index for the stray points'
 * pruning. */
ps_status ps_pipeline_knn_graph(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    int strays = pl->params.method == PS_METHOD_AUTO;
    ps_knn_graph_input in = knn_input(pl, span);
    return ps_knn_graph_build_memo(&in, &pl->graph, strays ? &pl->knn_memo : NULL, err);
}

/* One round of the outlier removal (outliers.h): stray points leave the
 * distinct points and the kNN graph (pruned, knn_graph.h, or where it
 * cannot be, built again on the rest), unless too few would remain.
 * span: the round's share of the progress, the search, then the graph.
 * *dropped out: how many left. */
static ps_status drop_outliers_once(ps_pipeline *pl, const ps_progress_span *span,
                                    size_t *dropped, ps_error *err) {
    size_t u = pl->dedup.n_unique, count = 0;
    *dropped = 0;
    uint32_t *keep_for = malloc(u * sizeof *keep_for);
    if (!keep_for) return ps_fail(err, PS_ERR_NOMEM, "out of memory (outliers)");
    ps_status st = ps_outliers_find(&pl->graph, pl->threads, keep_for, &count, err);
    ps_control_progress(pl->ctl, span->phase, span->lo);
    if (st == PS_OK && count > 0 && u - count >= (size_t)pl->params.k + 1) {
        int pruned = 0;
        st = ps_outliers_drop(&pl->dedup, pl->in->n, keep_for, err);
        if (st == PS_OK)
            st = ps_knn_graph_prune(&pl->graph, pl->knn_memo, pl->points, keep_for, pl->threads,
                                    span, &pruned, err);
        if (st == PS_OK) st = distinct_points(pl, err);
        if (st == PS_OK && !pruned) {
            ps_knn_memo_free(pl->knn_memo);
            pl->knn_memo = NULL;
            ps_graph_free(&pl->graph);
            ps_knn_graph_input in = knn_input(pl, span);
            st = ps_knn_graph_build_tracked(&in, &pl->graph, err);
        }
        *dropped = count;
    }
    free(keep_for);
    return st;
}

/* Rounds of outlier removal until one finds none (a stray point hidden by
 * a farther one shows once that one is gone); the build's search index
 * goes after them. */
ps_status ps_pipeline_outliers(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    double share = (span->hi - span->lo) / PS_OUTLIER_ROUNDS;
    size_t dropped = 0;
    ps_status st = PS_OK;
    for (int round = 0; st == PS_OK && round < PS_OUTLIER_ROUNDS; round++) {
        ps_progress_span part = {span->ctl, span->phase, span->lo + share * (round + 0.2),
                                 span->lo + share * (round + 1)};
        st = drop_outliers_once(pl, &part, &dropped, err);
        pl->n_outliers += dropped;
        if (!dropped) break;
    }
    ps_knn_memo_free(pl->knn_memo);
    pl->knn_memo = NULL;
    return st;
}

ps_status ps_pipeline_components(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    (void)span;
    pl->component = malloc(pl->dedup.n_unique * sizeof *pl->component);
    if (!pl->component) return ps_fail(err, PS_ERR_NOMEM, "out of memory (components)");
    pl->n_components = ps_graph_components(&pl->graph, pl->component);
    return PS_OK;
}

/* The crease split's and merge's normals: the normals smoothed to the
 * crease scale (ps_crease_scale_iterations, crease.h), so that a crease
 * must hold at that scale. */
static ps_status crease_scale(ps_pipeline *pl, ps_error *err) {
    pl->crease_normals = pl->normals;
    int more = ps_crease_scale_iterations(!ps_noise_clean(pl->normals_report.noise),
                                          pl->normals_report.smoothing);
    if (more == 0) return PS_OK;
    size_t u = pl->graph.n;
    pl->crease_normals = malloc(u * 3 * sizeof *pl->crease_normals);
    if (!pl->crease_normals) return ps_fail(err, PS_ERR_NOMEM, "out of memory (normals)");
    memcpy(pl->crease_normals, pl->normals, u * 3 * sizeof *pl->crease_normals);
    return ps_normals_smooth(&pl->graph, pl->crease_normals, more, pl->threads, err);
}

/* The input's normals of the distinct points, or NULL (*given; none given
 * is no failure). */
static ps_status given_normals(const ps_pipeline *pl, double **given, ps_error *err) {
    size_t u = pl->dedup.n_unique;
    *given = NULL;
    if (!pl->in->normals) return PS_OK;
    *given = malloc(u * 3 * sizeof **given);
    if (!*given) return ps_fail(err, PS_ERR_NOMEM, "out of memory (normals)");
    for (size_t i = 0; i < u; i++)
        memcpy(*given + 3 * i, pl->in->normals + 3 * (size_t)pl->dedup.first[i],
               3 * sizeof **given);
    return PS_OK;
}

/* Normals (given, or PCA) of the distinct points, brought to the scale of
 * the reference sampling (normals_smooth.h) and kept for the boundary cut
 * and the patch merge, and the crease scale's, kept for the crease split
 * and merge. */
ps_status ps_pipeline_normals(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    size_t u = pl->dedup.n_unique;
    double *given = NULL;
    pl->normals = malloc(u * 3 * sizeof *pl->normals);
    if (!pl->normals) return ps_fail(err, PS_ERR_NOMEM, "out of memory (normals)");
    ps_status st = given_normals(pl, &given, err);
    ps_normals_input in = {.graph = &pl->graph, .points = pl->points, .given = given,
                           .component = pl->component, .n_components = pl->n_components,
                           .smooth = pl->params.smooth_normals};
    if (st == PS_OK)
        st = ps_normals_build_tracked(&in, pl->threads, span, pl->normals, &pl->normals_report,
                                      err);
    free(given); /* now, so that the smoothings below reuse its pages */
    if (st == PS_OK)
        st = ps_normals_smooth(&pl->graph, pl->normals, ps_density_iterations(u), pl->threads, err);
    return st == PS_OK ? crease_scale(pl, err) : st;
}

/* The crease scale's strengths, kept for the crease split and merge; then
 * the crease metric on the normals, and the points' spacings (kept for
 * the profile split) from the same pass. */
ps_status ps_pipeline_crease_metric(ps_pipeline *pl, const ps_progress_span *span,
                                    ps_error *err) {
    size_t u = pl->dedup.n_unique;
    (void)span;
    pl->creases.strength = malloc(u * sizeof *pl->creases.strength);
    pl->spacing = malloc(u * sizeof *pl->spacing);
    if (!pl->creases.strength || !pl->spacing)
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (crease metric)");
    ps_status st = ps_crease_strengths(&pl->graph, pl->points, pl->crease_normals, pl->threads,
                                       &pl->creases, err);
    if (st != PS_OK) return st;
    return ps_crease_weights(&pl->graph, pl->points, pl->normals, pl->threads, &pl->edge_scales,
                             pl->spacing, err);
}

/* ---- centrality, supernodes, hierarchy ------------------------------------ */

ps_status ps_pipeline_centrality(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    size_t u = pl->dedup.n_unique;
    ps_params *p = &pl->params;
    (void)span; /* the centrality reports over its whole phase */
    if (p->centrality == PS_CENTRALITY_AUTO)
        p->centrality = u <= PS_EXACT_AUTO_LIMIT ? PS_CENTRALITY_EXACT : PS_CENTRALITY_APPROX;
    if (p->centrality == PS_CENTRALITY_APPROX && p->samples == 0)
        p->samples = ps_centrality_default_samples(u);
    pl->f = malloc(u * sizeof *pl->f);
    if (!pl->f) return ps_fail(err, PS_ERR_NOMEM, "out of memory (centrality)");
    ps_centrality_input in = {.component = pl->component,
                              .n_components = pl->n_components, .mode = p->centrality,
                              .samples = p->samples, .threads = pl->threads,
                              .coarse_min = PS_COARSE_MIN_POINTS, .ctl = pl->ctl};
    int used = 0;
    ps_status st = ps_centrality_borrowing(&in, &pl->graph, pl->f, NULL, &used, err);
    if (st == PS_OK && p->centrality == PS_CENTRALITY_APPROX) p->samples = used;
    return st;
}

ps_status ps_pipeline_supernodes(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    ps_params *p = &pl->params;
    ps_supernodes_input in = {.graph = &pl->graph, .f = pl->f, .component = pl->component,
                              .n_components = pl->n_components, .persistence = p->persistence,
                              .use_minima = p->use_minima, .threads = pl->threads};
    return ps_supernodes_build_tracked(&in, span, &pl->sn, &p->persistence, err);
}

ps_status ps_pipeline_f2_split(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    (void)span;
    return ps_f2_split(&pl->graph, pl->f, pl->params.persistence, &pl->sn, err);
}

ps_status ps_pipeline_crease_split(ps_pipeline *pl, const ps_progress_span *span,
                                   ps_error *err) {
    (void)span;
    return ps_crease_split(&pl->graph, &pl->creases, pl->f, &pl->sn, err);
}

ps_status ps_pipeline_profile_split(ps_pipeline *pl, const ps_progress_span *span,
                                    ps_error *err) {
    (void)span;
    ps_status st = ps_profile_split(&pl->graph, pl->points, pl->f, pl->spacing, &pl->sn, err);
    free(pl->spacing); /* read by the profile split alone */
    pl->spacing = NULL;
    return st;
}

ps_status ps_pipeline_ncut(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    (void)span; /* the bisections report over their whole phase */
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

/* ---- refine phase --------------------------------------------------------- */

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

/* The paper's refinement (refine.h), then each point's group. */
ps_status ps_pipeline_feature_merge(ps_pipeline *pl, const ps_progress_span *span,
                                    ps_error *err) {
    (void)span;
    pl->group_of_leaf = malloc((size_t)pl->n_tree * sizeof *pl->group_of_leaf);
    if (!pl->group_of_leaf) return ps_fail(err, PS_ERR_NOMEM, "out of memory (refine)");
    ps_refine_input in = {.graph = &pl->graph, .f = pl->f, .supernode_of = pl->sn.supernode_of,
                          .is_minimum = pl->sn.is_minimum, .component = pl->component,
                          .tree = pl->tree, .n_tree = pl->n_tree,
                          .feature_threshold = pl->params.feature_threshold};
    ps_status st = ps_refine(&in, pl->group_of_leaf, &pl->merges, &pl->n_merges, err);
    return st == PS_OK ? point_groups(pl, err) : st;
}

ps_status ps_pipeline_boundary_cut(ps_pipeline *pl, const ps_progress_span *span,
                                   ps_error *err) {
    ps_boundary_cut_input bc = {
        .graph = &pl->graph,
        .points = pl->points,
        .normals = pl->normals,
        .scales = pl->edge_scales,
        .n_groups = pl->n_tree,
        .n_supernodes = pl->sn.m,
        .sinks = pl->sn.sinks,
        .span = span,
        .threads = pl->threads,
    };
    return ps_boundary_cut(&bc, pl->group_of_point, pl->sn.supernode_of, err);
}

/* A merge of segments (segment_graph.h) over the given normals (the
 * crease merge and the convex merge read the crease scale's, the patch
 * merge the raw ones); each looks for boundaries only among the edges the
 * merge before it found (merges only join segments), pl->boundary. */
static ps_status merge(ps_pipeline *pl, ps_merge_fn *fn, const double *normals, ps_error *err) {
    ps_merge_input in = {.graph = &pl->graph, .points = pl->points, .normals = normals,
                         .f = pl->f, .mean_angular = pl->creases.mean,
                         .median_strength = pl->creases.median,
                         .n_groups = pl->n_tree, .threads = pl->threads,
                         .boundary = &pl->boundary};
    return fn(&in, pl->group_of_point, pl->group_of_leaf, &pl->merges, &pl->n_merges, err);
}

ps_status ps_pipeline_crease_merge(ps_pipeline *pl, const ps_progress_span *span,
                                   ps_error *err) {
    (void)span;
    return merge(pl, ps_crease_merge, pl->crease_normals, err);
}

ps_status ps_pipeline_convex_merge(ps_pipeline *pl, const ps_progress_span *span,
                                   ps_error *err) {
    (void)span;
    return merge(pl, ps_convex_merge, pl->crease_normals, err);
}

/* The last merge: the boundary edges go after it. */
ps_status ps_pipeline_patch_merge(ps_pipeline *pl, const ps_progress_span *span, ps_error *err) {
    (void)span;
    ps_status st = merge(pl, ps_patch_merge, pl->normals, err);
    free(pl->boundary.ends);
    pl->boundary = (ps_edge_list){0};
    return st;
}

/* ---- release and result --------------------------------------------------- */

void ps_pipeline_shed(ps_pipeline *pl) {
    ps_knn_memo_free(pl->knn_memo);
    ps_graph_free(&pl->graph);
    free(pl->component);
    if (pl->crease_normals != pl->normals) free(pl->crease_normals);
    free(pl->normals);
    free(pl->creases.strength);
    free(pl->spacing);
    free(pl->boundary.ends);
    pl->knn_memo = NULL;
    pl->component = NULL;
    pl->crease_normals = pl->normals = pl->creases.strength = pl->spacing = NULL;
    pl->boundary = (ps_edge_list){0};
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

ps_status ps_pipeline_result(ps_pipeline *pl, const ps_result_parts *parts, ps_result **out,
                             ps_error *err) {
    ps_status st = ps_result_build(parts, &pl->params, out, err);
    if (st == PS_OK) pl->tree = NULL, pl->n_tree = 0;
    return st;
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
