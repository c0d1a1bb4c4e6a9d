/* config.c: pointsegd's flags and POINTSEG_* environment variables, from one table. */
#include "config.h"

#include "pointseg.h"

#include <ctype.h>
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef enum opt_kind { OPT_INT, OPT_SIZE, OPT_TEXT, OPT_FLAG } opt_kind;

/* Where an option's default comes from: its default_text read like any
 * value, the number of online cores, half the memory the process may use,
 * or default_text as a directory that is the default only when it exists
 * (else none). */
typedef enum default_rule {
    DEFAULT_TEXT, DEFAULT_CORES, DEFAULT_HALF_MEMORY, DEFAULT_DIR_IF_PRESENT
} default_rule;

typedef struct opt_spec {
    const char *name; /* flag without "--"; env is POINTSEG_ + upper-case, '-' -> '_' */
    opt_kind kind;
    size_t offset;    /* into ps_config */
    size_t text_cap;  /* OPT_TEXT: buffer size */
    double min, max;  /* OPT_INT, OPT_SIZE */
    const char *default_text; /* shown by --help; the default itself unless rule says otherwise */
    default_rule rule;
    const char *help;
} opt_spec;

#define INT_OPT(n, f, lo, hi, d, h) {n, OPT_INT, offsetof(ps_config, f), 0, lo, hi, d, DEFAULT_TEXT, h}
#define SIZE_OPT(n, f, lo, hi, d, h) {n, OPT_SIZE, offsetof(ps_config, f), 0, lo, hi, d, DEFAULT_TEXT, h}
#define TEXT_SPEC(n, f, d, r, h) \
    {n, OPT_TEXT, offsetof(ps_config, f), sizeof(((ps_config *)0)->f), 0, 0, d, r, h}
#define TEXT_OPT(n, f, d, h) TEXT_SPEC(n, f, d, DEFAULT_TEXT, h)
#define DIR_OPT(n, f, d, h) TEXT_SPEC(n, f, d, DEFAULT_DIR_IF_PRESENT, h)

static const opt_spec options[] = {
    INT_OPT("port", port, 0, 65535, "8080", "TCP port (0 = any free port)"),
    TEXT_OPT("bind", bind, "127.0.0.1", "IPv4 address to listen on"),
    {"threads", OPT_INT, offsetof(ps_config, threads), 0, 1, 1024, "cores", DEFAULT_CORES,
     "worker threads running jobs"},
    INT_OPT("queue-size", queue_size, 1, 1000000, "64", "jobs waiting for a worker; more is a 503"),
    SIZE_OPT("max-body", max_body, 1, 1e15, "268435456", "largest request body in bytes, after gzip (413)"),
    SIZE_OPT("max-points", max_points, 1, 1e12, "5000000", "most points in one request (413)"),
    {"max-memory", OPT_SIZE, offsetof(ps_config, max_memory), 0, 1, 1e15, "half the memory",
     DEFAULT_HALF_MEMORY, "bytes one job may need by its estimate (413)"},
    INT_OPT("job-ttl", job_ttl, 0, 1e8, "600", "seconds a finished job is kept"),
    INT_OPT("max-jobs-kept", max_jobs_kept, 1, 1e7, "1000", "finished jobs kept at most"),
    SIZE_OPT("max-kept-bytes", max_kept_bytes, 0, 1e15, "268435456",
             "bytes of kept results at most (the oldest finished jobs go first)"),
    INT_OPT("max-connections", max_connections, 1, 1e6, "1000",
            "open connections; over it only health checks are served (8 more)"),
    INT_OPT("max-connections-per-ip", max_connections_per_ip, 0, 1e6, "100",
            "open connections from one address (0 = no limit)"),
    INT_OPT("header-timeout", header_timeout, 1, 86400, "10",
            "seconds to send a request's head (from connect, or the previous answer)"),
    SIZE_OPT("min-upload-rate", min_upload_rate, 0, 1e12, "4096",
             "bytes a second a body must average, after header-timeout (0 = none)"),
    INT_OPT("drain-seconds", drain_seconds, 0, 86400, "30", "on SIGTERM, wait this long for jobs"),
    TEXT_OPT("token", token, "", "bearer token required on every route but /healthz and /readyz"),
    TEXT_OPT("cors-origin", cors_origin, "", "allowed CORS origins: * or a comma-separated list"),
    DIR_OPT("static-dir", static_dir, "clients/web", "directory served at / (if it exists)"),
    TEXT_OPT("replica-name", replica_name, "", "prefix of job ids (routing between replicas)"),
    TEXT_OPT("redis", redis, "", "redis://[:password@]host[:port][/db]: jobs on a queue shared by replicas"),
    INT_OPT("job-lease", job_lease, 2, 86400, "30", "with --redis: seconds before a silent worker's job runs elsewhere"),
    {"quiet", OPT_FLAG, offsetof(ps_config, quiet), 0, 0, 1, "off", DEFAULT_TEXT, "no per-request log lines"},
};
#define N_OPTIONS (sizeof options / sizeof options[0])

