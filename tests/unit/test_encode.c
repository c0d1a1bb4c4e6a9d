/* test_encode.c: the encoders (api/encode_*.c) on a result built by hand:
 * the JSON document parsed back with cJSON field by field, the labels text,
 * the binary PLY byte by byte, and the segment palette. */
#include "decode.h"
#include "encode.h"
#include "number_text.h"
#include "random_bits.h"
#include "testlib.h"

#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- a small hand-made result ------------------------------------------- */

/* 6 points, 3 supernodes; the root (0) split into leaves 1 and 2, leaf 2
 * split into leaves 3 and 4, leaf 4 merged into leaf 3: segments 0 (leaf 1)
 * and 1 (leaf 3). */
enum { N = 6 };
static int labels[N] = {0, 0, 1, 1, 0, 1};
static int point_supernode[N] = {0, 0, 1, 2, 0, 2};
static double centrality[N] = {1.5, 2.25, 0.125, 3.0, 1e-7, 123456.789};
static int seg0_sn[] = {0}, seg1_sn[] = {1, 2};
static int root_sn[] = {0, 1, 2}, leaf1_sn[] = {0}, node2_sn[] = {1, 2};
static int leaf3_sn[] = {1}, leaf4_sn[] = {2};

static ps_result small_result(void) {
    static ps_supernode supernodes[3] = {
        {4, 3, 2.25, 0, 0}, {2, 1, 0.125, 1, 1}, {5, 2, 123456.789, 0, 1}};
    static ps_segment_info segments[2] = {{3, 2.25, 1, seg0_sn, 1},
                                          {3, 0.5, 2, seg1_sn, 3}};
    static ps_tree_node tree[5] = {
        {0, -1, {1, 2}, 3, root_sn, 0.05}, {1, 0, {-1, -1}, 1, leaf1_sn, -1},
        {2, 0, {3, 4}, 2, node2_sn, 0.2},  {3, 2, {-1, -1}, 1, leaf3_sn, 0.9},
        {4, 2, {-1, -1}, 1, leaf4_sn, -1}};
    static ps_merge merges[1] = {{4, 3, 0.0625, PS_STEP_CREASE_MERGE}};
    ps_result r;
    memset(&r, 0, sizeof r);
    r.n_points = N;
    r.dim = 3;
    r.labels = labels;
    r.point_supernode = point_supernode;
    r.centrality = centrality;
    r.n_components = 1;
    r.normal_smoothing = 3;
    r.n_outliers = 2;
    r.n_filled = 7;
    r.n_supernodes = 3;
    r.supernodes = supernodes;
    r.n_tree_nodes = 5;
    r.tree = tree;
    r.n_segments = 2;
    r.segments = segments;
    r.n_merges = 1;
    r.merges = merges;
    ps_params_default(&r.params);
    r.params.samples = 3;
    r.params.use_f2 = 1;
    r.params.use_minima = 0;
    for (int ph = 0; ph < PS_PHASE_COUNT; ph++) r.timings.ms[ph] = ph + 0.5;
    for (int s = 0; s < PS_STEP_COUNT; s++) r.timings.step_ms[s] = s + 0.25;
    r.timings.total_ms = 12.5;
    return r;
}

/* ---- JSON helpers ------------------------------------------------------- */

static cJSON *encode_and_parse_with(const ps_pointset *in, const ps_result *r, unsigned include) {
    size_t len = 0;
    char *text = ps_encode_json(in, r, include, &len);
    if (!text) return NULL;
    cJSON *doc = len == strlen(text) ? cJSON_ParseWithLength(text, len) : NULL;
    free(text);
    return doc;
}

static cJSON *encode_and_parse(const ps_result *r, unsigned include) {
    return encode_and_parse_with(NULL, r, include);
}

static double num(const cJSON *obj, const char *name) {
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(obj, name);
    return cJSON_IsNumber(item) ? item->valuedouble : NAN;
}

/* 1 when obj[name] is an array holding exactly want[0..n). */
static int int_array_is(const cJSON *obj, const char *name, const int *want, int n) {
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(obj, name);
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) != n) return 0;
    for (int i = 0; i < n; i++) {
        const cJSON *v = cJSON_GetArrayItem(arr, i);
        if (!cJSON_IsNumber(v) || v->valuedouble != want[i]) return 0;
    }
    return 1;
}

static int is_true(const cJSON *obj, const char *name) {
    return cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(obj, name));
}

