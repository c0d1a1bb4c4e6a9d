/*
 * core_share.h: the machine's cores shared among the jobs this daemon runs
 * at once.  A job that leaves its thread count to the service (threads = 0)
 * gets the cores no other job holds, at least one: alone on an idle daemon
 * it runs as fast as the command-line tool; under load each job keeps a
 * core, as the worker pool intends.  A job's share is fixed when it starts
 * (labels never depend on it).
 */
#ifndef PS_CORE_SHARE_H
#define PS_CORE_SHARE_H

/* Sets the cores to share (tests; the default is the online cores). */
void ps_core_share_init(int cores);

/* Threads for a job asking for requested (> 0: exactly that many; 0: the
 * free cores, at least 1), counted as held until ps_core_share_give. */
int ps_core_share_take(int requested);

/* Gives back what ps_core_share_take returned. */
void ps_core_share_give(int taken);

#endif
