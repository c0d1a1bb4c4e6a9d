/*
 * segment_graph.c: the segments' adjacency, and merging two segments
 * (segment_graph.h).
 */
#include "refine/segment_graph.h"

#include "util/parallel.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define GATHER_CHUNKS 64 /* fixed runs of points whose boundary edges are gathered side by side */

/* The mean squared distance of n points from their centroid, from the sum
 * of the points and of their squared norms (<= 0 when rounding leaves
 * no spread). */
static double spread2(const double sum[3], double norm2_sum, double n) {
    double centroid2 = 0;
    for (int d = 0; d < 3; d++) centroid2 += (sum[d] / n) * (sum[d] / n);
    return norm2_sum / n - centroid2;
}

double ps_boundary_width(const ps_boundary *r) {
    double variance = spread2(r->midpoint_sum, r->norm2_sum, (double)r->edges);
    return variance > 0 ? 2 * sqrt(variance) : 0;
}

double ps_segment_bulge(const ps_segment_graph *sg, int s) {
    if (!sg->sums || sg->size[s] == 0) return 0;
    const ps_segment_sums *m = &sg->sums[s];
    double n = (double)sg->size[s], nc = 0;
    for (int d = 0; d < 3; d++) nc += (m->normal_sum[d] / n) * (m->point_sum[d] / n);
    double variance = spread2(m->point_sum, m->norm2_sum, n);
    return variance > 0 ? (m->dot_sum / n - nc) / sqrt(variance) : 0;
}

int ps_segment_protrudes(const ps_segment_graph *sg, int s, const ps_boundary *r, double factor) {
    return sg->f_max[s] - sg->f_min[s] > factor * ps_boundary_width(r);
}

static int same_pair(const ps_boundary *p, const ps_boundary *q) {
    return p->a == q->a && p->b == q->b;
}

/* By pair, then by position: a stable sort by pair, so that the records of
 * one pair are summed in list order (the sums' rounding depends on it). */
static int compare_boundary(const void *x, const void *y) {
    const ps_boundary *p = x, *q = y;
    if (p->a != q->a) return p->a < q->a ? -1 : 1;
    if (p->b != q->b) return p->b < q->b ? -1 : 1;
    return (p->position > q->position) - (p->position < q->position);
}

/* Sorts the records and sums those of one pair; drops a == b. */
static void coalesce(ps_segment_graph *sg) {
    if (sg->count == 0) return;
    for (size_t i = 0; i < sg->count; i++) sg->list[i].position = i;
    qsort(sg->list, sg->count, sizeof *sg->list, compare_boundary);
    size_t out = 0;
    for (size_t i = 0; i < sg->count; i++) {
        if (sg->list[i].a == sg->list[i].b) continue;
        if (out > 0 && same_pair(&sg->list[out - 1], &sg->list[i])) {
            ps_boundary *sum = &sg->list[out - 1];
            sum->marked += sg->list[i].marked;
            sum->edges += sg->list[i].edges;
            for (int d = 0; d < 3; d++) sum->midpoint_sum[d] += sg->list[i].midpoint_sum[d];
            sum->norm2_sum += sg->list[i].norm2_sum;
        } else {
            sg->list[out++] = sg->list[i];
        }
    }
    sg->count = out;
}

/* The record of edge p-q joining segments a and b.  Midpoints are taken
 * relative to point 0, so that the sums keep their precision far from the
 * origin. */
static ps_boundary edge_record(const ps_segment_graph_input *in, size_t p, size_t q, int a,
                               int b) {
    ps_boundary r = {.a = a < b ? a : b, .b = a < b ? b : a, .edges = 1};
    r.marked = in->mark ? in->mark(in->context, in->group, p, q) != 0 : 0;
    if (in->points)
        for (int d = 0; d < 3; d++) {
            double mid = 0.5 * (in->points[3 * p + d] + in->points[3 * q + d]) - in->points[d];
            r.midpoint_sum[d] = mid;
            r.norm2_sum += mid * mid;
        }
    return r;
}

/* The records of a run of points (or of candidate edges), in edge order,
 * and their edges' ends when the caller wants them. */
