/*
 * config.h: pointsegd's configuration: command-line flags, each also read
 * from the environment as POINTSEG_<NAME> (flags win over the environment,
 * the environment over the defaults).
 */
#ifndef PS_CONFIG_H
#define PS_CONFIG_H

#include <stddef.h>
#include <stdio.h>

typedef struct ps_config {
    int port;              /* --port, default 8080 */
    char bind[64];         /* --bind, default 127.0.0.1 (IPv4 address) */
    int threads;           /* --threads: worker threads, default = cores */
    int queue_size;        /* --queue-size: waiting jobs, default 64 */
    size_t max_body;       /* --max-body: bytes (after gzip), default 256 MiB */
    size_t max_points;     /* --max-points, default 5,000,000 */
    size_t max_memory;     /* --max-memory: bytes a job may need by its estimate, default half the memory */
    int job_ttl;           /* --job-ttl: seconds a finished job is kept, default 600 */
    int max_jobs_kept;     /* --max-jobs-kept: finished jobs kept, default 1000 */
    size_t max_kept_bytes; /* --max-kept-bytes: their results' bytes, default 256 MiB */
    int max_connections;   /* --max-connections: open connections, default 1000 (+ health room) */
    int max_connections_per_ip; /* --max-connections-per-ip: default 100, 0 = no limit */
    int header_timeout;    /* --header-timeout: seconds to send a request head, default 10 */
    size_t min_upload_rate; /* --min-upload-rate: bytes/s of a body, default 4096, 0 = none */
    int drain_seconds;     /* --drain-seconds: wait for running jobs on SIGTERM, default 30 */
    char token[256];       /* --token: bearer token, "" = none */
    char cors_origin[512]; /* --cors-origin: "*" or comma-separated origins, "" = none */
    char static_dir[512];  /* --static-dir, default clients/web when it exists */
    char replica_name[64]; /* --replica-name: job id prefix, "" = none */
    char redis[512];       /* --redis: redis://... URL of the shared job queue, "" = in-process */
    int job_lease;         /* --job-lease: seconds a worker's hold on a Redis job lasts unrenewed */
    int quiet;             /* --quiet: no request log */
} ps_config;

/* Fills c from the defaults, then the environment, then argv.  Returns 0 to
 * run, 1 when --help or --version was printed to out (exit 0), -1 after
 * printing an error to err (exit 2). */
int ps_config_load(ps_config *c, int argc, char **argv, FILE *out, FILE *err);

/* Prints every flag with its environment variable and default. */
void ps_config_usage(FILE *out);

/* bytes, or the memory limit in cgroup_file when lower: a cgroup v2
 * memory.max or a v1 memory.limit_in_bytes.  A missing file, "max", 0 and
 * v1's "unlimited" (a number near 2^63, above any machine) leave bytes.
 * The --max-memory default is half of it. */
size_t ps_memory_capped(size_t bytes, const char *cgroup_file);

#endif
