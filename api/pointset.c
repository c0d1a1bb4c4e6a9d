/* pointset.c: releasing a decoded ps_pointset. */
#include "pointset.h"

#include <stdlib.h>
#include <string.h>

void ps_pointset_free(ps_pointset *ps) {
    if (!ps) return;
    free(ps->points);
    free(ps->normals);
    free(ps->faces);
    for (size_t i = 0; i < ps->n_params; i++) {
        free(ps->params[i].name);
        free(ps->params[i].value);
    }
    free(ps->params);
    memset(ps, 0, sizeof *ps);
}
