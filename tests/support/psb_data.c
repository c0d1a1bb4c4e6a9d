/* psb_data.c: loading and scoring the PSB developer set (psb_data.h). */
#include "psb_data.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "decode.h"
#include "pointseg.h"

static int has_off_dir(const char *dir) {
    char path[4096];
    struct stat st;
    snprintf(path, sizeof path, "%s/off", dir);
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

int ps_psb_find_dir(const char *given, char *out, size_t cap) {
    const char *env = getenv("POINTSEG_SHARED");
    if (given)
        snprintf(out, cap, "%s", given);
    else if (env)
        snprintf(out, cap, "%s/psb-dev", env);
    else
        snprintf(out, cap, "../shared/data/psb-dev");
    return has_off_dir(out);
}

static int compare_int(const void *x, const void *y) {
    int a = *(const int *)x, b = *(const int *)y;
    return (a > b) - (a < b);
}

/* The id of "ID.off", or -1 for any other name. */
static int off_file_id(const char *name) {
    char *end;
    long id = strtol(name, &end, 10);
    if (end == name || strcmp(end, ".off") != 0 || id < 0 || id > 100000) return -1;
    return (int)id;
}

int *ps_psb_model_ids(const char *dir, size_t *count) {
    char path[4096];
    snprintf(path, sizeof path, "%s/off", dir);
    *count = 0;
    DIR *d = opendir(path);
    if (!d) return NULL;
    size_t cap = 64;
    int *ids = malloc(cap * sizeof *ids);
    struct dirent *e;
    while (ids && (e = readdir(d))) {
        int id = off_file_id(e->d_name);
        if (id < 0) continue;
        if (*count == cap) {
            int *grown = realloc(ids, 2 * cap * sizeof *ids);
            if (!grown) { free(ids); ids = NULL; break; }
            ids = grown;
            cap *= 2;
        }
        ids[(*count)++] = id;
    }
    closedir(d);
    if (!ids || *count == 0) { free(ids); *count = 0; return NULL; }
    qsort(ids, *count, sizeof *ids, compare_int);
    return ids;
}

const char *ps_psb_category(int id) {
    static const char *const names[20] = {
        "Human", "Cup", "Glasses", "Airplane", "Ant", "Chair", "Octopus",
        "Table", "Teddy", "Hand", "Plier", "Fish", "Bird", "Spring",
        "Armadillo", "Bust", "Mech", "Bearing", "Vase", "Fourleg"};
    if (id < 1 || id > 400) return "?";
    return names[(id - 1) / 20];
}

int ps_psb_load_mesh(const char *dir, int id, ps_pointset *mesh) {
    char path[4096];
    char *bytes = NULL;
    size_t len = 0;
    ps_api_error err;
    snprintf(path, sizeof path, "%s/off/%d.off", dir, id);
    memset(mesh, 0, sizeof *mesh);
    if (ps_read_file(path, &bytes, &len, &err) != 0 ||
        ps_decode(bytes, len, NULL, mesh, &err) != 0) {
        fprintf(stderr, "%s: %s\n", path, err.message);
        free(bytes);
        return -1;
    }
    free(bytes);
    if (mesh->n_faces == 0 || mesh->dim != 3) {
        fprintf(stderr, "%s: expected a 3-d mesh with faces\n", path);
        ps_pointset_free(mesh);
        return -1;
    }
    return 0;
}

int ps_read_int_file(const char *path, int **values, size_t *count, char *msg,
                     size_t cap) {
    char *bytes = NULL;
    size_t len = 0;
    ps_api_error err;
    if (ps_read_file(path, &bytes, &len, &err) != 0) {
        snprintf(msg, cap, "%s", err.message);
        return -1;
    }
    int rc = ps_decode_labels(bytes, len, values, count, &err);
    if (rc != 0) snprintf(msg, cap, "%s: %s", path, err.message);
    free(bytes);
    return rc;
}

static int seg_exists(const char *dir, int id, int k, char *path, size_t cap) {
    struct stat st;
    snprintf(path, cap, "%s/seg/%d/%d_%d.seg", dir, id, id, k);
    return stat(path, &st) == 0;
}

int ps_psb_load_humans(const char *dir, int id, size_t n_faces, ps_psb_humans *h) {
    char path[4096], msg[600];
    int n = 0;
    while (seg_exists(dir, id, n, path, sizeof path)) n++;
    memset(h, 0, sizeof *h);
    h->n_faces = n_faces;
    if (n == 0) {
        fprintf(stderr, "%s/seg/%d: no human segmentation\n", dir, id);
        return -1;
    }
    h->labels = calloc((size_t)n, sizeof *h->labels);
    if (!h->labels) return -1;
    h->n_humans = n;
    for (int k = 0; k < n; k++) {
        size_t count = 0;
        seg_exists(dir, id, k, path, sizeof path);
        if (ps_read_int_file(path, &h->labels[k], &count, msg, sizeof msg) != 0) {
            fprintf(stderr, "%s\n", msg);
            ps_psb_humans_free(h);
            return -1;
        }
        if (count != n_faces) {
            fprintf(stderr, "%s: %zu labels for %zu faces\n", path, count, n_faces);
            ps_psb_humans_free(h);
            return -1;
        }
    }
    return 0;
}

void ps_psb_humans_free(ps_psb_humans *h) {
    for (int k = 0; k < h->n_humans; k++) free(h->labels[k]);
    free(h->labels);
    memset(h, 0, sizeof *h);
}

static size_t distinct_labels(const int *labels, size_t n, int *scratch) {
    memcpy(scratch, labels, n * sizeof *scratch);
    qsort(scratch, n, sizeof *scratch, compare_int);
    size_t distinct = n > 0;
    for (size_t i = 1; i < n; i++) distinct += scratch[i] != scratch[i - 1];
    return distinct;
}

double ps_psb_mean_segments(const ps_psb_humans *h) {
    int *scratch = malloc((h->n_faces ? h->n_faces : 1) * sizeof *scratch);
    if (!scratch || h->n_humans == 0) { free(scratch); return NAN; }
    double total = 0;
    for (int k = 0; k < h->n_humans; k++)
        total += (double)distinct_labels(h->labels[k], h->n_faces, scratch);
    free(scratch);
    return total / h->n_humans;
}

double ps_psb_human_agreement(const ps_psb_humans *h) {
    if (h->n_humans < 2) return NAN;
    double total = 0;
    int pairs = 0;
    for (int a = 0; a < h->n_humans; a++)
        for (int b = a + 1; b < h->n_humans; b++, pairs++)
            total += ps_rand_index_error(h->labels[a], h->labels[b], h->n_faces);
    return total / pairs;
}

double ps_psb_score_parts(const ps_pointset *mesh, const int *vertex_labels,
                          const ps_psb_humans *h, double *under, double *over) {
    *under = *over = NAN;
    int *faces = malloc((mesh->n_faces ? mesh->n_faces : 1) * sizeof *faces);
    if (!faces || h->n_humans == 0 || h->n_faces != mesh->n_faces) {
        free(faces);
        return NAN;
    }
    ps_face_labels_from_vertices(vertex_labels, mesh->faces, mesh->n_faces, faces);
    double total = 0, joined = 0, split = 0;
    for (int k = 0; k < h->n_humans; k++) {
        double a_only, b_only;
        total += ps_rand_index_parts(faces, h->labels[k], mesh->n_faces, &a_only, &b_only);
        joined += a_only, split += b_only;
    }
    free(faces);
    *under = joined / h->n_humans, *over = split / h->n_humans;
    return total / h->n_humans;
}

double ps_psb_score(const ps_pointset *mesh, const int *vertex_labels,
                    const ps_psb_humans *h) {
    double under, over;
    return ps_psb_score_parts(mesh, vertex_labels, h, &under, &over);
}
