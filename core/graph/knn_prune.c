/*
 * knn_prune.c: points taken out of a built kNN graph without building it
 * again (ps_knn_graph_prune, knn_graph.h).
 *
 * A kept row's own k nearest change only when one of them is removed, or
 * when its k-th nearest ties in single precision with its last candidate
 * (a point beyond the candidates could then step in): those rows are
 * searched again on the build's index with the removed points taken out
 * of it (FLANN skips them), which finds what an index on the kept points
 * alone would.  An edge p ~ q is there when q is among p's k nearest or p
 * among q's, so besides losing the removed columns only the rows of the
 * re-searched points and of the points in their old or new lists can
 * change: those are rebuilt from their candidates (the old row, the new
 * list, the re-searched rows that now list them), the others copied.  The
 * rows are written in place, in order, unless a rebuilt row would grow
 * past the next row's unread entries (then into fresh arrays).
 */
#include "graph/knn_graph.h"
#include "graph/knn_memo.h"

#include "util/control.h"
#include "util/sort_util.h"

#include <stdlib.h>
#include <string.h>

/* A row that gains an entry through a re-searched row's new list. */
typedef struct gain {
    uint32_t row, from;
} gain;

typedef struct prune {
    ps_graph *g;
    ps_knn_memo *memo;
    const double *points;
    size_t n;                 /* #P points before the removal */
    uint32_t *new_of;         /* #P new number, or PS_KNN_GONE */
    size_t kept;
    uint32_t *again;          /* rows searched again, increasing */
    size_t n_again;
    unsigned char *rebuilt;   /* #P 1 for a row rebuilt from its candidates */
    gain *gains;              /* sorted by (row, from) */
    size_t n_gains;
    size_t *side_start;       /* #kept+1 where each rebuilt row starts in side */
    uint32_t *side;           /* the rebuilt rows, old numbering */
    size_t n_side, side_capacity;
    size_t *new_offsets;      /* #kept+1 */
} prune;

static void prune_free(prune *pr) {
    free(pr->new_of), free(pr->again), free(pr->rebuilt), free(pr->gains);
    free(pr->side_start), free(pr->side), free(pr->new_offsets);
}

static int is_gone(const prune *pr, uint32_t p) {
    return pr->new_of[p] == PS_KNN_GONE;
}

static const uint32_t *list_of(const prune *pr, uint32_t p) {
    return pr->memo->knn + (size_t)p * (size_t)pr->memo->k;
}

static int listed(const prune *pr, uint32_t p, uint32_t q) {
    const uint32_t *list = list_of(pr, p);
    for (int t = 0; t < pr->memo->k; t++)
        if (list[t] == q) return 1;
    return 0;
}

/* The removed points leave memo's index; current_of starts as the identity
 * at the first prune. */
static int remove_from_index(prune *pr) {
    ps_knn_memo *mm = pr->memo;
    if (!mm->current_of) {
        mm->current_of = malloc(mm->n_first * sizeof *mm->current_of);
        if (!mm->current_of) return -1;
        for (size_t f = 0; f < mm->n_first; f++) mm->current_of[f] = (uint32_t)f;
    }
    for (size_t f = 0; f < mm->n_first; f++) {
        uint32_t p = mm->current_of[f];
        if (p != PS_KNN_GONE && is_gone(pr, p) &&
            flann_remove_point_double(mm->index, (unsigned)f) != 0)
            return -1;
    }
    return 0;
}

/* Kept rows whose own list lost a point, or whose k-th nearest ties with
 * what lies beyond its candidates. */
static int rows_to_search(prune *pr) {
    size_t n = pr->g->n, count = 0;
    pr->again = malloc((n ? n : 1) * sizeof *pr->again);
    if (!pr->again) return -1;
    for (uint32_t p = 0; p < n; p++) {
        if (is_gone(pr, p)) continue;
        int lost = pr->memo->saturated[p];
        for (int t = 0; !lost && t < pr->memo->k; t++) lost = is_gone(pr, list_of(pr, p)[t]);
        if (lost) pr->again[count++] = p;
    }
    pr->n_again = count;
    return 0;
}

/* Rows whose edges can change beyond the removed columns: the re-searched
 * rows and the kept points in their lists. */
static void mark_rebuilt(prune *pr) {
    for (size_t i = 0; i < pr->n_again; i++) {
        uint32_t r = pr->again[i];
        pr->rebuilt[r] = 1;
        for (int t = 0; t < pr->memo->k; t++)
            if (!is_gone(pr, list_of(pr, r)[t])) pr->rebuilt[list_of(pr, r)[t]] = 1;
    }
}