typedef struct record_list {
    ps_boundary *list;
    uint32_t *ends;  /* #count by 2, or NULL when not wanted */
    size_t count, capacity;
    int failed;  /* out of memory */
} record_list;

/* Room for one more record (and its ends when wanted); 0 when out of memory. */
static int record_room(record_list *r, int want_ends) {
    if (r->count < r->capacity) return 1;
    size_t grown = r->capacity ? 2 * r->capacity : 256;
    ps_boundary *list = realloc(r->list, grown * sizeof *list);
    if (list) r->list = list;
    uint32_t *ends = want_ends ? realloc(r->ends, 2 * grown * sizeof *ends) : NULL;
    if (ends) r->ends = ends;
    if (!list || (want_ends && !ends)) return 0;
    r->capacity = grown;
    return 1;
}

typedef struct gather_job {
    const ps_segment_graph_input *in;
    record_list *chunks;  /* #GATHER_CHUNKS */
} gather_job;

/* The record of edge p < q, joining segments a != b, in chunk c. */
static void gather_edge(const gather_job *j, size_t c, size_t p, size_t q, int a, int b) {
    record_list *r = &j->chunks[c];
    if (r->failed) return;
    if (!record_room(r, j->in->found != NULL)) {
        r->failed = 1;
        return;
    }
    if (r->ends) r->ends[2 * r->count] = (uint32_t)p, r->ends[2 * r->count + 1] = (uint32_t)q;
    r->list[r->count++] = edge_record(j->in, p, q, a, b);
}

/* Chunk c: the points [n c / GATHER_CHUNKS, n (c + 1) / GATHER_CHUNKS), or
 * that share of the candidate edges. */
static void gather_chunks(void *ctx, size_t begin, size_t end, int worker) {
    const gather_job *j = ctx;
    const ps_graph *g = j->in->graph;
    const ps_edge_list *cand = j->in->candidates;
    const int *group = j->in->group;
    (void)worker;
    for (size_t c = begin; c < end; c++) {
        if (cand) {
            for (size_t i = cand->count * c / GATHER_CHUNKS;
                 i < cand->count * (c + 1) / GATHER_CHUNKS; i++) {
                size_t p = cand->ends[2 * i], q = cand->ends[2 * i + 1];
                if (group[p] != group[q]) gather_edge(j, c, p, q, group[p], group[q]);
            }
            continue;
        }
        for (size_t p = g->n * c / GATHER_CHUNKS; p < g->n * (c + 1) / GATHER_CHUNKS; p++)
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
                size_t q = g->neighbors[e];
                if (q > p && group[p] != group[q]) gather_edge(j, c, p, q, group[p], group[q]);
            }
    }
}

/* The chunks' edge ends joined in chunk order into in->found; 0 when out
 * of memory. */
static int join_ends(const record_list *chunks, size_t total, ps_edge_list *found) {
    found->ends = malloc(2 * (total ? total : 1) * sizeof *found->ends);
    found->count = 0;
    if (!found->ends) return 0;
    for (size_t c = 0; c < GATHER_CHUNKS; c++) {
        if (chunks[c].count == 0) continue; /* its ends may be NULL */
        memcpy(found->ends + 2 * found->count, chunks[c].ends,
               2 * chunks[c].count * sizeof *found->ends);
        found->count += chunks[c].count;
    }
    return 1;
}

/* One record per edge p < q joining two segments: the chunks gather
 * theirs side by side, then join in chunk order (the edge order of one
 * pass over the arcs, whatever the thread count; candidates keep that
 * order). */
static int gather_boundaries(ps_segment_graph *sg, const ps_segment_graph_input *in) {
    record_list chunks[GATHER_CHUNKS] = {{0}};
    gather_job j = {in, chunks};
    ps_parallel_for(ps_parallel_threads(in->threads), GATHER_CHUNKS, 1, gather_chunks, &j);
    size_t total = 0;
    int failed = 0;
    for (size_t c = 0; c < GATHER_CHUNKS; c++) total += chunks[c].count, failed |= chunks[c].failed;
    sg->list = failed ? NULL : malloc((total ? total : 1) * sizeof *sg->list);
    for (size_t c = 0; sg->list && c < GATHER_CHUNKS; c++) {
        if (chunks[c].count == 0) continue; /* its list may be NULL */
        memcpy(sg->list + sg->count, chunks[c].list, chunks[c].count * sizeof *sg->list);
        sg->count += chunks[c].count;
    }
    int ok = sg->list && (!in->found || join_ends(chunks, total, in->found));
    for (size_t c = 0; c < GATHER_CHUNKS; c++) free(chunks[c].list), free(chunks[c].ends);
    if (!ok) return 0;
    coalesce(sg);
    return 1;
}

