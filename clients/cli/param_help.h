/*
 * param_help.h: the parameter part of the `pointseg` help text, generated
 * from the one parameter table (api/params_table.h) so that every parameter
 * is listed with its flag, values, default and help line.
 */
#ifndef PS_CLI_PARAM_HELP_H
#define PS_CLI_PARAM_HELP_H

#include <stdio.h>

/* Writes one entry per table parameter to out, e.g.
 *   "  --k N    neighbours per point in the kNN graph\n"
 *   "           integer in [1, 64], default 7\n" */
void cli_print_param_help(FILE *out);

#endif
