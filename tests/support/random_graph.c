/*
 * random_graph.c: random symmetric graphs (random_graph.h), built dense
 * and then packed into CSR rows sorted by neighbour.
 */
#include "random_graph.h"
#include "random_bits.h"

#include <stdlib.h>

unsigned test_rng_below(test_rng *r, unsigned bound) {
    return (unsigned)((ps_random_bits(&r->s) >> 20) % bound);
}

double test_rng_unit(test_rng *r) {
    return (double)(ps_random_bits(&r->s) >> 11) / 9007199254740992.0;
}

static double random_length(test_rng *r, double lo, double hi, int whole) {
    if (whole) return lo + test_rng_below(r, (unsigned)(hi - lo) + 1);
    return lo + (hi - lo) * test_rng_unit(r);
}

void test_random_graph(size_t n, int degree, double lo, double hi, int whole, size_t isolated,
                       unsigned long long seed, ps_graph *g) {
    test_rng r = {seed};
    size_t joined = n - isolated;
    double *w = calloc(n * n, sizeof *w);
    for (size_t e = 0; w && joined > 1 && e < joined * (size_t)degree / 2; e++) {
        size_t a = test_rng_below(&r, (unsigned)joined), b = test_rng_below(&r, (unsigned)joined);
        if (a != b) w[a * n + b] = w[b * n + a] = random_length(&r, lo, hi, whole);
    }
    g->n = n;
    g->offsets = malloc((n + 1) * sizeof *g->offsets);
    size_t most = n > 0 ? n * n : 1;
    g->neighbors = malloc(most * sizeof *g->neighbors);
    g->weights = malloc(most * sizeof *g->weights);
    size_t m = 0;
    for (size_t p = 0; w && p < n; p++) {
        g->offsets[p] = m;
        for (size_t q = 0; q < n; q++)
            if (w[p * n + q] > 0) g->neighbors[m] = (uint32_t)q, g->weights[m++] = w[p * n + q];
    }
    g->offsets[n] = m;
    free(w);
}
