/*
 * bench_solids.c: plain man-made solids scanned with noise.  Each solid is
 * a union of boxes (a beam, boards, a cube, an L, a T, a table, a chair,
 * shelves, stairs, a bench, a frame, a box on a box), 40,000 points drawn
 * uniformly on its surface, segmented clean and with Gaussian noise of a
 * sixth and of a quarter of the point spacing on every coordinate (default
 * parameters).  It prints each solid's segment counts and how far the
 * noisy labels lie from the clean ones (1 - RI over the same points), and
 * their means: noise should not change the parts.  See tests/bench/README.md.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench_machine.h"
#include "pointseg.h"
#include "random_bits.h"

#define POINTS 40000
#define MAX_BOXES 6
#define NOISE_LEVELS 2

typedef struct box { double at[3], size[3]; } box;

typedef struct solid {
    const char *name;
    int n_boxes;
    box boxes[MAX_BOXES];
} solid;

static const solid SOLIDS[] = {
    {"beam", 1, {{{0, 0, 0}, {12, 1, 1}}}},
    {"board", 1, {{{0, 0, 0}, {24, 3, 0.3}}}},
    {"plank", 1, {{{0, 0, 0}, {10, 2, 0.25}}}},
    {"cube", 1, {{{0, 0, 0}, {2, 2, 2}}}},
    {"L", 2, {{{0, 0, 0}, {6, 1, 1}}, {{0, 0, 0}, {1, 6, 1}}}},
    {"T", 2, {{{0, 0, 0}, {6, 1, 1}}, {{2.5, 0, 1}, {1, 1, 5}}}},
    {"box on a box", 2, {{{0, 0, 0}, {4, 4, 2}}, {{1, 1, 2}, {2, 2, 2}}}},
    {"stairs", 3, {{{0, 0, 0}, {3, 1, 1}}, {{0, 1, 0}, {3, 1, 2}}, {{0, 2, 0}, {3, 1, 3}}}},
    {"bench", 3, {{{0, 0, 1.5}, {8, 1.5, 0.3}}, {{0.5, 0, 0}, {0.4, 1.5, 1.5}}, {{7.1, 0, 0}, {0.4, 1.5, 1.5}}}},
    {"frame", 4,
     {{{0, 0, 0}, {5, 0.5, 0.5}}, {{0, 0, 4.5}, {5, 0.5, 0.5}}, {{0, 0, 0.5}, {0.5, 0.5, 4}},
      {{4.5, 0, 0.5}, {0.5, 0.5, 4}}}},
    {"table", 5,
     {{{0, 0, 3}, {6, 4, 0.3}}, {{0.2, 0.2, 0}, {0.3, 0.3, 3}}, {{5.5, 0.2, 0}, {0.3, 0.3, 3}},
      {{0.2, 3.5, 0}, {0.3, 0.3, 3}}, {{5.5, 3.5, 0}, {0.3, 0.3, 3}}}},
    {"shelves", 5,
     {{{0, 0, 0}, {0.3, 2, 6}}, {{4.3, 0, 0}, {0.3, 2, 6}}, {{0.3, 0, 0.5}, {4, 2, 0.3}},
      {{0.3, 0, 3}, {4, 2, 0.3}}, {{0.3, 0, 5.7}, {4, 2, 0.3}}}},
    {"chair", 6,
     {{{0, 0, 2}, {3, 3, 0.3}}, {{0, 0, 0}, {0.3, 0.3, 2}}, {{2.7, 0, 0}, {0.3, 0.3, 2}},
      {{0, 2.7, 0}, {0.3, 0.3, 2}}, {{2.7, 2.7, 0}, {0.3, 0.3, 2}}, {{0, 2.7, 2.3}, {3, 0.3, 3}}}},
};
#define N_SOLIDS (sizeof SOLIDS / sizeof SOLIDS[0])

static const double NOISE[NOISE_LEVELS] = {1.0 / 6, 1.0 / 4};

static double face_area(const box *b, int face) {
    int axis = face / 2;
    return b->size[(axis + 1) % 3] * b->size[(axis + 2) % 3];
}

static double solid_area(const solid *s) {
    double area = 0;
    for (int b = 0; b < s->n_boxes; b++)
        for (int f = 0; f < 6; f++) area += face_area(&s->boxes[b], f);
    return area;
}

/* Whether x lies strictly inside box b. */
static int inside(const box *b, const double *x) {
    for (int a = 0; a < 3; a++)
        if (!(x[a] > b->at[a] + 1e-9 && x[a] < b->at[a] + b->size[a] - 1e-9)) return 0;
    return 1;
}

