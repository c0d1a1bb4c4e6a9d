/*
 * test_surface_fill.c: a tube meshed in rings farther apart than the
 * spacing along each ring (a turned CAD part's mesh).  The fill adds
 * exactly the points the target asks for, on the tube's triangles, evenly
 * (every band between two rings gets its area's share), with each host a
 * corner of the point's triangle and interpolated unit normals; it moves
 * with the mesh under rotation and scaling, another seed samples the
 * triangles elsewhere, and it adds nothing to a dense mesh, to faces
 * without area or to a noisy mesh.  End to end, a bare point set of rings
 * falls apart into its rings, the same points with their faces come out
 * whole (but with exact centrality, which runs on the input as given),
 * the same for any thread count and a moved copy, and the answers cover
 * the caller's points only; a mesh of duplicate points and degenerate
 * triangles is answered, a regular icosahedron (its roughness 0 but for
 * rounding) is filled, a coarse turned part's supernodes lie in their
 * points' segments though their sinks are added points, and a face
 * pointing past the points is refused.
 * The tube unwelded (each triangle with copies of its own vertices) is as
 * smooth, as rough when noisy, and as filled and whole as welded, even
 * given over the reference sampling by its copies.
 */
#include "graph/reference_density.h"
#include "graph/surface_fill.h"
#include "progress_seen.h"
#include "random_bits.h"
#include "result_checks.h"
#include "testlib.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RING 64    /* points per ring of radius 1: 0.098 apart */
#define RINGS 11   /* rings 1 apart along z */
#define N_TUBE (RING * RINGS)
#define N_BAND_FACES (2 * RING * (RINGS - 1))
#define TARGET 20000

typedef struct tube {
    double points[3 * N_TUBE];
    double normals[3 * N_TUBE];
    uint32_t faces[3 * N_BAND_FACES];
} tube;

/* ps_surface_fill_build with in's distinct points found first. */
static ps_status fill_build(const ps_input *in, size_t target, int fills, ps_surface_fill *out,
                            ps_error *err) {
    ps_dedup corners;
    ps_status st = ps_dedup_build(in->points, in->n, in->dim, &corners, err);
    if (st == PS_OK) st = ps_surface_fill_build(in, &corners, target, fills, out, err);
    ps_dedup_free(&corners);
    return st;
}

/* ps_surface_fill_roughness with in's distinct points found first; -1 when
 * out of memory. */
static double roughness(const ps_input *in) {
    ps_dedup corners;
    if (ps_dedup_build(in->points, in->n, in->dim, &corners, NULL) != PS_OK) return -1;
    double r = ps_surface_fill_roughness(in, &corners);
    ps_dedup_free(&corners);
    return r;
}

static uint32_t at(int ring, int i) { return (uint32_t)(ring * RING + (i % RING)); }

/* Points in rings with radial normals; each band between two rings in two
 * triangles per step. */
static void tube_make(tube *t) {
    for (int r = 0; r < RINGS; r++)
        for (int i = 0; i < RING; i++) {
            double a = 2 * acos(-1.0) * i / RING;
            double *p = t->points + 3 * at(r, i), *n = t->normals + 3 * at(r, i);
            p[0] = cos(a), p[1] = sin(a), p[2] = r;
            n[0] = cos(a), n[1] = sin(a), n[2] = 0;
        }
    uint32_t *f = t->faces;
    for (int r = 0; r + 1 < RINGS; r++)
        for (int i = 0; i < RING; i++) {
            f[0] = at(r, i), f[1] = at(r, i + 1), f[2] = at(r + 1, i), f += 3;
            f[0] = at(r, i + 1), f[1] = at(r + 1, i + 1), f[2] = at(r + 1, i), f += 3;
        }
}

static ps_input tube_input(const tube *t) {
    return (ps_input){.points = t->points, .n = N_TUBE, .dim = 3, .faces = t->faces,
                      .n_faces = N_BAND_FACES};
}

