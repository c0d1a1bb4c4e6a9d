/* test_ncut_tree.c: the normalized-cut hierarchy on hand-made similarity
 * matrices (ncut_tree.h): blocks, no structure, components, order, cancel. */
#include "hierarchy/ncut_tree.h"
#include "testlib.h"

#include <stdlib.h>

#define MAX_M 16

typedef struct fixture {
    int m;
    double W[MAX_M * MAX_M];
    int component[MAX_M];
} fixture;

static void set_w(fixture *f, int u, int v, double w) {
    f->W[u * f->m + v] = f->W[v * f->m + u] = w;
}

/* block[u] labels; weight inside a block `in`, between blocks a and b
 * link(a, b) from a small table; W(u,u) = 1. */
static void fill_blocks(fixture *f, int m, const int *block, double in,
                        const double link[3][3]) {
    f->m = m;
    for (int u = 0; u < m; u++) {
        f->component[u] = 0;
        for (int v = 0; v <= u; v++)
            set_w(f, u, v, u == v ? 1 : block[u] == block[v] ? in : link[block[u]][block[v]]);
    }
}

static int same_set(const ps_tree_node *node, const int *ids, int count) {
    if (node->n_supernodes != count) return 0;
    for (int i = 0; i < count; i++)
        if (node->supernodes[i] != ids[i]) return 0;
    return 1;
}

static int is_leaf(const ps_tree_node *node) {
    return node->children[0] == -1 && node->children[1] == -1;
}

