/* threads.c: the desktop's worker threads (POSIX): a small pool, started on first use, that runs one job on several workers and waits for all of them. */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include <pthread.h>
#include <sched.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "platform.h"

static pthread_mutex_t th_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t th_start = PTHREAD_COND_INITIALIZER;
static pthread_cond_t th_done = PTHREAD_COND_INITIALIZER;
static int th_started;       /* workers running besides the caller (ids 1..th_started) */
static unsigned long th_gen; /* counts jobs: a new value wakes the workers */
static int th_active;        /* workers taking part in the current job, the caller included */
static int th_pending;       /* of those besides the caller, still working */
static void (*th_job)(void *ctx, int worker);
static void *th_ctx;
static int th_quit; /* set at exit: the workers return */
static pthread_t th_ids[PLAT_MAX_THREADS];
static int th_limit = PLAT_MAX_THREADS; /* lowered when the system refuses a thread */

static void *th_main(void *arg)
{
    int id = (int)(intptr_t)arg;
    unsigned long seen = 0;
    pthread_mutex_lock(&th_lock);
    for (;;) {
        while (th_gen == seen)
            pthread_cond_wait(&th_start, &th_lock);
        seen = th_gen;
        if (th_quit)
            break;
        if (id < th_active) {
            void (*job)(void *, int) = th_job;
            void *ctx = th_ctx;
            pthread_mutex_unlock(&th_lock);
            job(ctx, id);
            pthread_mutex_lock(&th_lock);
            if (--th_pending == 0)
                pthread_cond_signal(&th_done);
        }
    }
    pthread_mutex_unlock(&th_lock);
    return NULL;
}

/* At exit: the workers finish and are joined, so that nothing of theirs is left behind. */
static void th_stop(void)
{
    pthread_mutex_lock(&th_lock);
    th_quit = 1;
    th_gen++;
    pthread_cond_broadcast(&th_start);
    pthread_mutex_unlock(&th_lock);
    for (int i = 1; i <= th_started; i++)
        pthread_join(th_ids[i], NULL);
}

int plat_cpu_count(void)
{
    /* The processors this process may run on (its affinity mask, e.g. under taskset or a
     * container's cpuset), not all of the machine's. */
    cpu_set_t set;
    long n = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set)
                                                         : sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > PLAT_MAX_THREADS ? PLAT_MAX_THREADS : (int)n;
}

void plat_parallel(int threads, void (*job)(void *ctx, int worker), void *ctx)
{
    pthread_mutex_lock(&th_lock);
    if (threads > th_limit)
        threads = th_limit;
    while (th_started < threads - 1) {
        if (th_started == 0 && atexit(th_stop) != 0)
            break; /* without a way to stop them, no workers: one thread does it all */
        if (pthread_create(&th_ids[th_started + 1], NULL, th_main,
                           (void *)(intptr_t)(th_started + 1)) != 0) {
            fprintf(stderr, "%s: warning: could not start a worker thread; using %d\n",
                    plat_program(), th_started + 1);
            th_limit = th_started + 1; /* said once: later jobs use what there is */
            break;
        }
        th_started++;
    }
    if (threads > th_started + 1)
        threads = th_started + 1;
    if (threads <= 1) {
        pthread_mutex_unlock(&th_lock);
        job(ctx, 0);
        return;
    }
    th_job = job;
    th_ctx = ctx;
    th_active = threads;
    th_pending = threads - 1;
    th_gen++;
    pthread_cond_broadcast(&th_start);
    pthread_mutex_unlock(&th_lock);
    job(ctx, 0);
    pthread_mutex_lock(&th_lock);
    while (th_pending > 0)
        pthread_cond_wait(&th_done, &th_lock);
    pthread_mutex_unlock(&th_lock);
}
