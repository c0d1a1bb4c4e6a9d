/*
 * shapes.c: the synthetic test shapes of shapes.h.
 *
 * A shape is a union of primitives (spheres, capsules, axis-aligned
 * ellipsoids).  Each primitive gets round(density * area) points drawn
 * uniformly on its own surface; points that fall inside another primitive
 * are dropped, so what remains samples the surface of the union.  The
 * generator (xorshift64*) restarts from a constant seed for every call.
 */
#include "shapes.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef enum prim_kind { PRIM_SPHERE, PRIM_CAPSULE, PRIM_ELLIPSOID } prim_kind;

typedef struct prim {
    prim_kind kind;
    double a[3];   /* centre (sphere, ellipsoid) or first axis end (capsule) */
    double b[3];   /* second axis end (capsule) */
    double r[3];   /* radius in r[0]; ellipsoid semi-axes r[0..2] */
    int part;
} prim;

typedef struct rng {
    uint64_t s;
} rng;

static double rng_uniform(rng *g) {
    g->s ^= g->s >> 12;
    g->s ^= g->s << 25;
    g->s ^= g->s >> 27;
    uint64_t x = g->s * 2685821657736338717ULL;
    return (double)(x >> 11) * (1.0 / 9007199254740992.0);
}

/* A uniform point on the unit sphere (Archimedes: z uniform in [-1, 1]). */
static void unit_sphere_point(rng *g, double u[3]) {
    double z = 2.0 * rng_uniform(g) - 1.0;
    double phi = 2.0 * PI * rng_uniform(g);
    double rho = sqrt(1.0 - z * z);
    u[0] = rho * cos(phi);
    u[1] = rho * sin(phi);
    u[2] = z;
}

static double dot3(const double x[3], const double y[3]) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

static double capsule_length(const prim *p) {
    double d[3] = {p->b[0] - p->a[0], p->b[1] - p->a[1], p->b[2] - p->a[2]};
    return sqrt(dot3(d, d));
}

/* Thomsen's approximation of the ellipsoid area (relative error < 1.1%). */
static double ellipsoid_area(const double r[3]) {
    const double e = 1.6075;
    double ab = pow(r[0] * r[1], e), ac = pow(r[0] * r[2], e), bc = pow(r[1] * r[2], e);
    return 4.0 * PI * pow((ab + ac + bc) / 3.0, 1.0 / e);
}

static double prim_area(const prim *p) {
    switch (p->kind) {
    case PRIM_SPHERE: return 4.0 * PI * p->r[0] * p->r[0];
    case PRIM_CAPSULE:
        return 2.0 * PI * p->r[0] * capsule_length(p) + 4.0 * PI * p->r[0] * p->r[0];
    case PRIM_ELLIPSOID: return ellipsoid_area(p->r);
    }
    return 0.0;
}

static double segment_distance(const double x[3], const double a[3], const double b[3]) {
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
    double len2 = dot3(d, d);
    double t = len2 > 0.0 ? dot3(v, d) / len2 : 0.0;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    double w[3] = {v[0] - t * d[0], v[1] - t * d[1], v[2] - t * d[2]};
    return sqrt(dot3(w, w));
}

/* Strictly inside (a hair of margin keeps shared boundary points). */
static int prim_contains(const prim *p, const double x[3]) {
    const double margin = 1e-9;
    switch (p->kind) {
    case PRIM_SPHERE: {
        double v[3] = {x[0] - p->a[0], x[1] - p->a[1], x[2] - p->a[2]};
        return sqrt(dot3(v, v)) < p->r[0] - margin;
    }
    case PRIM_CAPSULE: return segment_distance(x, p->a, p->b) < p->r[0] - margin;
    case PRIM_ELLIPSOID: {
        double s = 0.0;
        for (int i = 0; i < 3; i++) {
            double c = (x[i] - p->a[i]) / p->r[i];
            s += c * c;
        }
        return s < 1.0 - margin;
    }
    }
    return 0;
}

