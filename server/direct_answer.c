/* direct_answer.c: the answer written straight to a half-closed client's
 * socket (direct_answer.h). */
#include "direct_answer.h"

#include "deadline.h"

#include <errno.h>
#include <microhttpd.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>

#define HEAD_CAP 4096

typedef struct head {
    char text[HEAD_CAP];
    size_t len;
    int overflow;
} head;

static void append(head *h, const char *fmt, const char *a, const char *b) {
    int n = snprintf(h->text + h->len, sizeof h->text - h->len, fmt, a, b);
    if (n < 0 || (size_t)n >= sizeof h->text - h->len) h->overflow = 1;
    else h->len += (size_t)n;
}

static enum MHD_Result add_header(void *cls, enum MHD_ValueKind kind, const char *name, const char *value) {
    (void)kind;
    append(cls, "%s: %s\r\n", name, value);
    return MHD_YES;
}

/* Sends all of data on the non-blocking fd by the monotonic deadline. */
static int send_by(int fd, const char *data, size_t len, double deadline) {
    while (len) {
        ssize_t n = send(fd, data, len, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n > 0) {
            data += n;
            len -= (size_t)n;
            continue;
        }
        if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return -1;
        double left = deadline - ps_monotonic_seconds();
        struct pollfd p = {fd, POLLOUT, 0};
        if (left <= 0 || poll(&p, 1, (int)(left * 1000) + 1) < 0 || (p.revents & (POLLERR | POLLHUP))) return -1;
    }
    return 0;
}

int ps_connection_fd(struct MHD_Connection *conn) {
    const union MHD_ConnectionInfo *info = MHD_get_connection_info(conn, MHD_CONNECTION_INFO_CONNECTION_FD);
    return info ? info->connect_fd : -1;
}

int ps_peer_done_sending(int fd) {
    char c;
    return fd >= 0 && recv(fd, &c, 1, MSG_PEEK | MSG_DONTWAIT) == 0;
}

int ps_direct_answer(int fd, int status, struct MHD_Response *resp, const char *body, size_t len,
                     double timeout_s) {
    head h = {.len = 0};
    char code[16], date[64], length[32];
    time_t now = time(NULL);
    struct tm gmt;
    const char *reason = MHD_get_reason_phrase_for((unsigned)status);
    snprintf(code, sizeof code, "%d", status);
    strftime(date, sizeof date, "%a, %d %b %Y %H:%M:%S GMT", gmtime_r(&now, &gmt));
    snprintf(length, sizeof length, "%zu", len);
    append(&h, "HTTP/1.1 %s %s\r\n", code, reason[0] ? reason : "Unknown");
    append(&h, "%s: %s\r\n", MHD_HTTP_HEADER_DATE, date);
    MHD_get_response_headers(resp, add_header, &h);
    append(&h, "%s: %s\r\n", MHD_HTTP_HEADER_CONTENT_LENGTH, length);
    append(&h, "%s: %s\r\n\r\n", MHD_HTTP_HEADER_CONNECTION, "close");
    if (fd < 0 || h.overflow) return -1;
    double deadline = ps_monotonic_seconds() + timeout_s;
    return send_by(fd, h.text, h.len, deadline) || send_by(fd, body, len, deadline) ? -1 : 0;
}
