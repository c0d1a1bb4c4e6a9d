/*
 * render_image.h: a small software renderer for `pointseg render`: an
 * orthographic view of a coloured point set fitted to the image, with
 * Lambert shading.  Triangles (when given) are rasterized with flat shading
 * from their normals; otherwise points are splatted into a z-buffer and
 * shaded from the normals of the depth image.
 */
#ifndef PS_CLI_RENDER_IMAGE_H
#define PS_CLI_RENDER_IMAGE_H

#include <stddef.h>
#include <stdint.h>

typedef struct cli_scene {
    size_t n;                  /* #P */
    int dim;                   /* coordinates per point; the first 3 are used (z = 0 if 2) */
    const double *points;      /* #P by dim */
    const unsigned char *rgb;  /* #P by 3 colours */
    size_t n_faces;            /* #F, 0 = render the points */
    const uint32_t *faces;     /* #F by 3 indices into points, or NULL */
} cli_scene;

typedef struct cli_view {
    int width, height;  /* pixels, each >= 1 */
    double toward[3];   /* direction from the model to the eye (need not be unit) */
    double up[3];       /* roughly up on the picture (projected; not parallel to toward) */
} cli_view;

/* Renders s seen from v into image (#height rows by #width pixels by 3
 * bytes, top row first; background white).  Returns 0, or -1 when out of
 * memory or v.toward is zero or parallel to v.up. */
int cli_render_image(const cli_scene *s, const cli_view *v, unsigned char *image);

#endif
