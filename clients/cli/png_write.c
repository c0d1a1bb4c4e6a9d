/*
 * png_write.c: the PNG writer of `pointseg render` (png_write.h): filter
 * type 0 on every row, the whole image deflated in one IDAT chunk.
 */
#include "png_write.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

static void put_u32_be(unsigned char *p, uint32_t v) {
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* One chunk: length, type, data, CRC32 of type and data. */
static int write_chunk(FILE *f, const char type[4], const unsigned char *data, size_t len) {
    unsigned char head[8], tail[4];
    put_u32_be(head, (uint32_t)len);
    memcpy(head + 4, type, 4);
    uLong crc = crc32(0L, (const Bytef *)type, 4);
    if (len) crc = crc32(crc, data, (uInt)len);
    put_u32_be(tail, (uint32_t)crc);
    return fwrite(head, 1, 8, f) == 8 && (len == 0 || fwrite(data, 1, len, f) == len) &&
                   fwrite(tail, 1, 4, f) == 4
               ? 0
               : -1;
}

/* The raw scanlines, each prefixed with filter byte 0, deflated; NULL when
 * out of memory. */
static unsigned char *deflate_rows(const unsigned char *rgb, int width, int height,
                                   size_t *out_len) {
    size_t row = (size_t)width * 3;
    size_t raw_len = (row + 1) * (size_t)height;
    unsigned char *raw = malloc(raw_len);
    uLongf packed_len = compressBound((uLong)raw_len);
    unsigned char *packed = malloc(packed_len);
    if (raw && packed) {
        for (int y = 0; y < height; y++) {
            raw[(size_t)y * (row + 1)] = 0;
            memcpy(raw + (size_t)y * (row + 1) + 1, rgb + (size_t)y * row, row);
        }
        if (compress2(packed, &packed_len, raw, (uLong)raw_len, Z_BEST_COMPRESSION) == Z_OK) {
            free(raw);
            *out_len = packed_len;
            return packed;
        }
    }
    free(raw);
    free(packed);
    return NULL;
}

int cli_png_write(const char *path, const unsigned char *rgb, int width, int height) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    unsigned char ihdr[13];
    put_u32_be(ihdr, (uint32_t)width);
    put_u32_be(ihdr + 4, (uint32_t)height);
    ihdr[8] = 8;  /* bits per channel */
    ihdr[9] = 2;  /* truecolour RGB */
    ihdr[10] = 0; /* deflate */
    ihdr[11] = 0; /* adaptive filtering (each row says its filter) */
    ihdr[12] = 0; /* no interlace */
    size_t idat_len = 0;
    unsigned char *idat = deflate_rows(rgb, width, height, &idat_len);
    if (!idat) {
        errno = ENOMEM;
        return -1;
    }
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(signature, 1, 8, f) == 8 && write_chunk(f, "IHDR", ihdr, 13) == 0 &&
             write_chunk(f, "IDAT", idat, idat_len) == 0 && write_chunk(f, "IEND", NULL, 0) == 0;
    int saved = errno;
    if (f && fclose(f) != 0) ok = 0;
    else errno = saved;
    free(idat);
    return ok ? 0 : -1;
}
