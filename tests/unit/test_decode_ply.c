/* test_decode_ply.c: the PLY decoder: ascii and both binary byte orders,
 * every scalar type, skipped properties and elements, faces, and bad input
 * (truncated, lying or huge counts, an ascii line with a value too many
 * or too few, NaN, bad indices, limits); vertex
 * colours; the header helpers. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "decode.h"
#include "decode_check.h"
#include "decode_ply_header.h"
#include "testlib.h"

typedef struct bytes_out {
    char data[8192];
    size_t len;
} bytes_out;

static void put_text(bytes_out *b, const char *s) {
    size_t n = strlen(s);
    memcpy(b->data + b->len, s, n);
    b->len += n;
}

static void put_bits(bytes_out *b, uint64_t bits, size_t size, int big) {
    for (size_t i = 0; i < size; i++) {
        size_t shift = 8 * (big ? size - 1 - i : i);
        b->data[b->len++] = (char)(unsigned char)(bits >> shift);
    }
}

/* Writes v as PLY type `type` ("char" .. "double") in the byte order big. */
static void put_value(bytes_out *b, const char *type, double v, int big) {
    if (!strcmp(type, "float") || !strcmp(type, "float32")) {
        float f = (float)v;
        uint32_t bits;
        memcpy(&bits, &f, 4);
        put_bits(b, bits, 4, big);
    } else if (!strcmp(type, "double") || !strcmp(type, "float64")) {
        uint64_t bits;
        memcpy(&bits, &v, 8);
        put_bits(b, bits, 8, big);
    } else {
        size_t size = strstr(type, "char") || strstr(type, "8") ? 1
                      : strstr(type, "short") || strstr(type, "16") ? 2 : 4;
        put_bits(b, (uint64_t)(int64_t)v, size, big);
    }
}

static int decode_fails(const char *bytes, size_t len, const ps_decode_limits *lim, int status,
                        const char *needle) {
    return ps_check_decode_fails(ps_decode_ply, bytes, len, lim, status, needle);
}

static int text_fails(const char *text, int status, const char *needle) {
    return decode_fails(text, strlen(text), NULL, status, needle);
}

static const char ascii_ply[] =
    "ply\r\n"
    "format ascii 1.0\r\n"
    "comment made by hand\r\n"
    "obj_info nothing\r\n"
    "element face 2\r\n"
    "property uchar flags\r\n"
    "property list uchar int vertex_indices\r\n"
    "element vertex 4\r\n"
    "property float x\r\n"
    "property uchar red\r\n"
    "property list uchar float uv\r\n"
    "property double z\r\n"
    "property float y\r\n"
    "element edge 1\r\n"
    "property list int int ends\r\n"
    "end_header\r\n"
    "7 4 0 1 2 3\r\n"
    "7 3 3 2 1\r\n"
    "0 255 2 0.5 0.5 0 0\r\n"
    "1 255 0 0 0\r\n"
    "1.5 255 1 9 -2 1\r\n"
    "0 1 0 3.25 1e2\r\n"
    "2 0 1\r\n";

static void test_ascii_crlf_any_order(void) {
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode_ply(ascii_ply, sizeof ascii_ply - 1, NULL, &ps, &err) == 0);
    CHECK(ps.n == 4 && ps.dim == 3 && ps.normals == NULL);
    CHECK_NEAR(ps.points[6], 1.5, 0);
    CHECK_NEAR(ps.points[7], 1, 0);
    CHECK_NEAR(ps.points[8], -2, 0);
    CHECK_NEAR(ps.points[10], 100, 0);
    CHECK_NEAR(ps.points[11], 3.25, 0);
    REQUIRE(ps.n_faces == 3);
    static const uint32_t want[] = {0, 1, 2, 0, 2, 3, 3, 2, 1};
    CHECK(!memcmp(ps.faces, want, sizeof want));
    ps_pointset_free(&ps);
    CHECK(ps.points == NULL && ps.n == 0);
}

