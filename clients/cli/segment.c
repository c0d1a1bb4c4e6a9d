/*
 * segment.c: `pointseg segment INPUT [-o OUT] [--NAME VALUE ...]`: reads a
 * point set (any format ps_decode knows; "-" = stdin), segments it and
 * writes the result as JSON, labels or a coloured PLY (stdout by default).
 * Every parameter flag is a name of the parameter table and goes through
 * ps_request_param_set; parameters inside a JSON body apply first, flags
 * override them.  With --server URL the input goes to a pointsegd daemon
 * instead (remote.h), the flags in the query string.  Errors:
 * "pointseg: WHAT: message" on stderr, exit 2 for bad input or usage, 1 for
 * an internal failure.
 */
#include "commands.h"
#include "decode.h"
#include "encode.h"
#include "param_help.h"
#include "params_table.h"
#include "remote.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { HELP_SHOWN = -1, NOT_HANDLED = -2 };

typedef struct flag_value {
    const char *option; /* "--ncut-threshold", for messages */
    const char *name;   /* "ncut-threshold": as given, '-' or '_' */
    const char *value;
} flag_value;

typedef struct segment_args {
    const char *input;     /* path or "-" */
    const char *out_path;  /* NULL = stdout */
    const char *server;    /* --server URL, or NULL */
    const char *token;     /* --token, else $POINTSEG_TOKEN, or NULL */
    int async;             /* --async: queue a job on the server and poll it */
    flag_value *flags;     /* #n_flags parameter flags in command-line order */
    int n_flags;
} segment_args;

static const char segment_usage[] =
    "usage: pointseg segment INPUT [-o OUT] [--output json|labels|ply] [--NAME VALUE ...]\n"
    "\n"
    "Segments the point set in INPUT (PLY, OFF, OBJ, XYZ/CSV or a JSON body\n"
    "{\"points\": [[x,y,z], ...], \"params\": {...}}; \"-\" reads stdin) into its\n"
    "parts and writes the result to OUT (default: stdout).\n"
    "\n"
    "  -o OUT          write the result to OUT (\"-\": stdout, the default)\n"
    "  --server URL    segment on a pointsegd daemon instead of locally\n"
    "  --async         with --server: queue a job (POST /jobs) and poll it\n"
    "  --token TOKEN   with --server: bearer token (default $POINTSEG_TOKEN)\n"
    "  -h, --help      this text\n"
    "\n"
    "Parameters (--NAME VALUE or --NAME=VALUE; '-' and '_' alike in NAME;\n"
    "parameters given in a JSON body apply first, flags override them):\n";

static void print_segment_help(FILE *out) {
    fputs(segment_usage, out);
    cli_print_param_help(out);
    fputs("\nExit status: 0 ok, 1 internal failure, 2 bad input or usage.\n", out);
}

static int usage_error(const char *what, const char *message) {
    fprintf(stderr, "pointseg: %s: %s\ntry 'pointseg segment --help'\n", what, message);
    return EXIT_USAGE;
}

/* Exit status for an api error: the caller's fault (4xx) or ours. */
static int api_exit(const char *what, const ps_api_error *err) {
    fprintf(stderr, "pointseg: %s: %s\n", what, err->message);
    return err->http_status >= 500 ? EXIT_INTERNAL : EXIT_USAGE;
}

/* ---- argument parsing --------------------------------------------------- */

/* "--name=value" or "--name [value]" at argv[*i] (a parameter flag); a bool
 * flag without "=" is "true" and takes no next argument.  The '=' in argv
 * is overwritten to end the name. */
static int parse_param_flag(int argc, char **argv, int *i, segment_args *a) {
    const char *option = argv[*i];
    char *name = argv[*i] + 2;
    char *eq = strchr(name, '=');
    if (eq) *eq = 0;
    const ps_param_spec *spec = ps_param_find(name);
    if (!spec) return usage_error(option, "unknown option");
    const char *value = eq ? eq + 1 : NULL;
    if (!value && spec->type == PS_PT_BOOL) value = "true";
    if (!value && *i + 1 >= argc) return usage_error(option, "option needs a value");
    if (!value) value = argv[++*i];
    a->flags[a->n_flags++] = (flag_value){option, name, value};
    return 0;
}

