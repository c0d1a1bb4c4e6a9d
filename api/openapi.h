/*
 * openapi.h: the OpenAPI 3.1 document of pointsegd (every route, parameter,
 * schema and error), generated from the parameter table (params_table.h) so
 * every parameter appears with its type, default, range or choices and help.
 */
#ifndef PS_OPENAPI_H
#define PS_OPENAPI_H

#include <stddef.h>

/* A malloc'ed JSON document; *len its length.  NULL when memory runs out. */
char *ps_openapi_json(size_t *len);

#endif
