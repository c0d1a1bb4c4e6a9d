/*
 * patch_normal.c: a point's normal fitted on the patch of agreeing
 * normals around it (patch_normal.h): a breadth-first walk of
 * PS_PATCH_NORMAL_RINGS rings, then one PCA plane.
 */
#include "features/patch_normal.h"

#include "util/sym3.h"
#include "util/vec3.h"

#include <math.h>
#include <stdlib.h>

typedef struct patch_walk {
    uint32_t *queue; /* #P the patch's points, p first */
    uint32_t *seen;  /* #P the walk that last reached each point */
    uint32_t walk;
} patch_walk;

/* The points within PS_PATCH_NORMAL_RINGS rings of p into w->queue; their
 * count. */
static size_t gather_rings(const ps_graph *g, uint32_t p, patch_walk *w) {
    size_t head = 0, tail = 0;
    w->walk++;
    w->queue[tail++] = p, w->seen[p] = w->walk;
    for (int ring = 0; ring < PS_PATCH_NORMAL_RINGS; ring++)
        for (size_t end = tail; head < end; head++) {
            uint32_t v = w->queue[head];
            for (size_t e = g->offsets[v]; e < g->offsets[v + 1]; e++) {
                uint32_t q = g->neighbors[e];
                if (w->seen[q] != w->walk) w->seen[q] = w->walk, w->queue[tail++] = q;
            }
        }
    return tail;
}

/* The patch points whose normals lie within the agreement of the first's
 * (p's, which agrees with itself), moved to the front of patch; their
 * count. */
static size_t keep_agreeing(const double *normals, uint32_t *patch, size_t count) {
    const double *own = normals + 3 * (size_t)patch[0];
    double agree = cos(PS_PATCH_NORMAL_AGREE * 3.14159265358979323846 / 180);
    size_t kept = 0;
    for (size_t i = 0; i < count; i++)
        if (ps_dot3(normals + 3 * (size_t)patch[i], own) >= agree) patch[kept++] = patch[i];
    return kept;
}

/* n out: the PCA plane's normal of the count patch points whose normals
 * lie within the agreement of p's (patch[0]), signed as p's; p's own when
 * under 4. */
static void fit_patch(const double *points, const double *normals, uint32_t *patch,
                      size_t count, double n[3]) {
    const double *own = normals + 3 * (size_t)patch[0];
    size_t used = keep_agreeing(normals, patch, count);
    for (int a = 0; a < 3; a++) n[a] = own[a];
    if (used < 4) return;
    double mean[3] = {0, 0, 0}, cov[3][3] = {{0}};
    for (size_t i = 0; i < used; i++)
        for (int a = 0; a < 3; a++) mean[a] += points[3 * (size_t)patch[i] + a];
    for (int a = 0; a < 3; a++) mean[a] /= (double)used;
    for (size_t i = 0; i < used; i++) {
        const double *x = points + 3 * (size_t)patch[i];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) cov[a][b] += (x[a] - mean[a]) * (x[b] - mean[b]);
    }
    double v[3];
    ps_sym3_smallest(cov, v);
    double sign = ps_dot3(v, own) < 0 ? -1 : 1;
    for (int a = 0; a < 3; a++) n[a] = sign * v[a];
}

ps_status ps_patch_normals(const ps_graph *g, const double *points, const double *normals,
                           const uint32_t *ids, size_t m, double *out, ps_error *err) {
    patch_walk w = {.queue = malloc(g->n * sizeof *w.queue),
                    .seen = calloc(g->n, sizeof *w.seen)};
    ps_status st = PS_OK;
    if (!w.queue || !w.seen)
        st = ps_fail(err, PS_ERR_NOMEM, "out of memory (patch normals)");
    for (size_t i = 0; st == PS_OK && i < m; i++) {
        size_t count = gather_rings(g, ids[i], &w);
        fit_patch(points, normals, w.queue, count, out + 3 * (size_t)ids[i]);
    }
    free(w.queue);
    free(w.seen);
    return st;
}