static int by_row_then_from(const void *x, const void *y) {
    const gain *a = x, *b = y;
    if (a->row != b->row) return a->row < b->row ? -1 : 1;
    return (a->from > b->from) - (a->from < b->from);
}

/* Every (t, r) with t in the new list of a re-searched row r. */
static int collect_gains(prune *pr) {
    size_t k = (size_t)pr->memo->k, most = pr->n_again * k;
    pr->gains = malloc((most ? most : 1) * sizeof *pr->gains);
    if (!pr->gains) return -1;
    for (size_t i = 0; i < pr->n_again; i++)
        for (size_t t = 0; t < k; t++)
            pr->gains[pr->n_gains++] = (gain){list_of(pr, pr->again[i])[t], pr->again[i]};
    qsort(pr->gains, pr->n_gains, sizeof *pr->gains, by_row_then_from);
    return 0;
}

static int side_push(prune *pr, uint32_t q) {
    if (pr->n_side == pr->side_capacity) {
        size_t capacity = pr->side_capacity ? 2 * pr->side_capacity : 1024;
        uint32_t *grown = realloc(pr->side, capacity * sizeof *grown);
        if (!grown) return -1;
        pr->side = grown, pr->side_capacity = capacity;
    }
    pr->side[pr->n_side++] = q;
    return 0;
}

/* First gain of row p. */
static size_t first_gain(const prune *pr, uint32_t p) {
    size_t lo = 0, hi = pr->n_gains;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (pr->gains[mid].row < p) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* Row p from its candidates (kept old entries, its list, its gains):
 * those q with q in p's list or p in q's, sorted, appended to side. */
static int rebuild_row(prune *pr, uint32_t p) {
    const ps_graph *g = pr->g;
    size_t start = pr->n_side;
    int failed = 0;
    for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
        if (!is_gone(pr, g->neighbors[e])) failed |= side_push(pr, g->neighbors[e]);
    for (int t = 0; t < pr->memo->k; t++) failed |= side_push(pr, list_of(pr, p)[t]);
    for (size_t i = first_gain(pr, p); i < pr->n_gains && pr->gains[i].row == p; i++)
        failed |= side_push(pr, pr->gains[i].from);
    if (failed) return -1;
    uint32_t *row = pr->side + start;
    size_t len = pr->n_side - start, kept = 0;
    qsort(row, len, sizeof *row, ps_compare_u32);
    for (size_t i = 0; i < len; i++) {
        int edge = listed(pr, p, row[i]) || listed(pr, row[i], p);
        if ((kept == 0 || row[i] != row[kept - 1]) && edge) row[kept++] = row[i];
    }
    pr->n_side = start + kept;
    return 0;
}

/* new_offsets from each kept row's new length; 1 when every row fits in
 * place (ends no later than the next old row starts). */
static int plan_rows(prune *pr) {
    const ps_graph *g = pr->g;
    int in_place = 1;
    pr->new_offsets[0] = 0;
    for (uint32_t p = 0; p < g->n; p++) {
        if (is_gone(pr, p)) continue;
        size_t np = pr->new_of[p], len = 0;
        if (pr->rebuilt[p]) {
            len = pr->side_start[np + 1] - pr->side_start[np];
        } else {
            for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
                len += !is_gone(pr, g->neighbors[e]);
        }
        pr->new_offsets[np + 1] = pr->new_offsets[np] + len;
        in_place &= pr->new_offsets[np + 1] <= g->offsets[p + 1];
    }
    return in_place;
}

/* Writes the new rows, renumbered, into neighbors / weights (g's own
 * arrays when in place). */
static void write_rows(prune *pr, uint32_t *neighbors, double *weights) {
    const ps_graph *g = pr->g;
    int dim = pr->memo->dim;
    for (uint32_t p = 0; p < g->n; p++) {
        if (is_gone(pr, p)) continue;
        size_t np = pr->new_of[p], out = pr->new_offsets[np];
        if (pr->rebuilt[p]) {
            for (size_t i = pr->side_start[np]; i < pr->side_start[np + 1]; i++) {
                uint32_t q = pr->side[i];
                neighbors[out] = pr->new_of[q];
                weights[out++] = ps_knn_distance(pr->points + (size_t)p * (size_t)dim,
                                                 pr->points + (size_t)q * (size_t)dim, dim);
            }
            continue;
        }
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (is_gone(pr, q)) continue;
            neighbors[out] = pr->new_of[q];
            weights[out++] = g->weights[e];
        }
    }
}

/* g becomes the new graph (in place, or fresh arrays when a row would
 * overrun); -1 when out of memory. */
