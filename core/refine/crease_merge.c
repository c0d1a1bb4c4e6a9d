/*
 * crease_merge.c: segments joined by a boundary that is not a concave
 * crease merge (crease_merge.h), over the adjacency of segment_graph.h
 * with the creased boundary edges marked.
 */
#include "refine/crease_merge.h"

#include "features/crease.h"
#include "refine/segment_graph.h"

#include <math.h>
#include <stdlib.h>

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

/* Whether one of p's edges into segments a and b that run along the
 * boundary edge's line (across, unit #3) has an angular term of crease or
 * more (the first such edge answers; any crease <= 0 is met, as by an
 * edge-less point's strength 0): only those can make a crease of the
 * boundary between a and b.  A wing root next to the boundary between nose
 * and fuselage is in a third segment; a fillet running across that
 * boundary bends along it, not across. */
static int creased_within(const ps_merge_input *in, const int *group, size_t p, int a, int b,
                          const double *across, double crease) {
    const ps_graph *g = in->graph;
    if (crease <= 0) return 1;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
        size_t r = g->neighbors[e];
        if ((group[r] != a && group[r] != b) || !along(in->points, p, r, across)) continue;
        if (ps_crease_angular(in->points + 3 * p, in->normals + 3 * p, in->points + 3 * r,
                              in->normals + 3 * r, 0.0) >= crease)
            return 1;
    }
    return 0;
}

ps_crease_test ps_crease_test_of(const ps_merge_input *in) {
    double scale = fmax(in->mean_angular, PS_CREASE_MERGE_NOISE * in->median_strength);
    return (ps_crease_test){in, PS_CREASE_MERGE_STRENGTH * scale};
}

/* Whether the boundary edge p-q is creased (see crease_merge.h). */
int ps_crease_marked_edge(void *context, const int *group, size_t p, size_t q) {
    const ps_crease_test *test = context;
    const ps_merge_input *in = test->in;
    double across[3], length2 = 0;
    for (int i = 0; i < 3; i++) {
        across[i] = in->points[3 * q + i] - in->points[3 * p + i];
        length2 += across[i] * across[i];
    }
    if (length2 > 0)
        for (int i = 0; i < 3; i++) across[i] /= sqrt(length2);
    int a = group[p], b = group[q];
    return creased_within(in, group, p, a, b, across, test->crease) ||
           creased_within(in, group, q, a, b, across, test->crease);
}

/* The smaller segment of record i. */
static int smaller_of(const ps_segment_graph *sg, size_t i) {
    int a = sg->list[i].a, b = sg->list[i].b;
    return sg->size[b] <= sg->size[a] ? b : a;
}

/* The segment of record i other than s. */
static int other_of(const ps_segment_graph *sg, size_t i, int s) {
    return s == sg->list[i].a ? sg->list[i].b : sg->list[i].a;
}

/* Whether segment s is a cavity: it curves inwards (ps_segment_bulge). */
static int cavity(const ps_segment_graph *sg, int s) {
    return ps_segment_bulge(sg, s) < -PS_CREASE_MERGE_CAVITY;
}

/* The core: the segment that holds the least f (ties: the lowest id),
 * the shape's centre; -1 when there is none. */
static int core_of(const ps_segment_graph *sg) {
    int core = -1;
    for (int s = 0; s < sg->n_groups; s++)
        if (sg->alias[s] == s && sg->size[s] > 0 && (core < 0 || sg->f_min[s] < sg->f_min[core]))
            core = s;
    return core;
}

/* Whether record i's part protrudes: its smaller segment, or the other
 * when the smaller is the core (the centre of a plus sign can be smaller
 * than each of its arms, and sticks out of nothing), is no cavity and
 * its feature size is over PS_CREASE_MERGE_PROTRUSION times the width of
 * its boundary. */
static int protrudes(const ps_segment_graph *sg, size_t i, int core) {
    int s = smaller_of(sg, i);
    if (s == core) s = other_of(sg, i, s);
    return !cavity(sg, s) && ps_segment_protrudes(sg, s, &sg->list[i], PS_CREASE_MERGE_PROTRUSION);
}

/* The creased fraction of record i's boundary; 0 when its smaller segment
 * is a cavity, which merges whatever its creases. */
static double creased_fraction(const ps_segment_graph *sg, size_t i) {
    if (cavity(sg, smaller_of(sg, i))) return 0;
    return (double)sg->list[i].marked / (double)sg->list[i].edges;
}

/* The record with the smallest creased fraction, or -1 when none is below
 * the threshold; protruding parts stay. */
static long weakest_boundary(const ps_segment_graph *sg, double threshold) {
    long best = -1;
    double best_fraction = threshold;
    int core = core_of(sg);
    for (size_t i = 0; i < sg->count; i++) {
        double fraction = creased_fraction(sg, i);
        if (fraction < best_fraction && !protrudes(sg, i, core))
            best = (long)i, best_fraction = fraction;
    }
    return best;
}

/* Merges the pair of record i: the smaller segment into the larger (ties:
 * the higher id into the lower). */
static int merge_pair(ps_segment_graph *sg, size_t i, ps_merge **merges, int *n_merges) {
    int loser = smaller_of(sg, i);
    return ps_segment_graph_merge(sg, loser, other_of(sg, i, loser), merges, n_merges);
}

ps_status ps_crease_merge(const ps_merge_input *in, int *group_of_point,
                          int *group_of_leaf, ps_merge **merges, int *n_merges,
                          ps_error *err) {
    ps_crease_test test = ps_crease_test_of(in);
    if (in->mean_angular < PS_CREASE_FLAT) test.crease = INFINITY; /* protrusions alone stay */
    ps_segment_graph sg;
    ps_segment_graph_input sgi = {.graph = in->graph, .f = in->f, .points = in->points,
                                  .normals = in->normals, .group = group_of_point,
                                  .n_groups = in->n_groups,
                                  .mark = ps_crease_marked_edge, .context = &test,
                                  .threads = in->threads};
    ps_status st = ps_segment_graph_build_along(&sg, &sgi, in->boundary, err);
    for (long i; st == PS_OK && (i = weakest_boundary(&sg, PS_CREASE_MERGE_FRACTION)) >= 0;)
        if (!merge_pair(&sg, (size_t)i, merges, n_merges))
            st = ps_fail(err, PS_ERR_NOMEM, "out of memory (crease merge)");
    if (st == PS_OK) ps_segment_graph_apply(&sg, group_of_point, in->graph->n, group_of_leaf);
    ps_segment_graph_free(&sg);
    return st;
}