/* Vertex colours: uchar red green blue in any order kept as they are. */
static void test_colors_ascii(void) {
    static const char text[] = "ply\nformat ascii 1.0\nelement vertex 2\nproperty uchar blue\n"
                               "property float x\nproperty float y\nproperty uchar red\n"
                               "property float z\nproperty uchar green\nend_header\n"
                               "3 0 0 1 0 2\n255 1 1 200 1 0\n";
    static const unsigned char want[] = {1, 2, 3, 200, 0, 255};
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode_ply(text, sizeof text - 1, NULL, &ps, &err) == 0);
    REQUIRE(ps.n == 2 && ps.colors != NULL);
    CHECK(memcmp(ps.colors, want, sizeof want) == 0);
    CHECK(ps.points[3] == 1 && ps.points[5] == 1);
    ps_pointset_free(&ps);
    CHECK(ps.colors == NULL);
}

/* Float colours (0..1) are scaled to bytes, clamped and rounded, in both
 * byte orders; without all three channels there are no colours. */
static void test_colors_binary_float_and_partial(void) {
    static const double channel[2][3] = {{0.0, 0.5, 1.0}, {-0.25, 2.0, 0.1}};
    static const unsigned char want[] = {0, 128, 255, 0, 255, 26};
    for (int big = 0; big <= 1; big++) {
        bytes_out b = {.len = 0};
        put_text(&b, "ply\n");
        put_text(&b, big ? "format binary_big_endian 1.0\n" : "format binary_little_endian 1.0\n");
        put_text(&b, "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                     "property float red\nproperty double green\nproperty float blue\n"
                     "end_header\n");
        for (int i = 0; i < 2; i++) {
            for (int c = 0; c < 3; c++) put_value(&b, "float", i + c, big);
            put_value(&b, "float", channel[i][0], big);
            put_value(&b, "double", channel[i][1], big);
            put_value(&b, "float", channel[i][2], big);
        }
        ps_pointset ps;
        ps_api_error err;
        REQUIRE(ps_decode_ply(b.data, b.len, NULL, &ps, &err) == 0);
        REQUIRE(ps.colors != NULL);
        CHECK_MSG(memcmp(ps.colors, want, sizeof want) == 0, "big %d", big);
        ps_pointset_free(&ps);
    }
    static const char red_only[] = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                   "property float y\nproperty uchar red\nend_header\n0 0 9\n";
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode_ply(red_only, sizeof red_only - 1, NULL, &ps, &err) == 0);
    CHECK(ps.n == 1 && ps.dim == 2 && ps.colors == NULL);
    ps_pointset_free(&ps);
}

static const char *const all_types[] = {"char", "uchar", "short", "ushort",
                                        "int", "uint", "float", "double"};
static const char *const all_aliases[] = {"int8", "uint8", "int16", "uint16",
                                          "int32", "uint32", "float32", "float64"};

/* A binary PLY: vertices with x y z nx ny nz of the given types in a
 * shuffled order with a colour and (when with_list) a list between them,
 * a face element with an extra property, an "edge" element after it. */
static void build_binary(bytes_out *b, int big, const char *xyz_type, const char *n_type,
                         const char *index_type, int with_list) {
    char line[128];
    b->len = 0;
    put_text(b, "ply\n");
    put_text(b, big ? "format binary_big_endian 1.0\n" : "format binary_little_endian 1.0\n");
    put_text(b, "element vertex 3\n");
    snprintf(line, sizeof line, "property %s nz\nproperty %s y\nproperty uchar red\n", n_type,
             xyz_type);
    put_text(b, line);
    if (with_list) put_text(b, "property list ushort double extra\n");
    snprintf(line, sizeof line, "property %s x\nproperty %s nx\nproperty %s z\nproperty %s ny\n",
             xyz_type, n_type, xyz_type, n_type);
    put_text(b, line);
    put_text(b, "element face 2\nproperty short quality\n");
    snprintf(line, sizeof line, "property list uint %s vertex_index\n", index_type);
    put_text(b, line);
    put_text(b, "element edge 1\nproperty list uchar int ends\nproperty float w\nend_header\n");
    for (int i = 0; i < 3; i++) {
        put_value(b, n_type, -1, big);           /* nz */
        put_value(b, xyz_type, 10 + i, big);     /* y */
        put_value(b, "uchar", 200, big);
        if (with_list) {
            put_value(b, "ushort", 2, big);
            put_value(b, "double", 1, big);
            put_value(b, "double", 2, big);
        }
        put_value(b, xyz_type, i, big);          /* x */
        put_value(b, n_type, 1, big);            /* nx */
        put_value(b, xyz_type, 20 + i, big);     /* z */
        put_value(b, n_type, 0, big);            /* ny */
    }
    for (int f = 0; f < 2; f++) {
        put_value(b, "short", -5, big);
        put_value(b, "uint", 3, big);
        for (int k = 0; k < 3; k++) put_value(b, index_type, f ? 2 - k : k, big);
    }
    put_value(b, "uchar", 2, big);
    put_value(b, "int", 0, big);
    put_value(b, "int", 1, big);
    put_value(b, "float", 0.5, big);
}

