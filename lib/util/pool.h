/* Internal: a stage's threads, kept between blocks. */
#ifndef REFLECT_POOL_H
#define REFLECT_POOL_H

#include <stddef.h>

/* The most threads any stage, pass or renderer runs (-j and
 * REFLECT_THREADS are held to it). */
#define RF__THREADS_MAX 256

struct rf__pool;

/* Runs task `task` on thread `thread` (0 is the caller; below
 * rf__pool_threads). */
typedef void rf__pool_fn(void *arg, size_t task, int thread);

/* nthreads counting the caller's (at most RF__THREADS_MAX), started by
 * the first rf__pool_run; fewer start if the system refuses. */
int rf__pool_create(struct rf__pool **p, int nthreads);
int rf__pool_threads(const struct rf__pool *p);
/* Runs tasks 0..ntasks-1, each once, on whichever thread is free, the
 * caller's included; returns when all are done.  One batch at a time. */
void rf__pool_run(struct rf__pool *p, size_t ntasks, rf__pool_fn *fn, void *arg);
void rf__pool_destroy(struct rf__pool *p);

#endif
