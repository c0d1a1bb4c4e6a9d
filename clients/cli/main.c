/*
 * main.c: the `pointseg` command-line tool: dispatches to a subcommand
 * (commands.h) or prints the help or the version.
 */
#include "commands.h"
#include "param_help.h"
#include "pointseg.h"

#include <stdio.h>
#include <string.h>

static const char main_usage[] =
    "usage: pointseg segment INPUT [-o OUT] [--output json|labels|ply] [--NAME VALUE ...]\n"
    "       pointseg score MESH LABELS SEG [SEG...]\n"
    "       pointseg render IN.ply -o OUT.png [--width W --height H --view X,Y,Z --up X,Y,Z]\n"
    "       pointseg --help | --version\n"
    "\n"
    "Segments point-sampled surfaces into their parts (after \"Segmenting Point\n"
    "Sets\", Yamazaki, Natarajan, Bai, Hamann).\n"
    "\n"
    "  segment   segment a point set; `pointseg segment --help` for details\n"
    "  score     Rand Index error of vertex labels against face segmentations\n"
    "  render    draw a coloured PLY (segment --output ply) as a PNG picture\n"
    "\n"
    "Parameters of segment (--NAME VALUE or --NAME=VALUE; '-' and '_' alike):\n";

static void print_main_help(FILE *out) {
    fputs(main_usage, out);
    cli_print_param_help(out);
    fputs("\nExit status: 0 ok, 1 internal failure, 2 bad input or usage.\n", out);
}

int main(int argc, char **argv) {
    const char *cmd = argc > 1 ? argv[1] : NULL;
    if (!cmd) {
        fputs("pointseg: no command given\ntry 'pointseg --help'\n", stderr);
        return 2;
    }
    if (strcmp(cmd, "segment") == 0) return cli_segment(argc - 1, argv + 1);
    if (strcmp(cmd, "score") == 0) return cli_score(argc - 1, argv + 1);
    if (strcmp(cmd, "render") == 0) return cli_render(argc - 1, argv + 1);
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        print_main_help(stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0) {
        printf("pointseg %s\n", PS_VERSION);
        return 0;
    }
    fprintf(stderr, "pointseg: unknown command '%s'\ntry 'pointseg --help'\n", cmd);
    return 2;
}