/* "-o OUT", "--server URL" / "--server=URL", "--token TOKEN", "--async",
 * "--help"; NOT_HANDLED if argv[*i] is none of them, 0 when handled, else
 * HELP_SHOWN or an exit status. */
static int parse_fixed_option(int argc, char **argv, int *i, segment_args *a) {
    const char *arg = argv[*i];
    if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) return HELP_SHOWN;
    if (strcmp(arg, "--async") == 0) {
        a->async = 1;
        return 0;
    }
    if (strncmp(arg, "--server=", 9) == 0) {
        a->server = arg + 9;
        return 0;
    }
    if (strcmp(arg, "-o") != 0 && strcmp(arg, "--server") != 0 && strcmp(arg, "--token") != 0)
        return NOT_HANDLED;
    if (*i + 1 >= argc) return usage_error(arg, "option needs a value");
    if (arg[1] == 'o') a->out_path = argv[++*i];
    else if (arg[2] == 's') a->server = argv[++*i];
    else a->token = argv[++*i];
    return 0;
}

static int parse_positional(const char *arg, segment_args *a) {
    if (a->input) return usage_error(arg, "more than one INPUT given");
    a->input = arg;
    return 0;
}

/* Fills a from argv[1..argc); 0, HELP_SHOWN or an exit status. */
static int parse_args(int argc, char **argv, segment_args *a) {
    int only_positional = 0;
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i];
        int rc;
        if (only_positional || arg[0] != '-' || strcmp(arg, "-") == 0) {
            rc = parse_positional(arg, a);
        } else if (strcmp(arg, "--") == 0) {
            only_positional = 1;
            rc = 0;
        } else if ((rc = parse_fixed_option(argc, argv, &i, a)) == NOT_HANDLED) {
            rc = strncmp(arg, "--", 2) == 0 ? parse_param_flag(argc, argv, &i, a)
                                             : usage_error(arg, "unknown option");
        }
        if (rc) return rc;
    }
    return a->input ? 0 : usage_error("segment", "no INPUT given");
}

/* Sets one parameter; on error prints "pointseg: WHERE: message". */
static int apply_param(ps_request_params *rp, const char *name, const char *value,
                       const char *where) {
    ps_api_error err;
    if (ps_request_param_set(rp, name, value, &err) == 0) return 0;
    fprintf(stderr, "pointseg: %s: %s\n", where, err.message);
    return EXIT_USAGE;
}

/* The flags, each checked alone (before any input is read). */
static int check_flags(const segment_args *a) {
    ps_request_params scratch;
    ps_request_params_default(&scratch);
    for (int i = 0; i < a->n_flags; i++)
        if (apply_param(&scratch, a->flags[i].name, a->flags[i].value, a->flags[i].option))
            return EXIT_USAGE;
    return 0;
}

/* Defaults, then the body's parameters, then the flags. */
static int request_params(const segment_args *a, const ps_pointset *ps, const char *what,
                          ps_request_params *rp) {
    ps_request_params_default(rp);
    for (size_t i = 0; i < ps->n_params; i++)
        if (apply_param(rp, ps->params[i].name, ps->params[i].value, what)) return EXIT_USAGE;
    for (int i = 0; i < a->n_flags; i++)
        if (apply_param(rp, a->flags[i].name, a->flags[i].value, a->flags[i].option))
            return EXIT_USAGE;
    return 0;
}

/* ---- the work ------------------------------------------------------------ */

static int read_input(const char *path, const char *what, ps_pointset *ps) {
    char *bytes = NULL;
    size_t len = 0;
    ps_api_error err;
    if (ps_read_file(path, &bytes, &len, &err) != 0) return api_exit(what, &err);
    int rc = ps_decode(bytes, len, NULL, ps, &err);
    free(bytes);
    if (rc) return api_exit(what, &err);
    for (int i = 0; i < ps->n_warnings; i++) fprintf(stderr, "pointseg: warning: %s: %s\n", what, ps->warnings[i]);
    return 0;
}

