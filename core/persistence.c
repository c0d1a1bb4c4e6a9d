/*
 * persistence.c: persistence-based merging of flow basins (persistence.h).
 * Border edges are sorted by saddle height, then a union-find over the
 * basins, each set represented by its highest peak, merges the lower peak
 * whenever its persistence is under the component's threshold.  The
 * border edges of the merged basins are those of the list whose ends
 * still lie apart, in the same order: no pass over the graph again.
 */
#include "persistence.h"

#include "component_range.h"
#include "union_find.h"
#include <stdlib.h>

static int by_height_desc(const void *a, const void *b) {
    const ps_saddle *x = a, *y = b;
    if (x->height != y->height) return x->height > y->height ? -1 : 1;
    if (x->p != y->p) return x->p < y->p ? -1 : 1;
    return (x->q > y->q) - (x->q < y->q);
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
            if (q <= p || flow->sink_of[q] == a) continue;
            if (!saddles_room(&s, k, &capacity)) return free(s), NULL;
            s[k++] = (ps_saddle){f[p] < f[q] ? f[p] : f[q], (uint32_t)p, q};
        }
    }
    if (!s) s = malloc(sizeof *s);
    if (s) qsort(s, k, sizeof *s, by_height_desc);
    *count = k;
    return s;
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

static void merge_sweep(const ps_saddle *s, size_t count, const double *f, const int *component,
                        const double *threshold, const ps_flow *flow, int *parent,
                        size_t *size, size_t min_size) {
    for (size_t i = 0; i < count; i++) {
        int a = ps_union_find_root(parent, flow->sink_of[s[i].p]);
        int b = ps_union_find_root(parent, flow->sink_of[s[i].q]);
        if (a == b) continue;
        int low = peak_below(flow, f, a, b) ? a : b, high = low == a ? b : a;
        double persistence = f[flow->sinks[low]] - s[i].height;
        if (persistence < threshold[component[s[i].p]] || size[low] < min_size ||
            size[high] < min_size) {
            int keep = size[high] < min_size && size[low] >= min_size ? low : high;
            int gone = keep == high ? low : high;
            parent[gone] = keep;
            size[keep] += size[gone];
        }
    }
}

void ps_flow_merge(ps_flow *flow, int *parent, int *new_id, size_t n) {
    int m = flow->n_sinks, kept = 0;
    for (int s = 0; s < m; s++) parent[s] = ps_union_find_root(parent, s);
    for (int s = 0; s < m; s++)
        if (parent[s] == s) new_id[s] = kept, flow->sinks[kept++] = flow->sinks[s];
    for (size_t p = 0; p < n; p++) flow->sink_of[p] = new_id[parent[flow->sink_of[p]]];
    flow->n_sinks = kept;
}

ps_status ps_flow_simplify_along(const ps_graph *g, const double *f, const int *component,
                                 int n_components, double fraction, size_t min_size,
                                 ps_saddle *s, size_t *count, ps_flow *flow, ps_error *err) {
    if (fraction <= 0 || flow->n_sinks < 2) return PS_OK;
    double *threshold = ps_component_thresholds(f, component, g->n, n_components, fraction);
    int m = flow->n_sinks;
    int *parent = malloc((size_t)m * sizeof *parent), *new_id = malloc((size_t)m * sizeof *new_id);
    size_t *size = calloc((size_t)m, sizeof *size);
    int ok = threshold && parent && new_id && size;
    if (ok) {
        for (int k = 0; k < m; k++) parent[k] = k;
        for (size_t p = 0; p < g->n; p++) size[flow->sink_of[p]]++;
        merge_sweep(s, *count, f, component, threshold, flow, parent, size, min_size);
        ps_flow_merge(flow, parent, new_id, g->n);
        ps_saddles_keep_borders(flow, s, count);
    }
    free(threshold);
    free(parent);
    free(new_id);
    free(size);
    return ok ? PS_OK : ps_fail(err, PS_ERR_NOMEM, "persistence: out of memory");
}

ps_status ps_flow_simplify(const ps_graph *g, const double *f, const int *component,
                           int n_components, double fraction, size_t min_size,
                           ps_flow *flow, ps_error *err) {
    if (fraction <= 0 || flow->n_sinks < 2) return PS_OK;
    size_t count = 0;
    ps_saddle *s = ps_flow_border_saddles(g, f, flow, &count);
    ps_status st = s ? ps_flow_simplify_along(g, f, component, n_components, fraction, min_size,
                                              s, &count, flow, err)
                     : ps_fail(err, PS_ERR_NOMEM, "persistence: out of memory");
    free(s);
    return st;
}
