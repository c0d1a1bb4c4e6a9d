/*
 * graph.c: a CSR graph's release and its connected components (graph.h).
 */
#include "graph/graph.h"

#include "util/union_find.h"

#include <stdlib.h>
#include <string.h>

void ps_graph_free(ps_graph *g) {
    if (!g) return;
    free(g->offsets), free(g->neighbors), free(g->weights);
    memset(g, 0, sizeof *g);
}

/* Union-find with parents always pointing to lower ids. */
int ps_graph_components(const ps_graph *g, int *component) {
    int n = (int)g->n;
    for (int p = 0; p < n; p++) component[p] = p;
    for (int p = 0; p < n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            int a = ps_union_find_root(component, p);
            int b = ps_union_find_root(component, (int)g->neighbors[e]);
            if (a < b) component[b] = a;
            if (b < a) component[a] = b;
        }
    /* Ascending p: a root takes the next label; any other vertex's parent is
     * lower, so it already holds its root's label. */
    int count = 0;
    for (int p = 0; p < n; p++) component[p] = component[p] == p ? count++ : component[component[p]];
    return count;
}
