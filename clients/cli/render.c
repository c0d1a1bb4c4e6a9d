/*
 * render.c: `pointseg render IN.ply -o OUT.png [--width W] [--height H]
 * [--view x,y,z] [--up x,y,z]`: draws a coloured PLY (pointseg's `--output ply`) as a
 * PNG: an orthographic, Lambert-shaded view fitted to the model, triangles
 * when the file has faces, else point splats (render_image.h).
 */
#include "commands.h"
#include "decode.h"
#include "png_write.h"
#include "render_image.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { HELP_SHOWN = -1, MAX_SIDE = 8192, GREY = 200 };

typedef struct render_args {
    const char *input, *output;
    cli_view view;
} render_args;

static const char render_usage[] =
    "usage: pointseg render IN.ply -o OUT.png [--width W] [--height H]\n"
    "                       [--view X,Y,Z] [--up X,Y,Z]\n"
    "\n"
    "Draws a coloured PLY (the output of `pointseg segment --output ply`) as a\n"
    "PNG: an orthographic view fitted to the model, Lambert shaded; triangles\n"
    "with flat shading when the file has faces, else one disc per point.\n"
    "\n"
    "  -o OUT.png      the picture to write (required)\n"
    "  --width W       pixels (default 800)\n"
    "  --height H      pixels (default 600)\n"
    "  --view X,Y,Z    direction from the model to the eye (default 0,0,1)\n"
    "  --up X,Y,Z      the direction drawn upwards (default 0,1,0)\n"
    "  -h, --help      this text\n"
    "\n"
    "Vertices without colours are drawn grey.\n"
    "Exit status: 0 ok, 1 internal failure, 2 bad input or usage.\n";

static int usage_error(const char *what, const char *message) {
    fprintf(stderr, "pointseg: %s: %s\ntry 'pointseg render --help'\n", what, message);
    return EXIT_USAGE;
}

static int parse_side(const char *option, const char *text, int *out) {
    char *end;
    errno = 0;
    long v = strtol(text, &end, 10);
    if (errno || end == text || *end || v < 1 || v > MAX_SIDE)
        return usage_error(option, "expected an integer from 1 to 8192");
    *out = (int)v;
    return 0;
}

static int parse_direction(const char *option, const char *text, double out[3]) {
    char *end;
    const char *p = text;
    for (int c = 0; c < 3; c++) {
        out[c] = strtod(p, &end);
        if (end == p || *end != (c < 2 ? ',' : '\0')) return usage_error(option, "expected X,Y,Z");
        p = end + 1;
    }
    if (out[0] == 0 && out[1] == 0 && out[2] == 0) return usage_error(option, "direction is zero");
    return 0;
}

/* One option with its value at argv[*i]; 0 or an exit status. */
static int parse_option(int argc, char **argv, int *i, render_args *a) {
    const char *opt = argv[*i];
    if (strcmp(opt, "-o") && strcmp(opt, "--width") && strcmp(opt, "--height") &&
        strcmp(opt, "--view") && strcmp(opt, "--up"))
        return usage_error(opt, "unknown option");
    if (*i + 1 >= argc) return usage_error(opt, "option needs a value");
    const char *value = argv[++*i];
    if (strcmp(opt, "-o") == 0) a->output = value;
    else if (strcmp(opt, "--width") == 0) return parse_side(opt, value, &a->view.width);
    else if (strcmp(opt, "--height") == 0) return parse_side(opt, value, &a->view.height);
    else if (strcmp(opt, "--view") == 0) return parse_direction(opt, value, a->view.toward);
    else return parse_direction(opt, value, a->view.up);
    return 0;
}

static int parse_args(int argc, char **argv, render_args *a) {
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        int rc = 0;
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) return HELP_SHOWN;
        if (arg[0] == '-' && arg[1]) rc = parse_option(argc, argv, &i, a);
        else if (a->input) rc = usage_error(arg, "more than one input given");
        else a->input = arg;
        if (rc) return rc;
    }
    if (!a->input) return usage_error("render", "no input given");
    if (!a->output) return usage_error("render", "no output given (-o OUT.png)");
    return 0;
}

/* Grey for every point of ps (an input without colours). */
static unsigned char *grey_colors(const ps_pointset *ps) {
    unsigned char *rgb = malloc(ps->n * 3 + 1);
    if (rgb) memset(rgb, GREY, ps->n * 3);
    return rgb;
}

static int draw(const render_args *a, const ps_pointset *ps, const unsigned char *rgb) {
    cli_scene scene = {ps->n, ps->dim, ps->points, rgb, ps->faces ? ps->n_faces : 0, ps->faces};
    unsigned char *image = malloc((size_t)a->view.width * (size_t)a->view.height * 3);
    int rc = image && cli_render_image(&scene, &a->view, image) == 0 ? 0 : EXIT_INTERNAL;
    if (rc) fprintf(stderr, "pointseg: render: out of memory, or --view parallel to --up\n");
    if (!rc && cli_png_write(a->output, image, a->view.width, a->view.height) != 0) {
        fprintf(stderr, "pointseg: %s: %s\n", a->output, strerror(errno));
        rc = EXIT_INTERNAL;
    }
    free(image);
    return rc;
}

static int render_file(const render_args *a) {
    char *bytes = NULL;
    size_t len = 0;
    ps_api_error err;
    ps_pointset ps;
    memset(&ps, 0, sizeof ps);
    int rc = ps_read_file(a->input, &bytes, &len, &err) || ps_decode(bytes, len, NULL, &ps, &err);
    if (rc) {
        fprintf(stderr, "pointseg: %s: %s\n", a->input, err.message);
        rc = err.http_status >= 500 ? EXIT_INTERNAL : EXIT_USAGE;
    } else if (ps.n == 0) {
        rc = usage_error(a->input, "no points to draw");
    } else if (ps.colors) {
        rc = draw(a, &ps, ps.colors);
    } else {
        unsigned char *rgb = grey_colors(&ps);
        rc = rgb ? draw(a, &ps, rgb) : EXIT_INTERNAL;
        free(rgb);
    }
    free(bytes);
    ps_pointset_free(&ps);
    return rc;
}

int cli_render(int argc, char **argv) {
    render_args a = {NULL, NULL, {800, 600, {0, 0, 1}, {0, 1, 0}}};
    int rc = parse_args(argc, argv, &a);
    if (rc == HELP_SHOWN) {
        fputs(render_usage, stdout);
        return 0;
    }
    return rc ? rc : render_file(&a);
}