static int binary_decodes_right(int big, const char *xyz_type, const char *n_type,
                                const char *index_type, int with_list) {
    bytes_out b;
    ps_pointset ps;
    ps_api_error err;
    build_binary(&b, big, xyz_type, n_type, index_type, with_list);
    if (ps_decode_ply(b.data, b.len, NULL, &ps, &err)) {
        fprintf(stderr, "  %s %s %s: %s\n", xyz_type, n_type, index_type, err.message);
        return 0;
    }
    int ok = ps.n == 3 && ps.dim == 3 && ps.normals && ps.n_faces == 2;
    for (size_t i = 0; ok && i < 3; i++)
        ok = ps.points[3 * i] == (double)i && ps.points[3 * i + 1] == 10.0 + (double)i &&
             ps.points[3 * i + 2] == 20.0 + (double)i && ps.normals[3 * i] == 1 &&
             ps.normals[3 * i + 1] == 0 && ps.normals[3 * i + 2] == -1;
    ok = ok && ps.faces[0] == 0 && ps.faces[2] == 2 && ps.faces[3] == 2 && ps.faces[5] == 0;
    ps_pointset_free(&ps);
    return ok;
}

static void test_binary_every_type_both_endians(void) {
    static const char *const signed_types[] = {"char", "short", "int", "float",
                                               "double", "int8", "int16", "float64"};
    for (int big = 0; big < 2; big++)
        for (int t = 0; t < 8; t++) {
            const char *index_type = all_types[(t + 5) % 8];
            CHECK_MSG(binary_decodes_right(big, all_types[t], signed_types[t], index_type, 0),
                      "big=%d xyz=%s normals=%s index=%s", big, all_types[t], signed_types[t],
                      index_type);
            CHECK_MSG(binary_decodes_right(big, all_aliases[t], "float", all_aliases[t], 1),
                      "big=%d xyz=%s with a list", big, all_aliases[t]);
        }
}

static void test_two_dimensional(void) {
    static const char text[] = "ply\nformat ascii 1.0\nelement vertex 2\nproperty int y\n"
                               "property int x\nproperty int nx\nproperty int ny\nend_header\n"
                               "1 2 0 1\n3 4 1 0\n";
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode_ply(text, sizeof text - 1, NULL, &ps, &err) == 0);
    CHECK(ps.n == 2 && ps.dim == 2 && ps.normals && ps.faces == NULL);
    CHECK(ps.points[0] == 2 && ps.points[1] == 1 && ps.points[2] == 4 && ps.points[3] == 3);
    CHECK(ps.normals[0] == 0 && ps.normals[1] == 1);
    ps_pointset_free(&ps);
}

static void test_missing_coordinate(void) {
    static const char text[] = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                               "property float z\nend_header\n1 2\n";
    CHECK(decode_fails(text, sizeof text - 1, NULL, 422, "no scalar property y"));
    static const char none[] = "ply\nformat ascii 1.0\nelement face 0\nend_header\n";
    CHECK(decode_fails(none, sizeof none - 1, NULL, 422, "no vertex element"));
}

