/*
 * direct_answer.h: an answer written straight to the socket of a client that
 * has shut down its write side while its request waited for a job.
 *
 * libmicrohttpd 0.9.75 in poll mode reads a resumed connection before it
 * lets the request handler answer, and closes it on the read EOF: a client
 * that sent its request and then shut down its write side (scripts, some
 * proxies) would get no answer.  So such an answer is serialized here (the
 * status line, the response's headers, Date, Content-Length and
 * Connection: close, then the body) and sent before the connection is
 * resumed; libmicrohttpd then closes it.  A client whose shutdown arrives
 * in the microseconds between that check and libmicrohttpd queuing the
 * answer still loses it.
 */
#ifndef PS_DIRECT_ANSWER_H
#define PS_DIRECT_ANSWER_H

#include <stddef.h>

struct MHD_Connection;
struct MHD_Response;

/* The connection's socket, or -1. */
int ps_connection_fd(struct MHD_Connection *conn);

/* 1 when the peer of fd has shut down its write side (a read EOF is
 * pending), 0 when not or not known. */
int ps_peer_done_sending(int fd);

/* Sends status, resp's headers and body[0..len) on fd (non-blocking; waits
 * for room up to timeout_s).  0 once all is sent, -1 otherwise. */
int ps_direct_answer(int fd, int status, struct MHD_Response *resp, const char *body, size_t len,
                     double timeout_s);

#endif
