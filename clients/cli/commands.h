/*
 * commands.h: the subcommands of the `pointseg` tool, one file each.
 * Each takes the arguments after the subcommand name (argv[0] is the
 * subcommand) and returns the exit status: 0 ok, EXIT_INTERNAL (1) failure,
 * EXIT_USAGE (2) bad input or usage.
 */
#ifndef PS_CLI_COMMANDS_H
#define PS_CLI_COMMANDS_H

enum { EXIT_INTERNAL = 1, EXIT_USAGE = 2 }; /* exit statuses of the subcommands */

int cli_segment(int argc, char **argv); /* segment.c: segment a file */
int cli_score(int argc, char **argv);   /* score.c: Rand Index error of labels */
int cli_render(int argc, char **argv);  /* render.c: draw a coloured PLY as a PNG */

#endif