/* Even and odd ids are two dense blocks, weakly linked. */
static void test_two_blocks_split(void) {
    static const int block[10] = {0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
    static const double link[3][3] = {{0, 0.01, 0}, {0.01, 0, 0}, {0, 0, 0}};
    static const int evens[5] = {0, 2, 4, 6, 8}, odds[5] = {1, 3, 5, 7, 9};
    fixture f;
    fill_blocks(&f, 10, block, 1, link);
    ps_tree_node *tree;
    int n;
    REQUIRE(ps_ncut_tree_build(f.W, f.m, f.component, 0.3, NULL, &tree, &n, NULL) == PS_OK);
    REQUIRE(n == 3);
    CHECK(tree[0].parent == -1 && tree[0].children[0] == 1 && tree[0].children[1] == 2);
    CHECK(same_set(&tree[1], evens, 5));
    CHECK(same_set(&tree[2], odds, 5));
    /* cut 25 * 0.01, assoc of each block 25 + 0.25 */
    CHECK_NEAR(tree[0].ncut, 2 * 0.25 / 25.25, 1e-12);
    for (int i = 1; i <= 2; i++) {
        CHECK(is_leaf(&tree[i]) && tree[i].parent == 0 && tree[i].id == i);
        CHECK_NEAR(tree[i].ncut, 1, 1e-9); /* any split of a uniform block */
    }
    ps_tree_free(tree, n);
}

/* Similar everywhere: the best split is refused and recorded. */
static void test_no_structure_not_split(void) {
    fixture f = {.m = 12};
    for (int u = 0; u < f.m; u++)
        for (int v = 0; v <= u; v++)
            set_w(&f, u, v, u == v ? 1 : 0.9 + 0.2 * ((u * 7 + v * 3) % 5) / 4.0);
    ps_tree_node *tree;
    int n;
    REQUIRE(ps_ncut_tree_build(f.W, f.m, f.component, 0.3, NULL, &tree, &n, NULL) == PS_OK);
    REQUIRE(n == 1);
    CHECK(is_leaf(&tree[0]) && tree[0].n_supernodes == 12);
    CHECK_MSG(tree[0].ncut > 0.8 && tree[0].ncut < 1.2, "ncut %g", tree[0].ncut);
    for (int u = 0; u < 12; u++) CHECK(tree[0].supernodes[u] == u);
    ps_tree_free(tree, n);
}

/* Components interleaved: split off one component at a time, NCut 0. */
static void test_three_components(void) {
    fixture f = {.m = 6};
    for (int u = 0; u < 6; u++) {
        f.component[u] = u % 3;
        for (int v = 0; v <= u; v++) set_w(&f, u, v, u % 3 == v % 3 ? 1 : 0);
    }
    ps_tree_node *tree;
    int n;
    REQUIRE(ps_ncut_tree_build(f.W, 6, f.component, 0.3, NULL, &tree, &n, NULL) == PS_OK);
    REQUIRE(n == 5);
    static const int c0[2] = {0, 3}, rest[4] = {1, 2, 4, 5}, c1[2] = {1, 4}, c2[2] = {2, 5};
    CHECK(tree[0].ncut == 0 && tree[0].children[0] == 1 && tree[0].children[1] == 2);
    CHECK(same_set(&tree[1], c0, 2) && is_leaf(&tree[1]));
    CHECK_NEAR(tree[1].ncut, 1, 1e-9); /* {0, 3} refused: 1/2 + 1/2 */
    CHECK(same_set(&tree[2], rest, 4) && tree[2].ncut == 0);
    CHECK(tree[2].children[0] == 3 && tree[2].children[1] == 4);
    CHECK(same_set(&tree[3], c1, 2) && tree[3].parent == 2 && is_leaf(&tree[3]));
    CHECK(same_set(&tree[4], c2, 2) && tree[4].parent == 2 && is_leaf(&tree[4]));
    ps_tree_free(tree, n);
}

/* Blocks A = 8..11, B = 0..3, C = 4..7 in a chain A - B - C, A - B the
 * weakest: A | B C first, then B | C, breadth first; children[0] is always
 * the side of the lowest id, whatever the eigenvector's orientation. */
static void test_chain_order_and_determinism(void) {
    static const int block[12] = {1, 1, 1, 1, 2, 2, 2, 2, 0, 0, 0, 0};
    static const double link[3][3] = {{0, 0.001, 0}, {0.001, 0, 0.02}, {0, 0.02, 0}};
    static const int a[4] = {8, 9, 10, 11}, bc[8] = {0, 1, 2, 3, 4, 5, 6, 7},
                     b[4] = {0, 1, 2, 3}, c[4] = {4, 5, 6, 7};
    fixture f;
    fill_blocks(&f, 12, block, 1, link);
    ps_tree_node *tree, *again;
    int n, n_again;
    REQUIRE(ps_ncut_tree_build(f.W, 12, f.component, 0.3, NULL, &tree, &n, NULL) == PS_OK);
    REQUIRE(n == 5);
    CHECK(same_set(&tree[1], bc, 8) && same_set(&tree[2], a, 4));
    CHECK(same_set(&tree[3], b, 4) && same_set(&tree[4], c, 4));
    CHECK(tree[1].children[0] == 3 && tree[1].children[1] == 4 && is_leaf(&tree[2]));
    CHECK(tree[0].ncut < tree[1].ncut && tree[1].ncut < 0.1);
    REQUIRE(ps_ncut_tree_build(f.W, 12, f.component, 0.3, NULL, &again, &n_again, NULL) ==
            PS_OK);
    REQUIRE(n_again == n);
    for (int i = 0; i < n; i++) CHECK(tree[i].ncut == again[i].ncut);
    ps_tree_free(tree, n);
    ps_tree_free(again, n_again);
}

static void record_progress(void *user, ps_phase phase, double fraction) {
    double *last = user;
    if (phase == PS_PHASE_HIERARCHY && fraction >= *last) *last = fraction;
    else *last = -1; /* wrong phase or going backwards */
}

static void test_progress_and_cancel(void) {
    fixture f = {.m = 6};
    for (int u = 0; u < 6; u++) {
        f.component[u] = u % 3;
        for (int v = 0; v <= u; v++) set_w(&f, u, v, u % 3 == v % 3 ? 1 : 0);
    }
    double last = 0;
    volatile int cancel = 0;
    ps_control ctl = {.progress = record_progress, .user = &last, .cancel = &cancel};
    ps_tree_node *tree;
    int n;
    REQUIRE(ps_ncut_tree_build(f.W, 6, f.component, 0.3, &ctl, &tree, &n, NULL) == PS_OK);
    CHECK(last == 1.0);
    ps_tree_free(tree, n);
    cancel = 1;
    ps_error err = {0};
    CHECK(ps_ncut_tree_build(f.W, 6, f.component, 0.3, &ctl, &tree, &n, &err) ==
          PS_ERR_CANCELLED);
    CHECK(tree == NULL && n == 0 && err.status == PS_ERR_CANCELLED);
}

static void test_single_and_invalid(void) {
    double one = 4, zero_diag[4] = {0, 1, 1, 1};
    int component[2] = {0, 0};
    ps_tree_node *tree;
    int n;
    REQUIRE(ps_ncut_tree_build(&one, 1, component, 0.3, NULL, &tree, &n, NULL) == PS_OK);
    CHECK(n == 1 && tree[0].ncut == -1 && is_leaf(&tree[0]) && tree[0].supernodes[0] == 0);
    ps_tree_free(tree, n);
    ps_error err = {0};
    CHECK(ps_ncut_tree_build(zero_diag, 2, component, 0.3, NULL, &tree, &n, &err) ==
          PS_ERR_INVALID);
}

PS_TEST_MAIN(TEST(test_two_blocks_split), TEST(test_no_structure_not_split),
             TEST(test_three_components), TEST(test_chain_order_and_determinism),
             TEST(test_progress_and_cancel), TEST(test_single_and_invalid))
