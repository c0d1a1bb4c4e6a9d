/* daemon_proc.c: the pointsegd child-process helpers of daemon_proc.h. */
#include "daemon_proc.h"

#include <arpa/inet.h>
#include <libgen.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdio.h>
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

int ps_test_daemon_stop(pid_t *pid, double timeout_s) {
    int status = 0;
    if (*pid <= 0) return -1;
    kill(*pid, SIGTERM);
    for (double waited = 0; waited < timeout_s; waited += 0.02) {
        if (waitpid(*pid, &status, WNOHANG) == *pid) {
            *pid = 0;
            if (WIFEXITED(status)) return WEXITSTATUS(status);
            fprintf(stderr, "pointsegd was killed by signal %d after SIGTERM\n",
                    WIFSIGNALED(status) ? WTERMSIG(status) : -1);
            return -1;
        }
        ps_test_sleep_ms(20);
    }
    fprintf(stderr, "pointsegd still running %.0f s after SIGTERM; SIGKILL\n", timeout_s);
    kill(*pid, SIGKILL);
    waitpid(*pid, &status, 0);
    *pid = 0;
    return -1;
}
