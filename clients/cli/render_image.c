/*
 * render_image.c: the software renderer of `pointseg render`
 * (render_image.h).  The camera is an orthonormal frame (right, up,
 * toward); a point projects to pixel (cx + s * x.right, cy - s * x.up) at
 * depth x.toward (larger = nearer).  The scale s fits the projected
 * bounding box into the image with a margin.
 */
#include "render_image.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MARGIN 0.06   /* fraction of the image left free on each side */
#define AMBIENT 0.35  /* light everywhere; the rest is Lambert */
#define NO_DEPTH (-FLT_MAX)

typedef struct camera {
    double right[3], up[3], toward[3], light[3];
    double scale, offset_x, offset_y; /* pixel = offset + scale * coordinate */
} camera;

typedef struct frame {
    int width, height;
    unsigned char *image; /* #height by #width by 3 */
    float *depth;         /* #height by #width, NO_DEPTH = empty */
} frame;

static double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static int normalize3(double v[3]) {
    double len = sqrt(dot3(v, v));
    if (!(len > 0)) return -1;
    for (int c = 0; c < 3; c++) v[c] /= len;
    return 0;
}

static void point_xyz(const cli_scene *s, size_t i, double out[3]) {
    const double *x = s->points + i * (size_t)s->dim;
    for (int c = 0; c < 3; c++) out[c] = c < s->dim ? x[c] : 0.0;
}

/* right, up, toward from the view; the light comes from above-left of the
 * eye. */
static int make_frame(const cli_view *v, camera *cam) {
    memcpy(cam->toward, v->toward, sizeof cam->toward);
    if (normalize3(cam->toward)) return -1;
    cross3(v->up, cam->toward, cam->right);
    if (normalize3(cam->right)) return -1;
    cross3(cam->toward, cam->right, cam->up);
    for (int c = 0; c < 3; c++)
        cam->light[c] = cam->toward[c] + 0.5 * cam->up[c] - 0.4 * cam->right[c];
    normalize3(cam->light);
    return 0;
}

/* Scale and offsets that fit every projected point in the image. */
static void fit_view(const cli_scene *s, int width, int height, camera *cam) {
    double lo[2] = {DBL_MAX, DBL_MAX}, hi[2] = {-DBL_MAX, -DBL_MAX}, p[3];
    for (size_t i = 0; i < s->n; i++) {
        point_xyz(s, i, p);
        double xy[2] = {dot3(p, cam->right), dot3(p, cam->up)};
        for (int c = 0; c < 2; c++) {
            if (xy[c] < lo[c]) lo[c] = xy[c];
            if (xy[c] > hi[c]) hi[c] = xy[c];
        }
    }
    double span_x = hi[0] - lo[0], span_y = hi[1] - lo[1];
    double sx = span_x > 0 ? width * (1 - 2 * MARGIN) / span_x : DBL_MAX;
    double sy = span_y > 0 ? height * (1 - 2 * MARGIN) / span_y : DBL_MAX;
    cam->scale = sx < sy ? sx : sy;
    if (cam->scale == DBL_MAX) cam->scale = 1;
    cam->offset_x = width / 2.0 - cam->scale * (lo[0] + hi[0]) / 2;
    cam->offset_y = height / 2.0 + cam->scale * (lo[1] + hi[1]) / 2;
}

/* Pixel x, pixel y (down) and depth in pixel units. */
static void project(const camera *cam, const double p[3], double out[3]) {
    out[0] = cam->offset_x + cam->scale * dot3(p, cam->right);
    out[1] = cam->offset_y - cam->scale * dot3(p, cam->up);
    out[2] = cam->scale * dot3(p, cam->toward);
}

/* Lambert, two-sided (scans have no consistent orientation). */
static double lambert(const camera *cam, const double normal[3]) {
    return AMBIENT + (1 - AMBIENT) * fabs(dot3(normal, cam->light));
}

static void put_pixel(frame *f, size_t at, const unsigned char rgb[3], double light) {
    for (int c = 0; c < 3; c++)
        f->image[3 * at + (size_t)c] = (unsigned char)(rgb[c] * light + 0.5);
}

/* ---- triangles ----------------------------------------------------------- */

/* The colour most of the corners share (the first corner's on a tie). */
static const unsigned char *face_color(const cli_scene *s, const uint32_t *face) {
    const unsigned char *a = s->rgb + 3 * (size_t)face[0], *b = s->rgb + 3 * (size_t)face[1],
                        *c = s->rgb + 3 * (size_t)face[2];
    return memcmp(a, b, 3) != 0 && memcmp(b, c, 3) == 0 ? b : a;
}

static double edge(const double a[3], const double b[3], double x, double y) {
    return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
}

static int clamp_int(double v, int lo, int hi) {
    return v < lo ? lo : v > hi ? hi : (int)v;
}