/* Two unit vectors completing the unit vector d to an orthonormal frame. */
static void frame_of(const double d[3], double e1[3], double e2[3]) {
    double h[3] = {1.0, 0.0, 0.0};
    if (fabs(d[0]) > 0.9) h[0] = 0.0, h[1] = 1.0;
    e1[0] = d[1] * h[2] - d[2] * h[1];
    e1[1] = d[2] * h[0] - d[0] * h[2];
    e1[2] = d[0] * h[1] - d[1] * h[0];
    double len = sqrt(dot3(e1, e1));
    for (int i = 0; i < 3; i++) e1[i] /= len;
    e2[0] = d[1] * e1[2] - d[2] * e1[1];
    e2[1] = d[2] * e1[0] - d[0] * e1[2];
    e2[2] = d[0] * e1[1] - d[1] * e1[0];
}

/* Side of a capsule: cylinder with probability (cylinder area / total),
 * else a uniform sphere point moved to the end cap on its side. */
static void capsule_point(const prim *p, rng *g, double x[3]) {
    double len = capsule_length(p), r = p->r[0];
    double d[3] = {(p->b[0] - p->a[0]) / len, (p->b[1] - p->a[1]) / len,
                   (p->b[2] - p->a[2]) / len};
    double cyl = 2.0 * PI * r * len;
    if (rng_uniform(g) * prim_area(p) < cyl) {
        double e1[3], e2[3];
        frame_of(d, e1, e2);
        double t = rng_uniform(g) * len, phi = 2.0 * PI * rng_uniform(g);
        for (int i = 0; i < 3; i++)
            x[i] = p->a[i] + t * d[i] + r * (cos(phi) * e1[i] + sin(phi) * e2[i]);
        return;
    }
    double u[3];
    unit_sphere_point(g, u);
    const double *end = dot3(u, d) >= 0.0 ? p->b : p->a;
    for (int i = 0; i < 3; i++) x[i] = end[i] + r * u[i];
}

/* Uniform on the ellipsoid: map a sphere point, accept it with probability
 * proportional to the local area stretch. */
static void ellipsoid_point(const prim *p, rng *g, double x[3]) {
    const double *r = p->r;
    double bc = r[1] * r[2], ac = r[0] * r[2], ab = r[0] * r[1];
    double most = fmax(bc, fmax(ac, ab));
    double u[3];
    for (;;) {
        unit_sphere_point(g, u);
        double stretch = sqrt(bc * bc * u[0] * u[0] + ac * ac * u[1] * u[1] +
                              ab * ab * u[2] * u[2]);
        if (rng_uniform(g) * most <= stretch) break;
    }
    for (int i = 0; i < 3; i++) x[i] = p->a[i] + r[i] * u[i];
}

static void prim_point(const prim *p, rng *g, double x[3]) {
    switch (p->kind) {
    case PRIM_SPHERE: {
        double u[3];
        unit_sphere_point(g, u);
        for (int i = 0; i < 3; i++) x[i] = p->a[i] + p->r[0] * u[i];
        return;
    }
    case PRIM_CAPSULE: capsule_point(p, g, x); return;
    case PRIM_ELLIPSOID: ellipsoid_point(p, g, x); return;
    }
}

static int covered_by_other(const prim *prims, int count, int self, const double x[3]) {
    for (int j = 0; j < count; j++)
        if (j != self && prim_contains(&prims[j], x)) return 1;
    return 0;
}

static double *sample_union(const prim *prims, int count, double density, size_t *n,
                            int **part) {
    size_t cap = 0, want[16];
    for (int i = 0; i < count; i++) {
        want[i] = (size_t)lround(density * prim_area(&prims[i]));
        cap += want[i];
    }
    double *pts = malloc((cap ? cap : 1) * 3 * sizeof *pts);
    int *ids = part ? malloc((cap ? cap : 1) * sizeof *ids) : NULL;
    if (!pts || (part && !ids)) {
        free(pts);
        free(ids);
        *n = 0;
        if (part) *part = NULL;
        return NULL;
    }
    rng g = {0x9E3779B97F4A7C15ULL};
    size_t kept = 0;
    for (int i = 0; i < count; i++) {
        for (size_t s = 0; s < want[i]; s++) {
            double x[3];
            prim_point(&prims[i], &g, x);
            if (covered_by_other(prims, count, i, x)) continue;
            memcpy(&pts[3 * kept], x, sizeof x);
            if (ids) ids[kept] = prims[i].part;
            kept++;
        }
    }
    *n = kept;
    if (part) *part = ids;
    return pts;
}

