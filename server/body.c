/* body.c: request body assembly: gzip inflate (every member of a
 * concatenated stream), multipart split (one file part), size bound. */
#include "body.h"

#include <microhttpd.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <zlib.h>

#define INFLATE_CHUNK 65536
#define MAX_FIELDS 64
#define MAX_FIELD_BYTES 4096

struct ps_body {
    size_t max_body;
    char *data;
    size_t len, cap;
    int gzip, multipart;
    z_stream z;
    int z_ended;          /* the last member so far is complete */
    unsigned char *chunk; /* #INFLATE_CHUNK inflate output */
    struct MHD_PostProcessor *pp;
    int has_file;
    ps_body_field fields[MAX_FIELDS];
    size_t n_fields;
    ps_api_error error;   /* first error of the multipart iterator */
    int failed;
};

static int grow(ps_body *b, size_t need) {
    if (need <= b->cap) return 0;
    size_t cap = b->cap ? b->cap : 65536;
    while (cap < need) cap *= 2;
    if (cap > b->max_body) cap = b->max_body;
    char *p = realloc(b->data, cap + 1);
    if (!p) return -1;
    b->data = p;
    b->cap = cap;
    return 0;
}

static int append_data(ps_body *b, const char *src, size_t n, ps_api_error *err) {
    if (n == 0) return 0; /* an empty part: b->data may still be NULL */
    if (n > b->max_body - b->len)
        return ps_api_fail(err, 413, "request body larger than the limit of %zu bytes", b->max_body);
    if (grow(b, b->len + n)) return ps_api_fail(err, 500, "out of memory reading the body");
    memcpy(b->data + b->len, src, n);
    b->len += n;
    b->data[b->len] = 0;
    return 0;
}

/* A call at offset 0 begins a field, except that libmicrohttpd, when a read
 * ends right after a short value, first calls with no bytes at offset 0 and
 * then again at offset 0 with the value: that second call continues the
 * field.  (An empty field followed by one of the same name reads as one.) */
static int begins_field(const ps_body_field *f, const char *key, uint64_t off) {
    return !f || strcmp(f->name, key) || (off == 0 && f->value[0]);
}

static int append_field(ps_body *b, const char *key, const char *src, uint64_t off, size_t n) {
    ps_body_field *f = b->n_fields ? &b->fields[b->n_fields - 1] : NULL;
    if (begins_field(f, key, off)) {
        if (b->n_fields == MAX_FIELDS)
            return ps_api_fail(&b->error, 400, "more than %d multipart fields", MAX_FIELDS);
        f = &b->fields[b->n_fields];
        f->name = strdup(key);
        f->value = calloc(1, 1);
        if (!f->name || !f->value) {
            free(f->name);
            free(f->value);
            return ps_api_fail(&b->error, 500, "out of memory reading multipart fields");
        }
        b->n_fields++;
    }
    size_t have = strlen(f->value);
    if (have + n > MAX_FIELD_BYTES)
        return ps_api_fail(&b->error, 400, "multipart field '%s' longer than %d bytes", key, MAX_FIELD_BYTES);
    char *v = realloc(f->value, have + n + 1);
    if (!v) return ps_api_fail(&b->error, 500, "out of memory reading multipart fields");
    memcpy(v + have, src, n);
    v[have + n] = 0;
    f->value = v;
    return 0;
}

static enum MHD_Result on_part(void *cls, enum MHD_ValueKind kind, const char *key,
                               const char *filename, const char *content_type,
                               const char *transfer_encoding, const char *data,
                               uint64_t off, size_t size) {
    ps_body *b = cls;
    (void)kind, (void)filename, (void)content_type, (void)transfer_encoding;
    if (!key) return MHD_YES;
    if (!strcmp(key, "file")) {
        if (b->has_file && off == 0) {
            ps_api_fail(&b->error, 400, "multipart/form-data body has more than one 'file' part");
            return MHD_NO;
        }
        b->has_file = 1;
        return append_data(b, data, size, &b->error) ? MHD_NO : MHD_YES;
    }
    return append_field(b, key, data, off, size) ? MHD_NO : MHD_YES;
}

/* libmicrohttpd 0.9.75 takes as the boundary all that follows a
 * case-sensitive "boundary=" in the Content-Type, so that
 * "boundary=b; charset=UTF-8" (Apache HttpClient's) or "BOUNDARY=b"
 * (parameter names are case-insensitive, RFC 9110 5.6.6) finds no part.
 * Rewrites the value of the connection's Content-Type, in place in
 * libmicrohttpd's read buffer, as "multipart/form-data;boundary=b" (b quoted
 * if it was), never longer than it was; a type without a boundary parameter
 * is left as it is. */
static void put_boundary_last(char *ct) {
    static const char lead[] = "multipart/form-data;boundary=";
    char *p = strchr(ct, ';');
    for (; p; p = strchr(p, ';')) {
        p++;
        p += strspn(p, " \t");
        if (!strncasecmp(p, "boundary=", 9)) break;
    }
    if (!p) return;
    char *value = p + 9, *close = *value == '"' ? strchr(value + 1, '"') : NULL;
    size_t len = close ? (size_t)(close - value) + 1 : strcspn(value, "; \t");
    memmove(ct + sizeof lead - 1, value, len); /* value is at least that far in */
    memcpy(ct, lead, sizeof lead - 1);
    ct[sizeof lead - 1 + len] = 0;
}

