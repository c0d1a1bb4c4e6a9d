/*
 * psb_data.h: loading the PSB developer set (../shared/data/psb-dev, see its
 * README.md) for the scorer's test and the quality benchmark: model ids,
 * categories, meshes, human segmentations, and scoring vertex labels
 * against every human segmentation of a model.
 */
#ifndef PS_PSB_DATA_H
#define PS_PSB_DATA_H

#include <stddef.h>

#include "pointset.h"

/* The human segmentations of one model: #n_humans arrays of #n_faces face
 * labels each (human k is seg/ID/ID_k.seg). */
typedef struct ps_psb_humans {
    int n_humans;
    size_t n_faces;
    int **labels;
} ps_psb_humans;

/* The psb-dev directory: `given` if not NULL, else $POINTSEG_SHARED/psb-dev,
 * else ../shared/data/psb-dev.  Writes it to out (size cap) and returns 1 if
 * it holds an off/ directory, else 0. */
int ps_psb_find_dir(const char *given, char *out, size_t cap);

/* Model ids present as off/ID.off in dir, increasing.  Returns a malloc'ed
 * #count array (NULL with *count = 0 when none or out of memory). */
int *ps_psb_model_ids(const char *dir, size_t *count);

/* "Human", "Cup", ... for a benchmark id (1..400), "?" otherwise. */
const char *ps_psb_category(int id);

/* Reads off/ID.off into mesh (vertices and triangle faces); 0 or -1 with a
 * message on stderr. */
int ps_psb_load_mesh(const char *dir, int id, ps_pointset *mesh);

/* Reads every seg/ID/ID_K.seg; each must have n_faces lines.  0 or -1 with
 * a message on stderr. */
int ps_psb_load_humans(const char *dir, int id, size_t n_faces, ps_psb_humans *h);
void ps_psb_humans_free(ps_psb_humans *h);

/* Mean number of segments (distinct labels) over the human segmentations. */
double ps_psb_mean_segments(const ps_psb_humans *h);

/* People among themselves: the mean over pairs of the model's human
 * segmentations of 1 - RI between their face labels (the bench's metric
 * with one human standing in for the method); NAN with fewer than two. */
double ps_psb_human_agreement(const ps_psb_humans *h);

/* Mean over humans of 1 - RI of the face labels (majority of the #P
 * vertex_labels over mesh's #F by 3 faces); NAN when out of memory. */
double ps_psb_score(const ps_pointset *mesh, const int *vertex_labels,
                    const ps_psb_humans *h);

/* The same, and the means over humans of its two parts
 * (ps_rand_index_parts): *under, pairs the labels join and a human splits;
 * *over, the reverse. */
double ps_psb_score_parts(const ps_pointset *mesh, const int *vertex_labels,
                          const ps_psb_humans *h, double *under, double *over);

/* Reads a text file of whitespace-separated integers ("-" = stdin) into a
 * malloc'ed #count array.  0, or -1 with a message naming the file and line
 * in msg (size cap). */
int ps_read_int_file(const char *path, int **values, size_t *count, char *msg,
                     size_t cap);

#endif