static void test_huge_declared_count(void) {
    bytes_out b = {.len = 0};
    put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 1099511627776\n"
                 "property float x\nproperty float y\nproperty float z\nend_header\n");
    memset(b.data + b.len, 0, 1024 - b.len);
    b.len = 1024;
    CHECK(decode_fails(b.data, b.len, NULL, 400,
                       "vertex count 1099511627776 exceeds the data (needs 13194139533312 "
                       "bytes, "));
    b.len = 0;
    put_text(&b, "ply\nformat ascii 1.0\nelement vertex 18446744073709551615\n"
                 "property float x\nproperty float y\nend_header\n1 2\n");
    CHECK(decode_fails(b.data, b.len, NULL, 400, "exceeds the data"));
    b.len = 0;
    put_text(&b, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                 "element face 99999999999\nproperty list uchar int vertex_indices\n"
                 "end_header\n1 2\n3 0 0 0\n");
    CHECK(decode_fails(b.data, b.len, NULL, 400, "face count 99999999999 exceeds the data"));
    b.len = 0;
    put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 99999999999999999999\n"
                 "property float x\nend_header\n");
    CHECK(decode_fails(b.data, b.len, NULL, 400, "header line 3"));
}

static void test_truncated_and_lying(void) {
    bytes_out b;
    build_binary(&b, 0, "float", "float", "int", 0);
    size_t header = (size_t)(strstr(b.data, "end_header\n") - b.data) + 11;
    CHECK(decode_fails(b.data, header + 10, NULL, 400, "vertex count 3 exceeds the data"));
    CHECK(decode_fails(b.data, b.len - 3, NULL, 400, "truncated at byte offset"));
    size_t first_face = header + 3 * 25;
    b.data[first_face + 2] = 100; /* the list length of face 0: 100 little-endian */
    CHECK(decode_fails(b.data, b.len, NULL, 400, "truncated at byte offset"));
    b.data[first_face + 2] = 3;
    b.data[first_face + 5] = (char)0xff; /* high byte of the list length */
    CHECK(decode_fails(b.data, b.len, NULL, 400, "truncated at byte offset"));
    char want[64];
    static const char ascii[] = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                "property float y\nend_header\n10 20\n30 40\n50";
    snprintf(want, sizeof want, "truncated at byte offset %zu", sizeof ascii - 1);
    CHECK(decode_fails(ascii, sizeof ascii - 1, NULL, 400, want));
    static const char word[] = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                               "property float y\nend_header\n1 2\n3 four\n";
    snprintf(want, sizeof want, "expected a number at byte offset %zu",
             (size_t)(strstr(word, "four") - word));
    CHECK(decode_fails(word, sizeof word - 1, NULL, 400, want));
}

/* An ascii line with a value too many or too few (of a vertex, a face or
 * a skipped element) is a 400 naming the record, not values shifted into
 * the next points; a record wrapped onto a second line still reads. */
static void test_ascii_line_holds_one_record(void) {
    static const char head[] = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "element face 1\nproperty list uchar int vertex_indices\n"
                               "element camera 1\nproperty float f\nend_header\n";
    const struct {
        const char *data, *words;
    } bad[] = {
        {"0 0\n1 0 7\n0 1\n1 1\n3 0 1 2\n5\n", "values left on the line of vertex 1"},
        {"0 0\n1\n0 1\n1 1\n3 0 1 2\n5\n0\n", "values left on the line of vertex 1"},
        {"0 0\n1 0\n0 1\n1 1\n3 0 1 2 3\n5\n", "values left on the line of face 0"},
        {"0 0\n1 0\n0 1\n1 1\n3 0 1 2\n5 6\n", "values left on the line of camera 0"},
    };
    char text[512];
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(text, sizeof text, "%s%s", head, bad[i].data);
        CHECK_MSG(text_fails(text, 400, bad[i].words), "case %zu", i);
    }
    snprintf(text, sizeof text, "%s0 0\n1 0\n0 1\n1 1\n3 0 1\n 2\n5\n", head);
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode_ply(text, strlen(text), NULL, &ps, &err) == 0);
    CHECK(ps.n == 4 && ps.points[2] == 1 && ps.points[3] == 0 && ps.n_faces == 1);
    ps_pointset_free(&ps);
}