static void test_fills_the_tube_evenly(void) {
    static tube t;
    tube_make(&t);
    ps_input in = tube_input(&t);
    ps_surface_fill s;
    ps_error err;
    REQUIRE(fill_build(&in, TARGET, 1, &s, &err) == PS_OK);
    /* the dither's rounding: 1,280 triangles of 15.1 points each */
    REQUIRE(s.n_added > TARGET - N_TUBE - 100 && s.n_added < TARGET - N_TUBE + 100);
    CHECK(s.normals == NULL);
    CHECK(memcmp(s.points, t.points, sizeof t.points) == 0);
    size_t per_band[RINGS - 1] = {0};
    double chord = cos(acos(-1.0) / RING);  /* a flat triangle's nearest to the axis */
    for (size_t a = 0; a < s.n_added; a++) {
        const double *p = s.points + 3 * (N_TUBE + a), *h = t.points + 3 * (size_t)s.host[a];
        double radius = hypot(p[0], p[1]);
        CHECK(radius <= 1 + 1e-12 && radius >= chord - 1e-12);
        CHECK(p[2] >= 0 && p[2] <= RINGS - 1);
        /* the host is a corner of the point's triangle: within one band, one step */
        CHECK(fabs(h[2] - p[2]) <= 0.5 + 1e-12);
        CHECK(hypot(h[0] - p[0], h[1] - p[1]) <= 2 * acos(-1.0) / RING + 1e-12);
        per_band[p[2] >= RINGS - 1 ? RINGS - 2 : (int)p[2]]++;
    }
    double share = (double)s.n_added / (RINGS - 1);
    for (int b = 0; b < RINGS - 1; b++)
        CHECK_MSG(fabs((double)per_band[b] - share) <= 12, "band %d: %zu points, share %.1f", b,
                  per_band[b], share);
    ps_surface_fill_free(&s);
}

static void test_normals_interpolated(void) {
    static tube t;
    tube_make(&t);
    ps_input in = tube_input(&t);
    in.normals = t.normals;
    ps_surface_fill s;
    ps_error err;
    REQUIRE(fill_build(&in, TARGET, 1, &s, &err) == PS_OK);
    REQUIRE(s.normals != NULL);
    for (size_t a = 0; a < s.n_added; a++) {
        const double *p = s.points + 3 * (N_TUBE + a), *n = s.normals + 3 * (N_TUBE + a);
        double length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double radius = hypot(p[0], p[1]);
        CHECK(fabs(length - 1) < 1e-12);
        CHECK((n[0] * p[0] + n[1] * p[1]) / radius > 0.998);
    }
    ps_surface_fill_free(&s);
}

/* x -> scale * R x + shift, R a rotation about z then x. */
static void move(const double *p, double scale, double *out) {
    double c = cos(0.7), s = sin(0.7), c2 = cos(1.1), s2 = sin(1.1);
    double x = c * p[0] - s * p[1], y = s * p[0] + c * p[1], z = p[2];
    out[0] = scale * x + 3;
    out[1] = scale * (c2 * y - s2 * z) - 2;
    out[2] = scale * (s2 * y + c2 * z) + 5;
}

static void test_moves_with_the_mesh(void) {
    static tube t, moved;
    tube_make(&t);
    moved = t;
    for (size_t i = 0; i < N_TUBE; i++) move(t.points + 3 * i, 250.0, moved.points + 3 * i);
    ps_input a = tube_input(&t), b = tube_input(&moved);
    ps_surface_fill sa, sb;
    ps_error err;
    REQUIRE(fill_build(&a, TARGET, 1, &sa, &err) == PS_OK);
    REQUIRE(fill_build(&b, TARGET, 1, &sb, &err) == PS_OK);
    REQUIRE(sa.n_added == sb.n_added);
    size_t same = 0;
    for (size_t i = 0; i < sa.n_added; i++) {
        double expect[3];
        move(sa.points + 3 * (N_TUBE + i), 250.0, expect);
        const double *got = sb.points + 3 * (N_TUBE + i);
        double d = fabs(expect[0] - got[0]) + fabs(expect[1] - got[1]) + fabs(expect[2] - got[2]);
        same += d < 1e-9 * 250 && sa.host[i] == sb.host[i];
    }
    CHECK_MSG(same == sa.n_added, "%zu of %zu moved with the mesh", same,
              sa.n_added);
    ps_surface_fill_free(&sa);
    ps_surface_fill_free(&sb);
}

