/* test_daemon_proc.c: the child-process helpers the daemon tests stop
 * pointsegd with (daemon_proc.h): the stop says whether the process exited
 * (with which status), died by a signal (which) or outlived the timeout,
 * and the log tail keeps the last lines. */
#include "daemon_proc.h"
#include "testlib.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A child that waits for SIGTERM with `on_term` as its disposition:
 * SIG_DFL dies by it, SIG_IGN outlives it; or exits with `status` at once
 * when status >= 0. */
static pid_t child(void (*on_term)(int), int status) {
    pid_t pid = fork();
    if (pid != 0) return pid;
    if (status >= 0) _exit(status);
    signal(SIGTERM, on_term);
    for (;;) pause();
}

static void abort_on_term(int sig) {
    (void)sig;
    abort();
}

static void test_stop_says_how_the_process_ended(void) {
    char how[128];
    pid_t pid = child(SIG_DFL, 3);
    REQUIRE(pid > 0);
    ps_test_sleep_ms(50);
    CHECK(ps_test_daemon_stop(&pid, 5, how, sizeof how) == 3 && pid == 0);
    CHECK_MSG(!strcmp(how, "exited with status 3"), "%s", how);
    pid = child(abort_on_term, -1);
    REQUIRE(pid > 0);
    ps_test_sleep_ms(50);
    CHECK(ps_test_daemon_stop(&pid, 5, how, sizeof how) == -1);
    CHECK_MSG(!strcmp(how, "was killed by signal 6 (Aborted)"), "%s", how);
    pid = child(SIG_IGN, -1);
    REQUIRE(pid > 0);
    ps_test_sleep_ms(50);
    CHECK(ps_test_daemon_stop(&pid, 0.2, how, sizeof how) == -1 && pid == 0);
    CHECK_MSG(!strcmp(how, "was still running 0 s after SIGTERM (killed)"), "%s", how);
    CHECK(ps_test_daemon_stop(&pid, 1, how, sizeof how) == -1);
    CHECK_MSG(strstr(how, "no process"), "%s", how);
}

static void test_log_tail_keeps_the_last_lines(void) {
    char path[] = "/tmp/pointseg-tail-XXXXXX", out[64];
    int fd = mkstemp(path);
    REQUIRE(fd >= 0);
    FILE *f = fdopen(fd, "w");
    REQUIRE(f);
    for (int i = 1; i <= 40; i++) fprintf(f, "line %d\n", i);
    fclose(f);
    ps_test_log_tail(path, 2, out, sizeof out);
    CHECK_MSG(!strcmp(out, "line 39\nline 40\n"), "'%s'", out);
    ps_test_log_tail(path, 100, out, sizeof out);
    CHECK_MSG(strlen(out) == sizeof out - 1 && strstr(out, "line 40\n"), "'%s'", out);
    remove(path);
    ps_test_log_tail(path, 3, out, sizeof out);
    CHECK(out[0] == 0);
}

PS_TEST_MAIN(TEST(test_stop_says_how_the_process_ended), TEST(test_log_tail_keeps_the_last_lines))