static void test_non_finite_and_bad_index(void) {
    static const char nan[] = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                              "property float y\nend_header\n1 2\nnan 4\n";
    CHECK(decode_fails(nan, sizeof nan - 1, NULL, 422, "vertex 1 has a non-finite coordinate"));
    bytes_out b;
    build_binary(&b, 1, "double", "float", "int", 0);
    size_t header = (size_t)(strstr(b.data, "end_header\n") - b.data) + 11;
    size_t vertex_bytes = 4 + 8 + 1 + 8 + 4 + 8 + 4, face_bytes = 2 + 4 + 3 * 4;
    size_t face1_last = header + 3 * vertex_bytes + face_bytes + 2 + 4 + 8;
    b.data[face1_last + 3] = 7; /* face 1, third index: 7 (big-endian int) */
    CHECK(decode_fails(b.data, b.len, NULL, 422, "face 1 refers to vertex 7"));
    b.data[face1_last] = (char)0xff; /* -16777209 */
    CHECK(decode_fails(b.data, b.len, NULL, 422, "face 1 refers to vertex -"));
}

/* Binary faces of every size beside triangles: a quad and a pentagon are
 * fanned, a triangle after them read whole, a two-corner face adds nothing. */
static void test_binary_polygons(void) {
    bytes_out b;
    b.len = 0;
    put_text(&b, "ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty float x\n"
                 "property float y\nelement face 4\nproperty list uchar int vertex_indices\n"
                 "end_header\n");
    for (int i = 0; i < 5; i++) put_value(&b, "float", i, 0), put_value(&b, "float", i * i, 0);
    static const int corners[] = {4, 0, 1, 2, 3, 5, 4, 3, 2, 1, 0, 3, 1, 2, 4, 2, 0, 4};
    for (size_t k = 0; k < sizeof corners / sizeof *corners;) {
        int count = corners[k++];
        put_value(&b, "uchar", count, 0);
        for (int j = 0; j < count; j++) put_value(&b, "int", corners[k++], 0);
    }
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode_ply(b.data, b.len, NULL, &ps, &err) == 0);
    static const uint32_t want[] = {0, 1, 2, 0, 2, 3, 4, 3, 2, 4, 2, 1, 4, 1, 0, 1, 2, 4};
    REQUIRE(ps.n_faces == 6);
    CHECK(memcmp(ps.faces, want, sizeof want) == 0);
    ps_pointset_free(&ps);
}