static void test_nothing_to_add(void) {
    static tube t;
    tube_make(&t);
    ps_input in = tube_input(&t);
    ps_surface_fill s;
    ps_error err;
    REQUIRE(fill_build(&in, N_TUBE, 1, &s, &err) == PS_OK);
    CHECK(s.n_added == 0 && s.points == NULL && s.host == NULL);
    uint32_t flat[6] = {0, 0, 1, 2, 2, 2}; /* two triangles without area */
    in.faces = flat, in.n_faces = 2;
    REQUIRE(fill_build(&in, TARGET, 1, &s, &err) == PS_OK);
    CHECK(s.n_added == 0 && s.points == NULL);
    in = tube_input(&t);
    in.faces = NULL, in.n_faces = 0;
    REQUIRE(fill_build(&in, TARGET, 1, &s, &err) == PS_OK);
    CHECK(s.n_added == 0);
}

/* A mesh whose vertices are jittered by up to half their spacing along a
 * ring is noise on its triangles, and is not filled; the clean tube is
 * smooth. */
static void test_noisy_mesh_not_filled(void) {
    static tube t;
    tube_make(&t);
    ps_input in = tube_input(&t);
    CHECK(roughness(&in) < PS_FILL_MAX_ROUGHNESS / 10);
    uint64_t state = 88172645463325252ull;
    for (size_t i = 0; i < 3 * N_TUBE; i++) {
        t.points[i] += 0.1 * (ps_uniform_next(&state) - 0.5);
    }
    CHECK(roughness(&in) > PS_FILL_MAX_ROUGHNESS);
    ps_surface_fill s;
    ps_error err;
    REQUIRE(fill_build(&in, TARGET, 1, &s, &err) == PS_OK);
    CHECK(s.n_added == 0 && s.points == NULL);
}

/* Fills of other seeds add as many points (but for the dither) at other
 * places: independent samplings of the same triangles; seed 0 is the same
 * fill asked alone or with another. */
static void test_seeds_fill_independently(void) {
    static tube t;
    tube_make(&t);
    ps_input in = tube_input(&t);
    ps_surface_fill fills[2], one;
    ps_error err;
    REQUIRE(fill_build(&in, TARGET, 2, fills, &err) == PS_OK);
    REQUIRE(fill_build(&in, TARGET, 1, &one, &err) == PS_OK);
    ps_surface_fill a = fills[0], b = fills[1];
    REQUIRE(one.n_added == a.n_added);
    CHECK(memcmp(one.points, a.points, 3 * (N_TUBE + a.n_added) * sizeof *a.points) == 0);
    ps_surface_fill_free(&one);
    REQUIRE(a.n_added > 0 && b.n_added > 0);
    CHECK_MSG(fabs((double)a.n_added - (double)b.n_added) < 0.01 * (double)a.n_added,
              "%zu and %zu added", a.n_added, b.n_added);
    size_t same = 0, m = a.n_added < b.n_added ? a.n_added : b.n_added;
    for (size_t i = 0; i < m; i++) {
        const double *p = a.points + 3 * (N_TUBE + i), *q = b.points + 3 * (N_TUBE + i);
        same += fabs(p[0] - q[0]) + fabs(p[1] - q[1]) + fabs(p[2] - q[2]) < 1e-9;
    }
    CHECK_MSG(same < m / 100, "%zu of %zu added points in the same place", same, m);
    ps_surface_fill_free(&a);
    ps_surface_fill_free(&b);
}

/* Segments of the tube's points, with or without its faces; checks that the
 * answers cover the caller's points and that every sink is one of them. */
static int segments_of(const tube *t, int with_faces, ps_centrality_mode centrality,
                       int *components) {
    ps_input in = tube_input(t);
    if (!with_faces) in.faces = NULL, in.n_faces = 0;
    ps_params p;
    ps_params_default(&p);
    p.centrality = centrality;
    ps_result *r = NULL;
    ps_error err;
    if (ps_segment(&in, &p, NULL, &r, &err) != PS_OK) {
        CHECK_MSG(0, "ps_segment: %s", err.message);
        return -1;
    }
    CHECK(r->n_points == N_TUBE);
    if (with_faces && centrality != PS_CENTRALITY_EXACT) CHECK(r->n_filled > 10000);
    else CHECK(r->n_filled == 0);
    size_t total = 0;
    for (int g = 0; g < r->n_segments; g++) total += r->segments[g].size;
    CHECK(total == N_TUBE);
    for (int s = 0; s < r->n_supernodes; s++) {
        CHECK(r->supernodes[s].sink < N_TUBE);
        CHECK(r->supernodes[s].segment >= 0 && r->supernodes[s].segment < r->n_segments);
    }
    for (size_t i = 0; i < N_TUBE; i++)
        CHECK(r->labels[i] >= 0 && r->labels[i] < r->n_segments);
    int n = r->n_segments;
    *components = r->n_components;
    ps_result_free(r);
    return n;
}