/* ---- JSON tests --------------------------------------------------------- */

static void test_json_top_level(void) {
    ps_result r = small_result();
    cJSON *doc = encode_and_parse(&r, 0);
    REQUIRE(doc != NULL);
    CHECK(num(doc, "n_points") == N);
    CHECK(num(doc, "dimension") == 3);
    CHECK(num(doc, "n_components") == 1);
    CHECK(num(doc, "normal_smoothing") == 3);
    CHECK(num(doc, "n_outliers") == 2);
    CHECK(num(doc, "n_filled") == 7);
    CHECK(int_array_is(doc, "labels", labels, N));
    CHECK(num(doc, "n_segments") == 2);
    CHECK(cJSON_GetObjectItemCaseSensitive(doc, "point_supernode") == NULL);
    CHECK(cJSON_GetObjectItemCaseSensitive(doc, "centrality") == NULL);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(doc, "warnings")) == 0);
    CHECK(cJSON_GetArraySize(doc) == 15);
    cJSON_Delete(doc);
}

static void test_json_segments_and_supernodes(void) {
    ps_result r = small_result();
    cJSON *doc = encode_and_parse(&r, 0);
    REQUIRE(doc != NULL);
    const cJSON *segs = cJSON_GetObjectItemCaseSensitive(doc, "segments");
    REQUIRE(cJSON_GetArraySize(segs) == 2);
    const cJSON *s1 = cJSON_GetArrayItem(segs, 1);
    CHECK(num(s1, "id") == 1 && num(s1, "size") == 3 && num(s1, "tree_node") == 3);
    CHECK(num(s1, "feature_size") == 0.5);
    CHECK(int_array_is(s1, "supernodes", seg1_sn, 2));
    CHECK(int_array_is(cJSON_GetArrayItem(segs, 0), "supernodes", seg0_sn, 1));
    const cJSON *sns = cJSON_GetObjectItemCaseSensitive(doc, "supernodes");
    REQUIRE(cJSON_GetArraySize(sns) == 3);
    const cJSON *sn = cJSON_GetArrayItem(sns, 1);
    CHECK(num(sn, "id") == 1 && num(sn, "sink") == 2 && num(sn, "size") == 1);
    CHECK(num(sn, "centrality") == 0.125 && num(sn, "segment") == 1);
    CHECK(is_true(sn, "is_minimum"));
    CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(sns, 0),
                                                         "is_minimum")));
    CHECK_NEAR(num(cJSON_GetArrayItem(sns, 2), "centrality"), 123456.789, 1e-9);
    cJSON_Delete(doc);
}

static void test_json_hierarchy_and_merges(void) {
    ps_result r = small_result();
    cJSON *doc = encode_and_parse(&r, 0);
    REQUIRE(doc != NULL);
    const cJSON *h = cJSON_GetObjectItemCaseSensitive(doc, "hierarchy");
    const cJSON *nodes = cJSON_GetObjectItemCaseSensitive(h, "nodes");
    REQUIRE(cJSON_GetArraySize(nodes) == 5);
    const cJSON *root = cJSON_GetArrayItem(nodes, 0);
    const int root_children[] = {1, 2};
    CHECK(num(root, "id") == 0 && num(root, "parent") == -1 && num(root, "ncut") == 0.05);
    CHECK(int_array_is(root, "children", root_children, 2));
    CHECK(int_array_is(root, "supernodes", root_sn, 3));
    const cJSON *leaf = cJSON_GetArrayItem(nodes, 3);
    CHECK(num(leaf, "id") == 3 && num(leaf, "parent") == 2 && num(leaf, "ncut") == 0.9);
    CHECK(int_array_is(leaf, "children", NULL, 0));
    CHECK(int_array_is(leaf, "supernodes", leaf3_sn, 1));
    const cJSON *merges = cJSON_GetObjectItemCaseSensitive(doc, "merges");
    REQUIRE(cJSON_GetArraySize(merges) == 1);
    const cJSON *m = cJSON_GetArrayItem(merges, 0);
    CHECK(num(m, "segment") == 4 && num(m, "into") == 3 && num(m, "feature_size") == 0.0625);
    const cJSON *step = cJSON_GetObjectItemCaseSensitive(m, "step");
    CHECK(cJSON_IsString(step) && strcmp(step->valuestring, "crease_merge") == 0);
    cJSON_Delete(doc);
}

