/*
 * test_mesh_edges.c: a tube sampled in rings farther apart than the
 * spacing along each ring (a turned CAD part's mesh) has one kNN component
 * per ring; its faces join them into one: only the edges between rings are
 * added, rows stay sorted and duplicate-free with Euclidean weights, and a
 * mesh whose kNN graph is whole is left alone.  End to end, the faces turn
 * a tube cut into its rings back into one or a few parts, and a face
 * pointing past the points is refused.
 */
#include "knn_graph.h"
#include "mesh_edges.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RING 64    /* points per ring of radius 1: 0.098 apart */
#define RINGS 11   /* rings 1 apart along z */
#define N_TUBE (RING * RINGS)
#define N_BAND_FACES (2 * RING * (RINGS - 1))

typedef struct tube {
    double points[3 * N_TUBE];
    uint32_t faces[3 * N_BAND_FACES];
} tube;

static uint32_t at(int ring, int i) { return (uint32_t)(ring * RING + (i % RING)); }

/* Points in rings; each band between two rings in two triangles per step. */
static void tube_make(tube *t) {
    for (int r = 0; r < RINGS; r++)
        for (int i = 0; i < RING; i++) {
            double a = 2 * acos(-1.0) * i / RING;
            double *p = t->points + 3 * at(r, i);
            p[0] = cos(a), p[1] = sin(a), p[2] = r;
        }
    uint32_t *f = t->faces;
    for (int r = 0; r + 1 < RINGS; r++)
        for (int i = 0; i < RING; i++) {
            f[0] = at(r, i), f[1] = at(r, i + 1), f[2] = at(r + 1, i), f += 3;
            f[0] = at(r, i + 1), f[1] = at(r + 1, i + 1), f[2] = at(r + 1, i), f += 3;
        }
}

static void check_rows(const ps_graph *g, const double *points) {
    for (size_t p = 0; p < g->n; p++)
        for (size_t e = g->offsets[p]; e < g->offsets[p + 1]; e++) {
            uint32_t q = g->neighbors[e];
            if (e > g->offsets[p]) CHECK(g->neighbors[e - 1] < q);
            const double *a = points + 3 * p, *b = points + 3 * (size_t)q;
            double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                            (a[2] - b[2]) * (a[2] - b[2]));
            CHECK(fabs(g->weights[e] - d) < 1e-12);
        }
}

static void test_faces_join_the_rings(void) {
    static tube t;
    tube_make(&t);
    ps_graph g;
    ps_error err;
    REQUIRE(ps_knn_graph_build(t.points, N_TUBE, 3, 7, 1, &g, &err) == PS_OK);
    int component[N_TUBE];
    CHECK(ps_graph_components(&g, component) == RINGS);
    size_t edges_before = g.offsets[N_TUBE];
    uint32_t identity[N_TUBE];
    for (uint32_t i = 0; i < N_TUBE; i++) identity[i] = i;
    ps_mesh_bridge_input in = {t.points, 3, t.faces, N_BAND_FACES, identity, N_TUBE, component};
    size_t added = 0;
    REQUIRE(ps_mesh_bridges_add(&g, &in, &added, &err) == PS_OK);
    /* each step of a band adds r_i - r'_i and r_{i+1} - r'_i */
    CHECK(added == 2 * RING * (RINGS - 1));
    CHECK(g.offsets[N_TUBE] == edges_before + 2 * added);
    CHECK(ps_graph_components(&g, component) == 1);
    check_rows(&g, t.points);
    ps_graph_free(&g);
}

static void test_whole_graph_untouched(void) {
    static tube t;
    tube_make(&t);
    for (size_t i = 0; i < N_TUBE; i++) t.points[3 * i + 2] *= 0.05; /* rings 0.05 apart */
    ps_graph g;
    ps_error err;
    REQUIRE(ps_knn_graph_build(t.points, N_TUBE, 3, 7, 1, &g, &err) == PS_OK);
    int component[N_TUBE];
    CHECK(ps_graph_components(&g, component) == 1);
    uint32_t identity[N_TUBE];
    for (uint32_t i = 0; i < N_TUBE; i++) identity[i] = i;
    uint32_t *neighbors = g.neighbors;
    ps_mesh_bridge_input in = {t.points, 3, t.faces, N_BAND_FACES, identity, N_TUBE, component};
    size_t added = 1;
    REQUIRE(ps_mesh_bridges_add(&g, &in, &added, &err) == PS_OK);
    CHECK(added == 0);
    CHECK(g.neighbors == neighbors);
    ps_graph_free(&g);
}

/* Input points standing for one distinct point: the face edges go between
 * the distinct points, and an edge within one of them is none. */
static void test_duplicates_map_to_their_point(void) {
    double points[3 * 8] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,  /* a square */
                            0, 0, 9, 1, 0, 9, 0, 1, 9, 1, 1, 9}; /* far above it */
    ps_graph g;
    ps_error err;
    REQUIRE(ps_knn_graph_build(points, 8, 3, 3, 1, &g, &err) == PS_OK);
    int component[8];
    CHECK(ps_graph_components(&g, component) == 2);
    /* input point 8 duplicates 0, 9 duplicates 4 */
    uint32_t unique_of[10] = {0, 1, 2, 3, 4, 5, 6, 7, 0, 4};
    uint32_t faces[6] = {8, 9, 1, 0, 8, 9};
    ps_mesh_bridge_input in = {points, 3, faces, 2, unique_of, 10, component};
    size_t added = 0;
    REQUIRE(ps_mesh_bridges_add(&g, &in, &added, &err) == PS_OK);
    CHECK(added == 2); /* 0-4 and 1-4; 0-0 is no edge */
    CHECK(ps_graph_components(&g, component) == 1);
    check_rows(&g, points);
    ps_graph_free(&g);
}

static int segments_of(const tube *t, int with_faces) {
    ps_input in = {.points = t->points, .n = N_TUBE, .dim = 3};
    if (with_faces) in.faces = t->faces, in.n_faces = N_BAND_FACES;
    ps_params p;
    ps_params_default(&p);
    ps_result *r = NULL;
    ps_error err;
    if (ps_segment(&in, &p, NULL, &r, &err) != PS_OK) {
        CHECK_MSG(0, "ps_segment: %s", err.message);
        return -1;
    }
    int n = r->n_segments;
    CHECK(r->n_components == (with_faces ? 1 : RINGS));
    ps_result_free(r);
    return n;
}

static void test_segment_uses_the_faces(void) {
    static tube t;
    tube_make(&t);
    CHECK(segments_of(&t, 0) >= RINGS);
    CHECK(segments_of(&t, 1) <= 3);
}

static void test_face_past_the_points_refused(void) {
    static tube t;
    tube_make(&t);
    t.faces[3 * 5 + 1] = N_TUBE;
    ps_input in = {.points = t.points, .n = N_TUBE, .dim = 3, .faces = t.faces,
                   .n_faces = N_BAND_FACES};
    ps_params p;
    ps_params_default(&p);
    ps_result *r = NULL;
    ps_error err = {0};
    CHECK(ps_segment(&in, &p, NULL, &r, &err) == PS_ERR_INVALID);
    CHECK(r == NULL);
    CHECK_MSG(strstr(err.message, "face 5") != NULL, "message: %s", err.message);
}

PS_TEST_MAIN(TEST(test_faces_join_the_rings), TEST(test_whole_graph_untouched),
             TEST(test_duplicates_map_to_their_point), TEST(test_segment_uses_the_faces),
             TEST(test_face_past_the_points_refused))
