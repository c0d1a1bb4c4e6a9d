/*
 * reply_cut.h: a loopback relay in front of a redis-server that loses one
 * answer.  The first request holding a marker text reaches Redis and runs;
 * when Redis answers, the relay closes the client's connection instead of
 * passing the answer on, as when a call times out after Redis ran it.
 * Every other request and answer goes through unchanged.
 */
#ifndef PS_REPLY_CUT_H
#define PS_REPLY_CUT_H

typedef struct ps_reply_cut ps_reply_cut;

/* Starts the relay to 127.0.0.1:redis_port on a free loopback port; NULL
 * when it cannot. */
ps_reply_cut *ps_reply_cut_start(int redis_port, const char *marker);

/* The port clients connect to instead of Redis's. */
int ps_reply_cut_port(const ps_reply_cut *c);

/* 1 once the answer to the marked request was lost. */
int ps_reply_cut_done(ps_reply_cut *c);

/* Stops the relay and closes every connection. */
void ps_reply_cut_stop(ps_reply_cut *c);

#endif
