/*
 * daemon_harness.h: pointsegd's HTTP layer started in-process for the fuzz
 * targets that go through it (loopback, any free port, at most 64 points a
 * request so a job is quick, one worker), and the raw-socket exchange they
 * share: connect, send, read one whole answer.
 */
#ifndef PS_DAEMON_HARNESS_H
#define PS_DAEMON_HARNESS_H

#include <stddef.h>

#define PS_FUZZ_ANSWER_TIMEOUT_S 8 /* under run.sh's -timeout=10 */

/* The server's port; starts it on the first call (aborts if it cannot). */
int ps_fuzz_server_port(void);

/* A connected socket with receive and send timeouts, closed with a reset. */
int ps_fuzz_connect(int port);

int ps_fuzz_send_all(int fd, const void *data, size_t len);

/* Reads until one whole answer (head and Content-Length bytes of body) is
 * in, the peer closes, or the timeout passes.  Returns the answer's length
 * with *text (NUL-terminated, valid until the next call), or 0. */
size_t ps_fuzz_read_answer(int fd, const char **text);

#endif