static void test_json_params_and_timings(void) {
    ps_result r = small_result();
    cJSON *doc = encode_and_parse(&r, 0);
    REQUIRE(doc != NULL);
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(doc, "params");
    CHECK(num(p, "k") == 7 && num(p, "samples") == 3 && num(p, "threads") == 0);
    CHECK(num(p, "ncut_threshold") == r.params.ncut_threshold);
    CHECK(num(p, "feature_threshold") == r.params.feature_threshold);
    const cJSON *mode = cJSON_GetObjectItemCaseSensitive(p, "centrality");
    CHECK(cJSON_IsString(mode) && strcmp(mode->valuestring, "auto") == 0);
    CHECK(num(p, "persistence") == r.params.persistence);
    CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(p, "minima")));
    CHECK(is_true(p, "f2"));
    const cJSON *smooth = cJSON_GetObjectItemCaseSensitive(p, "smooth_normals");
    CHECK(cJSON_IsBool(smooth) && cJSON_IsTrue(smooth) == (r.params.smooth_normals != 0));
    CHECK(cJSON_GetArraySize(p) == 11);
    const cJSON *method = cJSON_GetObjectItemCaseSensitive(p, "method");
    CHECK(cJSON_IsString(method) && strcmp(method->valuestring, "auto") == 0);
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(doc, "timings_ms");
    CHECK(num(t, "knn") == 0.5 && num(t, "centrality") == 1.5 && num(t, "supernodes") == 2.5);
    CHECK(num(t, "hierarchy") == 3.5 && num(t, "refine") == 4.5 && num(t, "total") == 12.5);
    CHECK(cJSON_GetArraySize(t) == 7);
    const cJSON *steps = cJSON_GetObjectItemCaseSensitive(t, "steps");
    CHECK(cJSON_GetArraySize(steps) == PS_STEP_COUNT);
    CHECK(num(steps, "knn_graph") == 0.25 && num(steps, "boundary_cut") == 12.25);
    CHECK(num(steps, "patch_merge") == PS_STEP_COUNT - 0.75);
    cJSON_Delete(doc);
}

static void test_json_included_arrays(void) {
    ps_result r = small_result();
    cJSON *doc = encode_and_parse(&r, PS_INCLUDE_CENTRALITY | PS_INCLUDE_POINT_SUPERNODE);
    REQUIRE(doc != NULL);
    CHECK(int_array_is(doc, "point_supernode", point_supernode, N));
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(doc, "centrality");
    REQUIRE(cJSON_GetArraySize(f) == N);
    for (int i = 0; i < N; i++)
        CHECK_NEAR(cJSON_GetArrayItem(f, i)->valuedouble, centrality[i],
                   1e-8 * fabs(centrality[i]));
    cJSON_Delete(doc);
    doc = encode_and_parse(&r, PS_INCLUDE_CENTRALITY);
    REQUIRE(doc != NULL);
    CHECK(cJSON_GetObjectItemCaseSensitive(doc, "point_supernode") == NULL);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(doc, "centrality")) == N);
    cJSON_Delete(doc);
}

static void test_json_non_finite_is_null(void) {
    ps_result r = small_result();
    double f[N] = {1, NAN, INFINITY, -INFINITY, 2, 3};
    ps_supernode sn[3];
    memcpy(sn, r.supernodes, sizeof sn);
    sn[0].centrality = NAN;
    r.supernodes = sn;
    r.centrality = f;
    r.timings.total_ms = INFINITY;
    size_t len;
    char *text = ps_encode_json(NULL, &r, PS_INCLUDE_CENTRALITY, &len);
    REQUIRE(text != NULL);
    CHECK(strstr(text, "nan") == NULL && strstr(text, "inf") == NULL);
    cJSON *doc = cJSON_Parse(text);
    free(text);
    REQUIRE(doc != NULL);
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(doc, "centrality");
    CHECK(cJSON_GetArrayItem(arr, 0)->valuedouble == 1);
    for (int i = 1; i <= 3; i++) CHECK(cJSON_IsNull(cJSON_GetArrayItem(arr, i)));
    const cJSON *sns = cJSON_GetObjectItemCaseSensitive(doc, "supernodes");
    CHECK(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(sns, 0),
                                                        "centrality")));
    CHECK(cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(doc, "timings_ms"), "total")));
    cJSON_Delete(doc);
}

/* The input's warnings (what the decoder tolerated) are the document's, in
 * order; more than PS_MAX_WARNINGS are dropped, a long one is cut. */
