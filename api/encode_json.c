/*
 * encode_json.c: a ps_result as the JSON document (encode.h).  The small,
 * structured part (segments, supernodes, hierarchy, merges, params, timings)
 * is built with cJSON; the per-point arrays (labels, and on request
 * point_supernode and centrality) are written straight into a text buffer
 * and spliced in as raw JSON, since one cJSON node per point is slow.
 * Non-finite numbers are written as null.
 */
#include "encode.h"
#include "number_text.h"

#include <cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- per-point arrays as text ------------------------------------------- */

/* "[v0,v1,...]" for #n ints; malloc'ed, NULL when out of memory. */
static char *int_array_text(const int *v, size_t n) {
    char *text = malloc(n * (PS_INT_TEXT_MAX + 1) + 3);
    if (!text) return NULL;
    char *p = text;
    *p++ = '[';
    for (size_t i = 0; i < n; i++) {
        if (i) *p++ = ',';
        p = ps_put_int(p, v[i]);
    }
    *p++ = ']';
    *p = 0;
    return text;
}

static char *double_array_text(const double *v, size_t n) {
    char *text = malloc(n * (PS_DOUBLE_TEXT_MAX + 1) + 3);
    if (!text) return NULL;
    char *p = text;
    *p++ = '[';
    for (size_t i = 0; i < n; i++) {
        if (i) *p++ = ',';
        p = ps_put_double(p, v[i]);
    }
    *p++ = ']';
    *p = 0;
    return text;
}

/* Adds item under name; on failure deletes it.  0 or -1 (also for a NULL
 * item, so a failed create passes straight through). */
static int attach(cJSON *obj, const char *name, cJSON *item) {
    if (item && cJSON_AddItemToObject(obj, name, item)) return 0;
    cJSON_Delete(item);
    return -1;
}

/* Adds text (taken over and freed) as raw JSON under name. */
static int add_raw(cJSON *obj, const char *name, char *text) {
    cJSON *raw = text ? cJSON_CreateRaw(text) : NULL;
    free(text);
    return attach(obj, name, raw);
}

/* ---- small structured parts --------------------------------------------- */

static int add_number(cJSON *obj, const char *name, double v) {
    return attach(obj, name, isfinite(v) ? cJSON_CreateNumber(v) : cJSON_CreateNull());
}

/* A JSON array of #n ints (an empty array when n == 0). */
static int add_int_array(cJSON *obj, const char *name, const int *v, int n) {
    return attach(obj, name, n > 0 && v ? cJSON_CreateIntArray(v, n) : cJSON_CreateArray());
}

/* Appends a new object to arr; NULL when out of memory. */
static cJSON *append_object(cJSON *arr) {
    cJSON *obj = cJSON_CreateObject();
    if (obj && !cJSON_AddItemToArray(arr, obj)) {
        cJSON_Delete(obj);
        return NULL;
    }
    return obj;
}

static int add_segments(cJSON *doc, const ps_result *r) {
    cJSON *arr = cJSON_AddArrayToObject(doc, "segments");
    if (!arr) return -1;
    for (int i = 0; i < r->n_segments; i++) {
        const ps_segment_info *s = &r->segments[i];
        cJSON *o = append_object(arr);
        if (!o || add_number(o, "id", i) || add_number(o, "size", (double)s->size) ||
            add_number(o, "feature_size", s->feature_size) ||
            add_int_array(o, "supernodes", s->supernodes, s->n_supernodes) ||
            add_number(o, "tree_node", s->tree_node))
            return -1;
    }
    return 0;
}

static int add_supernodes(cJSON *doc, const ps_result *r) {
    cJSON *arr = cJSON_AddArrayToObject(doc, "supernodes");
    if (!arr) return -1;
    for (int i = 0; i < r->n_supernodes; i++) {
        const ps_supernode *s = &r->supernodes[i];
        cJSON *o = append_object(arr);
        if (!o || add_number(o, "id", i) || add_number(o, "sink", (double)s->sink) ||
            add_number(o, "size", (double)s->size) ||
            add_number(o, "centrality", s->centrality) ||
            !cJSON_AddBoolToObject(o, "is_minimum", s->is_minimum != 0) ||
            add_number(o, "segment", s->segment))
            return -1;
    }
    return 0;
}

static int add_tree_node(cJSON *nodes, const ps_tree_node *t) {
    int n_children = t->children[0] >= 0 ? 2 : 0;
    cJSON *o = append_object(nodes);
    return !o || add_number(o, "id", t->id) || add_number(o, "parent", t->parent) ||
                   add_int_array(o, "children", t->children, n_children) ||
                   add_int_array(o, "supernodes", t->supernodes, t->n_supernodes) ||
                   add_number(o, "ncut", t->ncut)
               ? -1
               : 0;
}

static int add_hierarchy(cJSON *doc, const ps_result *r) {
    cJSON *h = cJSON_AddObjectToObject(doc, "hierarchy");
    cJSON *nodes = h ? cJSON_AddArrayToObject(h, "nodes") : NULL;
    if (!nodes) return -1;
    for (int i = 0; i < r->n_tree_nodes; i++)
        if (add_tree_node(nodes, &r->tree[i])) return -1;
    return 0;
}

