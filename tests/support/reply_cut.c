/* reply_cut.c: the answer-losing relay of reply_cut.h, one thread polling
 * the listening socket and every client/Redis connection pair. */
#include "reply_cut.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#define MAX_PAIRS 32
#define POLL_MS 50

typedef struct pair {
    int client, redis;  /* -1: the slot is free */
    int doomed;         /* the marked request went this way: its answer is lost */
} pair;

struct ps_reply_cut {
    int listener, redis_port, port;
    char marker[64];
    int marked;          /* the marked request was seen (relay thread only) */
    pthread_t thread;
    pthread_mutex_t lock;
    int stop, done;
    pair pairs[MAX_PAIRS];
};

static int contains(const char *bytes, size_t len, const char *text) {
    size_t n = strlen(text);
    for (size_t i = 0; n && i + n <= len; i++)
        if (!memcmp(bytes + i, text, n)) return 1;
    return 0;
}

static int send_all(int fd, const char *bytes, size_t len) {
    while (len) {
        ssize_t n = send(fd, bytes, len, MSG_NOSIGNAL);
        if (n <= 0) return -1;
        bytes += n, len -= (size_t)n;
    }
    return 0;
}

static int connect_redis(int port) {
    struct sockaddr_in a = {.sin_family = AF_INET, .sin_port = htons((uint16_t)port)};
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd >= 0 && connect(fd, (struct sockaddr *)&a, sizeof a) == 0) return fd;
    if (fd >= 0) close(fd);
    return -1;
}

static void close_pair(pair *p) {
    if (p->client >= 0) close(p->client);
    if (p->redis >= 0) close(p->redis);
    *p = (pair){-1, -1, 0};
}

static void accept_client(ps_reply_cut *c) {
    int fd = accept(c->listener, NULL, NULL);
    if (fd < 0) return;
    for (int i = 0; i < MAX_PAIRS; i++)
        if (c->pairs[i].client < 0) {
            c->pairs[i] = (pair){fd, connect_redis(c->redis_port), 0};
            if (c->pairs[i].redis < 0) close_pair(&c->pairs[i]);
            return;
        }
    close(fd);
}

/* Bytes from the client go to Redis; the first holding the marker dooms
 * the pair's next answer. */
static void from_client(ps_reply_cut *c, pair *p) {
    char buf[65536];
    ssize_t n = recv(p->client, buf, sizeof buf, 0);
    if (n <= 0) {
        close_pair(p);
        return;
    }
    if (!c->marked && contains(buf, (size_t)n, c->marker)) c->marked = p->doomed = 1;
    if (send_all(p->redis, buf, (size_t)n)) close_pair(p);
}

/* Bytes from Redis go to the client, unless the pair is doomed: then the
 * answer is dropped and the client's connection closed. */
static void from_redis(ps_reply_cut *c, pair *p) {
    char buf[65536];
    ssize_t n = recv(p->redis, buf, sizeof buf, 0);
    if (n > 0 && p->doomed) {
        pthread_mutex_lock(&c->lock);
        c->done = 1;
        pthread_mutex_unlock(&c->lock);
    }
    if (n <= 0 || p->doomed || send_all(p->client, buf, (size_t)n)) close_pair(p);
}

static int stopping(ps_reply_cut *c) {
    pthread_mutex_lock(&c->lock);
    int stop = c->stop;
    pthread_mutex_unlock(&c->lock);
    return stop;
}

static void *relay_main(void *arg) {
    ps_reply_cut *c = arg;
    while (!stopping(c)) {
        struct pollfd fds[1 + 2 * MAX_PAIRS];
        fds[0] = (struct pollfd){c->listener, POLLIN, 0};
        for (int i = 0; i < MAX_PAIRS; i++) {
            fds[1 + 2 * i] = (struct pollfd){c->pairs[i].client, POLLIN, 0};
            fds[2 + 2 * i] = (struct pollfd){c->pairs[i].redis, POLLIN, 0};
        }
        if (poll(fds, 1 + 2 * MAX_PAIRS, POLL_MS) <= 0) continue;
        for (int i = 0; i < MAX_PAIRS; i++) {
            if (fds[1 + 2 * i].revents && c->pairs[i].client >= 0) from_client(c, &c->pairs[i]);
            if (fds[2 + 2 * i].revents && c->pairs[i].redis >= 0) from_redis(c, &c->pairs[i]);
        }
        if (fds[0].revents & POLLIN) accept_client(c);
    }
    return NULL;
}

static int listen_loopback(int *port) {
    struct sockaddr_in a = {.sin_family = AF_INET};
    socklen_t len = sizeof a;
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd < 0 || bind(fd, (struct sockaddr *)&a, sizeof a) || listen(fd, 16) ||
        getsockname(fd, (struct sockaddr *)&a, &len)) {
        if (fd >= 0) close(fd);
        return -1;
    }
    *port = ntohs(a.sin_port);
    return fd;
}

ps_reply_cut *ps_reply_cut_start(int redis_port, const char *marker) {
    ps_reply_cut *c = calloc(1, sizeof *c);
    if (!c || strlen(marker) >= sizeof c->marker) return free(c), NULL;
    c->redis_port = redis_port;
    strcpy(c->marker, marker);
    for (int i = 0; i < MAX_PAIRS; i++) c->pairs[i] = (pair){-1, -1, 0};
    pthread_mutex_init(&c->lock, NULL);
    c->listener = listen_loopback(&c->port);
    if (c->listener >= 0 && !pthread_create(&c->thread, NULL, relay_main, c)) return c;
    if (c->listener >= 0) close(c->listener);
    pthread_mutex_destroy(&c->lock);
    free(c);
    return NULL;
}

int ps_reply_cut_port(const ps_reply_cut *c) { return c->port; }

int ps_reply_cut_done(ps_reply_cut *c) {
    pthread_mutex_lock(&c->lock);
    int done = c->done;
    pthread_mutex_unlock(&c->lock);
    return done;
}

void ps_reply_cut_stop(ps_reply_cut *c) {
    if (!c) return;
    pthread_mutex_lock(&c->lock);
    c->stop = 1;
    pthread_mutex_unlock(&c->lock);
    pthread_join(c->thread, NULL);
    for (int i = 0; i < MAX_PAIRS; i++) close_pair(&c->pairs[i]);
    close(c->listener);
    pthread_mutex_destroy(&c->lock);
    free(c);
}
