/*
 * decode_ply_header.h: the header of a PLY file (format, elements in file
 * order with their counts and properties, where the data starts) and the
 * reading of one binary value.  Internal to api/ (decode_ply.c).
 */
#ifndef PS_DECODE_PLY_HEADER_H
#define PS_DECODE_PLY_HEADER_H

#include <stddef.h>
#include <stdint.h>

#include "api_error.h"

enum {
    PS_PLY_MAX_ELEMENTS = 32, PS_PLY_MAX_PROPERTIES = 256, PS_PLY_NAME_MAX = 32,
    PS_PLY_MAX_SKIPPED = 4,   /* header lines without a known keyword, skipped */
    PS_PLY_PREVIEW_MAX = 64   /* bytes kept of a skipped line, NUL included */
};

typedef enum ps_ply_format { PS_PLY_ASCII, PS_PLY_BINARY_LE, PS_PLY_BINARY_BE } ps_ply_format;

typedef enum ps_ply_type {
    PS_PLY_INT8, PS_PLY_UINT8, PS_PLY_INT16, PS_PLY_UINT16,
    PS_PLY_INT32, PS_PLY_UINT32, PS_PLY_FLOAT32, PS_PLY_FLOAT64
} ps_ply_type;

typedef struct ps_ply_property {
    char name[PS_PLY_NAME_MAX]; /* truncated to PS_PLY_NAME_MAX - 1 bytes */
    ps_ply_type type;           /* of the value, or of each list item */
    int is_list;
    ps_ply_type count_type;     /* lists only */
} ps_ply_property;

typedef struct ps_ply_element {
    char name[PS_PLY_NAME_MAX];
    uint64_t count;
    int first_property;         /* index into ps_ply_header.properties */
    int n_properties;
} ps_ply_element;

/* A header line that old exporters write without a keyword (Blender 2.4x:
 * "Created by Blender3D 247 - www.blender.org, source file: ..."). */
typedef struct ps_ply_skipped {
    size_t line;
    char preview[PS_PLY_PREVIEW_MAX]; /* its start, control bytes shown as '?' */
} ps_ply_skipped;

typedef struct ps_ply_header {
    ps_ply_format format;
    size_t data_offset;         /* first byte after "end_header\n" */
    int n_elements;
    ps_ply_element elements[PS_PLY_MAX_ELEMENTS];
    int n_properties;
    ps_ply_property properties[PS_PLY_MAX_PROPERTIES];
    int n_skipped;
    ps_ply_skipped skipped[PS_PLY_MAX_SKIPPED];
} ps_ply_header;

/* Parses the header of bytes (#len, starting "ply").  A line whose first
 * word is none of format, element, property, comment, obj_info and
 * end_header is skipped and listed in h->skipped (at most
 * PS_PLY_MAX_SKIPPED; one more is refused).  Returns 0, or -1 with a 400
 * naming the header line. */
int ps_ply_parse_header(const char *bytes, size_t len, ps_ply_header *h, ps_api_error *err);

/* Bytes of one value of type t (1, 2, 4 or 8). */
size_t ps_ply_type_size(ps_ply_type t);

/* The element named name, or NULL. */
const ps_ply_element *ps_ply_find_element(const ps_ply_header *h, const char *name);

/* Index within e (0-based) of its scalar property named name, or -1. */
int ps_ply_find_scalar(const ps_ply_header *h, const ps_ply_element *e, const char *name);

/* Property i (0-based, < e->n_properties) of element e. */
const ps_ply_property *ps_ply_property_of(const ps_ply_header *h, const ps_ply_element *e,
                                          int i);

/* Byte offset of property i of e within one binary record, as the sum of
 * the sizes of the properties before it (meaningful when none of them is a
 * list); i == e->n_properties gives the record's size. */
size_t ps_ply_scalar_offset(const ps_ply_header *h, const ps_ply_element *e, int i);

/* 1 when a binary file of format f has the other byte order than this
 * machine (its values must be byte-swapped), else 0. */
int ps_ply_needs_swap(ps_ply_format f);

/* The value of type t stored at `at` (ps_ply_type_size(t) bytes, byte-swapped
 * first when swap), as a double. */
double ps_ply_load_binary(const char *at, ps_ply_type t, int swap);

#endif
