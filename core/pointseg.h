/*
 * pointseg.h: the one public header of the pointseg core library.
 *
 * The core splits a point-sampled surface (or any point set in R^d, d >= 2)
 * into its natural parts, after "Segmenting Point Sets" (Yamazaki,
 * Natarajan, Bai, Hamann):
 *   1. features:   kNN graph, centrality f (mean geodesic distance), steepest
 *                  ascent flow of f to its sinks; one supernode per sink;
 *   2. hierarchy:  recursive normalized-cut bisection of the supernodes;
 *   3. refinement: segments with a small feature size merge into a
 *                  neighbour (method auto: then boundaries move onto
 *                  creases, and uncreased boundaries and flat patches
 *                  merge).
 * It knows no file format, no socket and no daemon thread: points in,
 * a ps_result out.  Everything here is reentrant; one call may use several
 * threads of its own (params.threads).
 */
#ifndef POINTSEG_H
#define POINTSEG_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PS_VERSION "0.1.0"
#define PS_MAX_DIM 64 /* largest supported point dimension */
#define PS_MAX_K 64   /* largest supported k (neighbours per point in the kNN graph) */
#define PS_MAX_COORDINATE 1e150 /* larger coordinates are refused: their
                                   squared distances would overflow */

/* ---- status and errors ------------------------------------------------ */

typedef enum ps_status {
    PS_OK = 0,
    PS_ERR_INVALID,   /* the input or a parameter is unusable (message says why) */
    PS_ERR_NOMEM,     /* an allocation failed */
    PS_ERR_CANCELLED, /* the caller's cancel flag was raised */
    PS_ERR_INTERNAL   /* a library call failed (FLANN, LAPACK): a bug, report it */
} ps_status;

typedef struct ps_error {
    ps_status status;
    char message[256]; /* human readable, names the problem */
} ps_error;

