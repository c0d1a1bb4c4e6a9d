/* pointset.c: a decoded ps_pointset's warnings, its core input and its
 * release. */
#include "pointset.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ps_pointset_warn(ps_pointset *ps, const char *fmt, ...) {
    if (ps->n_warnings == PS_MAX_WARNINGS) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(ps->warnings[ps->n_warnings++], PS_WARNING_MAX, fmt, ap);
    va_end(ap);
}

ps_input ps_pointset_input(const ps_pointset *ps) {
    ps_input in = {.points = ps->points, .n = ps->n, .dim = ps->dim, .normals = ps->normals,
                   .faces = ps->faces, .n_faces = ps->faces ? ps->n_faces : 0};
    return in;
}

void ps_pointset_free(ps_pointset *ps) {
    if (!ps) return;
    free(ps->points);
    free(ps->normals);
    free(ps->colors);
    free(ps->faces);
    for (size_t i = 0; i < ps->n_params; i++) {
        free(ps->params[i].name);
        free(ps->params[i].value);
    }
    free(ps->params);
    memset(ps, 0, sizeof *ps);
}