static prim sphere_prim(double cx, double cy, double cz, double r, int part) {
    return (prim){PRIM_SPHERE, {cx, cy, cz}, {0, 0, 0}, {r, r, r}, part};
}

static prim capsule_prim(const double a[3], const double b[3], double r, int part) {
    return (prim){PRIM_CAPSULE, {a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {r, r, r}, part};
}

double *ps_shape_dumbbell(double density, size_t *n, int **part) {
    const double left[3] = {-2.0, 0.0, 0.0}, right[3] = {2.0, 0.0, 0.0};
    prim prims[3] = {sphere_prim(-2.0, 0.0, 0.0, 1.0, 1),
                     sphere_prim(2.0, 0.0, 0.0, 1.0, 2),
                     capsule_prim(left, right, 0.25, 0)};
    return sample_union(prims, 3, density > 0.0 ? density : 105.0, n, part);
}

double *ps_shape_hand(double density, size_t *n, int **part) {
    const double palm[3] = {1.6, 2.0, 0.6};
    const double angle_deg[5] = {-70.0, -30.0, -5.0, 20.0, 45.0};
    const double length[5] = {1.6, 2.4, 2.8, 2.6, 2.0};
    const double radius[5] = {0.34, 0.3, 0.3, 0.3, 0.27};
    prim prims[6];
    prims[0] = (prim){PRIM_ELLIPSOID, {0, 0, 0}, {0, 0, 0}, {palm[0], palm[1], palm[2]}, 0};
    for (int f = 0; f < 5; f++) {
        double th = angle_deg[f] * PI / 180.0;
        double d[3] = {sin(th), cos(th), 0.0};
        double rim = 1.0 / sqrt(d[0] * d[0] / (palm[0] * palm[0]) +
                                d[1] * d[1] / (palm[1] * palm[1]));
        double base = 0.75 * rim, tip = rim + length[f];
        double a[3] = {base * d[0], base * d[1], 0.0}, b[3] = {tip * d[0], tip * d[1], 0.0};
        prims[f + 1] = capsule_prim(a, b, radius[f], f + 1);
    }
    return sample_union(prims, 6, density > 0.0 ? density : 82.0, n, part);
}

double *ps_shape_star(double density, size_t *n, int **part) {
    const double arm = 3.5, r = 0.35;
    prim prims[7];
    prims[0] = sphere_prim(0.0, 0.0, 0.0, 1.2, 0);
    for (int i = 0; i < 6; i++) {
        double a[3] = {0.0, 0.0, 0.0}, b[3] = {0.0, 0.0, 0.0};
        b[i / 2] = i % 2 ? -arm : arm;
        prims[i + 1] = capsule_prim(a, b, r, i + 1);
    }
    return sample_union(prims, 7, density > 0.0 ? density : 78.0, n, part);
}

double *ps_shape_sphere(double density, size_t *n, int **part) {
    prim s = sphere_prim(0.0, 0.0, 0.0, 1.0, 0);
    return sample_union(&s, 1, density > 0.0 ? density : 200.0, n, part);
}

void ps_shape_transform(double *pts, size_t n, double ax, double ay, double az,
                        double angle, double s, const double t[3]) {
    double len = sqrt(ax * ax + ay * ay + az * az);
    double k[3] = {0.0, 0.0, 1.0};
    if (len > 0.0) k[0] = ax / len, k[1] = ay / len, k[2] = az / len;
    double c = cos(angle), sn = sin(angle), v = 1.0 - c;
    double R[3][3] = {
        {c + k[0] * k[0] * v, k[0] * k[1] * v - k[2] * sn, k[0] * k[2] * v + k[1] * sn},
        {k[1] * k[0] * v + k[2] * sn, c + k[1] * k[1] * v, k[1] * k[2] * v - k[0] * sn},
        {k[2] * k[0] * v - k[1] * sn, k[2] * k[1] * v + k[0] * sn, c + k[2] * k[2] * v}};
    for (size_t p = 0; p < n; p++) {
        double *x = &pts[3 * p], y[3];
        for (int i = 0; i < 3; i++)
            y[i] = s * (R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2]) + (t ? t[i] : 0.0);
        memcpy(x, y, sizeof y);
    }
}
