/*
 * decode_scan.h: reading text that is not NUL-terminated (internal to api/):
 * lines with their numbers, tokens, and bounded number parsing.
 */
#ifndef PS_DECODE_SCAN_H
#define PS_DECODE_SCAN_H

#include <stddef.h>

#include "api_error.h"

/* A position in bytes [pos, end); line is the number (from 1) of the line
 * ps_lines_next returned last. */
typedef struct ps_lines {
    const char *pos, *end;
    size_t line;
} ps_lines;

void ps_lines_init(ps_lines *c, const char *bytes, size_t len);

/* The next line as [*start, *stop), without its end ("\n", "\r\n" or a
 * lone "\r") and with surrounding blanks trimmed.  Returns 0 when there are
 * no more lines. */
int ps_lines_next(ps_lines *c, const char **start, const char **stop);

/* The next line that is neither empty nor a '#' comment (same contract). */
int ps_lines_next_data(ps_lines *c, const char **start, const char **stop);

/* 1 for '\n' and '\r', which end a line ("\n", "\r\n" or a lone "\r"). */
int ps_is_line_end(char ch);

/* The first line end at or after p, or end. */
const char *ps_line_end(const char *p, const char *end);

/* Past the line end at p (one "\n", "\r\n" or "\r"); p when none is there. */
const char *ps_past_line_end(const char *p, const char *end);

/* 1 for space, tab, \r, \v, \f. */
int ps_is_blank(char ch);

/* The first non-blank at or after p (or end); stays on the line ('\n' is
 * not a blank). */
const char *ps_skip_blanks(const char *p, const char *end);

/* The first byte at or after p (or end) that is neither a blank nor '\n':
 * white space across lines (JSON's trailing space, ASCII PLY values). */
const char *ps_skip_space(const char *p, const char *end);

/* The end of the token starting at p: the first blank, byte of seps (may be
 * NULL) or end. */
const char *ps_token_end(const char *p, const char *end, const char *seps);

/* Parses all of [s, s+n) as a number (strtod syntax).  Returns 0, or -1 when
 * it is not one number (or longer than 127 bytes).  Non-finite values
 * ("nan", "inf", 1e999) parse; callers decide. */
int ps_parse_double(const char *s, size_t n, double *out);

/* Parses all of [s, s+n) as a decimal integer with optional sign.  Returns 0,
 * or -1 when it is not one or does not fit in a long long. */
int ps_parse_integer(const char *s, size_t n, long long *out);

/* The next field of a line [*p, end): skips blanks, stops at the end or at a
 * '#' comment (returns 0), else sets [*s, *t) to the field, moves *p past
 * it and past one separator of seps (may be NULL: blanks only) and returns
 * 1.  An empty field between separators returns -1. */
int ps_next_field(const char **p, const char *end, const char *seps, const char **s,
                  const char **t);

/* Parses the field [s, t) of line `line` as a finite number: 0, or -1 with
 * a 400 (not a number) or 422 (non-finite) naming the line. */
int ps_field_number(const char *s, const char *t, size_t line, double *v, ps_api_error *err);

/* Copies up to out_size - 1 bytes of [s, s+n) for a message, printable
 * ASCII only (others become '?'). */
void ps_preview(const char *s, size_t n, char *out, size_t out_size);

#endif
