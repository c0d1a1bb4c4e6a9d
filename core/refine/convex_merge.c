/*
 * convex_merge.c: adjacent segments whose union is convex merge
 * (convex_merge.h), over the adjacency of segment_graph.h with the crease
 * merge's creased boundary edges marked, and a sample of each segment's
 * points with their patch normals (patch_normal.h).
 */
#include "refine/convex_merge.h"

#include "features/crease.h"
#include "features/patch_normal.h"
#include "refine/crease_merge.h"
#include "refine/segment_graph.h"
#include "util/vec3.h"

#include <math.h>
#include <stdlib.h>

#define SAMPLES PS_CONVEX_MERGE_SAMPLES

/* Each segment's sample: point ids, SAMPLES slots per segment. */
typedef struct samples {
    uint32_t *point; /* #n_groups by SAMPLES */
    int *count;      /* #n_groups */
    double *normal;  /* #P by 3: the sampled points' patch normals */
} samples;

static void samples_free(samples *s) {
    free(s->point);
    free(s->count);
    free(s->normal);
}

/* Rank of a segment's j-th sample point among its size points (size >
 * SAMPLES): evenly spaced from the first to the last. */
static size_t sample_rank(int j, size_t size) {
    return (size_t)j * (size - 1) / (SAMPLES - 1);
}

/* The samples at the start, in one pass over the points; rank #n_groups
 * scratch (each segment's points seen so far). */
static void first_samples(samples *s, const int *group, size_t n, const size_t *size,
                          size_t *rank) {
    for (size_t p = 0; p < n; p++) {
        int g = group[p];
        size_t r = rank[g]++;
        int *c = &s->count[g];
        if (size[g] <= SAMPLES || (*c < SAMPLES && sample_rank(*c, size[g]) == r))
            s->point[(size_t)g * SAMPLES + (size_t)(*c)++] = (uint32_t)p;
    }
}

/* Appends want of the from_count points of from, evenly spaced, to to. */
static int pick(const uint32_t *from, int from_count, int want, uint32_t *to) {
    for (int j = 0; j < want; j++) to[j] = from[(size_t)j * (size_t)from_count / (size_t)want];
    return want;
}

/* winner's sample becomes the union's: from both samples in proportion to
 * the segments' sizes (before the merge). */
static void merge_samples(samples *s, int winner, int loser, size_t size_w, size_t size_l) {
    int cw = s->count[winner], cl = s->count[loser];
    int total = cw + cl < SAMPLES ? cw + cl : SAMPLES;
    int from_w = (int)lround((double)total * (double)size_w / (double)(size_w + size_l));
    if (from_w > cw) from_w = cw;
    if (total - from_w > cl) from_w = total - cl;
    uint32_t merged[SAMPLES];
    int m = pick(s->point + (size_t)winner * SAMPLES, cw, from_w, merged);
    m += pick(s->point + (size_t)loser * SAMPLES, cl, total - from_w, merged + m);
    for (int j = 0; j < m; j++) s->point[(size_t)winner * SAMPLES + (size_t)j] = merged[j];
    s->count[winner] = m;
    s->count[loser] = 0;
}

/* Where a point at offset d from a surface point lies against its tangent
 * plane: IN_FRONT, ON_PLANE (|d . n| within PS_CONVEX_MERGE_TOLERANCE
 * |d|) or BEHIND (further back). */
enum { IN_FRONT, ON_PLANE, BEHIND };

static int side_of(const double *d, const double *n) {
    double along = ps_dot3(d, n);
    double tolerance2 = PS_CONVEX_MERGE_TOLERANCE * PS_CONVEX_MERGE_TOLERANCE * ps_dot3(d, d);
    if (along * along <= tolerance2) return ON_PLANE;
    return along < 0 ? BEHIND : IN_FRONT;
}

/* The fraction of sample pairs (p of a, q of b) each behind or on the
 * other's tangent plane; 0 unless at least PS_CONVEX_MERGE_DEPTH of them
 * have one behind the other's plane (a flat union has no depth). */