static void test_json_warnings(void) {
    ps_result r = small_result();
    ps_pointset in;
    char long_text[400];
    memset(&in, 0, sizeof in);
    memset(long_text, 'w', sizeof long_text - 1);
    long_text[sizeof long_text - 1] = 0;
    ps_pointset_warn(&in, "first %d", 1);
    ps_pointset_warn(&in, "%s", long_text);
    for (int i = 0; i < PS_MAX_WARNINGS; i++) ps_pointset_warn(&in, "more");
    cJSON *doc = encode_and_parse_with(&in, &r, 0);
    REQUIRE(doc != NULL);
    const cJSON *w = cJSON_GetObjectItemCaseSensitive(doc, "warnings");
    CHECK(cJSON_GetArraySize(w) == PS_MAX_WARNINGS);
    CHECK(!strcmp(cJSON_GetArrayItem(w, 0)->valuestring, "first 1"));
    CHECK(strlen(cJSON_GetArrayItem(w, 1)->valuestring) == PS_WARNING_MAX - 1);
    CHECK(!strcmp(cJSON_GetArrayItem(w, PS_MAX_WARNINGS - 1)->valuestring, "more"));
    cJSON_Delete(doc);
}

static void test_json_empty_result(void) {
    ps_result r;
    memset(&r, 0, sizeof r);
    r.dim = 2;
    ps_params_default(&r.params);
    cJSON *doc = encode_and_parse(&r, PS_INCLUDE_CENTRALITY | PS_INCLUDE_POINT_SUPERNODE);
    REQUIRE(doc != NULL);
    CHECK(num(doc, "n_points") == 0 && num(doc, "dimension") == 2);
    CHECK(int_array_is(doc, "labels", NULL, 0));
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(doc, "segments")) == 0);
    cJSON_Delete(doc);
}

/* A big result: the hand-written arrays must stay exact at scale. */
static void test_json_large_labels(void) {
    enum { BIG = 200000 };
    ps_result r = small_result();
    int *big = malloc(BIG * sizeof *big);
    REQUIRE(big != NULL);
    for (int i = 0; i < BIG; i++) big[i] = (i * 7919) % 1000003 - (i % 3 == 0 ? 5 : 0);
    big[0] = -2147483647 - 1;
    big[1] = 2147483647;
    r.n_points = BIG;
    r.labels = big;
    r.point_supernode = big;
    cJSON *doc = encode_and_parse(&r, PS_INCLUDE_POINT_SUPERNODE);
    REQUIRE(doc != NULL);
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(doc, "labels");
    REQUIRE(cJSON_GetArraySize(arr) == BIG);
    int i = 0, mismatches = 0;
    for (const cJSON *v = arr->child; v; v = v->next, i++) mismatches += v->valuedouble != big[i];
    CHECK(mismatches == 0);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(doc, "point_supernode")) == BIG);
    cJSON_Delete(doc);
    free(big);
}

/* ---- number text ------------------------------------------------------ */

static void test_put_int(void) {
    static const int values[] = {0, 7, -7, 10, 1234567890, 2147483647, -2147483647 - 1};
    char got[32], want[32];
    for (size_t i = 0; i < sizeof values / sizeof values[0]; i++) {
        *ps_put_int(got, values[i]) = 0;
        snprintf(want, sizeof want, "%d", values[i]);
        CHECK_MSG(strcmp(got, want) == 0, "%s != %s", got, want);
    }
}

/* ps_put_double against printf's %.9g over values of every magnitude:
 * the same text nearly always, the same value to nine digits always. */
static void test_put_double_matches_printf(void) {
    static const double fixed[] = {1, -1, 0.5, 0.1, 1e-5, 1e-4, 123456789, 999999999.5,
                                   1e9, 99999.99999, 0.30000000000000004, 1e29, 1e-29,
                                   1e30, 1e-300, -2.5e300, 3.0e-310, 1.7976931348623157e308};
    char got[64], want[64];
    uint64_t state = 88172645463325252u;
    int differ = 0, total = 0;
    for (int i = 0; i < 200000; i++, total++) {
        double v;
        if (i < (int)(sizeof fixed / sizeof fixed[0])) {
            v = fixed[i];
        } else {
            double mantissa = (double)(ps_random_bits(&state) >> 11) / 9007199254740992.0;
            int e = (int)(ps_random_bits(&state) % 80) - 40;
            v = (i & 1 ? -mantissa : mantissa) * pow(10, e);
        }
        *ps_put_double(got, v) = 0;
        snprintf(want, sizeof want, "%.9g", v);
        if (strcmp(got, want) == 0 || (v == 0 && strcmp(got, "0") == 0)) continue;
        differ++;
        double g = strtod(got, NULL);
        CHECK_MSG(fabs(g - v) <= 1.01e-8 * fabs(v), "%.17g written as %s (printf: %s)", v, got,
                  want);
    }
    CHECK_MSG(differ * 1000 < total, "%d of %d differ from printf", differ, total);
    *ps_put_double(got, NAN) = 0;
    CHECK(strcmp(got, "null") == 0);
    *ps_put_double(got, -INFINITY) = 0;
    CHECK(strcmp(got, "null") == 0);
}

