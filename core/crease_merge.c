/*
 * crease_merge.c: segments joined by a boundary that is not a concave
 * crease merge (crease_merge.h).
 *
 * The boundaries are gathered once, in O(E): one record per kNN edge
 * joining two segments (whether it is creased),
 * sorted and summed into one record per pair.  A merge renames the loser in
 * every record and sums the records again; there are only as many records
 * as adjacent pairs, so the steps are cheap.
 */
#include "crease_merge.h"

#include "crease.h"

#include <math.h>
#include <stdlib.h>

typedef struct boundary {
    int a, b;      /* segment ids, a < b */
    long creased;  /* edges with an end on a crease */
    long edges;    /* kNN edges joining a and b */
} boundary;

typedef struct merge_state {
    size_t *size;     /* #n_groups points */
    double *f_min;    /* #n_groups */
    double *f_max;    /* #n_groups */
    int *alias;       /* #n_groups the segment it merged into, or itself */
    boundary *list;   /* #count */
    size_t count;
} merge_state;

static int compare_boundary(const void *x, const void *y) {
    const boundary *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return 0;
}

/* Sorts the records and sums those of one pair; drops a == b. */
static void coalesce(merge_state *s) {
    qsort(s->list, s->count, sizeof *s->list, compare_boundary);
    size_t out = 0;
    for (size_t i = 0; i < s->count; i++) {
        if (s->list[i].a == s->list[i].b) continue;
        if (out > 0 && compare_boundary(&s->list[out - 1], &s->list[i]) == 0) {
            s->list[out - 1].creased += s->list[i].creased;
            s->list[out - 1].edges += s->list[i].edges;
        } else {
            s->list[out++] = s->list[i];
        }
    }
    s->count = out;
}

/* Whether edge p-r runs within PS_CREASE_MERGE_CONE of the line of the
 * boundary edge across (unit, #3): it measures bending across the
 * boundary, not along it. */
static int along(const double *points, size_t p, size_t r, const double *across) {
    double d[3], length2 = 0, dot = 0;
    for (int i = 0; i < 3; i++) {
        d[i] = points[3 * r + i] - points[3 * p + i];
        length2 += d[i] * d[i];
        dot += d[i] * across[i];
    }
    return dot * dot >= PS_CREASE_MERGE_CONE * PS_CREASE_MERGE_CONE * length2;
}

/* p's largest angular term over its edges into segments a and b that run
 * along the boundary edge's line (across, unit #3): only those can make a
 * crease of the boundary between a and b.  A wing root next to the
 * boundary between nose and fuselage is in a third segment; a fillet
 * running across that boundary bends along it, not across. */
static double strength_within(const ps_crease_merge_input *in, const int *group, size_t p,
                              int a, int b, const double *across) {
    const ps_graph *g = in->graph;
    double best = 0;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        size_t r = g->neighbors[e];
        if ((group[r] != a && group[r] != b) || !along(in->points, p, r, across)) continue;
        double ang = ps_crease_angular(in->points + 3 * p, in->normals + 3 * p,
                                       in->points + 3 * r, in->normals + 3 * r, 0.0);
        if (ang > best) best = ang;
    }
    return best;
}

/* Whether the boundary edge p-q is creased (see crease_merge.h). */
static long creased_edge(const ps_crease_merge_input *in, const int *group, size_t p, size_t q,
                         double crease) {
    double across[3], length2 = 0;
    for (int i = 0; i < 3; i++) {
        across[i] = in->points[3 * q + i] - in->points[3 * p + i];
        length2 += across[i] * across[i];
    }
    if (length2 > 0)
        for (int i = 0; i < 3; i++) across[i] /= sqrt(length2);
    int a = group[p], b = group[q];
    return strength_within(in, group, p, a, b, across) >= crease ||
           strength_within(in, group, q, a, b, across) >= crease;
}

/* One record per edge p < q joining two segments. */
static ps_status gather_boundaries(const ps_crease_merge_input *in, const int *group,
                                   double crease, merge_state *s, ps_error *err) {
    const ps_graph *g = in->graph;
    size_t crossing = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            if (g->neighbors[e] > p && group[g->neighbors[e]] != group[p]) crossing++;
    s->list = malloc((crossing ? crossing : 1) * sizeof *s->list);
    if (!s->list) return ps_fail(err, PS_ERR_NOMEM, "out of memory (crease merge)");
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            size_t q = g->neighbors[e];
            int a = group[p], b = group[q];
            if (q <= p || a == b) continue;
            long creased = creased_edge(in, group, p, q, crease);
            s->list[s->count++] = (boundary){a < b ? a : b, a < b ? b : a, creased, 1};
        }
    coalesce(s);
    return PS_OK;
}

