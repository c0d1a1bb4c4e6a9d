/*
 * f2_split.c: splitting supernodes along their f2 maxima (f2_split.h).
 * One filtered graph (the kNN edges inside supernodes), one multi-source
 * Dijkstra for f2, one flow on it, one persistence pass per piece.
 */
#include "features/f2_split.h"

#include "features/flow.h"
#include "features/persistence.h"
#include "graph/dijkstra.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The kNN graph without the edges that leave a supernode. */
static ps_status inner_graph(const ps_graph *g, const int *supernode_of, ps_graph *h,
                             ps_error *err) {
    size_t kept = 0;
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            kept += supernode_of[g->neighbors[e]] == supernode_of[p];
    h->n = g->n;
    h->offsets = malloc((g->n + 1) * sizeof *h->offsets);
    h->neighbors = malloc((kept ? kept : 1) * sizeof *h->neighbors);
    h->weights = malloc((kept ? kept : 1) * sizeof *h->weights);
    if (!h->offsets || !h->neighbors || !h->weights)
        return ps_fail(err, PS_ERR_NOMEM, "f2: out of memory");
    size_t k = 0;
    for (size_t p = 0; p < g->n; p++) {
        h->offsets[p] = k;
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++)
            if (supernode_of[g->neighbors[e]] == supernode_of[p])
                h->neighbors[k] = g->neighbors[e], h->weights[k++] = g->weights[e];
    }
    h->offsets[g->n] = k;
    return PS_OK;
}

/* Sources, one per piece (#n_pieces): the piece's representative when it
 * holds one, else its lowest vertex. */
static uint32_t *f2_sources(const ps_supernodes *sn, const int *piece, int n_pieces,
                            size_t n) {
    uint32_t *src = malloc((size_t)(n_pieces ? n_pieces : 1) * sizeof *src);
    if (!src) return NULL;
    for (int c = 0; c < n_pieces; c++) src[c] = UINT32_MAX;
    for (int s = 0; s < sn->m; s++) src[piece[sn->sinks[s]]] = sn->sinks[s];
    for (size_t p = 0; p < n; p++)
        if (src[piece[p]] == UINT32_MAX) src[piece[p]] = (uint32_t)p;
    return src;
}

ps_status ps_f2_split(const ps_graph *g, const double *f, double persistence, ps_supernodes *sn,
                      ps_error *err) {
    ps_graph h = {0};
    ps_flow basins = {0};
    int *piece = malloc(g->n * sizeof *piece);
    double *f2 = malloc(g->n * sizeof *f2);
    ps_dijkstra *w = ps_dijkstra_new(g->n);
    uint32_t *src = NULL;
    ps_status st = piece && f2 && w ? inner_graph(g, sn->supernode_of, &h, err)
                                    : ps_fail(err, PS_ERR_NOMEM, "f2: out of memory");
    int n_pieces = st == PS_OK ? ps_graph_components(&h, piece) : 0;
    if (st == PS_OK && !(src = f2_sources(sn, piece, n_pieces, g->n)))
        st = ps_fail(err, PS_ERR_NOMEM, "f2: out of memory");
    if (st == PS_OK) {
        ps_dijkstra_run(w, &h, src, (size_t)n_pieces, f2, NULL);
        st = ps_flow_build(&h, f2, +1, &basins, err);
    }
    ps_persistence_input basins_in = {.graph = &h, .f = f2, .component = piece,
                                      .n_components = n_pieces, .fraction = persistence,
                                      .min_size = PS_PERSISTENCE_MIN_BASIN};
    if (st == PS_OK) st = ps_persistence_simplify(&basins_in, &basins, err);
    if (st == PS_OK)
        st = ps_supernodes_relabel(sn, basins.sink_of, basins.n_sinks, f, g->n, err);
    ps_flow_free(&basins);
    ps_graph_free(&h);
    ps_dijkstra_free(w);
    free(src), free(piece), free(f2);
    return st;
}
