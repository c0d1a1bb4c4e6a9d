/*
 * static_files.h: files under the static directory (the web viewer) by URL
 * path: "/" is index.html; paths with ".." or hidden segments are refused,
 * and so are symlinks below the directory (one could lead out of it).
 */
#ifndef PS_STATIC_FILES_H
#define PS_STATIC_FILES_H

#include <stddef.h>

/* Opens dir + url_path for reading.  Returns an fd (the caller closes it or
 * hands it to the response) with *size and *media_type set, or -1 when
 * there is no such regular file (a 404). */
int ps_static_open(const char *dir, const char *url_path, size_t *size, const char **media_type);

#endif