/* A point uniform on the boxes' faces (by area) into x; its box. */
static int draw_on_faces(const solid *s, double area, uint64_t *state, double *x) {
    double r = ps_uniform_next(state) * area;
    for (int b = 0; b < s->n_boxes; b++)
        for (int f = 0; f < 6; f++) {
            r -= face_area(&s->boxes[b], f);
            if (r > 0 && !(b == s->n_boxes - 1 && f == 5)) continue;
            const box *bx = &s->boxes[b];
            int axis = f / 2;
            for (int a = 0; a < 3; a++)
                x[a] = bx->at[a] + (a == axis ? (f % 2) * bx->size[a]
                                              : ps_uniform_next(state) * bx->size[a]);
            return b;
        }
    return 0;
}

/* POINTS points on the surface of the union (none inside another box),
 * written to pts #POINTS by 3. */
static void sample_solid(const solid *s, double *pts) {
    double area = solid_area(s);
    uint64_t state = 0x9E3779B97F4A7C15ULL;
    for (size_t i = 0; i < POINTS;) {
        double *x = pts + 3 * i;
        int own = draw_on_faces(s, area, &state, x), hidden = 0;
        for (int b = 0; b < s->n_boxes; b++) hidden |= b != own && inside(&s->boxes[b], x);
        if (!hidden) i++;
    }
}

/* Labels out #POINTS and the segment count of pts; -1 on failure. */
static int segment(const double *pts, int *labels) {
    ps_params p;
    ps_params_default(&p);
    ps_input in = {.points = pts, .n = POINTS, .dim = 3};
    ps_result *r = NULL;
    ps_error err;
    if (ps_segment(&in, &p, NULL, &r, &err) != PS_OK) {
        fprintf(stderr, "segment failed: %s\n", err.message);
        return -1;
    }
    for (size_t i = 0; i < POINTS; i++) labels[i] = r->labels[i];
    int segments = r->n_segments;
    ps_result_free(r);
    return segments;
}

int main(void) {
    ps_bench_print_machine("bench_solids");
    printf("\n%d points each; noise in point spacings (sqrt(area / points)); 1-RI of the noisy "
           "labels against the clean ones\n\n", POINTS);
    printf("%-14s %5s %5s | %9s %7s | %9s %7s\n", "solid", "boxes", "clean", "1/6: segs", "1-RI",
           "1/4: segs", "1-RI");
    double *clean = malloc(3 * POINTS * sizeof *clean), *noisy = malloc(3 * POINTS * sizeof *noisy);
    int *clean_labels = malloc(POINTS * sizeof *clean_labels);
    int *noisy_labels = malloc(POINTS * sizeof *noisy_labels);
    if (!clean || !noisy || !clean_labels || !noisy_labels) return 1;
    double sum[NOISE_LEVELS] = {0};
    int same_count[NOISE_LEVELS] = {0};
    for (size_t s = 0; s < N_SOLIDS; s++) {
        sample_solid(&SOLIDS[s], clean);
        int clean_segments = segment(clean, clean_labels);
        if (clean_segments < 0) return 1;
        printf("%-14s %5d %5d |", SOLIDS[s].name, SOLIDS[s].n_boxes, clean_segments);
        double spacing = sqrt(solid_area(&SOLIDS[s]) / POINTS);
        for (int level = 0; level < NOISE_LEVELS; level++) {
            uint64_t state = 0x2545F4914F6CDD1DULL + s;
            for (size_t i = 0; i < 3 * POINTS; i++)
                noisy[i] = clean[i] + NOISE[level] * spacing * ps_gaussian_next(&state);
            int segments = segment(noisy, noisy_labels);
            if (segments < 0) return 1;
            double error = ps_rand_index_error(clean_labels, noisy_labels, POINTS);
            sum[level] += error;
            same_count[level] += segments == clean_segments;
            printf(" %9d %7.4f |", segments, error);
        }
        printf("\n");
    }
    printf("\nmean 1-RI against the clean labels: noise 1/6 %.4f, 1/4 %.4f; the clean segment "
           "count kept by %d and %d of %zu solids\n",
           sum[0] / N_SOLIDS, sum[1] / N_SOLIDS, same_count[0], same_count[1], N_SOLIDS);
    free(clean), free(noisy), free(clean_labels), free(noisy_labels);
    return 0;
}