/* Fills the pixels whose centres lie inside the projected triangle v. */
static void fill_triangle(frame *f, const double v[3][3], const unsigned char rgb[3],
                          double light) {
    double area = edge(v[0], v[1], v[2][0], v[2][1]);
    if (area == 0) return;
    int x0 = clamp_int(floor(fmin(v[0][0], fmin(v[1][0], v[2][0]))), 0, f->width - 1);
    int x1 = clamp_int(ceil(fmax(v[0][0], fmax(v[1][0], v[2][0]))), 0, f->width - 1);
    int y0 = clamp_int(floor(fmin(v[0][1], fmin(v[1][1], v[2][1]))), 0, f->height - 1);
    int y1 = clamp_int(ceil(fmax(v[0][1], fmax(v[1][1], v[2][1]))), 0, f->height - 1);
    for (int y = y0; y <= y1; y++) {
        for (int x = x0; x <= x1; x++) {
            double px = x + 0.5, py = y + 0.5;
            double w0 = edge(v[1], v[2], px, py) / area, w1 = edge(v[2], v[0], px, py) / area;
            double w2 = 1 - w0 - w1;
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            float z = (float)(w0 * v[0][2] + w1 * v[1][2] + w2 * v[2][2]);
            size_t at = (size_t)y * (size_t)f->width + (size_t)x;
            if (z <= f->depth[at]) continue;
            f->depth[at] = z;
            put_pixel(f, at, rgb, light);
        }
    }
}

static void draw_faces(const cli_scene *s, const camera *cam, frame *f) {
    double corner[3][3], screen[3][3], e1[3], e2[3], normal[3];
    for (size_t t = 0; t < s->n_faces; t++) {
        const uint32_t *face = s->faces + 3 * t;
        for (int k = 0; k < 3; k++) {
            point_xyz(s, face[k], corner[k]);
            project(cam, corner[k], screen[k]);
        }
        for (int c = 0; c < 3; c++) {
            e1[c] = corner[1][c] - corner[0][c];
            e2[c] = corner[2][c] - corner[0][c];
        }
        cross3(e1, e2, normal);
        if (normalize3(normal)) continue;
        fill_triangle(f, (const double(*)[3])screen, face_color(s, face), lambert(cam, normal));
    }
}

/* ---- points -------------------------------------------------------------- */

/* Splat radius in pixels: about the spacing of n points spread over the
 * projected area (half of them facing the eye). */
static int splat_radius(const cli_scene *s, int width, int height) {
    double area = width * height * (1 - 2 * MARGIN) * (1 - 2 * MARGIN) * 0.5;
    double spacing = s->n ? sqrt(area / ((double)s->n / 2)) : 1;
    int r = (int)(0.6 * spacing + 0.5);
    return r < 1 ? 1 : r > 12 ? 12 : r;
}

/* Draws each point as a disc at its own depth; owner (#height by #width)
 * gets the index of the point that won each pixel. */
static void splat_points(const cli_scene *s, const camera *cam, frame *f, size_t *owner) {
    int r = splat_radius(s, f->width, f->height);
    double p[3], q[3];
    for (size_t i = 0; i < s->n; i++) {
        point_xyz(s, i, p);
        project(cam, p, q);
        int cx = (int)floor(q[0]), cy = (int)floor(q[1]);
        for (int y = cy - r; y <= cy + r; y++) {
            for (int x = cx - r; x <= cx + r; x++) {
                if (x < 0 || y < 0 || x >= f->width || y >= f->height) continue;
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > r * r) continue;
                size_t at = (size_t)y * (size_t)f->width + (size_t)x;
                if ((float)q[2] <= f->depth[at]) continue;
                f->depth[at] = (float)q[2];
                owner[at] = i;
            }
        }
    }
}

/* Depth slope along one axis at pixel at (0 where a neighbour is empty). */
static double depth_slope(const frame *f, size_t at, size_t step, int has_before, int has_after) {
    float before = has_before ? f->depth[at - step] : NO_DEPTH;
    float after = has_after ? f->depth[at + step] : NO_DEPTH;
    if (before == NO_DEPTH || after == NO_DEPTH) return 0;
    return (after - before) / 2.0;
}

/* Shades every covered pixel from the normal of the depth image, in the
 * camera frame (right, -down, toward). */
static void shade_points(const cli_scene *s, const camera *cam, frame *f, const size_t *owner) {
    for (int y = 0; y < f->height; y++) {
        for (int x = 0; x < f->width; x++) {
            size_t at = (size_t)y * (size_t)f->width + (size_t)x;
            if (f->depth[at] == NO_DEPTH) continue;
            double dx = depth_slope(f, at, 1, x > 0, x + 1 < f->width);
            double dy = depth_slope(f, at, (size_t)f->width, y > 0, y + 1 < f->height);
            double normal[3];
            for (int c = 0; c < 3; c++)
                normal[c] = -dx * cam->right[c] + dy * cam->up[c] + cam->toward[c];
            normalize3(normal);
            put_pixel(f, at, s->rgb + 3 * owner[at], lambert(cam, normal));
        }
    }
}

static int draw_points(const cli_scene *s, const camera *cam, frame *f) {
    size_t *owner = malloc((size_t)f->width * (size_t)f->height * sizeof *owner);
    if (!owner) return -1;
    splat_points(s, cam, f, owner);
    shade_points(s, cam, f, owner);
    free(owner);
    return 0;
}

int cli_render_image(const cli_scene *s, const cli_view *v, unsigned char *image) {
    camera cam;
    size_t pixels = (size_t)v->width * (size_t)v->height;
    frame f = {v->width, v->height, image, malloc(pixels * sizeof(float))};
    if (!f.depth || make_frame(v, &cam)) {
        free(f.depth);
        return -1;
    }
    for (size_t i = 0; i < pixels; i++) f.depth[i] = NO_DEPTH;
    memset(image, 255, pixels * 3);
    fit_view(s, v->width, v->height, &cam);
    int rc = 0;
    if (s->n_faces) draw_faces(s, &cam, &f);
    else rc = draw_points(s, &cam, &f);
    free(f.depth);
    return rc;
}
