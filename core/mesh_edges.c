/*
 * mesh_edges.c: the face edges between components of a kNN graph, merged
 * into its CSR rows (mesh_edges.h).
 */
#include "mesh_edges.h"

#include "knn_memo.h"
#include "sort_util.h"

#include <stdlib.h>
#include <string.h>

/* Face edge `e` (0..2) of triangle t as graph vertices; 0 when it is no
 * bridge (both ends in one component, or one distinct point). */
static int bridge_of(const ps_mesh_bridge_input *in, size_t t, int e, uint32_t *a, uint32_t *b) {
    *a = in->unique_of[in->faces[3 * t + (size_t)e]];
    *b = in->unique_of[in->faces[3 * t + (size_t)(e + 1) % 3]];
    return in->component[*a] != in->component[*b];
}

/* gain[p]: the directed bridges leaving p (duplicates included). */
static size_t count_bridges(const ps_mesh_bridge_input *in, size_t *gain) {
    size_t total = 0;
    uint32_t a, b;
    for (size_t t = 0; t < in->n_faces; t++)
        for (int e = 0; e < 3; e++)
            if (bridge_of(in, t, e, &a, &b)) gain[a]++, gain[b]++, total += 2;
    return total;
}

/* Copies g's rows into `neighbors` at `offsets` (each row with room for
 * its gain) and appends the bridges after them; fill: #U scratch. */
static void gather_rows(const ps_graph *g, const ps_mesh_bridge_input *in, const size_t *offsets,
                        uint32_t *neighbors, size_t *fill) {
    for (size_t p = 0; p < g->n; p++) {
        size_t len = g->offsets[p + 1] - g->offsets[p];
        memcpy(neighbors + offsets[p], g->neighbors + g->offsets[p], len * sizeof *neighbors);
        fill[p] = offsets[p] + len;
    }
    uint32_t a, b;
    for (size_t t = 0; t < in->n_faces; t++)
        for (int e = 0; e < 3; e++)
            if (bridge_of(in, t, e, &a, &b)) neighbors[fill[a]++] = b, neighbors[fill[b]++] = a;
}

/* Packs the rows to the front of `neighbors` (sorting and deduplicating
 * the rows that gained) and writes their weights: g's for rows that did
 * not gain, lengths for those that did.  Returns the packed edge count. */
static size_t pack_rows(const ps_graph *g, const ps_mesh_bridge_input *in, const size_t *gain,
                        size_t *offsets, uint32_t *neighbors, double *weights) {
    size_t out = 0;
    for (size_t p = 0; p < g->n; p++) {
        uint32_t *row = neighbors + offsets[p];
        size_t len = offsets[p + 1] - offsets[p], kept = 0;
        offsets[p] = out;
        if (!gain[p]) {
            memmove(neighbors + out, row, len * sizeof *neighbors);
            memcpy(weights + out, g->weights + g->offsets[p], len * sizeof *weights);
            out += len;
            continue;
        }
        qsort(row, len, sizeof *row, ps_compare_u32);
        for (size_t i = 0; i < len; i++)
            if (kept == 0 || row[i] != neighbors[out + kept - 1]) neighbors[out + kept++] = row[i];
        for (size_t e = out; e < out + kept; e++)
            weights[e] = ps_knn_distance(in->points + p * (size_t)in->dim,
                                         in->points + (size_t)neighbors[e] * (size_t)in->dim,
                                         in->dim);
        out += kept;
    }
    offsets[g->n] = out;
    return out;
}

ps_status ps_mesh_bridges_add(ps_graph *g, const ps_mesh_bridge_input *in, size_t *added,
                              ps_error *err) {
    size_t n = g->n;
    *added = 0;
    size_t *gain = calloc(n, sizeof *gain), *fill = malloc(n * sizeof *fill);
    size_t *offsets = malloc((n + 1) * sizeof *offsets);
    uint32_t *neighbors = NULL;
    double *weights = NULL;
    if (!gain || !fill || !offsets) goto nomem;
    size_t total = count_bridges(in, gain);
    if (total == 0) goto done;
    offsets[0] = 0;
    for (size_t p = 0; p < n; p++)
        offsets[p + 1] = offsets[p] + (g->offsets[p + 1] - g->offsets[p]) + gain[p];
    neighbors = malloc(offsets[n] * sizeof *neighbors);
    weights = malloc(offsets[n] * sizeof *weights);
    if (!neighbors || !weights) goto nomem;
    gather_rows(g, in, offsets, neighbors, fill);
    *added = (pack_rows(g, in, gain, offsets, neighbors, weights) - g->offsets[n]) / 2;
    free(g->offsets), free(g->neighbors), free(g->weights);
    g->offsets = offsets, g->neighbors = neighbors, g->weights = weights;
    offsets = NULL;
done:
    free(gain), free(fill), free(offsets);
    return PS_OK;
nomem:
    free(gain), free(fill), free(offsets), free(neighbors), free(weights);
    return ps_fail(err, PS_ERR_NOMEM, "out of memory (mesh edges)");
}