static void env_name(const char *flag, char *out, size_t cap) {
    size_t n = (size_t)snprintf(out, cap, "POINTSEG_");
    for (; *flag && n + 1 < cap; flag++) out[n++] = *flag == '-' ? '_' : (char)toupper((unsigned char)*flag);
    out[n] = 0;
}

static int set_number(ps_config *c, const opt_spec *o, const char *value, const char *source, FILE *err) {
    char *end;
    errno = 0;
    double v = strtod(value, &end);
    if (errno || end == value || *end || v != (double)(long long)v || v < o->min || v > o->max) {
        fprintf(err, "pointsegd: %s: '%s' is not an integer in [%.0f, %.0f]\n", source, value, o->min, o->max);
        return -1;
    }
    if (o->kind == OPT_INT) *(int *)((char *)c + o->offset) = (int)v;
    else *(size_t *)((char *)c + o->offset) = (size_t)v;
    return 0;
}

static int set_option(ps_config *c, const opt_spec *o, const char *value, const char *source, FILE *err) {
    char *field = (char *)c + o->offset;
    if (o->kind == OPT_FLAG) {
        *(int *)field = !value || !strcmp(value, "1") || !strcmp(value, "true") || !strcmp(value, "yes");
        return 0;
    }
    if (o->kind == OPT_TEXT) {
        if (strlen(value) >= o->text_cap) {
            fprintf(err, "pointsegd: %s: value longer than %zu bytes\n", source, o->text_cap - 1);
            return -1;
        }
        memcpy(field, value, strlen(value) + 1);
        return 0;
    }
    return set_number(c, o, value, source, err);
}

