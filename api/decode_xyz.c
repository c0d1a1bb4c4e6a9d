/* decode_xyz.c: ps_decode_xyz (decode.h), the XYZ/CSV decoder: one point
 * per line, numbers separated by blanks, ',' or ';', the same column count
 * on every line (6 columns = x y z nx ny nz), '#' comments and one
 * non-numeric header line allowed. */
#include "decode.h"

#include <stdlib.h>
#include <string.h>

#include "decode_scan.h"
#include "decode_util.h"

static const char *const xyz_separators = ",;";

/* 1 when the line's first field is not a number (a column header). */
static int is_header_line(const char *s, const char *e) {
    const char *fs, *ft;
    double v;
    return ps_next_field(&s, e, xyz_separators, &fs, &ft) == 1 &&
           ps_parse_double(fs, (size_t)(ft - fs), &v) != 0;
}

/* Appends the numbers of one line to values; *columns is set by the first
 * row (0 before it) and enforced after. */
static int read_row(const char *s, const char *e, size_t line, int max_columns, int *columns,
                    ps_dvec *values, ps_api_error *err) {
    const char *fs, *ft;
    int n = 0, rc;
    while ((rc = ps_next_field(&s, e, xyz_separators, &fs, &ft)) == 1) {
        double v;
        if (ps_field_number(fs, ft, line, &v, err)) return -1;
        if (++n > max_columns)
            return ps_api_fail(err, 422, "line %zu: more than %d columns", line, max_columns);
        if (ps_dvec_push(values, &v, 1, err)) return -1;
    }
    if (rc < 0) return ps_api_fail(err, 400, "line %zu: empty field", line);
    if (*columns == 0 && n < 2)
        return ps_api_fail(err, 422, "line %zu: %d column; at least 2 are needed", line, n);
    if (*columns && n != *columns)
        return ps_api_fail(err, 400, "line %zu: %d columns, expected %d", line, n, *columns);
    *columns = n;
    return 0;
}

static int read_rows(const char *bytes, size_t len, const ps_decode_limits *lim,
                     ps_dvec *values, int *columns, ps_api_error *err) {
    ps_decode_limits l = ps_decode_limits_of(lim);
    int max_columns = l.max_dim > 6 ? l.max_dim : 6;
    ps_lines lines;
    const char *s, *e;
    size_t rows = 0;
    int first = 1;
    ps_lines_init(&lines, bytes, len);
    *columns = 0;
    while (ps_lines_next_data(&lines, &s, &e)) {
        int header = first && is_header_line(s, e);
        first = 0;
        if (header) continue;
        if (ps_decode_check_points(++rows, lim, err) ||
            read_row(s, e, lines.line, max_columns, columns, values, err))
            return -1;
    }
    return 0;
}

/* Splits rows of 6 columns into points and normals (#n by 3 each). */
static int split_normals(ps_pointset *out, ps_api_error *err) {
    double *rows = out->points;
    out->points = malloc(out->n * 3 * sizeof *out->points);
    out->normals = malloc(out->n * 3 * sizeof *out->normals);
    if (!out->points || !out->normals) {
        free(rows);
        return ps_api_fail(err, 500, "out of memory");
    }
    for (size_t i = 0; i < out->n; i++) {
        memcpy(out->points + 3 * i, rows + 6 * i, 3 * sizeof *rows);
        memcpy(out->normals + 3 * i, rows + 6 * i + 3, 3 * sizeof *rows);
    }
    free(rows);
    return 0;
}

int ps_decode_xyz(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err) {
    ps_dvec values = {0};
    int columns;
    memset(out, 0, sizeof *out);
    if (read_rows(bytes, len, lim, &values, &columns, err)) {
        free(values.v);
        return -1;
    }
    out->points = values.v;
    out->n = columns ? values.len / (size_t)columns : 0;
    out->dim = columns == 6 ? 3 : columns;
    if (columns == 6 && split_normals(out, err)) {
        ps_pointset_free(out);
        return -1;
    }
    return ps_decode_finish(out, lim, "point", err);
}
