/*
 * segment_graph.c: the segments' adjacency, and merging two segments
 * (segment_graph.h).
 */
#include "segment_graph.h"

#include <stdlib.h>
#include <string.h>

static int compare_boundary(const void *x, const void *y) {
    const ps_boundary *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return 0;
}

/* Sorts the records and sums those of one pair; drops a == b. */
static void coalesce(ps_segment_graph *sg) {
    qsort(sg->list, sg->count, sizeof *sg->list, compare_boundary);
    size_t out = 0;
    for (size_t i = 0; i < sg->count; i++) {
        if (sg->list[i].a == sg->list[i].b) continue;
        if (out > 0 && compare_boundary(&sg->list[out - 1], &sg->list[i]) == 0) {
            sg->list[out - 1].marked += sg->list[i].marked;
            sg->list[out - 1].edges += sg->list[i].edges;
        } else {
            sg->list[out++] = sg->list[i];
        }
    }
    sg->count = out;
}

/* One record per edge p < q joining two segments. */
static int gather_boundaries(ps_segment_graph *sg, const ps_graph *g, const int *group,
                             ps_boundary_mark_fn mark, void *context) {
    size_t crossing = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            if (g->neighbors[e] > p && group[g->neighbors[e]] != group[p]) crossing++;
    sg->list = malloc((crossing ? crossing : 1) * sizeof *sg->list);
    if (!sg->list) return 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            int a = group[p], b = group[q];
            if (q <= p || a == b) continue;
            long marked = mark ? mark(context, group, p, q) != 0 : 0;
            sg->list[sg->count++] = (ps_boundary){a < b ? a : b, a < b ? b : a, marked, 1};
        }
    coalesce(sg);
    return 1;
}

static void measure_segments(ps_segment_graph *sg, const double *f, const int *group,
                             size_t n) {
    for (size_t p = 0; p < n; p++) {
        int a = group[p];
        if (sg->size[a] == 0 || f[p] < sg->f_min[a]) sg->f_min[a] = f[p];
        if (sg->size[a] == 0 || f[p] > sg->f_max[a]) sg->f_max[a] = f[p];
        sg->size[a]++;
    }
}

ps_status ps_segment_graph_build(ps_segment_graph *sg, const ps_graph *g, const double *f,
                                 const int *group, int n_groups, ps_boundary_mark_fn mark,
                                 void *context, ps_error *err) {
    size_t m = (size_t)(n_groups > 0 ? n_groups : 1);
    memset(sg, 0, sizeof *sg);
    sg->n_groups = n_groups;
    sg->size = calloc(m, sizeof *sg->size);
    sg->f_min = calloc(m, sizeof *sg->f_min);
    sg->f_max = calloc(m, sizeof *sg->f_max);
    sg->alias = malloc(m * sizeof *sg->alias);
    if (sg->size && sg->f_min && sg->f_max && sg->alias) {
        for (int i = 0; i < n_groups; i++) sg->alias[i] = i;
        measure_segments(sg, f, group, g->n);
        if (gather_boundaries(sg, g, group, mark, context)) return PS_OK;
    }
    ps_segment_graph_free(sg);
    return ps_fail(err, PS_ERR_NOMEM, "out of memory (segment graph)");
}

static int append_merge(ps_merge **merges, int *n_merges, ps_merge merge) {
    ps_merge *grown = realloc(*merges, ((size_t)*n_merges + 1) * sizeof *grown);
    if (!grown) return 0;
    grown[(*n_merges)++] = merge;
    *merges = grown;
    return 1;
}

int ps_segment_graph_merge(ps_segment_graph *sg, int loser, int winner, ps_merge **merges,
                           int *n_merges) {
    ps_merge merge = {loser, winner, sg->f_max[loser] - sg->f_min[loser]};
    if (!append_merge(merges, n_merges, merge)) return 0;
    sg->size[winner] += sg->size[loser];
    if (sg->f_min[loser] < sg->f_min[winner]) sg->f_min[winner] = sg->f_min[loser];
    if (sg->f_max[loser] > sg->f_max[winner]) sg->f_max[winner] = sg->f_max[loser];
    sg->alias[loser] = winner;
    for (size_t j = 0; j < sg->count; j++) {
        ps_boundary *r = &sg->list[j];
        if (r->a == loser) r->a = winner;
        if (r->b == loser) r->b = winner;
        if (r->a > r->b) {
            int t = r->a;
            r->a = r->b, r->b = t;
        }
    }
    coalesce(sg);
    return 1;
}

int ps_segment_graph_survivor(const ps_segment_graph *sg, int id) {
    while (sg->alias[id] != id) id = sg->alias[id];
    return id;
}

void ps_segment_graph_apply(const ps_segment_graph *sg, int *group_of_point, size_t n,
                            int *group_of_leaf) {
    for (size_t p = 0; p < n; p++)
        group_of_point[p] = ps_segment_graph_survivor(sg, group_of_point[p]);
    for (int t = 0; t < sg->n_groups; t++)
        if (group_of_leaf[t] >= 0)
            group_of_leaf[t] = ps_segment_graph_survivor(sg, group_of_leaf[t]);
}

void ps_segment_graph_free(ps_segment_graph *sg) {
    free(sg->size);
    free(sg->f_min);
    free(sg->f_max);
    free(sg->alias);
    free(sg->list);
    memset(sg, 0, sizeof *sg);
}