static ps_result *segment_tube(const tube *t, int threads, const ps_control *ctl) {
    ps_input in = tube_input(t);
    ps_params p;
    ps_params_default(&p);
    p.threads = threads;
    ps_result *r = NULL;
    ps_error err;
    CHECK_MSG(ps_segment(&in, &p, ctl, &r, &err) == PS_OK, "ps_segment: %s", err.message);
    return r;
}

/* ps_segment of in with the defaults, CHECKed to succeed; NULL when not. */
static ps_result *segment_mesh(const ps_input *in) {
    ps_result *r = NULL;
    ps_error err;
    CHECK_MSG(ps_segment(in, NULL, NULL, &r, &err) == PS_OK, "ps_segment: %s", err.message);
    return r;
}

/* The mesh is segmented in fills (ensemble.h): the same labels for any
 * thread count and for a moved copy, progress that never goes back. */
static void test_segment_in_fills_deterministic(void) {
    static tube t, moved;
    tube_make(&t);
    moved = t;
    for (size_t i = 0; i < N_TUBE; i++) move(t.points + 3 * i, 250.0, moved.points + 3 * i);
    ps_progress_seen seen = {{0}, {0}, {0}, 0};
    ps_control ctl = {.progress = ps_progress_seen_record, .user = &seen};
    ps_result *one = segment_tube(&t, 1, &ctl), *two = segment_tube(&t, 2, NULL),
              *far = segment_tube(&moved, 0, NULL);
    REQUIRE(one && two && far);
    CHECK(!seen.went_back);
    for (int ph = 0; ph < PS_PHASE_COUNT; ph++) CHECK(seen.last[ph] == 1.0);
    CHECK(memcmp(one->labels, two->labels, N_TUBE * sizeof *one->labels) == 0);
    CHECK(memcmp(one->labels, far->labels, N_TUBE * sizeof *one->labels) == 0);
    CHECK(one->n_filled > 10000 && one->n_filled == far->n_filled);
    ps_result_free(one), ps_result_free(two), ps_result_free(far);
}

/* A mesh of a few points with duplicate points, degenerate and repeated
 * triangles, and one real triangle: the fills cover the one triangle, and
 * every caller's point is answered. */
static void test_degenerate_mesh_in_fills(void) {
    double pts[3 * 12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 2, 2,
                          2, 2, 2, 0.5, 0.5, 0, 3, 0, 0, 3, 0, 0, 0, 3, 0, 1e-9, 0, 0};
    uint32_t faces[3 * 6] = {0, 0, 0, 0, 1, 1, 0, 1, 2, 0, 1, 2, 3, 4, 1, 8, 9, 10};
    ps_input in = {.points = pts, .n = 12, .dim = 3, .faces = faces, .n_faces = 6};
    ps_result *r = segment_mesh(&in);
    if (!r) return;
    CHECK(r->n_points == 12 && r->n_filled > 0);
    for (size_t i = 0; i < 12; i++) CHECK(r->labels[i] >= 0 && r->labels[i] < r->n_segments);
    ps_result_free(r);
}

/* A regular icosahedron: each triangle's normal is its corners' summed
 * normal but for rounding, which made 1 - cos a hair below 0 and the
 * roughness, the median, -2e-16: read as out of memory, the mesh was a
 * PS_ERR_NOMEM (a 500 from the daemon).  Now it is smooth, filled and
 * whole. */
static void test_regular_mesh_filled(void) {
    const double t = (1 + sqrt(5.0)) / 2;
    double pts[3 * 12] = {-1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t,
                          0, -1, -t, 0, 1, -t, t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1};
    uint32_t faces[3 * 20] = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11,
                              1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                              3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9,
                              4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    ps_input in = {.points = pts, .n = 12, .dim = 3, .faces = faces, .n_faces = 20};
    CHECK_MSG(roughness(&in) == 0, "roughness %g", roughness(&in));
    ps_result *r = segment_mesh(&in);
    if (!r) return;
    CHECK(r->n_points == 12 && r->n_filled > 10000);
    CHECK_MSG(r->n_segments == 1, "%d segments", r->n_segments);
    ps_result_free(r);
}

