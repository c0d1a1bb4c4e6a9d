/*
 * decode.h: bytes in, a ps_pointset out.  Formats are recognized from the
 * content, never from a file name: PLY (ascii, binary little and big endian;
 * any vertex properties of any PLY type; faces kept, other elements skipped),
 * OFF, OBJ (`v` and `f` lines), XYZ/CSV text (x y z per line, optional
 * normals as columns 4..6 when 6 columns; any dimension >= 2), and the JSON
 * request body {"points": [[x,y,z], ...], "params": {...}} or
 * {"points": [x,y,z,...], "dimension": 3}.
 *
 * Every failure is a ps_api_error with line or byte offset; no input makes a
 * decoder crash, read out of bounds or allocate more than the limits allow.
 */
#ifndef PS_DECODE_H
#define PS_DECODE_H

#include "api_error.h"
#include "pointset.h"

typedef enum ps_format {
    PS_FORMAT_UNKNOWN = 0,
    PS_FORMAT_PLY,
    PS_FORMAT_OFF,
    PS_FORMAT_OBJ,
    PS_FORMAT_XYZ,
    PS_FORMAT_JSON
} ps_format;

typedef struct ps_decode_limits {
    size_t max_points;  /* more is a 413 (0 = no limit) */
    int max_dim;        /* more is a 422 */
} ps_decode_limits;

ps_format ps_detect_format(const char *bytes, size_t len);
const char *ps_format_name(ps_format f);

/* Decodes bytes (need not be NUL-terminated).  lim may be NULL (defaults:
 * no point limit, PS_MAX_DIM).  Non-finite coordinates, an empty set and
 * dim < 2 are 422 errors.  Returns 0 or -1 with err set. */
int ps_decode(const char *bytes, size_t len, const ps_decode_limits *lim,
              ps_pointset *out, ps_api_error *err);

/* The format-specific entry points behind ps_decode (same contract; OFF
 * and OBJ give dim 3, errors name the line). */
int ps_decode_ply(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err);
int ps_decode_off(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err);
int ps_decode_obj(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err);
int ps_decode_xyz(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err);
int ps_decode_json(const char *bytes, size_t len, const ps_decode_limits *lim,
                   ps_pointset *out, ps_api_error *err);

/* A labels file: whitespace-separated decimal ints (one per line), as
 * `pointseg segment --output labels` writes and the benchmark's .seg files
 * are.  values malloc'ed #count.  Errors name the line (400). */
int ps_decode_labels(const char *bytes, size_t len, int **values, size_t *count,
                     ps_api_error *err);

/* Reads a whole file ("-" = stdin) into a malloc'ed buffer. */
int ps_read_file(const char *path, char **bytes, size_t *len, ps_api_error *err);

#endif