static double convexity(const ps_merge_input *in, const samples *s, int a, int b) {
    const uint32_t *pa = s->point + (size_t)a * SAMPLES, *pb = s->point + (size_t)b * SAMPLES;
    int ca = s->count[a], cb = s->count[b];
    if (ca == 0 || cb == 0) return 0;
    long pass = 0, deep = 0;
    for (int i = 0; i < ca; i++) {
        const double *x = in->points + 3 * (size_t)pa[i], *nx = s->normal + 3 * (size_t)pa[i];
        for (int j = 0; j < cb; j++) {
            const double *y = in->points + 3 * (size_t)pb[j];
            double d[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
            double back[3] = {-d[0], -d[1], -d[2]};
            int q_side = side_of(d, nx), p_side = side_of(back, s->normal + 3 * (size_t)pb[j]);
            if (q_side == IN_FRONT || p_side == IN_FRONT) continue;
            pass++;
            deep += q_side == BEHIND || p_side == BEHIND;
        }
    }
    double pairs = (double)ca * (double)cb;
    return (double)deep >= PS_CONVEX_MERGE_DEPTH * pairs ? (double)pass / pairs : 0;
}

/* The convexity at which record i's pair merges: lower when part of its
 * boundary is not creased. */
static double threshold_of(const ps_boundary *r) {
    double creased = r->edges ? (double)r->marked / (double)r->edges : 1;
    return creased <= PS_CONVEX_MERGE_OPEN_CREASED ? PS_CONVEX_MERGE_OPEN
                                                   : PS_CONVEX_MERGE_FRACTION;
}

/* The record of the most convex pair at or over its threshold, or -1. */
static long most_convex(const ps_merge_input *in, const ps_segment_graph *sg,
                        const samples *s) {
    long best = -1;
    double best_convexity = 0;
    for (size_t i = 0; i < sg->count; i++) {
        double c = convexity(in, s, sg->list[i].a, sg->list[i].b);
        if (c >= threshold_of(&sg->list[i]) && (best < 0 || c > best_convexity))
            best = (long)i, best_convexity = c;
    }
    return best;
}

/* Merges record i's pair, the smaller segment into the larger (ties: the
 * higher id into the lower); 0 when out of memory. */
static int merge_pair(ps_segment_graph *sg, samples *s, size_t i, ps_merge **merges,
                      int *n_merges) {
    int a = sg->list[i].a, b = sg->list[i].b;
    int loser = sg->size[b] <= sg->size[a] ? b : a, winner = loser == a ? b : a;
    merge_samples(s, winner, loser, sg->size[winner], sg->size[loser]);
    return ps_segment_graph_merge(sg, loser, winner, merges, n_merges);
}

/* The samples' patch normals; ids #m_groups * SAMPLES scratch. */
static ps_status sample_normals(const ps_merge_input *in, samples *s, size_t m_groups,
                                uint32_t *ids, ps_error *err) {
    size_t m = 0;
    for (size_t g = 0; g < m_groups; g++)
        for (int j = 0; j < s->count[g]; j++) ids[m++] = s->point[g * SAMPLES + (size_t)j];
    return ps_patch_normals(in->graph, in->points, in->normals, ids, m, s->normal, err);
}

static ps_status samples_init(samples *s, const ps_merge_input *in, const ps_segment_graph *sg,
                              const int *group, ps_error *err) {
    size_t m = (size_t)(sg->n_groups > 0 ? sg->n_groups : 1), n = in->graph->n;
    s->point = malloc(m * SAMPLES * sizeof *s->point);
    s->count = calloc(m, sizeof *s->count);
    s->normal = malloc(3 * n * sizeof *s->normal);
    size_t *rank = calloc(m, sizeof *rank);
    uint32_t *ids = malloc(m * SAMPLES * sizeof *ids);
    ps_status st = PS_OK;
    if (!s->point || !s->count || !s->normal || !rank || !ids) {
        st = ps_fail(err, PS_ERR_NOMEM, "out of memory (convex merge)");
    } else {
        first_samples(s, group, n, sg->size, rank);
        st = sample_normals(in, s, m, ids, err);
    }
    free(rank);
    free(ids);
    return st;
}

ps_status ps_convex_merge(const ps_merge_input *in, int *group_of_point,
                          int *group_of_leaf, ps_merge **merges, int *n_merges,
                          ps_error *err) {
    if (in->mean_angular < PS_CREASE_FLAT) return PS_OK; /* flat: no depth anywhere */
    ps_segment_graph sg;
    ps_crease_test test = ps_crease_test_of(in);
    ps_segment_graph_input sgi = {.graph = in->graph, .f = in->f, .group = group_of_point,
                                  .n_groups = in->n_groups,
                                  .mark = ps_crease_marked_edge, .context = &test,
                                  .threads = in->threads};
    ps_status st = ps_segment_graph_build_along(&sg, &sgi, in->boundary, err);
    if (st != PS_OK) return st;
    samples s = {0};
    st = samples_init(&s, in, &sg, group_of_point, err);
    for (long i; st == PS_OK && (i = most_convex(in, &sg, &s)) >= 0;)
        if (!merge_pair(&sg, &s, (size_t)i, merges, n_merges))
            st = ps_fail(err, PS_ERR_NOMEM, "out of memory (convex merge)");
    if (st == PS_OK) ps_segment_graph_apply(&sg, group_of_point, in->graph->n, group_of_leaf);
    ps_segment_graph_free(&sg);
    samples_free(&s);
    return st;
}
