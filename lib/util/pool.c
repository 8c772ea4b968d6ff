/*
 * Threads that live as long as a stage and take tasks from a counter.
 * Starting a thread per block cost a streaming stage more than its work:
 * on a small virtual machine pthread_create takes some 150 us, and a
 * new thread reaches its core late, so the block's first half waited for
 * the second.  Here the threads sleep between blocks, and whichever
 * thread is free takes the next task, so a late one costs nothing.
 */
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>

#include "util/util.h"
#include "util/pool.h"

struct rf__pool {
	int nthreads; /* with the caller's */
	pthread_t *tid;
	int started, launched;
	pthread_mutex_t mu;
	pthread_cond_t wake, done;
	unsigned long generation; /* one a batch */
	int quitting;
	int busy;                 /* pool threads still in the batch */
	rf__pool_fn *fn;
	void *arg;
	size_t ntasks;
	atomic_size_t next;
};

struct start {
	struct rf__pool *pool;
	int index;
};

static void
take_tasks(struct rf__pool *p, int thread)
{
	size_t task;

	while ((task = atomic_fetch_add(&p->next, 1)) < p->ntasks)
		p->fn(p->arg, task, thread);
}

/* A stack for signal handlers (sigaltstack) on each pool thread: plugin
 * code runs here, and a tool that reports a mode's crash (SA_ONSTACK)
 * can then report one that overflowed its stack too. */
#define ALTSTACK_BYTES ((size_t)1 << 16)

static void *
worker(void *arg)
{
	struct start *s = arg;
	struct rf__pool *p = s->pool;
	int index = s->index;
	unsigned long seen = 0;
	stack_t alt;

	free(s);
	alt.ss_flags = 0;
	alt.ss_size = ALTSTACK_BYTES;
	if ((alt.ss_sp = malloc(ALTSTACK_BYTES)) && sigaltstack(&alt, NULL) < 0) {
		free(alt.ss_sp);
		alt.ss_sp = NULL;
	}
	pthread_mutex_lock(&p->mu);
	for (;;) {
		while (p->generation == seen && !p->quitting)
			pthread_cond_wait(&p->wake, &p->mu);
		if (p->quitting)
			break;
		seen = p->generation;
		pthread_mutex_unlock(&p->mu);
		take_tasks(p, index);
		pthread_mutex_lock(&p->mu);
		if (--p->busy == 0)
			pthread_cond_signal(&p->done);
	}
	pthread_mutex_unlock(&p->mu);
	if (alt.ss_sp) {
		alt.ss_flags = SS_DISABLE;
		sigaltstack(&alt, NULL);
		free(alt.ss_sp);
	}
	return NULL;
}

int
rf__pool_create(struct rf__pool **pp, int nthreads)
{
	struct rf__pool *p;

	*pp = NULL;
	if (!(p = calloc(1, sizeof(*p))))
		return RF_ENOMEM;
	/* The tools hold -j to RF__THREADS_MAX; a library caller is held here. */
	p->nthreads = nthreads < 1 ? 1 : nthreads > RF__THREADS_MAX ? RF__THREADS_MAX : nthreads;
	if (p->nthreads > 1 && !(p->tid = calloc((size_t)p->nthreads, sizeof(pthread_t)))) {
		free(p);
		return RF_ENOMEM;
	}
	pthread_mutex_init(&p->mu, NULL);
	pthread_cond_init(&p->wake, NULL);
	pthread_cond_init(&p->done, NULL);
	atomic_init(&p->next, 0);
	*pp = p;
	return 0;
}

/* The threads start with the first batch, not with the pool: a tool that
 * dies on a bad header before its first row then leaves none behind.
 * Threads that cannot be had are not an error: the ones there are, the
 * caller at least, take every task. */
static void
start_threads(struct rf__pool *p)
{
	int i;

	p->launched = 1;
	for (i = 1; i < p->nthreads; i++) {
		struct start *s = malloc(sizeof(*s));

		if (!s)
			break;
		s->pool = p;
		s->index = i;
		if (pthread_create(&p->tid[i], NULL, worker, s) != 0) {
			free(s);
			break;
		}
		p->started++;
	}
}

int
rf__pool_threads(const struct rf__pool *p)
{
	return p->nthreads;
}

void
rf__pool_run(struct rf__pool *p, size_t ntasks, rf__pool_fn *fn, void *arg)
{
	/* One task needs no other thread: a stream of one-row frames starts
	 * none. */
	if (ntasks == 1 && !p->started) {
		fn(arg, 0, 0);
		return;
	}
	if (!p->launched)
		start_threads(p);
	pthread_mutex_lock(&p->mu);
	p->fn = fn;
	p->arg = arg;
	p->ntasks = ntasks;
	atomic_store(&p->next, 0);
	p->busy = p->started;
	p->generation++;
	pthread_cond_broadcast(&p->wake);
	pthread_mutex_unlock(&p->mu);
	take_tasks(p, 0);
	pthread_mutex_lock(&p->mu);
	while (p->busy > 0)
		pthread_cond_wait(&p->done, &p->mu);
	pthread_mutex_unlock(&p->mu);
}

void
rf__pool_destroy(struct rf__pool *p)
{
	int i;

	if (!p)
		return;
	pthread_mutex_lock(&p->mu);
	p->quitting = 1;
	pthread_cond_broadcast(&p->wake);
	pthread_mutex_unlock(&p->mu);
	for (i = 1; i <= p->started; i++)
		pthread_join(p->tid[i], NULL);
	pthread_mutex_destroy(&p->mu);
	pthread_cond_destroy(&p->wake);
	pthread_cond_destroy(&p->done);
	free(p->tid);
	free(p);
}
