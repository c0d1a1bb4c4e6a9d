/*
 * profile_split.c: supernodes cut where their level-set profile jumps
 * (profile_split.h).  The members of each supernode (a counting sort),
 * then per maximum's
 * supernode one pass over its points into bands of f and at most
 * PS_PROFILE_TRIES breadth-first fills inside it; then the supernodes are
 * rebuilt.
 */
#include "features/profile_split.h"

#include "features/persistence.h"
#include "util/sort_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef struct profile_work {
    const ps_graph *g;
    const double *points;
    const double *f;
    const ps_supernodes *sn;
    const double *spacing; /* #P mean kNN edge length */
    size_t *start;     /* #S+1: supernode s's points are members[start[s] .. start[s+1]) */
    uint32_t *members; /* #P by supernode, each in index order */
    double *scratch;   /* #P */
    int *label;        /* #P new supernode of each point */
    uint32_t *queue;   /* #P */
    double *band;      /* #band_cap perimeters of the current supernode's bands */
    size_t *above;     /* #band_cap+1: points in the bands before each band */
    size_t band_cap;
    int n_new;
} profile_work;

static double median(const double *x, size_t n, double *scratch) {
    memcpy(scratch, x, n * sizeof *scratch);
    return ps_select_kth(scratch, n, n / 2);
}

/* The points of supernode s at f >= t connected to top through such points
 * get label id (listed in queue); their count. */
static size_t fill_above(profile_work *w, uint32_t top, int s, double t, int id) {
    const ps_graph *g = w->g;
    size_t head = 0, tail = 0;
    w->label[top] = id;
    w->queue[tail++] = top;
    while (head < tail) {
        uint32_t p = w->queue[head++];
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (w->label[q] == id || w->sn->supernode_of[q] != s || w->f[q] < t) continue;
            w->label[q] = id;
            w->queue[tail++] = q;
        }
    }
    return tail;
}

/* Puts back label s on the count points of the last fill. */
static void undo_fill(profile_work *w, size_t count, int s) {
    for (size_t i = 0; i < count; i++) w->label[w->queue[i]] = s;
}

/* The perimeters of the nb bands of width h below top of the count points
 * in list, and the points before each band.  0 when out of memory. */
static int band_perimeters(profile_work *w, const uint32_t *list, size_t count, double top,
                           double h, size_t nb) {
    if (nb > w->band_cap) {
        double *band = realloc(w->band, nb * sizeof *band);
        if (band) w->band = band;
        size_t *above = realloc(w->above, (nb + 1) * sizeof *above);
        if (above) w->above = above;
        if (!band || !above) return 0;
        w->band_cap = nb;
    }
    memset(w->band, 0, nb * sizeof *w->band);
    memset(w->above, 0, (nb + 1) * sizeof *w->above);
    for (size_t i = 0; i < count; i++) {
        size_t j = (size_t)((top - w->f[list[i]]) / h);
        if (j >= nb) j = nb - 1;
        double a = w->spacing[list[i]];
        w->band[j] += a * a / h;
        w->above[j + 1]++;
    }
    for (size_t j = 0; j < nb; j++) w->above[j + 1] += w->above[j];
    return 1;
}

/* 1 when band j starts a jump: it and the PS_PROFILE_PERSIST bands below
 * are PS_PROFILE_JUMP times wider than the bands above it (the tip's cap
 * left out), at a depth at least their width. */
static int jump_at(profile_work *w, size_t j, double h) {
    const double *P = w->band;
    double radius = median(P, j, w->scratch) / (2.0 * PI);
    size_t cap = (size_t)(radius / h);
    if (cap >= j || j - cap < PS_PROFILE_MIN_BANDS) return 0;
    double reference = median(P + cap, j - cap, w->scratch);
    if (!(reference > 0.0) || (double)j * h < reference / PI) return 0;
    for (size_t below = 0; below <= PS_PROFILE_PERSIST; below++)
        if (!(P[j + below] > PS_PROFILE_JUMP * reference)) return 0;
    return 1;
}

