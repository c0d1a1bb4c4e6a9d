/*
 * encode.h: a ps_result out as bytes: the JSON document (README, "The JSON
 * document"), one label per line, or a PLY of the points coloured by segment
 * (faces kept when the input had them).  Buffers are malloc'ed; the caller
 * frees them.  Returns NULL only when memory runs out.
 */
#ifndef PS_ENCODE_H
#define PS_ENCODE_H

#include "params_table.h"
#include "pointset.h"

/* The result in the format rp->output asks for (JSON with rp->include's
 * parts, labels or PLY); *media_type (unless NULL) gets its media type,
 * ps_encode_media_type(rp->output).  in may be NULL for JSON and labels. */
char *ps_encode(const ps_pointset *in, const ps_result *r, const ps_request_params *rp,
                size_t *len, const char **media_type);

/* The Content-Type of an output format (a static string). */
const char *ps_encode_media_type(ps_output output);

/* in (may be NULL) gives the document its "warnings". */
char *ps_encode_json(const ps_pointset *in, const ps_result *r, unsigned include, size_t *len);
char *ps_encode_labels(const ps_result *r, size_t *len);
char *ps_encode_ply(const ps_pointset *in, const ps_result *r, size_t *len);

/* RGB colour of segment `label` (a fixed, well-spread palette). */
void ps_segment_color(int label, unsigned char rgb[3]);

#endif
