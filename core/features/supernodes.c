/*
 * supernodes.c: supernodes from the simplified ascent flow, and with
 * use_minima the split of each basin at its highest saddle, the points
 * below going to the merge tree's parts or else to the simplified descent
 * flow's minima (supernodes.h).
 */
#include "features/supernodes.h"

#include "features/flow.h"
#include "features/merge_tree.h"
#include "features/persistence.h"
#include "util/control.h"
#include "util/parallel.h"
#include "util/union_find.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Shares of the span reached after the two flows, the merge tree's parts
 * and the supernodes' assembly. */
#define FLOWS_DONE 0.5
#define PARTS_DONE 0.75
#define COMBINED 0.9

static void report(const ps_progress_span *span, double share) {
    if (span) ps_control_progress(span->ctl, span->phase, ps_progress_span_at(span, share));
}

/* The simplification of a flow of f (in->f or its negative) on in's graph
 * and components, at the given persistence. */
static ps_persistence_input persistence_input(const ps_supernodes_input *in, const double *f,
                                              double persistence) {
    return (ps_persistence_input){.graph = in->graph, .f = f, .component = in->component,
                                  .n_components = in->n_components, .fraction = persistence,
                                  .min_size = PS_PERSISTENCE_MIN_BASIN};
}

/* The descent flow, simplified. */
static ps_status simplified_descent(const ps_supernodes_input *in, double persistence,
                                    ps_flow *flow, ps_error *err) {
    const ps_graph *g = in->graph;
    double *minus_f = malloc((g->n ? g->n : 1) * sizeof *minus_f);
    if (!minus_f) return ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
    for (size_t p = 0; p < g->n; p++) minus_f[p] = -in->f[p];
    ps_persistence_input simplify = persistence_input(in, minus_f, persistence);
    ps_status st = ps_flow_build(g, minus_f, +1, flow, err);
    if (st == PS_OK) st = ps_persistence_simplify(&simplify, flow, err);
    free(minus_f);
    return st;
}

/* The ascent flow, simplified, and with minima its border saddles (*s,
 * #*count, the caller frees). */
static ps_status simplified_ascent(const ps_supernodes_input *in, double persistence,
                                   ps_flow *flow, ps_saddle **s, size_t *count, ps_error *err) {
    ps_persistence_input simplify = persistence_input(in, in->f, persistence);
    ps_status st = ps_flow_build(in->graph, in->f, +1, flow, err);
    if (st != PS_OK) return st;
    if (!in->use_minima) return ps_persistence_simplify(&simplify, flow, err);
    *s = ps_flow_border_saddles(in->graph, in->f, flow, count);
    if (!*s) return ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
    return ps_persistence_simplify_along(&simplify, *s, count, flow, err);
}

/* level #S out: each basin's highest saddle, min(f(p), f(q)) over edges to
 * other basins (s, #count: up's border saddles); -INFINITY-like (-1e300)
 * for a basin that meets none.  across, if not NULL, #S out: the basin on
 * the other side (-1 if none; the lowest of several at the same height). */
static void highest_saddles(const ps_saddle *s, size_t count, const ps_flow *up, double *level,
                            int *across) {
    for (int b = 0; b < up->n_sinks; b++) {
        level[b] = -1e300;
        if (across) across[b] = -1;
    }
    for (size_t i = 0; i < count; i++)
        for (int side = 0; side < 2; side++) {
            int a = up->sink_of[side ? s[i].q : s[i].p], b = up->sink_of[side ? s[i].p : s[i].q];
            double h = s[i].height;
            if (h > level[a] || (h == level[a] && across && b < across[a])) {
                level[a] = h;
                if (across) across[a] = b;
            }
        }
}

/* One round: every basin with fewer than min_size points above its highest
 * saddle joins the basin across that saddle; up's border saddles (#*count)
 * follow.  Returns how many joined. */
