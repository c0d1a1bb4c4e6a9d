/* guard.c: per-connection deadlines and the health room (guard.h). */
#include "guard.h"

#include "deadline.h"

#include <pthread.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <time.h>

#define HEALTH_ROOM_IDLE_SECONDS 1.0
#define EOF_GRACE_SECONDS 0.5 /* a phase change may still be on its way (a loaded machine) */

typedef enum conn_phase { PHASE_IDLE, PHASE_UPLOAD, PHASE_BUSY } conn_phase;

struct ps_guard_conn {
    int fd;
    conn_phase phase;
    double since;        /* monotonic seconds the phase began */
    size_t received;     /* PHASE_UPLOAD: body bytes so far */
    double eof_since;    /* the peer's end of input was first seen in this phase; 0 = not */
    int health_room;
    ps_guard_conn *prev, *next;
};

struct ps_guard {
    pthread_mutex_t lock;
    ps_guard_conn *conns;
    size_t open;
    int max_connections;
    double header_timeout, min_upload_rate;
};

ps_guard *ps_guard_new(int max_connections, double header_timeout, double min_upload_rate) {
    ps_guard *g = calloc(1, sizeof *g);
    if (!g) return NULL;
    pthread_mutex_init(&g->lock, NULL);
    g->max_connections = max_connections;
    g->header_timeout = header_timeout;
    g->min_upload_rate = min_upload_rate;
    return g;
}

void ps_guard_free(ps_guard *g) {
    if (!g) return;
    while (g->conns) ps_guard_closed(g, g->conns);
    pthread_mutex_destroy(&g->lock);
    free(g);
}

int ps_guard_conn_in_health_room(const ps_guard_conn *c) { return c && c->health_room; }

ps_guard_conn *ps_guard_opened(ps_guard *g, int fd) {
    ps_guard_conn *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->fd = fd;
    c->phase = PHASE_IDLE;
    c->since = ps_monotonic_seconds();
    pthread_mutex_lock(&g->lock);
    c->health_room = g->open >= (size_t)g->max_connections;
    c->next = g->conns;
    if (g->conns) g->conns->prev = c;
    g->conns = c;
    g->open++;
    pthread_mutex_unlock(&g->lock);
    return c;
}

void ps_guard_closed(ps_guard *g, ps_guard_conn *c) {
    if (!c) return;
    pthread_mutex_lock(&g->lock);
    if (c->prev) c->prev->next = c->next;
    else g->conns = c->next;
    if (c->next) c->next->prev = c->prev;
    g->open--;
    pthread_mutex_unlock(&g->lock);
    free(c);
}

static void enter(ps_guard *g, ps_guard_conn *c, conn_phase phase) {
    if (!c) return;
    pthread_mutex_lock(&g->lock);
    c->phase = phase;
    c->since = ps_monotonic_seconds();
    c->received = 0;
    c->eof_since = 0;
    pthread_mutex_unlock(&g->lock);
}

void ps_guard_request_begun(ps_guard *g, ps_guard_conn *c) { enter(g, c, PHASE_UPLOAD); }
void ps_guard_upload_done(ps_guard *g, ps_guard_conn *c) { enter(g, c, PHASE_BUSY); }
void ps_guard_answered(ps_guard *g, ps_guard_conn *c) { enter(g, c, PHASE_IDLE); }

void ps_guard_received(ps_guard *g, ps_guard_conn *c, size_t n) {
    if (!c) return;
    pthread_mutex_lock(&g->lock);
    c->received += n;
    pthread_mutex_unlock(&g->lock);
}

/* 1 when the peer ended its input and nothing is left to read. */
static int at_eof(int fd) {
    char c;
    return recv(fd, &c, 1, MSG_PEEK | MSG_DONTWAIT) == 0;
}

/* A connection waiting for a request head or receiving a body whose peer
 * has ended its input can never complete a request; libmicrohttpd would
 * keep it until its own timeout (an idle one after pipelined requests, or
 * one short of its Content-Length).  Closing it is no cut: the client left. */
static int abandoned(ps_guard_conn *c, double now) {
    if (c->phase == PHASE_BUSY || !at_eof(c->fd)) return c->eof_since = 0, 0;
    if (!c->eof_since) c->eof_since = now;
    return now - c->eof_since > EOF_GRACE_SECONDS;
}

static int past_deadline(const ps_guard *g, const ps_guard_conn *c, double now) {
    double waited = now - c->since;
    switch (c->phase) {
    case PHASE_IDLE:
        return waited > (c->health_room ? HEALTH_ROOM_IDLE_SECONDS : g->header_timeout);
    case PHASE_UPLOAD:
        return g->min_upload_rate > 0 && waited > g->header_timeout + (double)c->received / g->min_upload_rate;
    default:
        return 0;
    }
}

/* The lock is held while closing: a connection is only closed (its fd
 * released) after ps_guard_closed, so the fd is still its own. */
size_t ps_guard_sweep(ps_guard *g) {
    size_t cut = 0;
    double now = ps_monotonic_seconds();
    pthread_mutex_lock(&g->lock);
    for (ps_guard_conn *c = g->conns; c; c = c->next) {
        int late = past_deadline(g, c, now);
        if (!late && !abandoned(c, now)) continue;
        shutdown(c->fd, SHUT_RDWR);
        c->phase = PHASE_BUSY; /* once */
        cut += (size_t)late;
    }
    pthread_mutex_unlock(&g->lock);
    return cut;
}