static int add_merges(cJSON *doc, const ps_result *r) {
    cJSON *arr = cJSON_AddArrayToObject(doc, "merges");
    if (!arr) return -1;
    for (int i = 0; i < r->n_merges; i++) {
        const ps_merge *m = &r->merges[i];
        cJSON *o = append_object(arr);
        if (!o || add_number(o, "segment", m->segment) || add_number(o, "into", m->into) ||
            add_number(o, "feature_size", m->feature_size) ||
            !cJSON_AddStringToObject(o, "step", ps_step_name(m->step)))
            return -1;
    }
    return 0;
}

static int add_params(cJSON *doc, const ps_params *p) {
    cJSON *o = cJSON_AddObjectToObject(doc, "params");
    return !o || !cJSON_AddStringToObject(o, "method", ps_method_name(p->method)) ||
                   add_number(o, "k", p->k) ||
                   !cJSON_AddStringToObject(o, "centrality", ps_centrality_name(p->centrality)) ||
                   add_number(o, "samples", p->samples) ||
                   add_number(o, "persistence", p->persistence) ||
                   add_number(o, "ncut_threshold", p->ncut_threshold) ||
                   add_number(o, "feature_threshold", p->feature_threshold) ||
                   !cJSON_AddBoolToObject(o, "minima", p->use_minima != 0) ||
                   !cJSON_AddBoolToObject(o, "f2", p->use_f2 != 0) ||
                   !cJSON_AddBoolToObject(o, "smooth_normals", p->smooth_normals != 0) ||
                   add_number(o, "threads", p->threads)
               ? -1
               : 0;
}

/* timings_ms: each phase's, the total, and "steps": each step's (0 for a
 * step the method or input did not call for). */
static int add_timings(cJSON *doc, const ps_timings *t) {
    cJSON *o = cJSON_AddObjectToObject(doc, "timings_ms");
    if (!o) return -1;
    for (int ph = 0; ph < PS_PHASE_COUNT; ph++)
        if (add_number(o, ps_phase_name((ps_phase)ph), t->ms[ph])) return -1;
    if (add_number(o, "total", t->total_ms)) return -1;
    cJSON *steps = cJSON_AddObjectToObject(o, "steps");
    if (!steps) return -1;
    for (int s = 0; s < PS_STEP_COUNT; s++)
        if (add_number(steps, ps_step_name((ps_step)s), t->step_ms[s])) return -1;
    return 0;
}

static int add_warnings(cJSON *doc, const ps_pointset *in) {
    cJSON *arr = cJSON_AddArrayToObject(doc, "warnings");
    if (!arr) return -1;
    for (int i = 0; in && i < in->n_warnings; i++) {
        cJSON *w = cJSON_CreateString(in->warnings[i]);
        if (!w || !cJSON_AddItemToArray(arr, w)) return cJSON_Delete(w), -1;
    }
    return 0;
}

/* Per-point arrays the caller asked for (and the result has). */
static int add_included(cJSON *doc, const ps_result *r, unsigned include) {
    if ((include & PS_INCLUDE_POINT_SUPERNODE) && r->point_supernode &&
        add_raw(doc, "point_supernode", int_array_text(r->point_supernode, r->n_points)))
        return -1;
    if ((include & PS_INCLUDE_CENTRALITY) && r->centrality &&
        add_raw(doc, "centrality", double_array_text(r->centrality, r->n_points)))
        return -1;
    return 0;
}

static int fill_document(cJSON *doc, const ps_pointset *in, const ps_result *r, unsigned include) {
    size_t n_labels = r->labels ? r->n_points : 0;
    if (add_number(doc, "n_points", (double)r->n_points) || add_number(doc, "dimension", r->dim) ||
        add_number(doc, "n_components", r->n_components) ||
        add_number(doc, "normal_smoothing", r->normal_smoothing) ||
        add_number(doc, "n_filled", (double)r->n_filled) ||
        add_number(doc, "n_outliers", (double)r->n_outliers) ||
        add_raw(doc, "labels", int_array_text(r->labels, n_labels)) ||
        add_number(doc, "n_segments", r->n_segments))
        return -1;
    if (add_segments(doc, r) || add_supernodes(doc, r) || add_hierarchy(doc, r) ||
        add_merges(doc, r) || add_params(doc, &r->params) || add_timings(doc, &r->timings) ||
        add_warnings(doc, in))
        return -1;
    return add_included(doc, r, include);
}

char *ps_encode_json(const ps_pointset *in, const ps_result *r, unsigned include, size_t *len) {
    cJSON *doc = cJSON_CreateObject();
    char *text = NULL;
    if (doc && fill_document(doc, in, r, include) == 0) text = cJSON_PrintUnformatted(doc);
    cJSON_Delete(doc);
    if (text && len) *len = strlen(text);
    return text;
}