static int merge_round(const ps_graph *g, const double *f, ps_flow *up, size_t min_size,
                       ps_saddle *saddles, size_t *count, double *level, int *across, int *parent,
                       int *scratch) {
    int m = up->n_sinks, merged = 0;
    highest_saddles(saddles, *count, up, level, across);
    for (int s = 0; s < m; s++) parent[s] = s, scratch[s] = 0;
    for (size_t p = 0; p < g->n; p++) scratch[up->sink_of[p]] += f[p] >= level[up->sink_of[p]];
    for (int s = 0; s < m; s++) {
        if ((size_t)scratch[s] >= min_size || across[s] < 0) continue;
        int a = ps_union_find_root(parent, s), b = ps_union_find_root(parent, across[s]);
        if (a != b) parent[a] = b, merged++;
    }
    if (merged) {
        ps_persistence_merge(up, parent, scratch, g->n);
        ps_saddles_keep_borders(up, saddles, count);
    }
    return merged;
}

/* A basin whose part above its highest saddle is a handful of points (a
 * bump beside a crease) would set its neighbour's saddle level, and so cut
 * a limb too high: such basins join their neighbour, until none is left. */
static ps_status merge_shallow_tops(const ps_graph *g, const double *f, ps_flow *up,
                                    size_t min_size, ps_saddle *saddles, size_t *count,
                                    ps_error *err) {
    int m = up->n_sinks;
    double *level = malloc((size_t)(m ? m : 1) * sizeof *level);
    int *across = malloc((size_t)(m ? m : 1) * sizeof *across);
    int *parent = malloc((size_t)(m ? m : 1) * sizeof *parent);
    int *scratch = malloc((size_t)(m ? m : 1) * sizeof *scratch);
    ps_status st = level && across && parent && scratch
                       ? PS_OK
                       : ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
    while (st == PS_OK && up->n_sinks > 1 &&
           merge_round(g, f, up, min_size, saddles, count, level, across, parent, scratch) > 0) {
    }
    free(level), free(across), free(parent), free(scratch);
    return st;
}

static ps_status allocate(ps_supernodes *out, size_t n, int m, ps_error *err) {
    out->m = m;
    out->sinks = malloc((size_t)(m ? m : 1) * sizeof *out->sinks);
    out->is_minimum = calloc((size_t)(m ? m : 1), sizeof *out->is_minimum);
    out->sizes = calloc((size_t)(m ? m : 1), sizeof *out->sizes);
    out->supernode_of = malloc((n ? n : 1) * sizeof *out->supernode_of);
    if (out->sinks && out->is_minimum && out->sizes && out->supernode_of) return PS_OK;
    ps_supernodes_free(out);
    return ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
}

/* Drops empty supernodes (ids stay in order) and sets each one's
 * representative: its highest point for a maximum, lowest for a minimum. */
static int finish(ps_supernodes *out, const double *f, size_t n) {
    int *new_id = malloc((size_t)(out->m ? out->m : 1) * sizeof *new_id);
    int kept = 0;
    if (!new_id) return -1;
    for (int s = 0; s < out->m; s++) {
        new_id[s] = out->sizes[s] ? kept : -1;
        if (out->sizes[s]) {
            out->sizes[kept] = out->sizes[s];
            out->is_minimum[kept] = out->is_minimum[s];
            out->sinks[kept++] = UINT32_MAX;
        }
    }
    out->m = kept;
    for (size_t p = 0; p < n; p++) {
        int s = out->supernode_of[p] = new_id[out->supernode_of[p]];
        uint32_t r = out->sinks[s];
        if (r == UINT32_MAX || (out->is_minimum[s] ? f[p] < f[r] : f[p] > f[r]))
            out->sinks[s] = (uint32_t)p;
    }
    free(new_id);
    return 0;
}

/* Points of supernodes under min_size join the neighbouring supernode
 * (nearest kNN neighbour first) until none is left that can: a basin's part
 * above its saddle can be a handful of points across a crease. */
static void absorb_tiny(const ps_graph *g, ps_supernodes *out, size_t min_size) {
    for (int changed = 1; changed;) {
        changed = 0;
        for (size_t p = 0; p < g->n; p++) {
            int s = out->supernode_of[p], best = -1;
            double best_w = 0;
            if (out->sizes[s] >= min_size) continue;
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
                int t = out->supernode_of[g->neighbors[e]];
                if (out->sizes[t] >= min_size && (best < 0 || g->weights[e] < best_w))
                    best = t, best_w = g->weights[e];
            }
            if (best < 0) continue;
            out->supernode_of[p] = best;
            out->sizes[s]--, out->sizes[best]++;
            changed = 1;
        }
    }
}

