/*
 * http.h: the HTTP front of pointsegd on libmicrohttpd: its own I/O threads
 * (internal polling with poll(), a thread pool), never running a segmentation;
 * requests become jobs of the job backend (jobs.h).
 */
#ifndef PS_HTTP_H
#define PS_HTTP_H

#include <stddef.h>

#include "config.h"
#include "jobs.h"
#include "jobstore.h"

typedef struct ps_http ps_http;
struct ps_server;

/* Listens on cfg->bind:cfg->port.  NULL on failure (why says so).  cfg,
 * jobs (POST /segment) and store (/jobs) must outlive the server. */
ps_http *ps_http_start(const ps_config *cfg, ps_jobs *jobs, ps_jobstore *store, char *why,
                       size_t why_cap);

/* The port actually bound (useful with --port 0). */
int ps_http_port(ps_http *h);

/* Stops accepting connections; requests under way go on. */
void ps_http_quiesce(ps_http *h);

/* Waits up to `seconds` for the requests under way to be answered. */
void ps_http_wait_idle(ps_http *h, double seconds);

/* Closes every connection and frees the server. */
void ps_http_stop(ps_http *h);

#endif