static ps_status state_init(const ps_crease_merge_input *in, const int *group, double crease,
                            merge_state *s, ps_error *err) {
    size_t m = (size_t)(in->n_groups > 0 ? in->n_groups : 1);
    s->size = calloc(m, sizeof *s->size);
    s->f_min = malloc(m * sizeof *s->f_min);
    s->f_max = malloc(m * sizeof *s->f_max);
    s->alias = malloc(m * sizeof *s->alias);
    if (!s->size || !s->f_min || !s->f_max || !s->alias)
        return ps_fail(err, PS_ERR_NOMEM, "out of memory (crease merge)");
    for (int i = 0; i < in->n_groups; i++) s->alias[i] = i;
    for (size_t p = 0; p < in->graph->n; p++) {
        int a = group[p];
        double v = in->f[p];
        if (s->size[a] == 0 || v < s->f_min[a]) s->f_min[a] = v;
        if (s->size[a] == 0 || v > s->f_max[a]) s->f_max[a] = v;
        s->size[a]++;
    }
    return gather_boundaries(in, group, crease, s, err);
}

static void state_free(merge_state *s) {
    free(s->size);
    free(s->f_min);
    free(s->f_max);
    free(s->alias);
    free(s->list);
}

/* The record with the smallest creased fraction, or -1 when none is below
 * the threshold. */
static long weakest_boundary(const merge_state *s, double threshold) {
    long best = -1;
    double best_fraction = threshold;
    for (size_t i = 0; i < s->count; i++) {
        double fraction = (double)s->list[i].creased / (double)s->list[i].edges;
        if (fraction < best_fraction) best = (long)i, best_fraction = fraction;
    }
    return best;
}

static int append_merge(ps_merge **merges, int *n_merges, ps_merge merge) {
    ps_merge *grown = realloc(*merges, ((size_t)*n_merges + 1) * sizeof *grown);
    if (!grown) return 0;
    grown[(*n_merges)++] = merge;
    *merges = grown;
    return 1;
}

/* Merges the pair of record i: the smaller segment into the larger. */
static int merge_pair(merge_state *s, size_t i, ps_merge **merges, int *n_merges) {
    int a = s->list[i].a, b = s->list[i].b;
    int loser = s->size[b] <= s->size[a] ? b : a, winner = loser == a ? b : a;
    ps_merge merge = {loser, winner, s->f_max[loser] - s->f_min[loser]};
    if (!append_merge(merges, n_merges, merge)) return 0;
    s->size[winner] += s->size[loser];
    if (s->f_min[loser] < s->f_min[winner]) s->f_min[winner] = s->f_min[loser];
    if (s->f_max[loser] > s->f_max[winner]) s->f_max[winner] = s->f_max[loser];
    s->alias[loser] = winner;
    for (size_t j = 0; j < s->count; j++) {
        boundary *r = &s->list[j];
        if (r->a == loser) r->a = winner;
        if (r->b == loser) r->b = winner;
        if (r->a > r->b) {
            int t = r->a;
            r->a = r->b, r->b = t;
        }
    }
    coalesce(s);
    return 1;
}

static int survivor(const merge_state *s, int id) {
    while (s->alias[id] != id) id = s->alias[id];
    return id;
}

ps_status ps_crease_merge(const ps_crease_merge_input *in, int *group_of_point,
                          int *group_of_leaf, ps_merge **merges, int *n_merges,
                          ps_error *err) {
    if (in->mean_angular < PS_CREASE_FLAT) return PS_OK; /* no creases: no evidence */
    merge_state s = {0};
    ps_status st =
        state_init(in, group_of_point, PS_CREASE_MERGE_STRENGTH * in->mean_angular, &s, err);
    for (long i; st == PS_OK && (i = weakest_boundary(&s, in->threshold)) >= 0;)
        if (!merge_pair(&s, (size_t)i, merges, n_merges))
            st = ps_fail(err, PS_ERR_NOMEM, "out of memory (crease merge)");
    if (st == PS_OK) {
        for (size_t p = 0; p < in->graph->n; p++)
            group_of_point[p] = survivor(&s, group_of_point[p]);
        for (int t = 0; t < in->n_groups; t++)
            if (group_of_leaf[t] >= 0) group_of_leaf[t] = survivor(&s, group_of_leaf[t]);
    }
    state_free(&s);
    return st;
}