/* ---- labels ------------------------------------------------------------- */

static void test_labels_text(void) {
    ps_result r = small_result();
    size_t len = 0;
    char *text = ps_encode_labels(&r, &len);
    REQUIRE(text != NULL);
    CHECK(strcmp(text, "0\n0\n1\n1\n0\n1\n") == 0);
    CHECK(len == 12);
    free(text);
    int neg[2] = {-3, 1234567};
    r.n_points = 2;
    r.labels = neg;
    text = ps_encode_labels(&r, &len);
    REQUIRE(text != NULL);
    CHECK(strcmp(text, "-3\n1234567\n") == 0 && len == 11);
    free(text);
}

/* ---- PLY ---------------------------------------------------------------- */

static float float_le(const unsigned char *p) {
    uint32_t bits = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                    (uint32_t)p[3] << 24;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

static uint32_t u32_le(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* Encodes, checks the header has/lacks faces, returns the body. */
static const unsigned char *ply_body(const char *text, size_t len, int with_faces) {
    const char *end = strstr(text, "end_header\n");
    if (strncmp(text, "ply\nformat binary_little_endian 1.0\n", 36) != 0 || !end) return NULL;
    if (!strstr(text, "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
                      "property uchar red\nproperty uchar green\nproperty uchar blue\n"))
        return NULL;
    if ((strstr(text, "element face 2\nproperty list uchar int vertex_indices\n") != NULL) !=
        with_faces)
        return NULL;
    size_t header = (size_t)(end - text) + 11;
    return len == header + N * 15 + (with_faces ? 2 * 13 : 0)
               ? (const unsigned char *)text + header
               : NULL;
}

static void test_ply_vertices_and_colours(void) {
    ps_result r = small_result();
    double pts[N * 3];
    for (int i = 0; i < N * 3; i++) pts[i] = i * 0.5 - 1;
    ps_pointset in = {.n = N, .dim = 3, .points = pts};
    size_t len;
    char *text = ps_encode_ply(&in, &r, &len);
    REQUIRE(text != NULL);
    const unsigned char *v = ply_body(text, len, 0);
    REQUIRE(v != NULL);
    for (int i = 0; i < N; i++, v += 15) {
        unsigned char rgb[3];
        ps_segment_color(labels[i], rgb);
        for (int c = 0; c < 3; c++) CHECK(float_le(v + 4 * c) == (float)pts[3 * i + c]);
        CHECK(memcmp(v + 12, rgb, 3) == 0);
    }
    free(text);
}

static void test_ply_faces_and_2d(void) {
    ps_result r = small_result();
    double pts[N * 2];
    for (int i = 0; i < N * 2; i++) pts[i] = i + 0.25;
    uint32_t faces[6] = {0, 1, 2, 3, 4, 5};
    ps_pointset in = {.n = N, .dim = 2, .points = pts, .n_faces = 2, .faces = faces};
    size_t len;
    char *text = ps_encode_ply(&in, &r, &len);
    REQUIRE(text != NULL);
    const unsigned char *v = ply_body(text, len, 1);
    REQUIRE(v != NULL);
    for (int i = 0; i < N; i++, v += 15) {
        CHECK(float_le(v) == (float)pts[2 * i] && float_le(v + 4) == (float)pts[2 * i + 1]);
        CHECK(float_le(v + 8) == 0.0f);
    }
    for (int f = 0; f < 2; f++, v += 13) {
        CHECK(v[0] == 3);
        for (int c = 0; c < 3; c++) CHECK(u32_le(v + 1 + 4 * c) == faces[3 * f + c]);
    }
    free(text);
}

/* ps_decode_ply reads back the points (as floats) and the faces. */
static void test_ply_decodes_back(void) {
    ps_result r = small_result();
    double pts[N * 3];
    for (int i = 0; i < N * 3; i++) pts[i] = (i % 5) * 0.3 - (i % 2);
    uint32_t faces[6] = {0, 1, 2, 5, 4, 3};
    ps_pointset in = {.n = N, .dim = 3, .points = pts, .n_faces = 2, .faces = faces};
    size_t len;
    char *text = ps_encode_ply(&in, &r, &len);
    REQUIRE(text != NULL);
    ps_pointset back;
    ps_api_error err;
    memset(&back, 0, sizeof back);
    int rc = ps_decode_ply(text, len, NULL, &back, &err);
    free(text);
    REQUIRE(rc == 0);
    CHECK(back.n == N && back.dim == 3 && back.n_faces == 2);
    for (int i = 0; i < N * 3 && back.n == N; i++) CHECK(back.points[i] == (float)pts[i]);
    for (int i = 0; i < 6 && back.faces; i++) CHECK(back.faces[i] == faces[i]);
    ps_pointset_free(&back);
}

/* ps_encode: each output format's bytes are its encoder's, with the media
 * type the daemon sends. */
static void test_encode_dispatch(void) {
    ps_result r = small_result();
    double pts[N * 3] = {0};
    ps_pointset in = {.n = N, .dim = 3, .points = pts};
    static const struct {
        ps_output output;
        const char *media_type;
    } cases[] = {{PS_OUTPUT_JSON, "application/json"},
                 {PS_OUTPUT_LABELS, "text/plain; charset=utf-8"},
                 {PS_OUTPUT_PLY, "application/ply"}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        ps_request_params rp = {.output = cases[c].output, .include = PS_INCLUDE_CENTRALITY};
        size_t len = 0, want_len = 0;
        const char *media_type = NULL;
        char *got = ps_encode(&in, &r, &rp, &len, &media_type);
        char *want = cases[c].output == PS_OUTPUT_PLY      ? ps_encode_ply(&in, &r, &want_len)
                     : cases[c].output == PS_OUTPUT_LABELS ? ps_encode_labels(&r, &want_len)
                                                           : ps_encode_json(&in, &r, rp.include, &want_len);
        REQUIRE(got && want);
        CHECK(len == want_len && memcmp(got, want, len) == 0);
        CHECK(media_type && strcmp(media_type, cases[c].media_type) == 0);
        CHECK(strcmp(ps_encode_media_type(cases[c].output), cases[c].media_type) == 0);
        free(got), free(want);
    }
    ps_request_params labels_only = {.output = PS_OUTPUT_LABELS};
    size_t len = 0;
    char *text = ps_encode(NULL, &r, &labels_only, &len, NULL);
    REQUIRE(text != NULL);
    CHECK(len == 12 && memcmp(text, "0\n0\n1\n1\n0\n1\n", 12) == 0);
    free(text);
}

static void test_palette_distinct_and_cycling(void) {
    unsigned char a[3], b[3];
    int period = 0;
    ps_segment_color(0, a);
    for (int i = 1; i < 100 && !period; i++) {
        ps_segment_color(i, b);
        if (memcmp(a, b, 3) == 0) period = i;
    }
    CHECK(period >= 16 && period <= 32);
    for (int i = 0; i < period; i++)
        for (int j = i + 1; j < period; j++) {
            ps_segment_color(i, a);
            ps_segment_color(j, b);
            int d = abs(a[0] - b[0]) + abs(a[1] - b[1]) + abs(a[2] - b[2]);
            CHECK_MSG(d >= 50, "colours %d and %d differ by only %d", i, j, d);
        }
    ps_segment_color(-1, a);
    ps_segment_color(period - 1, b);
    CHECK(memcmp(a, b, 3) == 0);
}

PS_TEST_MAIN(TEST(test_json_top_level), TEST(test_json_segments_and_supernodes),
             TEST(test_json_hierarchy_and_merges), TEST(test_json_params_and_timings),
             TEST(test_json_included_arrays), TEST(test_json_non_finite_is_null),
             TEST(test_json_warnings), TEST(test_json_empty_result), TEST(test_json_large_labels), TEST(test_put_int),
             TEST(test_put_double_matches_printf), TEST(test_labels_text),
             TEST(test_ply_vertices_and_colours), TEST(test_ply_faces_and_2d),
             TEST(test_ply_decodes_back), TEST(test_encode_dispatch),
             TEST(test_palette_distinct_and_cycling))
