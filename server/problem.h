/*
 * problem.h: error documents in the RFC 9457 problem+json format
 * ({"type", "title", "status", "detail"}), the body of every error answer;
 * bytes of the detail that are not UTF-8 become U+FFFD.
 */
#ifndef PS_PROBLEM_H
#define PS_PROBLEM_H

#include <stddef.h>

#define PS_PROBLEM_MEDIA_TYPE "application/problem+json"

/* The reason phrase of an HTTP status ("Unprocessable Content"). */
const char *ps_problem_title(int status);

/* A malloc'ed copy of text with every byte that is not part of valid UTF-8
 * replaced by U+FFFD; NULL when memory runs out. */
char *ps_problem_utf8(const char *text);

/* A malloc'ed problem+json document for status with detail (may be NULL);
 * *len receives its length.  NULL only when memory runs out. */
char *ps_problem_json(int status, const char *detail, size_t *len);

#endif