#define SHAFT_RING 12
#define SHAFT_RINGS 5
#define SHAFT_TUBE_POINTS (SHAFT_RING * SHAFT_RINGS + 2)
#define SHAFT_TUBE_FACES (2 * SHAFT_RING * SHAFT_RINGS)

typedef struct shaft {
    double points[3 * 2 * SHAFT_TUBE_POINTS];
    uint32_t faces[3 * 2 * SHAFT_TUBE_FACES];
} shaft;

/* Tube number `which` of s along x, from x0 to x0 + length, of the given
 * radius: SHAFT_RINGS rings of SHAFT_RING points, closed at both ends by a
 * fan around a centre point. */
static void shaft_tube(shaft *s, int which, double x0, double length, double radius) {
    uint32_t base = (uint32_t)(which * SHAFT_TUBE_POINTS), ring = base + SHAFT_RING * SHAFT_RINGS;
    double *p = s->points + 3 * base;
    for (int r = 0; r < SHAFT_RINGS; r++)
        for (int i = 0; i < SHAFT_RING; i++, p += 3) {
            double a = 2 * acos(-1.0) * i / SHAFT_RING;
            p[0] = x0 + length * r / (SHAFT_RINGS - 1), p[1] = radius * cos(a),
            p[2] = radius * sin(a);
        }
    p[0] = x0, p[3] = x0 + length, p[1] = p[2] = p[4] = p[5] = 0;
    uint32_t *f = s->faces + 3 * (size_t)(which * SHAFT_TUBE_FACES);
    for (uint32_t r = 0; r < SHAFT_RINGS; r++)
        for (uint32_t i = 0; i < SHAFT_RING; i++) {
            uint32_t a = base + r * SHAFT_RING + i, b = base + r * SHAFT_RING + (i + 1) % SHAFT_RING;
            if (r + 1 < SHAFT_RINGS) {
                f[0] = a, f[1] = b, f[2] = a + SHAFT_RING, f += 3;
                f[0] = b, f[1] = b + SHAFT_RING, f[2] = a + SHAFT_RING, f += 3;
            } else {
                uint32_t c = base + i, d = base + (i + 1) % SHAFT_RING;
                f[0] = ring, f[1] = d, f[2] = c, f += 3;
                f[0] = ring + 1, f[1] = a, f[2] = b, f += 3;
            }
        }
}

/* A coarse turned part: a shaft 4 long of radius 0.3 and a collar 1 long
 * of radius 1 beyond it, 124 points on big triangles.  Some sinks of f
 * fall on points added to the triangles, nearest to a vertex of another
 * segment; a supernode took that vertex's segment, not its own points',
 * so two points' supernode lay outside their segment and segments listed
 * supernodes that were not theirs.  Now every answer is consistent. */
static void test_added_sinks_in_their_segment(void) {
    static shaft s;
    shaft_tube(&s, 0, 0, 4, 0.3);
    shaft_tube(&s, 1, 4, 1, 1);
    ps_input in = {.points = s.points, .n = 2 * SHAFT_TUBE_POINTS, .dim = 3, .faces = s.faces,
                   .n_faces = 2 * SHAFT_TUBE_FACES};
    ps_result *r = segment_mesh(&in);
    if (!r) return;
    CHECK(r->n_filled > 10000 && r->n_segments > 1);
    ps_check_result_consistent(r);
    ps_result_free(r);
}

/* The tube unwelded: each of its triangles, given copies times over,
 * with three copies of its own of its vertices (as a mesh exported
 * triangle by triangle); *n its points. */
static ps_input unwelded(const tube *t, int copies, double **points, uint32_t **faces, size_t *n) {
    size_t f = (size_t)copies * N_BAND_FACES;
    *n = 3 * f;
    *points = malloc(3 * *n * sizeof **points);
    *faces = malloc(3 * f * sizeof **faces);
    if (!*points || !*faces) return (ps_input){0};
    for (size_t i = 0; i < *n; i++) {
        memcpy(*points + 3 * i, t->points + 3 * (size_t)t->faces[i % (3 * N_BAND_FACES)],
               3 * sizeof **points);
        (*faces)[i] = (uint32_t)i;
    }
    return (ps_input){.points = *points, .n = *n, .dim = 3, .faces = *faces, .n_faces = f};
}

/* Unwelded, the clean tube is as smooth and the noisy one as rough as
 * welded: a corner's normal sums the triangles meeting at its point,
 * whichever copy of it each names (a triangle alone at each corner read
 * every unwelded mesh as smooth, so noise was filled over). */
