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

/* in (may be NULL) gives the document its "warnings". */
char *ps_encode_json(const ps_pointset *in, const ps_result *r, unsigned include, size_t *len);
char *ps_encode_labels(const ps_result *r, size_t *len);
char *ps_encode_ply(const ps_pointset *in, const ps_result *r, size_t *len);

/* RGB colour of segment `label` (a fixed, well-spread palette). */
void ps_segment_color(int label, unsigned char rgb[3]);

#endif
