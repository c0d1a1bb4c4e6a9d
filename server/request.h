/*
 * request.h: the state shared by the HTTP layer's files: the server (config,
 * job backend and job store, libmicrohttpd daemon, the list of requests
 * waiting for their job) and one request's state from its first callback
 * to its completion.
 */
#ifndef PS_REQUEST_H
#define PS_REQUEST_H

#include <pthread.h>
#include <stddef.h>

#include "api_error.h"
#include "body.h"
#include "config.h"
#include "guard.h"
#include "intake.h"
#include "jobs.h"
#include "jobstore.h"
#include "metrics.h"

#define PS_MAX_QUERY_PARAMS 64

struct MHD_Connection;
struct MHD_Daemon;
struct MHD_Response;
typedef struct ps_request ps_request;

typedef struct ps_server {
    const ps_config *cfg;
    ps_jobs *jobs;            /* the in-process queue: POST /segment */
    ps_jobstore *store;       /* asynchronous jobs: on jobs, or on Redis */
    struct MHD_Daemon *mhd;
    ps_guard *guard;          /* connection deadlines, health room */
    pthread_mutex_t lock;     /* guards waiting, in_flight, stop_watch */
    pthread_cond_t changed;   /* in_flight dropped, or stop_watch set */
    ps_request *waiting;      /* suspended synchronous requests */
    size_t in_flight;         /* requests begun and not completed */
    int stop_watch;
    pthread_t watcher;        /* cancels jobs of clients that went away */
    int has_watcher;
    char *openapi;            /* the OpenAPI document (openapi.h), built at start-up */
    size_t openapi_len;
} ps_server;

struct ps_request {
    ps_server *srv;
    struct MHD_Connection *conn;
    double t0;                /* monotonic seconds at the first callback */
    ps_guard_conn *guard_conn; /* the connection's guard record (may be NULL) */
    char method[16];
    char path[256];
    int path_too_long;        /* the URL path did not fit in path */
    int path_has_nul;         /* the URL path held %00 (ps_admit_path_has_nul) */
    int query_cut;            /* the query string had too many parameters */
    int http11;               /* HTTP/1.1 (may get a 102 probe) */
    int seen;                 /* the request head was handled */
    int routed;               /* ps_routes_begin ran */
    int defer_answer;         /* answers wait until the body is drained */
    struct MHD_Response *pending; /* a deferred answer, with status below */
    ps_route route;
    char job_id[96];          /* job of this request ("" = none) */
    int status;               /* answered status, 0 = not yet */
    size_t bytes;             /* answered body bytes */
    ps_media media;
    ps_body *body;
    ps_api_error error;       /* upload failure, or a failed submit */
    int failed;
    size_t read_after_failure; /* body bytes read since it failed */
    int suspended;            /* waits for its synchronous job */
    ps_job *job;              /* synchronous job, referenced */
    int waiting;              /* linked in srv->waiting */
    int cancel_sent;
    int probed;               /* a 102 went out to test a half-closed peer */
    int answer_direct;        /* the peer shut down its write side: answer on the socket */
    int sent_direct;          /* and that answer went out whole (direct_answer.h) */
    ps_request *prev, *next;  /* srv->waiting */
};

#endif
