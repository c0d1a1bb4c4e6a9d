/* random_shapes.c: the end-to-end tests' random surfaces (random_shapes.h). */
#include "random_shapes.h"
#include "random_bits.h"

#include <math.h>
#include <stdlib.h>

void ps_random_ball(double *pts, size_t n, double cx, double stretch, uint64_t seed) {
    for (size_t k = 0; k < n; k++) {
        double z = 2 * ps_uniform_next(&seed) - 1, a = 6.283185307179586 * ps_uniform_next(&seed);
        double r = sqrt(1 - z * z);
        pts[3 * k] = cx + r * cos(a), pts[3 * k + 1] = r * sin(a), pts[3 * k + 2] = stretch * z;
    }
}

double *ps_plain_sheet(int kind, size_t n) {
    double *pts = malloc(n * 3 * sizeof *pts);
    uint64_t state = 0x2545F4914F6CDD1DULL + (unsigned)kind;
    for (size_t k = 0; pts && k < n;) {
        double x = 2 * ps_uniform_next(&state) - 1, y = 2 * ps_uniform_next(&state) - 1;
        double r2 = x * x + y * y;
        if (kind > 0 && r2 >= 1) continue;
        double z = 0;
        if (kind == 2) { /* the disc lifted onto the cap, area-preserving (Lambert) */
            double s = sqrt(2 - r2);
            x *= s, y *= s, z = 1 - r2;
        }
        pts[3 * k] = x, pts[3 * k + 1] = y, pts[3 * k + 2] = z, k++;
    }
    return pts;
}

double *ps_random_box(double a, double b, double c, size_t n, uint64_t seed) {
    double *pts = malloc(n * 3 * sizeof *pts);
    const double side[3] = {a * b, a * c, b * c}, total = 2 * (side[0] + side[1] + side[2]);
    for (size_t k = 0; pts && k < n; k++) {
        double pick = total * ps_uniform_next(&seed), u = ps_uniform_next(&seed),
               v = ps_uniform_next(&seed);
        int face = 0;
        while (face < 5 && pick > side[face / 2]) pick -= side[face / 2], face++;
        double far = face % 2 ? 1 : 0, *p = pts + 3 * k;
        if (face < 2) p[0] = u * a, p[1] = v * b, p[2] = far * c;
        else if (face < 4) p[0] = u * a, p[1] = far * b, p[2] = v * c;
        else p[0] = far * a, p[1] = u * b, p[2] = v * c;
    }
    return pts;
}

double *ps_flat_hand(size_t *n, int **part) {
    const size_t palm = 3000, finger = 500, total = palm + 5 * finger;
    double *pts = malloc(total * 3 * sizeof *pts);
    *part = malloc(total * sizeof **part);
    uint64_t state = 2463534242ULL;
    size_t k = 0;
    while (pts && *part && k < total) {
        double u[2];
        for (int j = 0; j < 2; j++) u[j] = ps_uniform_next(&state);
        int which = k < palm ? 0 : 1 + (int)((k - palm) / finger);
        double x = 2 * u[0] - 1, y = 2 * u[1] - 1;
        if (which == 0 && x * x + y * y > 1) continue;
        if (which > 0) {
            double a = 3.14159265358979 * (0.15 + 0.175 * (which - 1));
            double t = 0.9 + 1.7 * u[0], w = 0.24 * u[1] - 0.12;
            x = t * cos(a) - w * sin(a), y = t * sin(a) + w * cos(a);
        }
        pts[3 * k] = x, pts[3 * k + 1] = y, pts[3 * k + 2] = 0;
        (*part)[k++] = which;
    }
    *n = total;
    return pts;
}

double *ps_bent_plus(double reach, size_t *n, int **part) {
    const size_t total = 20000;
    double *pts = malloc(total * 3 * sizeof *pts);
    *part = malloc(total * sizeof **part);
    uint64_t state = 0x9E3779B97F4A7C15ULL;
    size_t k = 0;
    while (pts && *part && k < total) {
        double u = reach * (2 * ps_uniform_next(&state) - 1);
        double v = reach * (2 * ps_uniform_next(&state) - 1);
        if (fabs(u) >= 1 && fabs(v) >= 1) continue;
        int arm = fabs(u) < 1 && fabs(v) < 1 ? 0 : fabs(u) >= 1 ? (u > 0 ? 1 : 2) : (v > 0 ? 3 : 4);
        pts[3 * k] = 3 * sin(u / 3), pts[3 * k + 1] = v, pts[3 * k + 2] = 3 * cos(u / 3);
        (*part)[k++] = arm;
    }
    *n = total;
    return pts;
}