/* Sets err (if not NULL) and returns status: the idiom for failing. */
ps_status ps_fail(ps_error *err, ps_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
const char *ps_status_name(ps_status status);

/* ---- parameters -------------------------------------------------------- */

typedef enum ps_centrality_mode {
    PS_CENTRALITY_AUTO = 0, /* exact when n <= PS_EXACT_AUTO_LIMIT, else approx */
    PS_CENTRALITY_EXACT,    /* Dijkstra from every point: O(n^2 log n) time */
    PS_CENTRALITY_APPROX    /* farthest-point samples, S Dijkstras */
} ps_centrality_mode;

#define PS_EXACT_AUTO_LIMIT 4096

/* ncut_threshold = 0 resolves to one of these (ps_params). */
#define PS_NCUT_PAPER 0.6
#define PS_NCUT_NEVER_STOP 2.0

typedef enum ps_method {
    PS_METHOD_AUTO = 0, /* the default: stray points left out, crease-aware
                           metric (3-D), persistence, minima, crease split
                           and merge, convex merge, patch merge
                           (docs/method.md) */
    PS_METHOD_PAPER     /* the published pipeline: Euclidean geodesics, every
                           sink a supernode, no minima, no f2, NCut stop
                           at PS_NCUT_PAPER */
} ps_method;

typedef struct ps_params {
    ps_method method;
    int k;                    /* neighbours per point in the kNN graph (default 7) */
    ps_centrality_mode centrality;
    int samples;              /* approx centrality samples; 0 = ceil(sqrt(n)), at most 512;
                                 shared by the draws of ensemble.h (each its share) */
    double persistence;       /* merge sinks whose persistence is below this
                                 fraction of the range of f (persistence.h) */
    double ncut_threshold;    /* stop bisecting when NCut exceeds this; 0 = the
                                 method's own: PS_NCUT_PAPER for paper, none
                                 (PS_NCUT_NEVER_STOP) for auto, whose segments
                                 come from refinement alone */
    double feature_threshold; /* merge segments whose feature size is below this
                                 fraction of the range of f */
    int use_minima;           /* also make supernodes of the minima of f, for
                                 the central regions below each basin's
                                 highest saddle (supernodes.h) */
    int use_f2;               /* split supernodes along the maxima of f2, the
                                 distance to their own sink (f2_split.h) */
    int smooth_normals;       /* method auto, normals estimated: smooth them as
                                 much as the scan's measured noise asks
                                 (normals_smooth.h; clean input is left as
                                 it is); on by default */
    int threads;              /* worker threads; 0 = all cores */
} ps_params;

/* Fills p with the defaults (the ones the README documents). */
void ps_params_default(ps_params *p);

/* Checks every field's range; returns PS_OK or PS_ERR_INVALID naming it. */
ps_status ps_params_check(const ps_params *p, ps_error *err);

const char *ps_centrality_name(ps_centrality_mode mode);
const char *ps_method_name(ps_method method);

/* ---- input ------------------------------------------------------------- */

typedef struct ps_input {
    const double *points;  /* #P by dim, row major; finite, at most
                              PS_MAX_COORDINATE; a point set whose typical
                              extent is far from 1 (below 2^-16 or above
                              2^64) is segmented as its copy scaled by a
                              power of two to about 1 (core/input_scale.h);
                              one that cannot be (a tiny extent beside
                              coordinates some 2^514 times larger) is
                              refused */
    size_t n;              /* #P */
    int dim;               /* 2 <= dim <= PS_MAX_DIM; method auto segments 2-D
                              points as the plane z = 0 in 3-D (a flat surface,
                              whose parts stick out of its outline) */
    const double *normals; /* optional #P by dim, row major, finite, of any
                              length; NULL if absent (2-D normals are
                              dropped with the lift) */
    const uint32_t *faces; /* optional #F by 3 triangles of a mesh (indices into
                              points); NULL if absent.  Method auto, dim 3,
                              centrality not exact: a mesh of fewer than
                              26,667 points is filled with points on its
                              triangles up to that many (an even sampling,
                              core/graph/surface_fill.h; not a noisy mesh),
                              three times independently, and the fill the
                              others agree with most answers (ensemble.h);
                              only the input points get answers */
    size_t n_faces;        /* #F */
} ps_input;

/* ---- progress and cancellation ------------------------------------------ */

typedef enum ps_phase {
    PS_PHASE_KNN = 0,
    PS_PHASE_CENTRALITY,
    PS_PHASE_SUPERNODES,
    PS_PHASE_HIERARCHY,
    PS_PHASE_REFINE,
    PS_PHASE_COUNT
} ps_phase;

const char *ps_phase_name(ps_phase phase); /* "knn", "centrality", ... */

/* The method's steps, in the order they run, each within a phase
 * (docs/method.md has a section on each).  Some run for every method,
 * some for method auto, some for auto in 3-D only (the crease-aware
 * steps), the f2 split when asked for. */
typedef enum ps_step {
    PS_STEP_KNN_GRAPH = 0,   /* knn: the kNN graph */
    PS_STEP_OUTLIERS,        /* knn: stray points left out (auto) */
    PS_STEP_COMPONENTS,      /* knn: connected components */
    PS_STEP_NORMALS,         /* knn: outward normals (auto, 3-D) */
    PS_STEP_CREASE_METRIC,   /* knn: crease strengths and the crease metric (auto, 3-D) */
    PS_STEP_CENTRALITY,      /* centrality */
    PS_STEP_SUPERNODES,      /* supernodes: flow to sinks, persistence, minima */
    PS_STEP_F2_SPLIT,        /* supernodes: split at maxima of f2 (when asked) */
    PS_STEP_CREASE_SPLIT,    /* supernodes: split along closed creases (auto, 3-D) */
    PS_STEP_PROFILE_SPLIT,   /* supernodes: a thin limb cut off a wide part (auto, 3-D) */
    PS_STEP_NCUT,            /* hierarchy: normalized-cut bisection */
    PS_STEP_FEATURE_MERGE,   /* refine: segments of small feature size merge */
    PS_STEP_BOUNDARY_CUT,    /* refine: boundaries onto concave creases (auto, 3-D) */
    PS_STEP_CREASE_MERGE,    /* refine: an uncreased boundary is no part boundary (auto, 3-D) */
    PS_STEP_CONVEX_MERGE,    /* refine: convex unions merge (auto, 3-D) */
    PS_STEP_PATCH_MERGE,     /* refine: flat patches and crumbs merge (auto, 3-D) */
    PS_STEP_COUNT
} ps_step;

const char *ps_step_name(ps_step step); /* "knn_graph", "outliers", ... */
ps_phase ps_step_phase(ps_step step);

/* Called from the calling thread or a worker of the call, never concurrently
 * with itself; fraction in [0, 1] within the phase, nondecreasing.  Every
 * phase reports 0, then fractions as its steps go (the kNN queries, the
 * normals, the coarse graph and the Dijkstras of the centrality, the cuts
 * of the hierarchy, the steps of supernodes and refine), then 1. */
typedef void (*ps_progress_fn)(void *user, ps_phase phase, double fraction);

typedef struct ps_control {
    ps_progress_fn progress;     /* may be NULL */
    void *user;                  /* passed to progress */
    const volatile int *cancel;  /* may be NULL; nonzero = stop soon
                                    (read with relaxed atomics; raise it
                                    with ps_cancel_raise) */
} ps_control;

/* Sets *flag, a ps_control cancel flag, to 1 from any thread, also while a
 * run reads it: an atomic store, as the run's reads are atomic loads (a
 * plain store from another thread would race with them). */
void ps_cancel_raise(volatile int *flag);

/* ---- result ------------------------------------------------------------ */

typedef struct ps_supernode {
    size_t sink;       /* index of the sink point (a local max of f, or min) */
    size_t size;       /* points that flow to it */
    double centrality; /* f at the sink */
    int is_minimum;    /* 1 when the sink is a minimum of f (use_minima) */
    int segment;       /* final segment id */
} ps_supernode;

typedef struct ps_tree_node {
    int id;            /* index in ps_result.tree; the root is 0 */
    int parent;        /* -1 for the root */
    int children[2];   /* -1, -1 for a leaf */
    int n_supernodes;
    int *supernodes;   /* #n_supernodes supernode ids */
    double ncut;       /* NCut of this node's split; for a leaf, of the split
                          that was refused (or -1 when none was possible) */
} ps_tree_node;

typedef struct ps_segment_info {
    size_t size;          /* points */
    double feature_size;  /* max f - min f over its points */
    int n_supernodes;
    int *supernodes;      /* #n_supernodes supernode ids, increasing */
    int tree_node;        /* the hierarchy leaf it grew from */
} ps_segment_info;

typedef struct ps_merge {
    int segment;          /* hierarchy leaf (tree node id) merged away */
    int into;             /* hierarchy leaf (tree node id) it merged into */
    double feature_size;  /* feature size of the merged segment, in f units */
    ps_step step;         /* the refinement step that merged it: PS_STEP_FEATURE_MERGE,
                             _CREASE_MERGE, _CONVEX_MERGE or _PATCH_MERGE */
} ps_merge;

typedef struct ps_timings {
    double ms[PS_PHASE_COUNT];     /* wall time per phase, milliseconds */
    double step_ms[PS_STEP_COUNT]; /* ... per step (0 for a step that did not run); with
                                      samplings side by side (ensemble.h) a phase's wall
                                      time shared among its steps by their summed times */
    double total_ms;
} ps_timings;

typedef struct ps_result {
    size_t n_points;
    int dim;
    int *labels;           /* #P final segment per point, 0..n_segments-1,
                              numbered by decreasing size (ties: lowest point) */
    int *point_supernode;  /* #P supernode per point */
    double *centrality;    /* #P f per point (input units) */
    int n_components;      /* connected components of the kNN graph (of the
                              filled surface when faces were given) */
    int normal_smoothing;  /* iterations the estimated normals were smoothed
                              (params.smooth_normals on a noisy scan; else 0) */
    size_t n_filled;       /* points added on the faces (ps_input.faces) by
                              the fill that answers, 0 when none were; they
                              get no answers */
    size_t n_outliers;     /* distinct points left out as stray (method auto:
                              far from their neighbours' spacing); each takes
                              the answers of its nearest kept neighbour */

    int n_supernodes;
    ps_supernode *supernodes;  /* #n_supernodes */

    int n_tree_nodes;
    ps_tree_node *tree;        /* #n_tree_nodes, tree[0] is the root */

    int n_segments;
    ps_segment_info *segments;      /* #n_segments, index = label */

    int n_merges;
    ps_merge *merges;          /* #n_merges in the order they happened */

    ps_params params;          /* effective parameters (samples resolved, ...) */
    ps_timings timings;
} ps_result;

/* Segments in.  On PS_OK *out holds a result the caller frees with
 * ps_result_free.  On failure *out is NULL and err says why.  ctl may be
 * NULL.  The output depends only on the input and params, never on
 * params.threads or timing. */
ps_status ps_segment(const ps_input *in, const ps_params *params,
                     const ps_control *ctl, ps_result **out, ps_error *err);

void ps_result_free(ps_result *r);

/* Bytes ps_segment is expected to take at its peak for in with params
 * (the input's own arrays not included; in->n, in->dim, in->n_faces and,
 * when not NULL, in->points are read: a point set of extreme extent is
 * segmented as a scaled copy, core/input_scale.h): an upper estimate from
 * measured runs (memory_estimate.c), for a service to refuse a job that
 * cannot fit before it starts.  Below 26,667 points it covers a mesh
 * segmented in fills up to that many (ps_input.faces); a mesh (n_faces >
 * 0) of any size is covered too, since its distinct points may be fewer
 * than the reference (an unwelded mesh repeats its corners). */
size_t ps_segment_memory_estimate(const ps_input *in, const ps_params *params);

/* ---- scoring (Princeton Segmentation Benchmark conventions) ------------ */

/* Rand Index error 1 - RI between two labellings of the same n items.
 * Labels are arbitrary non-negative ints.  O(n + distinct pairs) time. */
double ps_rand_index_error(const int *a, const int *b, size_t n);

/* The same error split in two: *a_only (may be NULL) the share of the
 * item pairs that a puts together and b apart, *b_only the reverse; the
 * error is their sum.  With a a segmentation and b a human's, a_only is
 * under-segmentation (joined what people split), b_only over-segmentation.
 * NAN (and NAN shares) when out of memory. */
double ps_rand_index_parts(const int *a, const int *b, size_t n, double *a_only,
                           double *b_only);

/* Face labels from vertex labels: the majority label of the 3 vertices, or
 * the first vertex's when all differ.  faces is #F by 3. */
void ps_face_labels_from_vertices(const int *vertex_labels,
                                  const uint32_t *faces, size_t n_faces,
                                  int *face_labels);

#ifdef __cplusplus
}
#endif
#endif
