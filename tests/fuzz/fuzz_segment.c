/* fuzz_segment.c: libFuzzer target for the core itself (tests/fuzz/run.sh).
 * The input's first bytes choose the parameters (k, method, centrality,
 * f2, normals smoothing, threads, dimension) and whether normals come
 * along; the rest are the points, 16-bit coordinates on a grid of 1/64 (so
 * duplicates, collinear runs and far outliers are common), then the
 * normals, 8-bit and not normalized (zero ones included).  ps_segment must
 * return PS_OK or PS_ERR_INVALID and never crash.  No triangles: a small
 * mesh is filled up to 26,667 points (method auto), too slow to fuzz here;
 * the daemon's targets send meshes. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pointseg.h"

#define MAX_POINTS 300

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct reader {
    const uint8_t *at;
    size_t left;
} reader;

static int16_t next16(reader *r) {
    if (r->left < 2) return 0;
    int16_t v = (int16_t)(uint16_t)(r->at[0] | (r->at[1] << 8));
    r->at += 2, r->left -= 2;
    return v;
}

static uint8_t next8(reader *r) {
    if (r->left < 1) return 0;
    r->left--;
    return *r->at++;
}

static void read_params(uint8_t a, uint8_t b, ps_params *p) {
    ps_params_default(p);
    p->k = 1 + a % 16;
    p->method = (b & 1) ? PS_METHOD_PAPER : PS_METHOD_AUTO;
    p->centrality = (ps_centrality_mode)((b >> 1) % 3);
    p->use_f2 = (b >> 3) & 1;
    p->smooth_normals = (b >> 4) & 1;
    p->threads = 1 + ((b >> 5) & 1);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 4) return 0;
    ps_params p;
    read_params(data[0], data[1], &p);
    int dim = 2 + data[2] % 2, with_normals = data[3] & 1;
    reader r = {data + 4, size - 4};
    size_t n = r.left / (2 * (size_t)dim);
    if (n > MAX_POINTS) n = MAX_POINTS;
    double *points = malloc((n ? n : 1) * (size_t)dim * sizeof *points);
    double *normals = with_normals ? malloc((n ? n : 1) * (size_t)dim * sizeof *normals) : NULL;
    if (!points || (with_normals && !normals)) abort();
    for (size_t i = 0; i < n * (size_t)dim; i++) points[i] = next16(&r) / 64.0;
    for (size_t i = 0; with_normals && i < n * (size_t)dim; i++)
        normals[i] = (int8_t)next8(&r) / 127.0;
    ps_input in = {.points = points, .n = n, .dim = dim, .normals = normals};
    ps_result *res = NULL;
    ps_error err;
    ps_status st = ps_segment(&in, &p, NULL, &res, &err);
    if (st != PS_OK && st != PS_ERR_INVALID) abort();
    if (st == PS_OK) ps_result_free(res);
    free(points), free(normals);
    return 0;
}
