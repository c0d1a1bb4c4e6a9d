/*
 * score.c: `pointseg score MESH LABELS SEG [SEG...]`, the Rand Index error
 * (Princeton Segmentation Benchmark conventions) of a vertex labelling of a
 * mesh against one or more face segmentations, e.g. the benchmark's human
 * ones.  Vertex labels become face labels by the majority of each face's
 * three vertices (the first vertex's label when all differ).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "decode.h"
#include "pointseg.h"

static const char score_usage[] =
    "usage: pointseg score MESH LABELS SEG [SEG...]\n"
    "\n"
    "Scores a vertex labelling of a mesh against face segmentations with the\n"
    "Rand Index error 1 - RI of the Princeton Segmentation Benchmark\n"
    "(0 = the same partition, lower is better).\n"
    "\n"
    "  MESH    a mesh with faces in any format pointseg reads (OFF for PSB,\n"
    "          PLY, OBJ)\n"
    "  LABELS  one integer per vertex, one per line, in the mesh's vertex\n"
    "          order (what `pointseg segment --output labels` writes)\n"
    "  SEG     one segment number per face, one per line, in face order\n"
    "          (a PSB .seg file)\n"
    "\n"
    "Each face takes the label most of its 3 vertices have (the first\n"
    "vertex's when all differ).  Label values are arbitrary: only equality\n"
    "matters.  Prints the 1-RI of each SEG and their mean.\n"
    "Exit status: 0 ok, 1 out of memory, 2 bad usage, unreadable input or a\n"
    "count that does not match the mesh.\n";

/* Reads a file of integers that must hold exactly `expected` of them
 * (`what` names them in the message); 0, or 2 with a message. */
static int read_counted_ints(const char *path, size_t expected, const char *what,
                             int **values) {
    char *bytes = NULL;
    size_t len = 0, count = 0;
    ps_api_error err;
    if (ps_read_file(path, &bytes, &len, &err) != 0) {
        fprintf(stderr, "pointseg score: %s\n", err.message);
        return 2;
    }
    int rc = ps_decode_labels(bytes, len, values, &count, &err);
    free(bytes);
    if (rc != 0) {
        fprintf(stderr, "pointseg score: %s: %s\n", path, err.message);
        return err.http_status == 500 ? 1 : 2;
    }
    if (count != expected) {
        fprintf(stderr, "pointseg score: %s has %zu labels but the mesh has %zu %s\n",
                path, count, expected, what);
        free(*values);
        *values = NULL;
        return 2;
    }
    return 0;
}

static int load_mesh(const char *path, ps_pointset *mesh) {
    char *bytes = NULL;
    size_t len = 0;
    ps_api_error err;
    if (ps_read_file(path, &bytes, &len, &err) != 0 ||
        ps_decode(bytes, len, NULL, mesh, &err) != 0) {
        fprintf(stderr, "pointseg score: %s: %s\n", path, err.message);
        free(bytes);
        return 2;
    }
    free(bytes);
    if (mesh->n_faces == 0) {
        fprintf(stderr, "pointseg score: %s has no faces; a mesh is needed\n", path);
        ps_pointset_free(mesh);
        return 2;
    }
    return 0;
}

/* Prints the error of face_labels against every SEG file; 0 or 2. */
static int score_against(const int *face_labels, size_t n_faces, char **seg_paths,
                         int n_segs) {
    double total = 0;
    printf("%-40s %8s\n", "segmentation", "1-RI");
    for (int s = 0; s < n_segs; s++) {
        int *truth = NULL;
        if (read_counted_ints(seg_paths[s], n_faces, "faces", &truth) != 0) return 2;
        double error = ps_rand_index_error(face_labels, truth, n_faces);
        free(truth);
        printf("%-40s %8.4f\n", seg_paths[s], error);
        total += error;
    }
    printf("%-40s %8.4f\n", "mean", total / n_segs);
    return 0;
}

int cli_score(int argc, char **argv) {
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(score_usage, stdout);
            return 0;
        }
    }
    if (argc < 4) {
        fputs(score_usage, stderr);
        return 2;
    }
    ps_pointset mesh;
    memset(&mesh, 0, sizeof mesh);
    int rc = load_mesh(argv[1], &mesh);
    if (rc != 0) return rc;
    int *vertex_labels = NULL;
    rc = read_counted_ints(argv[2], mesh.n, "vertices", &vertex_labels);
    int *face_labels = rc == 0 ? malloc(mesh.n_faces * sizeof *face_labels) : NULL;
    if (rc == 0 && !face_labels) {
        fprintf(stderr, "pointseg score: out of memory\n");
        rc = 1;
    }
    if (rc == 0) {
        ps_face_labels_from_vertices(vertex_labels, mesh.faces, mesh.n_faces, face_labels);
        rc = score_against(face_labels, mesh.n_faces, argv + 3, argc - 3);
    }
    free(face_labels);
    free(vertex_labels);
    ps_pointset_free(&mesh);
    return rc;
}
