/*
 * decode_text.h: the text decoders behind ps_decode_text (internal to api/).
 * Same contract as ps_decode: bytes (#len, not NUL-terminated) in, *out
 * filled (dim 3 for OFF and OBJ), or -1 with err naming the line.
 */
#ifndef PS_DECODE_TEXT_H
#define PS_DECODE_TEXT_H

#include "decode.h"

int ps_decode_off(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err);
int ps_decode_obj(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err);
int ps_decode_xyz(const char *bytes, size_t len, const ps_decode_limits *lim,
                  ps_pointset *out, ps_api_error *err);

#endif