static void test_limits_and_garbage(void) {
    bytes_out b;
    build_binary(&b, 0, "float", "float", "int", 0);
    ps_decode_limits lim = {2, 64};
    CHECK(decode_fails(b.data, b.len, &lim, 413, "3 points exceed the limit of 2"));
    CHECK(text_fails("", 400, "expected \"ply\""));
    CHECK(text_fails("ply\nformat ascii 1.0\n", 400, "no end_header"));
    CHECK(text_fails("ply\nformat ascii 2\nelement v\nend_header\n", 400, "line 3"));
    CHECK(text_fails("ply\nformat ebcdic 1.0\nend_header\n", 400, "unknown format"));
    CHECK(text_fails("ply\nelement vertex 0\nend_header\n", 400, "no format"));
    CHECK(text_fails("ply\nformat ascii 1.0\nproperty float x\nend_header\n", 400,
                     "property before any element"));
    CHECK(text_fails("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n",
                     400, "line 4"));
    CHECK(text_fails("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                     "property float y\nend_header\n", 422, "no points"));
    CHECK(text_fails("ply\nformat ascii 1.0\nend_header now\n", 400, "line 3: unknown keyword \"end_header\""));
    CHECK(text_fails("ply\nformat ascii 1.0\na\nb\nc\nd\nwhatever\x01\nend_header\n", 400,
                     "line 7: unknown keyword \"whatever?\" (too many lines without a keyword)"));
}

/* Blender 2.4x writes a line without a keyword between format and the
 * elements: skipped, with a warning naming it; the data still has to
 * match the header. */
static void test_header_line_without_keyword(void) {
    static const char blender[] = "ply\nformat ascii 1.0\n"
                                  "Created by Blender3D 247 - www.blender.org, source file: 'hand.blend'\n"
                                  "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                  "element face 1\nproperty list uchar uint vertex_indices\nend_header\n"
                                  "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    ps_pointset ps;
    ps_api_error err;
    REQUIRE(ps_decode(blender, sizeof blender - 1, NULL, &ps, &err) == 0);
    CHECK(ps.n == 3 && ps.n_faces == 1 && ps.points[3] == 1 && ps.points[7] == 1);
    CHECK(ps.n_warnings == 1 &&
          !strcmp(ps.warnings[0], "PLY header line 3 skipped: no keyword in "
                                  "\"Created by Blender3D 247 - www.blender.org, source file: 'hand.\""));
    ps_pointset_free(&ps);
    char cut[sizeof blender];
    memcpy(cut, blender, sizeof blender);
    CHECK(ps_check_decode_fails(ps_decode, cut, sizeof blender - 1 - 2, NULL, 400,
                                "PLY data truncated at byte offset 249"));
    static const char clean[] = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                "end_header\n0 0\n1 0\n0 1\n";
    REQUIRE(ps_decode(clean, sizeof clean - 1, NULL, &ps, &err) == 0);
    CHECK(ps.n_warnings == 0);
    ps_pointset_free(&ps);
}

static void check_model(const char *name, size_t n, size_t n_faces, int normals) {
    char rel[256];
    ps_pointset ps;
    double ms;
    snprintf(rel, sizeof rel, "models/%s", name);
    int decoded = ps_decode_shared_file(rel, &ps, &ms);
    if (decoded == 0) return; /* skipped */
    REQUIRE(decoded == 1);
    printf("  %s: %zu vertices, %zu faces in %.2f ms\n", name, ps.n, ps.n_faces, ms);
    CHECK(ps.n == n && ps.dim == 3 && ps.n_faces == n_faces && (ps.normals != NULL) == normals);
    for (size_t i = 0; i < 3 * ps.n_faces; i++) CHECK(ps.faces[i] < ps.n);
    ps_pointset_free(&ps);
}

static void test_horse(void) { check_model("horse.ply", 48485, 96966, 1); }
static void test_bunny(void) { check_model("bunny.ply", 35947, 69451, 0); }

/* The header helpers (decode_ply_header.h). */
static void test_shared_value_reader(void) {
    static const char text[] = "ply\nformat binary_big_endian 1.0\nelement vertex 1\n"
                               "property short a\nproperty float b\nproperty uchar c\n"
                               "property double d\nend_header\n";
    static const char big_minus_two[] = {(char)0xff, (char)0xfe};
    static const char big_one_and_a_half[] = {0x3f, (char)0xc0, 0, 0};
    ps_ply_header h;
    ps_api_error err;
    REQUIRE(ps_ply_parse_header(text, sizeof text - 1, &h, &err) == 0);
    const ps_ply_element *v = ps_ply_find_element(&h, "vertex");
    REQUIRE(v && v->n_properties == 4);
    CHECK(!strcmp(ps_ply_property_of(&h, v, 2)->name, "c"));
    static const size_t offsets[] = {0, 2, 6, 7, 15};
    for (int i = 0; i <= 4; i++) CHECK_MSG(ps_ply_scalar_offset(&h, v, i) == offsets[i], "%d", i);
    int swap = ps_ply_needs_swap(h.format);
    CHECK(swap != ps_ply_needs_swap(PS_PLY_BINARY_LE));
    CHECK(ps_ply_load_binary(big_minus_two, PS_PLY_INT16, swap) == -2);
    CHECK(ps_ply_load_binary(big_minus_two, PS_PLY_UINT16, swap) == 65534);
    CHECK(ps_ply_load_binary(big_one_and_a_half, PS_PLY_FLOAT32, swap) == 1.5);
    CHECK(ps_ply_load_binary(big_minus_two, PS_PLY_INT8, swap) == -1);
}

PS_TEST_MAIN(TEST(test_ascii_crlf_any_order), TEST(test_colors_ascii),
             TEST(test_colors_binary_float_and_partial), TEST(test_binary_every_type_both_endians),
             TEST(test_two_dimensional), TEST(test_missing_coordinate),
             TEST(test_huge_declared_count), TEST(test_truncated_and_lying),
             TEST(test_ascii_line_holds_one_record),
             TEST(test_non_finite_and_bad_index), TEST(test_limits_and_garbage),
             TEST(test_header_line_without_keyword), TEST(test_binary_polygons),
             TEST(test_horse), TEST(test_bunny), TEST(test_shared_value_reader))