static int run_segment(const ps_pointset *ps, const ps_params *params, const char *what,
                       ps_result **result) {
    ps_input in = ps_pointset_input(ps);
    ps_error err;
    ps_status st = ps_segment(&in, params, NULL, result, &err);
    if (st == PS_OK) return 0;
    fprintf(stderr, "pointseg: %s: %s\n", what, err.message);
    return st == PS_ERR_INVALID ? EXIT_USAGE : EXIT_INTERNAL;
}

/* Writes bytes to path (NULL or "-" = stdout); 0 or an exit status. */
static int write_output(const char *path, const char *bytes, size_t len) {
    if (path && strcmp(path, "-") == 0) path = NULL;
    FILE *f = path ? fopen(path, "wb") : stdout;
    int ok = f && fwrite(bytes, 1, len, f) == len;
    if (f) ok = (path ? fclose(f) : fflush(f)) == 0 && ok;
    if (ok) return 0;
    fprintf(stderr, "pointseg: %s: %s\n", path ? path : "stdout", strerror(errno));
    return EXIT_INTERNAL;
}

/* Segments the decoded input and writes the result. */
static int segment_and_write(const segment_args *a, const ps_pointset *ps, const char *what) {
    ps_request_params rp;
    ps_result *result = NULL;
    size_t len = 0;
    int rc = request_params(a, ps, what, &rp);
    if (!rc) rc = run_segment(ps, &rp.core, what, &result);
    if (rc) return rc;
    char *bytes = ps_encode(ps, result, &rp, &len, NULL);
    ps_result_free(result);
    if (!bytes) {
        fprintf(stderr, "pointseg: %s: out of memory encoding the result\n", what);
        return EXIT_INTERNAL;
    }
    rc = write_output(a->out_path, bytes, len);
    free(bytes);
    return rc;
}

static int segment_file(const segment_args *a) {
    const char *what = strcmp(a->input, "-") == 0 ? "<stdin>" : a->input;
    ps_pointset ps;
    memset(&ps, 0, sizeof ps);
    int rc = read_input(a->input, what, &ps);
    if (!rc) rc = segment_and_write(a, &ps, what);
    ps_pointset_free(&ps);
    return rc;
}

/* Sends the input file to a->server and writes the answer. */
static int segment_remote(const segment_args *a) {
    const char *what = strcmp(a->input, "-") == 0 ? "<stdin>" : a->input;
    char *bytes = NULL, *answer = NULL;
    size_t len = 0, answer_len = 0;
    ps_api_error err;
    if (ps_read_file(a->input, &bytes, &len, &err) != 0) return api_exit(what, &err);
    cli_remote_param *params = malloc((size_t)(a->n_flags + 1) * sizeof *params);
    int rc = EXIT_INTERNAL;
    if (params) {
        for (int i = 0; i < a->n_flags; i++)
            params[i] = (cli_remote_param){a->flags[i].name, a->flags[i].value};
        const char *token = a->token ? a->token : getenv("POINTSEG_TOKEN");
        cli_remote r = {a->server, token && *token ? token : NULL, a->async, params, a->n_flags};
        rc = cli_remote_segment(&r, bytes, len, what, &answer, &answer_len);
    } else {
        fputs("pointseg: out of memory\n", stderr);
    }
    if (!rc) rc = write_output(a->out_path, answer, answer_len);
    free(answer);
    free(params);
    free(bytes);
    return rc;
}

int cli_segment(int argc, char **argv) {
    segment_args a = {NULL, NULL, NULL, NULL, 0, NULL, 0};
    a.flags = malloc((size_t)(argc > 0 ? argc : 1) * sizeof *a.flags);
    if (!a.flags) {
        fputs("pointseg: out of memory\n", stderr);
        return EXIT_INTERNAL;
    }
    int rc = parse_args(argc, argv, &a);
    if (rc == HELP_SHOWN) print_segment_help(stdout);
    if (!rc) rc = check_flags(&a);
    if (!rc && !a.server && (a.async || a.token))
        rc = usage_error(a.async ? "--async" : "--token", "needs --server");
    if (!rc) rc = a.server ? segment_remote(&a) : segment_file(&a);
    free(a.flags);
    return rc == HELP_SHOWN ? 0 : rc;
}