static void test_unwelded_roughness(void) {
    static tube t;
    tube_make(&t);
    double *points;
    uint32_t *faces;
    size_t n;
    ps_input in = unwelded(&t, 1, &points, &faces, &n);
    REQUIRE(in.points);
    CHECK(roughness(&in) < PS_FILL_MAX_ROUGHNESS / 10);
    free(points), free(faces);
    uint64_t state = 88172645463325252ull;
    for (size_t i = 0; i < 3 * N_TUBE; i++) {
        t.points[i] += 0.1 * (ps_uniform_next(&state) - 0.5);
    }
    in = unwelded(&t, 1, &points, &faces, &n);
    REQUIRE(in.points);
    CHECK_MSG(roughness(&in) > PS_FILL_MAX_ROUGHNESS, "roughness %g",
              roughness(&in));
    free(points), free(faces);
}

/* The tube unwelded and its triangles given 7 times (26,880 points, over
 * the reference sampling, 704 distinct): filled and whole as the welded
 * tube, every copy of a vertex answered alike (counted with its copies it
 * was not filled and fell apart into its rings). */
static void test_unwelded_mesh_filled_as_welded(void) {
    static tube t;
    tube_make(&t);
    double *points;
    uint32_t *faces;
    size_t n;
    ps_input in = unwelded(&t, 7, &points, &faces, &n);
    REQUIRE(in.points && n > PS_DENSITY_REFERENCE_POINTS);
    ps_result *r = NULL;
    ps_error err;
    ps_status st = ps_segment(&in, NULL, NULL, &r, &err);
    CHECK_MSG(st == PS_OK, "ps_segment: %s", err.message);
    if (st != PS_OK) {
        free(points), free(faces);
        return;
    }
    CHECK(r->n_points == n);
    CHECK_MSG(r->n_filled > PS_DENSITY_REFERENCE_POINTS - N_TUBE - 500, "%zu filled", r->n_filled);
    CHECK_MSG(r->n_segments <= 3 && r->n_components == 1, "%d segments, %d components",
              r->n_segments, r->n_components);
    for (size_t i = 3 * N_BAND_FACES; i < n; i++)
        CHECK(r->labels[i] == r->labels[i % (3 * N_BAND_FACES)]);
    ps_result_free(r);
    free(points), free(faces);
}

static void test_segment_fills_the_faces(void) {
    static tube t;
    tube_make(&t);
    int components = 0;
    CHECK(segments_of(&t, 0, PS_CENTRALITY_AUTO, &components) >= RINGS);
    CHECK(components == RINGS);
    CHECK(segments_of(&t, 1, PS_CENTRALITY_AUTO, &components) <= 3);
    CHECK(components == 1);
}

/* Exact centrality is quadratic in the points: it runs on the input as
 * given, and the rings stay apart. */
static void test_exact_centrality_not_filled(void) {
    static tube t;
    tube_make(&t);
    int components = 0;
    CHECK(segments_of(&t, 1, PS_CENTRALITY_EXACT, &components) >= RINGS);
    CHECK(components == RINGS);
}

static void test_face_past_the_points_refused(void) {
    static tube t;
    tube_make(&t);
    t.faces[3 * 5 + 1] = N_TUBE;
    ps_input in = tube_input(&t);
    ps_params p;
    ps_params_default(&p);
    ps_result *r = NULL;
    ps_error err = {0};
    CHECK(ps_segment(&in, &p, NULL, &r, &err) == PS_ERR_INVALID);
    CHECK(r == NULL);
    CHECK_MSG(strstr(err.message, "face 5") != NULL, "message: %s", err.message);
}

PS_TEST_MAIN(TEST(test_fills_the_tube_evenly), TEST(test_normals_interpolated),
             TEST(test_moves_with_the_mesh), TEST(test_seeds_fill_independently),
             TEST(test_nothing_to_add),
             TEST(test_noisy_mesh_not_filled),
             TEST(test_segment_fills_the_faces), TEST(test_segment_in_fills_deterministic),
             TEST(test_degenerate_mesh_in_fills), TEST(test_regular_mesh_filled),
             TEST(test_added_sinks_in_their_segment),
             TEST(test_exact_centrality_not_filled),
             TEST(test_face_past_the_points_refused), TEST(test_unwelded_roughness),
             TEST(test_unwelded_mesh_filled_as_welded))
