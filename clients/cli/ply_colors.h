/*
 * ply_colors.h: the per-vertex colours (red, green, blue) of a PLY file,
 * which the point decoder (api/decode.h) skips.  Used by `pointseg render`.
 */
#ifndef PS_CLI_PLY_COLORS_H
#define PS_CLI_PLY_COLORS_H

#include <stddef.h>

/* Reads the colours of the n vertices of the PLY in bytes (#len) into rgb
 * (#n by 3 bytes; float colours in [0, 1] are scaled to 0..255).  Handles
 * ascii and binary files whose first element is "vertex" with scalar
 * properties only.  Returns 1 when rgb was filled, 0 when the file has no
 * colours in that form (rgb untouched), -1 when the data is truncated. */
int cli_ply_read_colors(const char *bytes, size_t len, size_t n, unsigned char *rgb);

#endif