static int rewrite_graph(prune *pr) {
    ps_graph *g = pr->g;
    int in_place = plan_rows(pr);
    size_t edges = pr->new_offsets[pr->kept];
    uint32_t *neighbors = in_place ? g->neighbors : malloc((edges ? edges : 1) * sizeof *neighbors);
    double *weights = in_place ? g->weights : malloc((edges ? edges : 1) * sizeof *weights);
    if (!neighbors || !weights) {
        if (!in_place) free(neighbors), free(weights);
        return -1;
    }
    write_rows(pr, neighbors, weights);
    if (!in_place) free(g->neighbors), free(g->weights);
    free(g->offsets);
    g->offsets = pr->new_offsets, pr->new_offsets = NULL;
    g->n = pr->kept;
    uint32_t *fewer = realloc(neighbors, (edges ? edges : 1) * sizeof *fewer);
    double *lighter = realloc(weights, (edges ? edges : 1) * sizeof *lighter);
    g->neighbors = fewer ? fewer : neighbors;
    g->weights = lighter ? lighter : weights;
    return 0;
}

/* The memo in the new numbering: lists, flags and current_of. */
static void renumber_memo(prune *pr) {
    ps_knn_memo *mm = pr->memo;
    size_t k = (size_t)mm->k;
    for (uint32_t p = 0; p < pr->n; p++) {
        if (is_gone(pr, p)) continue;
        size_t np = pr->new_of[p];
        for (size_t t = 0; t < k; t++) mm->knn[np * k + t] = pr->new_of[mm->knn[(size_t)p * k + t]];
        mm->saturated[np] = mm->saturated[p];
    }
    for (size_t f = 0; f < mm->n_first; f++)
        if (mm->current_of[f] != PS_KNN_GONE) mm->current_of[f] = pr->new_of[mm->current_of[f]];
}

/* Rebuilt rows into side, in new order. */
static int rebuild_rows(prune *pr) {
    pr->side_start[0] = 0;
    for (uint32_t p = 0; p < pr->g->n; p++) {
        if (is_gone(pr, p)) continue;
        if (pr->rebuilt[p] && rebuild_row(pr, p) != 0) return -1;
        pr->side_start[pr->new_of[p] + 1] = pr->n_side;
    }
    return 0;
}

static size_t number_kept(prune *pr, const uint32_t *keep_for) {
    size_t kept = 0;
    for (size_t p = 0; p < pr->g->n; p++)
        pr->new_of[p] = keep_for[p] == p ? (uint32_t)kept++ : PS_KNN_GONE;
    return kept;
}

static ps_status prune_rows(prune *pr, int threads, const ps_progress_span *span, ps_error *err) {
    size_t n = pr->g->n;
    pr->rebuilt = calloc(n ? n : 1, 1);
    pr->side_start = malloc((pr->kept + 1) * sizeof *pr->side_start);
    pr->new_offsets = malloc((pr->kept + 1) * sizeof *pr->new_offsets);
    if (!pr->rebuilt || !pr->side_start || !pr->new_offsets || remove_from_index(pr) != 0 ||
        rows_to_search(pr) != 0)
        return ps_fail(err, PS_ERR_NOMEM, "knn: out of memory (prune)");
    mark_rebuilt(pr);
    ps_status st = ps_knn_query_rows(pr->memo, pr->points, pr->again, pr->n_again, threads, span,
                                     err);
    if (st != PS_OK) return st;
    mark_rebuilt(pr);
    if (collect_gains(pr) != 0 || rebuild_rows(pr) != 0 || rewrite_graph(pr) != 0)
        return ps_fail(err, PS_ERR_NOMEM, "knn: out of memory (prune)");
    renumber_memo(pr);
    return PS_OK;
}

ps_status ps_knn_graph_prune(ps_graph *g, ps_knn_memo *memo, const double *points,
                             const uint32_t *keep_for, int threads, const ps_progress_span *span,
                             int *pruned, ps_error *err) {
    *pruned = 0;
    if (!memo || !memo->index || !memo->saturated) return PS_OK;
    prune pr = {.g = g, .memo = memo, .points = points, .n = g->n,
                .new_of = malloc((g->n ? g->n : 1) * sizeof *pr.new_of)};
    if (!pr.new_of) return ps_fail(err, PS_ERR_NOMEM, "knn: out of memory (prune)");
    pr.kept = number_kept(&pr, keep_for);
    size_t m = (size_t)memo->k + 1 + PS_KNN_EXTRA;
    ps_status st = PS_OK;
    if ((pr.kept < m ? pr.kept : m) == (size_t)memo->m) {
        st = pr.kept < g->n ? prune_rows(&pr, ps_parallel_threads(threads), span, err) : PS_OK;
        *pruned = st == PS_OK;
    }
    prune_free(&pr);
    if (*pruned) ps_control_progress(span->ctl, span->phase, span->hi);
    return st;
}
