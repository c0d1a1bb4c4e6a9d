/* result_checks.c: the end-to-end tests' runs of ps_segment and checks of
 * a ps_result (result_checks.h). */
#include "result_checks.h"

#include "testlib.h"

#include <math.h>
#include <stdlib.h>

int ps_majority_label(const ps_result *r, const int *part, int which, double *purity) {
    int *count = calloc((size_t)r->n_segments, sizeof *count);
    size_t total = 0;
    for (size_t i = 0; i < r->n_points; i++)
        if (part[i] == which) count[r->labels[i]]++, total++;
    int best = 0;
    for (int s = 1; s < r->n_segments; s++)
        if (count[s] > count[best]) best = s;
    *purity = total ? (double)count[best] / (double)total : 0;
    free(count);
    return best;
}

void ps_check_parts_separate(const ps_result *r, const int *part, int first, int last,
                             double min_purity) {
    int labels[16];
    for (int a = first; a <= last; a++) {
        double purity;
        labels[a] = ps_majority_label(r, part, a, &purity);
        CHECK_MSG(purity >= min_purity, "part %d: only %.2f of it in one segment", a, purity);
        for (int b = first; b < a; b++)
            CHECK_MSG(labels[a] != labels[b], "parts %d and %d share segment %d", a, b,
                      labels[a]);
    }
}

void ps_check_result_consistent(const ps_result *r) {
    size_t seg_total = 0, sn_total = 0;
    for (size_t i = 0; i < r->n_points; i++) {
        REQUIRE(r->labels[i] >= 0 && r->labels[i] < r->n_segments);
        REQUIRE(r->point_supernode[i] >= 0 && r->point_supernode[i] < r->n_supernodes);
        CHECK(r->supernodes[r->point_supernode[i]].segment == r->labels[i]);
        CHECK(isfinite(r->centrality[i]));
    }
    for (int s = 0; s < r->n_segments; s++) {
        seg_total += r->segments[s].size;
        CHECK(r->segments[s].feature_size >= 0);
        if (s > 0) CHECK(r->segments[s].size <= r->segments[s - 1].size);
    }
    for (int s = 0; s < r->n_supernodes; s++) sn_total += r->supernodes[s].size;
    CHECK(seg_total == r->n_points);
    CHECK(sn_total == r->n_points);
    REQUIRE(r->n_tree_nodes >= 1);
    CHECK(r->tree[0].parent == -1 && r->tree[0].n_supernodes == r->n_supernodes);
    for (int t = 0; t < r->n_tree_nodes; t++) {
        const ps_tree_node *node = &r->tree[t];
        if (node->children[0] < 0) continue;
        const ps_tree_node *a = &r->tree[node->children[0]], *b = &r->tree[node->children[1]];
        CHECK(a->parent == t && b->parent == t);
        CHECK(a->n_supernodes + b->n_supernodes == node->n_supernodes);
    }
    for (int m = 0; m < r->n_merges; m++) { /* named by a refinement step, in the order they ran */
        ps_step step = r->merges[m].step;
        CHECK_MSG(step == PS_STEP_FEATURE_MERGE || step == PS_STEP_CREASE_MERGE ||
                      step == PS_STEP_CONVEX_MERGE || step == PS_STEP_PATCH_MERGE,
                  "merge %d: step %s", m, ps_step_name(step));
        if (m > 0) CHECK(step >= r->merges[m - 1].step);
    }
}

double ps_moved_share(const ps_result *a, const int *labels_b, size_t n) {
    size_t na = (size_t)a->n_segments, nb = 0, agree = 0;
    for (size_t i = 0; i < n; i++)
        if ((size_t)labels_b[i] + 1 > nb) nb = (size_t)labels_b[i] + 1;
    size_t *table = calloc(na * nb, sizeof *table);
    if (!table) return 1;
    for (size_t i = 0; i < n; i++) table[(size_t)a->labels[i] * nb + (size_t)labels_b[i]]++;
    for (size_t s = 0; s < na; s++) {
        size_t best = 0;
        for (size_t t = 0; t < nb; t++)
            if (table[s * nb + t] > best) best = table[s * nb + t];
        agree += best;
    }
    free(table);
    return 1.0 - (double)agree / (double)n;
}

ps_result *ps_segment_with(const double *pts, size_t n, const ps_params *p) {
    ps_input in = {.points = pts, .n = n, .dim = 3};
    ps_result *r = NULL;
    ps_error err = {0};
    ps_status st = ps_segment(&in, p, NULL, &r, &err);
    CHECK_MSG(st == PS_OK, "ps_segment failed: %s", err.message);
    return r;
}

ps_result *ps_segment_default(const double *pts, size_t n) {
    ps_params p;
    ps_params_default(&p);
    return ps_segment_with(pts, n, &p);
}

int ps_check_parts_with(double *pts, size_t n, int *part, int first, int last,
                        double min_purity, const ps_params *p) {
    if (!pts || !part) {
        CHECK(pts && part);
        return -1;
    }
    ps_result *r = ps_segment_with(pts, n, p);
    int smoothing = r ? r->normal_smoothing : -1;
    CHECK(r != NULL);
    if (r) {
        ps_check_result_consistent(r);
        ps_check_parts_separate(r, part, first, last, min_purity);
    }
    ps_result_free(r);
    free(pts);
    free(part);
    return smoothing;
}

int ps_check_shape_parts(double *pts, size_t n, int *part, int first, int last,
                         double min_purity) {
    ps_params p;
    ps_params_default(&p);
    return ps_check_parts_with(pts, n, part, first, last, min_purity, &p);
}

void ps_check_one_part(double *pts, size_t n, const char *name) {
    REQUIRE(pts);
    ps_result *r = ps_segment_default(pts, n);
    REQUIRE(r);
    CHECK_MSG(r->n_segments == 1, "%s: %d segments", name, r->n_segments);
    ps_result_free(r);
    free(pts);
}
