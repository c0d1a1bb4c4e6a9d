/*
 * persistence.c: persistence-based merging of flow basins (persistence.h).
 * Border edges are sorted by saddle height, then a union-find over the
 * basins, each set represented by its highest peak, merges the lower peak
 * whenever its persistence is under the component's threshold.  The
 * border edges of the merged basins are those of the list whose ends
 * still lie apart, in the same order: no pass over the graph again.
 */
#include "features/persistence.h"

#include "features/component_range.h"
#include "util/union_find.h"
#include <stdlib.h>

#define INSERTION_RUN 16 /* saddles per run sorted by insertion before the merges */

/* The sweep's order: height from high to low, then p, then q (a total
 * order: an edge is listed once). */
static int saddle_before(const ps_saddle *x, const ps_saddle *y) {
    if (x->height != y->height) return x->height > y->height;
    return x->p != y->p ? x->p < y->p : x->q < y->q;
}

static void insertion_sort(ps_saddle *s, size_t n) {
    for (size_t i = 1; i < n; i++) {
        ps_saddle x = s[i];
        size_t j = i;
        for (; j > 0 && saddle_before(&x, &s[j - 1]); j--) s[j] = s[j - 1];
        s[j] = x;
    }
}

/* Sorted runs from[lo, mid) and from[mid, hi) merged into to[lo, hi). */
static void merge_runs(const ps_saddle *from, ps_saddle *to, size_t lo, size_t mid, size_t hi) {
    size_t i = lo, j = mid, k = lo;
    while (i < mid && j < hi) to[k++] = saddle_before(&from[j], &from[i]) ? from[j++] : from[i++];
    while (i < mid) to[k++] = from[i++];
    while (j < hi) to[k++] = from[j++];
}

/* s (#n) in the sweep's order: a bottom-up merge sort through tmp (#n);
 * returns the array that holds the result (s or tmp). */
static ps_saddle *sort_saddles(ps_saddle *s, size_t n, ps_saddle *tmp) {
    for (size_t lo = 0; lo < n; lo += INSERTION_RUN)
        insertion_sort(s + lo, n - lo < INSERTION_RUN ? n - lo : INSERTION_RUN);
    ps_saddle *from = s, *to = tmp;
    for (size_t width = INSERTION_RUN; width < n; width *= 2) {
        for (size_t lo = 0; lo < n; lo += 2 * width) {
            size_t mid = lo + width < n ? lo + width : n;
            size_t hi = lo + 2 * width < n ? lo + 2 * width : n;
            merge_runs(from, to, lo, mid, hi);
        }
        ps_saddle *t = from;
        from = to, to = t;
    }
    return from;
}

/* s (#*capacity) grown to hold one more than *count; 0 when out of memory. */
static int saddles_room(ps_saddle **s, size_t count, size_t *capacity) {
    if (count < *capacity) return 1;
    size_t more = *capacity ? 2 * *capacity : 1024;
    ps_saddle *grown = realloc(*s, more * sizeof *grown);
    if (!grown) return 0;
    *s = grown, *capacity = more;
    return 1;
}

ps_saddle *ps_flow_border_saddles(const ps_graph *g, const double *f, const ps_flow *flow,
                                  size_t *count) {
    size_t k = 0, capacity = 0;
    ps_saddle *s = NULL;
    for (size_t p = 0; p < g->n; p++) {
        int a = flow->sink_of[p];
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if ((q <= p) | (flow->sink_of[q] == a)) continue; /* one test, no short circuit */
            if (!saddles_room(&s, k, &capacity)) return free(s), NULL;
            s[k++] = (ps_saddle){f[p] < f[q] ? f[p] : f[q], (uint32_t)p, q};
        }
    }
    ps_saddle *tmp = malloc((k ? k : 1) * sizeof *tmp);
    if (!tmp) return free(s), NULL;
    ps_saddle *sorted = k ? sort_saddles(s, k, tmp) : tmp;
    free(sorted == s ? tmp : s);
    *count = k;
    return sorted;
}