/* libmicrohttpd's post processor on the connection's multipart body. */
static struct MHD_PostProcessor *new_post_processor(struct MHD_Connection *conn, ps_body *b) {
    const char *ct = MHD_lookup_connection_value(conn, MHD_HEADER_KIND, MHD_HTTP_HEADER_CONTENT_TYPE);
    if (ct) put_boundary_last((char *)(uintptr_t)ct);
    return MHD_create_post_processor(conn, 65536, on_part, b);
}

ps_body *ps_body_new(struct MHD_Connection *conn, size_t max_body, size_t reserve,
                     int gzip, int multipart, ps_api_error *err) {
    ps_body *b = calloc(1, sizeof *b);
    if (!b) return ps_api_fail(err, 500, "out of memory"), NULL;
    b->max_body = max_body;
    b->gzip = gzip;
    b->multipart = multipart;
    if (!gzip && !multipart && reserve && reserve <= max_body && grow(b, reserve)) goto nomem;
    if (gzip) {
        b->chunk = malloc(INFLATE_CHUNK);
        if (!b->chunk || inflateInit2(&b->z, 15 + 32) != Z_OK) goto nomem;
    }
    if (multipart) {
        b->pp = new_post_processor(conn, b);
        if (!b->pp) {
            ps_body_free(b);
            return ps_api_fail(err, 400, "multipart/form-data without a usable boundary"), NULL;
        }
    }
    return b;
nomem:
    ps_body_free(b);
    return ps_api_fail(err, 500, "out of memory"), NULL;
}

/* Bytes after inflating: to the post processor or the buffer. */
static int take(ps_body *b, const char *data, size_t len, ps_api_error *err) {
    if (!b->multipart) return append_data(b, data, len, err);
    if (MHD_post_process(b->pp, data, len) == MHD_YES) return 0;
    if (b->error.http_status) {
        *err = b->error;
        return -1;
    }
    return ps_api_fail(err, 400, "malformed multipart/form-data body");
}

/* Inflates data; a new gzip member may start where one ended ("cat a.gz
 * b.gz"), so input after a member's end starts the next one. */
static int inflate_feed(ps_body *b, const char *data, size_t len, ps_api_error *err) {
    b->z.next_in = (unsigned char *)(uintptr_t)data;
    b->z.avail_in = (uInt)len;
    while (b->z.avail_in) {
        if (b->z_ended) {
            inflateReset(&b->z);
            b->z_ended = 0;
        }
        b->z.next_out = b->chunk;
        b->z.avail_out = INFLATE_CHUNK;
        int rc = inflate(&b->z, Z_NO_FLUSH);
        if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR)
            return ps_api_fail(err, 400, "bad gzip body: %s", b->z.msg ? b->z.msg : "corrupt stream");
        if (take(b, (const char *)b->chunk, INFLATE_CHUNK - b->z.avail_out, err)) return -1;
        if (rc == Z_STREAM_END) b->z_ended = 1;
        if (rc == Z_BUF_ERROR) break;
    }
    return 0;
}

int ps_body_feed(ps_body *b, const char *data, size_t len, ps_api_error *err) {
    if (b->failed) return -1;
    int rc = 0;
    while (len && !rc) {
        size_t piece = len > (1u << 30) ? (1u << 30) : len;
        rc = b->gzip ? inflate_feed(b, data, piece, err) : take(b, data, piece, err);
        data += piece;
        len -= piece;
    }
    b->failed = rc != 0;
    return rc;
}

int ps_body_finish(ps_body *b, ps_api_error *err) {
    if (b->failed) return -1;
    if (b->gzip && !b->z_ended) return ps_api_fail(err, 400, "bad gzip body: the stream is truncated");
    if (b->multipart) {
        int complete = MHD_destroy_post_processor(b->pp) == MHD_YES;
        b->pp = NULL;
        if (!complete) return ps_api_fail(err, 400, "multipart/form-data body is truncated or malformed");
        if (!b->has_file) return ps_api_fail(err, 400, "multipart/form-data body has no 'file' part");
    }
    return 0;
}

const char *ps_body_data(const ps_body *b, size_t *len) {
    *len = b->len;
    return b->data ? b->data : "";
}

const ps_body_field *ps_body_fields(const ps_body *b, size_t *count) {
    *count = b->n_fields;
    return b->fields;
}

void ps_body_free(ps_body *b) {
    if (!b) return;
    if (b->pp) MHD_destroy_post_processor(b->pp);
    if (b->gzip) inflateEnd(&b->z);
    for (size_t i = 0; i < b->n_fields; i++) {
        free(b->fields[i].name);
        free(b->fields[i].value);
    }
    free(b->chunk);
    free(b->data);
    free(b);
}
