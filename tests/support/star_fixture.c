/*
 * star_fixture.c: the star test fixture of star_fixture.h and a merge's
 * run on it.
 */
#include "star_fixture.h"

#include "features/normals.h"
#include "shapes.h"

#include <stdlib.h>
#include <string.h>

double ps_star_along_arm(const double *x, int k) {
    int axis = (k - 1) / 2;
    return (k - 1) % 2 ? -x[axis] : x[axis];
}

int ps_star_build(ps_star *s) {
    return ps_star_build_dense(s, 0);
}

int ps_star_build_dense(ps_star *s, double density) {
    memset(s, 0, sizeof *s);
    s->points = ps_shape_star(density, &s->n, &s->part);
    s->normals = s->points ? malloc(s->n * 3 * sizeof *s->normals) : NULL;
    int *component = s->normals ? malloc(s->n * sizeof *component) : NULL;
    ps_error err = {0};
    int ok = component && ps_knn_graph_build(s->points, s->n, 3, 7, 1, &s->graph, &err) == PS_OK;
    int nc = ok ? ps_graph_components(&s->graph, component) : 0;
    ps_normals_input in = {.graph = &s->graph, .points = s->points, .component = component,
                           .n_components = nc};
    ok = ok && ps_normals_build(&in, s->normals, NULL, &err) == PS_OK;
    free(component);
    return ok;
}

void ps_star_free(ps_star *s) {
    free(s->points);
    free(s->normals);
    free(s->part);
    ps_graph_free(&s->graph);
    memset(s, 0, sizeof *s);
}

ps_status ps_star_merge(const ps_star *s, ps_merge_fn *merge, const ps_star_merge_input *in,
                        int *group, int *leaf, ps_merge **merges, int *n_merges) {
    double *zeros = in->f ? NULL : calloc(s->n, sizeof *zeros);
    if (!in->f && !zeros) return PS_ERR_NOMEM;
    ps_merge_input m = {.graph = &s->graph,
                        .points = in->points ? in->points : s->points,
                        .normals = in->normals ? in->normals : s->normals,
                        .f = in->f ? in->f : zeros,
                        .mean_angular = in->mean_angular,
                        .median_strength = in->median_strength,
                        .n_groups = in->n_groups,
                        .threads = 1};
    for (int t = 0; t < in->n_groups; t++) leaf[t] = t;
    *merges = NULL, *n_merges = 0;
    ps_error err = {0};
    ps_status st = merge(&m, group, leaf, merges, n_merges, &err);
    free(zeros);
    return st;
}