void ps_saddles_keep_borders(const ps_flow *flow, ps_saddle *s, size_t *count) {
    size_t kept = 0;
    for (size_t i = 0; i < *count; i++)
        if (flow->sink_of[s[i].p] != flow->sink_of[s[i].q]) s[kept++] = s[i];
    *count = kept;
}

/* Is sink a's peak below sink b's?  Ties: the higher vertex id is lower. */
static int peak_below(const ps_flow *flow, const double *f, int a, int b) {
    double fa = f[flow->sinks[a]], fb = f[flow->sinks[b]];
    return fa < fb || (fa == fb && flow->sinks[a] > flow->sinks[b]);
}

static void merge_sweep(const ps_persistence_input *in, const ps_saddle *s, size_t count,
                        const double *threshold, const ps_flow *flow, int *parent,
                        size_t *size) {
    const double *f = in->f;
    size_t min_size = in->min_size;
    for (size_t i = 0; i < count; i++) {
        int a = ps_union_find_root(parent, flow->sink_of[s[i].p]);
        int b = ps_union_find_root(parent, flow->sink_of[s[i].q]);
        if (a == b) continue;
        int low = peak_below(flow, f, a, b) ? a : b, high = low == a ? b : a;
        double persistence = f[flow->sinks[low]] - s[i].height;
        if (persistence < threshold[in->component[s[i].p]] || size[low] < min_size ||
            size[high] < min_size) {
            int keep = size[high] < min_size && size[low] >= min_size ? low : high;
            int gone = keep == high ? low : high;
            parent[gone] = keep;
            size[keep] += size[gone];
        }
    }
}

void ps_persistence_merge(ps_flow *flow, int *parent, int *new_id, size_t n) {
    int m = flow->n_sinks, kept = 0;
    for (int s = 0; s < m; s++) parent[s] = ps_union_find_root(parent, s);
    for (int s = 0; s < m; s++)
        if (parent[s] == s) new_id[s] = kept, flow->sinks[kept++] = flow->sinks[s];
    for (size_t p = 0; p < n; p++) flow->sink_of[p] = new_id[parent[flow->sink_of[p]]];
    flow->n_sinks = kept;
}

ps_status ps_persistence_simplify_along(const ps_persistence_input *in, ps_saddle *s,
                                        size_t *count, ps_flow *flow, ps_error *err) {
    if (in->fraction <= 0 || flow->n_sinks < 2) return PS_OK;
    const ps_graph *g = in->graph;
    double *threshold = ps_component_thresholds(in->f, in->component, g->n, in->n_components,
                                                in->fraction);
    int m = flow->n_sinks;
    int *parent = malloc((size_t)m * sizeof *parent), *new_id = malloc((size_t)m * sizeof *new_id);
    size_t *size = calloc((size_t)m, sizeof *size);
    int ok = threshold && parent && new_id && size;
    if (ok) {
        for (int k = 0; k < m; k++) parent[k] = k;
        for (size_t p = 0; p < g->n; p++) size[flow->sink_of[p]]++;
        merge_sweep(in, s, *count, threshold, flow, parent, size);
        ps_persistence_merge(flow, parent, new_id, g->n);
        ps_saddles_keep_borders(flow, s, count);
    }
    free(threshold);
    free(parent);
    free(new_id);
    free(size);
    return ok ? PS_OK : ps_fail(err, PS_ERR_NOMEM, "persistence: out of memory");
}

ps_status ps_persistence_simplify(const ps_persistence_input *in, ps_flow *flow, ps_error *err) {
    if (in->fraction <= 0 || flow->n_sinks < 2) return PS_OK;
    size_t count = 0;
    ps_saddle *s = ps_flow_border_saddles(in->graph, in->f, flow, &count);
    ps_status st = s ? ps_persistence_simplify_along(in, s, &count, flow, err)
                     : ps_fail(err, PS_ERR_NOMEM, "persistence: out of memory");
    free(s);
    return st;
}