/* The two flows of build_once, one per item of a parallel loop: the
 * ascent flow with its shallow tops merged and, with minima, its border
 * saddles (item 0) and, with minima, the descent flow (item 1).  Each item
 * has its own status and error. */
typedef struct flows_task {
    const ps_supernodes_input *in;
    double persistence; /* in->persistence, or as raised */
    ps_flow flow[2];    /* up, down */
    ps_saddle *saddles; /* #n_saddles up's border saddles (with minima) */
    size_t n_saddles;
    ps_status status[2];
    ps_error error[2];
} flows_task;

static void flow_items(void *context, size_t begin, size_t end, int worker) {
    (void)worker;
    flows_task *t = context;
    const ps_supernodes_input *in = t->in;
    for (size_t i = begin; i < end; i++) {
        ps_error *err = &t->error[i];
        ps_status st;
        if (i == 1) {
            st = simplified_descent(in, t->persistence, &t->flow[1], err);
        } else {
            st = simplified_ascent(in, t->persistence, &t->flow[0], &t->saddles, &t->n_saddles,
                                   err);
            if (st == PS_OK && in->use_minima && t->persistence > 0)
                st = merge_shallow_tops(in->graph, in->f, &t->flow[0], PS_PERSISTENCE_MIN_BASIN,
                                        t->saddles, &t->n_saddles, err);
        }
        t->status[i] = st;
    }
}

/* Both flows, side by side (one alone runs inline); the first failure is
 * copied to err. */
static ps_status both_flows(flows_task *t, ps_error *err) {
    int count = t->in->use_minima ? 2 : 1;
    ps_parallel_for(ps_parallel_threads(t->in->threads), (size_t)count, 1, flow_items, t);
    for (int i = 0; i < count; i++)
        if (t->status[i] != PS_OK) {
            if (err) *err = t->error[i];
            return t->status[i];
        }
    return PS_OK;
}

/* Supernodes from t's flows: the basins (above their highest saddles,
 * with use_minima), then the merge tree's parts, then the minima.
 * part_of #P: -1 or a part in [0, n_parts); supernodes under min_size
 * points are absorbed by a neighbour (0: none). */
static ps_status combine(const flows_task *t, const int *part_of, int n_parts, size_t min_size,
                         ps_supernodes *out, ps_error *err) {
    const ps_graph *g = t->in->graph;
    const double *f = t->in->f;
    const ps_flow *up = &t->flow[0], *down = t->in->use_minima ? &t->flow[1] : NULL;
    int n_up = up->n_sinks + n_parts, n_down = down ? down->n_sinks : 0;
    ps_status st = allocate(out, g->n, n_up + n_down, err);
    double *level = down ? malloc((size_t)up->n_sinks * sizeof *level) : NULL;
    if (st != PS_OK || (down && !level)) {
        free(level);
        if (st == PS_OK) ps_supernodes_free(out);
        return ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
    }
    if (down) highest_saddles(t->saddles, t->n_saddles, up, level, NULL);
    for (int s = 0; s < n_down; s++) out->is_minimum[n_up + s] = 1;
    for (size_t p = 0; p < g->n; p++) {
        int a = up->sink_of[p];
        int s = down && f[p] < level[a] ? n_up + down->sink_of[p] : a;
        if (part_of && part_of[p] >= 0) s = up->n_sinks + part_of[p];
        out->supernode_of[p] = s;
        out->sizes[s]++;
    }
    free(level);
    if (min_size) absorb_tiny(g, out, min_size);
    if (finish(out, f, g->n) == 0) return PS_OK;
    ps_supernodes_free(out);
    return ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
}

/* With minima, the merge tree's parts of t's ascent flow: part_of #P out,
 * or NULL when its allocation failed (PS_ERR_NOMEM); *n_parts out. */