static int is_directory(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

size_t ps_memory_capped(size_t bytes, const char *cgroup_file) {
    unsigned long long limit;
    FILE *f = fopen(cgroup_file, "r");
    if (!f) return bytes;
    if (fscanf(f, "%llu", &limit) == 1 && limit > 0 && limit < bytes) bytes = (size_t)limit;
    fclose(f);
    return bytes;
}

/* The machine's memory, or the cgroup's limit (a container) when lower:
 * cgroup v2's memory.max, or v1's memory controller. */
static size_t usable_memory(void) {
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    size_t bytes = pages > 0 && page > 0 ? (size_t)pages * (size_t)page : (size_t)1 << 32;
    bytes = ps_memory_capped(bytes, "/sys/fs/cgroup/memory.max");
    return ps_memory_capped(bytes, "/sys/fs/cgroup/memory/memory.limit_in_bytes");
}

/* Every option's default, from the table (the text --help shows). */
static int set_defaults(ps_config *c, FILE *err) {
    memset(c, 0, sizeof *c);
    for (size_t i = 0; i < N_OPTIONS; i++) {
        const opt_spec *o = &options[i];
        if (o->rule == DEFAULT_CORES) {
            long cores = sysconf(_SC_NPROCESSORS_ONLN);
            *(int *)((char *)c + o->offset) = cores > 0 ? (int)cores : 1;
        } else if (o->rule == DEFAULT_HALF_MEMORY) {
            *(size_t *)((char *)c + o->offset) = usable_memory() / 2;
        } else if (o->rule == DEFAULT_TEXT || is_directory(o->default_text)) {
            if (set_option(c, o, o->default_text, "built-in default", err)) return -1;
        }
    }
    return 0;
}

static const opt_spec *find_option(const char *name, size_t len) {
    for (size_t i = 0; i < N_OPTIONS; i++)
        if (strlen(options[i].name) == len && !strncmp(options[i].name, name, len)) return &options[i];
    return NULL;
}

static int load_environment(ps_config *c, FILE *err) {
    char name[64];
    for (size_t i = 0; i < N_OPTIONS; i++) {
        env_name(options[i].name, name, sizeof name);
        const char *value = getenv(name);
        if (value && set_option(c, &options[i], value, name, err)) return -1;
    }
    return 0;
}

/* One argv entry (and maybe the next): returns arguments consumed or -1. */
static int load_flag(ps_config *c, int argc, char **argv, int i, FILE *err) {
    const char *arg = argv[i] + 2;
    const char *eq = strchr(arg, '=');
    const opt_spec *o = find_option(arg, eq ? (size_t)(eq - arg) : strlen(arg));
    if (!o) {
        fprintf(err, "pointsegd: unknown option %s (see --help)\n", argv[i]);
        return -1;
    }
    if (o->kind == OPT_FLAG) return set_option(c, o, eq ? eq + 1 : NULL, argv[i], err) ? -1 : 1;
    if (eq) return set_option(c, o, eq + 1, argv[i], err) ? -1 : 1;
    if (i + 1 >= argc) {
        fprintf(err, "pointsegd: %s needs a value\n", argv[i]);
        return -1;
    }
    return set_option(c, o, argv[i + 1], argv[i], err) ? -1 : 2;
}

void ps_config_usage(FILE *out) {
    char env[64];
    fprintf(out, "usage: pointsegd [options]\n"
                 "HTTP service segmenting point sets (POST /segment, /jobs; see /openapi.json).\n"
                 "Every option is also read from the environment variable shown.\n\n");
    for (size_t i = 0; i < N_OPTIONS; i++) {
        env_name(options[i].name, env, sizeof env);
        fprintf(out, "  --%-22s %-31s %s (default: %s)\n", options[i].name, env, options[i].help,
                options[i].default_text[0] ? options[i].default_text : "none");
    }
    fprintf(out, "  --help, --version\n");
}

/* A replica name begins the job ids that travel in URLs (/jobs/ID): only
 * characters that no path splits and no decoding changes. */
static int check_replica_name(const char *name, FILE *err) {
    if (!name[strspn(name, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_.")]) return 0;
    fprintf(err, "pointsegd: --replica-name '%s': letters, digits, '-', '_' and '.' only (it begins job "
                 "ids in URLs)\n", name);
    return -1;
}

int ps_config_load(ps_config *c, int argc, char **argv, FILE *out, FILE *err) {
    if (set_defaults(c, err) || load_environment(c, err)) return -1;
    for (int i = 1; i < argc;) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            ps_config_usage(out);
            return 1;
        }
        if (!strcmp(argv[i], "--version")) {
            fprintf(out, "pointsegd %s\n", PS_VERSION);
            return 1;
        }
        if (strncmp(argv[i], "--", 2)) {
            fprintf(err, "pointsegd: unexpected argument %s (see --help)\n", argv[i]);
            return -1;
        }
        int used = load_flag(c, argc, argv, i, err);
        if (used < 0) return -1;
        i += used;
    }
    return check_replica_name(c->replica_name, err);
}
