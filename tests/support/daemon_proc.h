/*
 * daemon_proc.h: what the tests and benchmarks that run pointsegd as a
 * child process share: a free loopback port, the daemon binary next to the
 * running program (BUILD/x/prog -> BUILD/pointsegd), a short sleep, a
 * SIGTERM stop that waits for the exit status and says how the process
 * ended, and the last lines of a log.
 */
#ifndef PS_DAEMON_PROC_H
#define PS_DAEMON_PROC_H

#include <stddef.h>
#include <sys/types.h>

void ps_test_sleep_ms(long ms);

/* A loopback TCP port free right now, or -1. */
int ps_test_free_port(void);

/* BUILD/pointsegd for a program in BUILD/<dir>/; 0 or -1. */
int ps_test_daemon_path(char *out, size_t cap);

/* SIGTERM, then wait up to timeout_s (SIGKILL after that); *pid becomes 0.
 * Returns the exit status, or -1 (killed by a signal, timed out, or no
 * process).  how (may be NULL) says which: "exited with status 1",
 * "was killed by signal 6 (Aborted)", "was still running 10 s after
 * SIGTERM (killed)". */
int ps_test_daemon_stop(pid_t *pid, double timeout_s, char *how, size_t how_cap);

/* The last `lines` lines of the file at path into out (empty when it
 * cannot be read). */
void ps_test_log_tail(const char *path, int lines, char *out, size_t cap);

#endif