/* Adds point p to the sums of its segment (relative to point 0). */
static void add_sums(ps_segment_sums *m, const double *points, const double *normals, size_t p) {
    for (int d = 0; d < 3; d++) {
        double x = points[3 * p + d] - points[d], nx = normals[3 * p + d];
        m->point_sum[d] += x;
        m->normal_sum[d] += nx;
        m->dot_sum += nx * x;
        m->norm2_sum += x * x;
    }
}

static void measure_segments(ps_segment_graph *sg, const ps_segment_graph_input *in) {
    const double *f = in->f;
    for (size_t p = 0; p < in->graph->n; p++) {
        int a = in->group[p];
        if (sg->sums) add_sums(&sg->sums[a], in->points, in->normals, p);
        if (sg->size[a] == 0 || f[p] < sg->f_min[a]) sg->f_min[a] = f[p];
        if (sg->size[a] == 0 || f[p] > sg->f_max[a]) sg->f_max[a] = f[p];
        sg->size[a]++;
    }
}

ps_status ps_segment_graph_build(ps_segment_graph *sg, const ps_segment_graph_input *in,
                                 ps_error *err) {
    int n_groups = in->n_groups;
    size_t m = (size_t)(n_groups > 0 ? n_groups : 1);
    memset(sg, 0, sizeof *sg);
    sg->n_groups = n_groups;
    sg->size = calloc(m, sizeof *sg->size);
    sg->f_min = calloc(m, sizeof *sg->f_min);
    sg->f_max = calloc(m, sizeof *sg->f_max);
    sg->alias = malloc(m * sizeof *sg->alias);
    int with_sums = in->points && in->normals;
    if (with_sums) sg->sums = calloc(m, sizeof *sg->sums);
    if (sg->size && sg->f_min && sg->f_max && sg->alias && (!with_sums || sg->sums)) {
        for (int i = 0; i < n_groups; i++) sg->alias[i] = i;
        measure_segments(sg, in);
        if (gather_boundaries(sg, in)) return PS_OK;
    }
    ps_segment_graph_free(sg);
    return ps_fail(err, PS_ERR_NOMEM, "out of memory (segment graph)");
}

ps_status ps_segment_graph_build_along(ps_segment_graph *sg, ps_segment_graph_input *in,
                                       ps_edge_list *boundary, ps_error *err) {
    ps_edge_list found = {0};
    in->candidates = boundary && boundary->ends ? boundary : NULL;
    in->found = boundary ? &found : NULL;
    ps_status st = ps_segment_graph_build(sg, in, err);
    if (st == PS_OK && boundary) {
        free(boundary->ends);
        *boundary = found;
    } else {
        free(found.ends);
    }
    return st;
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
    ps_merge merge = {.segment = loser, .into = winner,
                      .feature_size = sg->f_max[loser] - sg->f_min[loser],
                      .step = PS_STEP_COUNT}; /* named by the step that ran it (segment.c) */
    if (!append_merge(merges, n_merges, merge)) return 0;
    sg->size[winner] += sg->size[loser];
    if (sg->f_min[loser] < sg->f_min[winner]) sg->f_min[winner] = sg->f_min[loser];
    if (sg->f_max[loser] > sg->f_max[winner]) sg->f_max[winner] = sg->f_max[loser];
    if (sg->sums) {
        ps_segment_sums *w = &sg->sums[winner], *l = &sg->sums[loser];
        for (int d = 0; d < 3; d++) {
            w->point_sum[d] += l->point_sum[d];
            w->normal_sum[d] += l->normal_sum[d];
        }
        w->dot_sum += l->dot_sum;
        w->norm2_sum += l->norm2_sum;
    }
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
    free(sg->sums);
    free(sg->list);
    memset(sg, 0, sizeof *sg);
}