/* The highest point of list #count (the lowest index among equals). */
static uint32_t highest(const double *f, const uint32_t *list, size_t count) {
    uint32_t top = list[0];
    for (size_t i = 1; i < count; i++)
        if (f[list[i]] > f[top]) top = list[i];
    return top;
}

/* Cuts supernode s at its first jump whose pieces are large enough.  0
 * when out of memory. */
static int split_one(profile_work *w, int s) {
    const uint32_t *list = w->members + w->start[s];
    size_t count = w->start[s + 1] - w->start[s];
    size_t need = (size_t)ceil(PS_PROFILE_MIN_SHARE * (double)count);
    if (need < PS_PERSISTENCE_MIN_BASIN) need = PS_PERSISTENCE_MIN_BASIN;
    if (count < 2 * need) return 1;
    double low = INFINITY;
    for (size_t i = 0; i < count; i++) {
        w->scratch[i] = w->spacing[list[i]];
        if (w->f[list[i]] < low) low = w->f[list[i]];
    }
    double h = PS_PROFILE_BAND_SPACINGS * ps_select_kth(w->scratch, count, count / 2);
    uint32_t top = highest(w->f, list, count);
    double range = w->f[top] - low;
    if (!(h > 0.0) || !(range > 0.0)) return 1;
    size_t nb = (size_t)(range / h) + 1;
    /* More bands than points (a few points strung far apart): no profile to
     * read, and the bands' medians work in the per-point scratch. */
    if (nb < PS_PROFILE_MIN_BANDS + 2 || nb > count) return 1;
    if (!band_perimeters(w, list, count, w->f[top], h, nb)) return 0;
    for (size_t j = 1, tries = 0; j + PS_PROFILE_PERSIST < nb && tries < PS_PROFILE_TRIES; j++) {
        size_t above = w->above[j];
        if (!jump_at(w, j, h) || above < need || count - above < need) continue;
        tries++;
        int id = w->sn->m + w->n_new;
        size_t got = fill_above(w, top, s, w->f[top] - (double)j * h, id);
        if (got >= need && count - got >= need) {
            w->n_new++;
            return 1;
        }
        undo_fill(w, got, s);
    }
    return 1;
}

static void work_free(profile_work *w) {
    free(w->start), free(w->members), free(w->scratch), free(w->label);
    free(w->queue), free(w->band), free(w->above);
}

static int work_alloc(profile_work *w, size_t n) {
    w->start = malloc(((size_t)w->sn->m + 1) * sizeof *w->start);
    w->members = malloc(n * sizeof *w->members);
    w->scratch = malloc(n * sizeof *w->scratch);
    w->label = malloc(n * sizeof *w->label);
    w->queue = malloc(n * sizeof *w->queue);
    return w->start && w->members && w->scratch && w->label && w->queue;
}

ps_status ps_profile_split(const ps_graph *g, const double *points, const double *f,
                           const double *spacing, ps_supernodes *sn, ps_error *err) {
    size_t n = g->n;
    if (n == 0) return PS_OK;
    profile_work w = {.g = g, .points = points, .f = f, .sn = sn, .spacing = spacing};
    int ok = work_alloc(&w, n);
    if (ok) {
        /* a supernode id is never negative: it reads the same as a uint32_t */
        ps_group_by_label((const uint32_t *)sn->supernode_of, n, (size_t)sn->m, w.start,
                          w.members);
        for (size_t p = 0; p < n; p++) w.label[p] = sn->supernode_of[p];
    }
    for (int s = 0; ok && s < sn->m; s++)
        if (!sn->is_minimum[s]) ok = split_one(&w, s);
    ps_status st = ok ? PS_OK : ps_fail(err, PS_ERR_NOMEM, "profile split: out of memory");
    if (st == PS_OK && w.n_new > 0 && sn->m + w.n_new <= PS_MAX_SUPERNODES)
        st = ps_supernodes_relabel(sn, w.label, sn->m + w.n_new, f, n, err);
    work_free(&w);
    return st;
}
