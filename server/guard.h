/*
 * guard.h: deadlines for slow and idle clients, and room for health checks
 * when connections run out.  libmicrohttpd's own idle timeout restarts on
 * every byte, so a request trickled one byte at a time is never cut; the
 * guard tracks each connection from libmicrohttpd's connection
 * notifications and cuts (shutdown(2), which libmicrohttpd then sees as the
 * peer's close) one that
 *   - has not sent a whole request head within header_timeout seconds of
 *     connecting or of its previous answer, or
 *   - uploads a body slower than min_upload_rate bytes a second, counted
 *     from the request's start with header_timeout seconds of grace, or
 *   - ended its input (EOF) while a head or a body is still due.
 * Connections opened while max_connections are already open are the health
 * room: they may only ask the health routes, and are cut after a second
 * idle.  Connections waiting for their job or being answered are never cut.
 */
#ifndef PS_GUARD_H
#define PS_GUARD_H

#include <stddef.h>

typedef struct ps_guard ps_guard;
typedef struct ps_guard_conn ps_guard_conn;

/* A connection's request may only be a health check: it came in over the limit. */
int ps_guard_conn_in_health_room(const ps_guard_conn *c);

ps_guard *ps_guard_new(int max_connections, double header_timeout, double min_upload_rate);
void ps_guard_free(ps_guard *g);

/* Connection life: opened (socket fd) and closed. */
ps_guard_conn *ps_guard_opened(ps_guard *g, int fd);
void ps_guard_closed(ps_guard *g, ps_guard_conn *c);

/* A request's head is in (its body, if any, comes next); n body bytes came
 * in; the body is complete (no deadline until the answer is sent); the
 * answer is sent (the connection waits for its next request). */
void ps_guard_request_begun(ps_guard *g, ps_guard_conn *c);
void ps_guard_received(ps_guard *g, ps_guard_conn *c, size_t n);
void ps_guard_upload_done(ps_guard *g, ps_guard_conn *c);
void ps_guard_answered(ps_guard *g, ps_guard_conn *c);

/* Cuts every connection past its deadline, and closes those whose client
 * ended its input; returns how many were cut (the first kind). */
size_t ps_guard_sweep(ps_guard *g);

#endif
