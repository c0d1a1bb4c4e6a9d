/* daemon_proc.c: the pointsegd child-process helpers of daemon_proc.h. */
#include "daemon_proc.h"

#include <arpa/inet.h>
#include <libgen.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

void ps_test_sleep_ms(long ms) {
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

int ps_test_free_port(void) {
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_addr.s_addr = htonl(INADDR_LOOPBACK)};
    socklen_t len = sizeof a;
    int fd = socket(AF_INET, SOCK_STREAM, 0), port = -1;
    if (fd < 0) return -1;
    if (!bind(fd, (struct sockaddr *)&a, sizeof a) && !getsockname(fd, (struct sockaddr *)&a, &len))
        port = ntohs(a.sin_port);
    close(fd);
    return port;
}

int ps_test_daemon_path(char *out, size_t cap) {
    char self[4096];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0) return -1;
    self[n] = 0;
    return snprintf(out, cap, "%s/../pointsegd", dirname(self)) < (int)cap ? 0 : -1;
}

/* The result of a stop, described in how (may be NULL). */
static int ended(int status, char *how, size_t cap) {
    char scratch[8];
    if (!how) how = scratch, cap = sizeof scratch;
    if (WIFEXITED(status)) {
        snprintf(how, cap, "exited with status %d", WEXITSTATUS(status));
        return WEXITSTATUS(status);
    }
    if (WIFSIGNALED(status))
        snprintf(how, cap, "was killed by signal %d (%s)", WTERMSIG(status), strsignal(WTERMSIG(status)));
    else
        snprintf(how, cap, "ended with wait status %#x", (unsigned)status);
    return -1;
}

int ps_test_daemon_stop(pid_t *pid, double timeout_s, char *how, size_t how_cap) {
    int status = 0;
    if (how) snprintf(how, how_cap, "was not running (no process)");
    if (*pid <= 0) return -1;
    kill(*pid, SIGTERM);
    for (double waited = 0; waited < timeout_s; waited += 0.02) {
        if (waitpid(*pid, &status, WNOHANG) == *pid) {
            *pid = 0;
            return ended(status, how, how_cap);
        }
        ps_test_sleep_ms(20);
    }
    kill(*pid, SIGKILL);
    waitpid(*pid, &status, 0);
    *pid = 0;
    if (how) snprintf(how, how_cap, "was still running %.0f s after SIGTERM (killed)", timeout_s);
    return -1;
}

void ps_test_log_tail(const char *path, int lines, char *out, size_t cap) {
    FILE *f = fopen(path, "rb");
    long size = f && !fseek(f, 0, SEEK_END) ? ftell(f) : -1;
    size_t n = 0;
    out[0] = 0;
    if (size > 0) {
        long from = size > (long)cap - 1 ? size - (long)cap + 1 : 0;
        if (!fseek(f, from, SEEK_SET)) n = fread(out, 1, cap - 1, f);
    }
    if (f) fclose(f);
    out[n] = 0;
    size_t start = n && out[n - 1] == '\n' ? n - 1 : n;
    int seen = 0;
    while (start > 0 && !(out[start - 1] == '\n' && ++seen == lines)) start--;
    memmove(out, out + start, n - start + 1);
}