static ps_status merge_tree_parts(const flows_task *t, int *part_of, int *n_parts,
                                  ps_error *err) {
    const ps_supernodes_input *in = t->in;
    ps_merge_tree_input parts = {.graph = in->graph, .f = in->f, .component = in->component,
                                 .n_components = in->n_components,
                                 .persistence = t->persistence, .up = &t->flow[0],
                                 .saddles = t->saddles, .n_saddles = t->n_saddles};
    return part_of ? ps_merge_tree_parts(&parts, part_of, n_parts, err)
                   : ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
}

static ps_status build_once(const ps_supernodes_input *in, double persistence,
                            const ps_progress_span *span, ps_supernodes *out, ps_error *err) {
    const ps_graph *g = in->graph;
    int use_minima = in->use_minima;
    memset(out, 0, sizeof *out);
    flows_task t = {.in = in, .persistence = persistence};
    ps_flow *up = &t.flow[0], *down = &t.flow[1];
    ps_status st = both_flows(&t, err);
    report(span, FLOWS_DONE);
    int *part_of = st == PS_OK && use_minima ? malloc(g->n * sizeof *part_of) : NULL;
    int n_parts = 0;
    if (st == PS_OK && use_minima) st = merge_tree_parts(&t, part_of, &n_parts, err);
    report(span, PARTS_DONE);
    size_t min_size = persistence > 0 ? PS_PERSISTENCE_MIN_BASIN : 0;
    if (st == PS_OK)
        st = combine(&t, part_of, n_parts, min_size, out, err);
    report(span, COMBINED);
    free(part_of);
    free(t.saddles);
    ps_flow_free(up);
    ps_flow_free(down);
    return st;
}

ps_status ps_supernodes_build(const ps_supernodes_input *in, ps_supernodes *out,
                              double *persistence_used, ps_error *err) {
    return ps_supernodes_build_tracked(in, NULL, out, persistence_used, err);
}

ps_status ps_supernodes_build_tracked(const ps_supernodes_input *in,
                                      const ps_progress_span *span, ps_supernodes *out,
                                      double *persistence_used, ps_error *err) {
    double persistence = in->persistence;
    for (int first = 1;; first = 0) {
        *persistence_used = persistence;
        ps_status st = build_once(in, persistence, first ? span : NULL, out, err);
        report(span, 1.0);
        if (st != PS_OK || out->m <= PS_MAX_SUPERNODES || persistence >= 1) return st;
        ps_supernodes_free(out);
        persistence = persistence > 0 ? fmin(1.0, persistence * 2) : 0.01;
    }
}

void ps_supernodes_free(ps_supernodes *s) {
    free(s->sinks);
    free(s->is_minimum);
    free(s->sizes);
    free(s->supernode_of);
    memset(s, 0, sizeof *s);
}

ps_status ps_supernodes_relabel(ps_supernodes *sn, const int *label, int m, const double *f,
                                size_t n, ps_error *err) {
    uint32_t *sinks = malloc((size_t)(m > 0 ? m : 1) * sizeof *sinks);
    int *is_min = malloc((size_t)(m > 0 ? m : 1) * sizeof *is_min);
    size_t *sizes = calloc((size_t)(m > 0 ? m : 1), sizeof *sizes);
    if (!sinks || !is_min || !sizes) {
        free(sinks), free(is_min), free(sizes);
        return ps_fail(err, PS_ERR_NOMEM, "supernodes: out of memory");
    }
    for (int s = 0; s < m; s++) sinks[s] = UINT32_MAX;
    for (size_t p = 0; p < n; p++) {
        int s = label[p];
        is_min[s] = sn->is_minimum[sn->supernode_of[p]];
        sizes[s]++;
        uint32_t r = sinks[s];
        if (r == UINT32_MAX || (is_min[s] ? f[p] < f[r] : f[p] > f[r])) sinks[s] = (uint32_t)p;
        sn->supernode_of[p] = s;
    }
    free(sn->sinks), free(sn->is_minimum), free(sn->sizes);
    sn->m = m, sn->sinks = sinks, sn->is_minimum = is_min, sn->sizes = sizes;
    return PS_OK;
}
