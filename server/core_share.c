/* core_share.c: the cores held by running jobs (core_share.h), under a mutex. */
#include "core_share.h"

#include <pthread.h>
#include <unistd.h>

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static int total; /* cores to share; 0 until first use */
static int held;  /* threads the running jobs took */

static int online_cores(void) {
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    return cores > 0 ? (int)cores : 1;
}

void ps_core_share_init(int cores) {
    pthread_mutex_lock(&lock);
    total = cores > 0 ? cores : online_cores();
    held = 0;
    pthread_mutex_unlock(&lock);
}

int ps_core_share_take(int requested) {
    pthread_mutex_lock(&lock);
    if (total == 0) total = online_cores();
    int threads = requested, free_cores = total - held;
    if (threads <= 0) threads = free_cores > 1 ? free_cores : 1;
    held += threads;
    pthread_mutex_unlock(&lock);
    return threads;
}

void ps_core_share_give(int taken) {
    pthread_mutex_lock(&lock);
    held -= taken;
    pthread_mutex_unlock(&lock);
}
