/*
 * A frame's rows in blocks, read ahead and written behind: while a stage
 * computes block k, a reader thread fills block k + 1 and a writer thread
 * sends block k - 1, so the time a pipe or a file takes overlaps the
 * compute instead of adding to it.  Two buffers each way: the most a
 * stage holds is four blocks.  Reads and writes keep stream order, so the
 * output is the same bytes as a loop of read, compute, write.
 *
 * The threads never exit the process: a failed read or write is handed
 * to the calling thread.  A failed write ends the process there, with the
 * message a plain loop would give; a failed read (bad input) is returned
 * once the threads are gone, so the caller can free its stage first and
 * a memory checker sees nothing left behind.
 */
#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

struct blocks {
	struct cli_io *io;
	size_t nrows, block, nblocks;
	float *in[2], *out[2];
	pthread_mutex_t mu;
	pthread_cond_t cv;
	/* Counts of blocks: read in, computed (its input let go of, its
	 * output ready), written out.  Block k lives in slot k % 2. */
	size_t read, computed, written;
	/* The first failure (an RF_E* code) and errno with it; stop tells
	 * the threads to give up. */
	int read_rc, read_errno, write_rc, write_errno, stop;
	int fn_rc; /* the main thread's alone */
};

static size_t
block_rows(const struct blocks *b, size_t k, size_t *y)
{
	*y = k * b->block;
	return b->nrows - *y < b->block ? b->nrows - *y : b->block;
}

/* Waits, the lock held, until *count > k, or until the side that makes
 * *count failed (*failed, NULL when only stop ends the wait) or stop;
 * returns whether to go on.  Each waiter watches only the failure that
 * starves it: the writer must go on sending the blocks already computed
 * after a read fails, since the main thread waits for them before it
 * stops the threads. */
static int
wait_past(struct blocks *b, const size_t *count, size_t k, const int *failed)
{
	while (*count <= k && !b->stop && !(failed && *failed))
		pthread_cond_wait(&b->cv, &b->mu);
	return *count > k;
}

static void
advance(struct blocks *b, size_t *count)
{
	pthread_mutex_lock(&b->mu);
	(*count)++;
	pthread_cond_broadcast(&b->cv);
	pthread_mutex_unlock(&b->mu);
}

static void
fail(struct blocks *b, int *rc, int *err, int code)
{
	pthread_mutex_lock(&b->mu);
	*rc = code;
	*err = errno;
	pthread_cond_broadcast(&b->cv);
	pthread_mutex_unlock(&b->mu);
}

static void *
reader(void *arg)
{
	struct blocks *b = arg;
	size_t k, y, n;
	int rc, go;

	for (k = 0; k < b->nblocks; k++) {
		if (k >= 2) {
			pthread_mutex_lock(&b->mu);
			go = wait_past(b, &b->computed, k - 2, NULL);
			pthread_mutex_unlock(&b->mu);
			if (!go)
				break;
		}
		n = block_rows(b, k, &y);
		if ((rc = rf_reader_read_rows(b->io->reader, b->in[k % 2], n)) < 0) {
			fail(b, &b->read_rc, &b->read_errno, rc);
			break;
		}
		advance(b, &b->read);
	}
	return NULL;
}

static void *
writer(void *arg)
{
	struct blocks *b = arg;
	size_t k, y, n;
	int rc, go;

	for (k = 0; k < b->nblocks; k++) {
		pthread_mutex_lock(&b->mu);
		go = wait_past(b, &b->computed, k, NULL);
		pthread_mutex_unlock(&b->mu);
		if (!go)
			break;
		n = block_rows(b, k, &y);
		if ((rc = rf_writer_write_rows(b->io->writer, b->out[k % 2], n)) < 0) {
			fail(b, &b->write_rc, &b->write_errno, rc);
			break;
		}
		advance(b, &b->written);
	}
	return NULL;
}

/* Stops and joins the threads and frees the buffers; dies if a write
 * failed, returns the error of a failed read. */
static int
finish(struct blocks *b, pthread_t *rt, pthread_t *wt)
{
	int i;

	pthread_mutex_lock(&b->mu);
	b->stop = 1;
	pthread_cond_broadcast(&b->cv);
	pthread_mutex_unlock(&b->mu);
	if (b->write_rc) {
		/* Not joined: the reader may wait on an upstream that waits
		 * on nothing.  A closed pipe ends us quietly. */
		errno = b->write_errno;
		die_status(b->write_rc, rf_writer_error(b->io->writer));
	}
	if (rt)
		pthread_join(*rt, NULL);
	if (wt)
		pthread_join(*wt, NULL);
	pthread_mutex_destroy(&b->mu);
	pthread_cond_destroy(&b->cv);
	for (i = 0; i < 2; i++) {
		free(b->in[i]);
		free(b->out[i]);
	}
	errno = b->read_errno;
	return b->fn_rc < 0 ? b->fn_rc : b->read_rc;
}

int
cli_blocks(struct cli_io *io, size_t nrows, size_t block, size_t in_floats,
           size_t out_floats, cli_block_fn *fn, void *arg)
{
	struct blocks b;
	pthread_t rt, wt;
	int reading = 0, writing, mapping, threads, go, i, rc;
	size_t k, y, n;
	const float *src;

	if (!nrows)
		return 0;
	cli_progress_frame(nrows);
	memset(&b, 0, sizeof(b));
	b.io = io;
	b.nrows = nrows;
	b.block = block ? block : 1;
	b.nblocks = (nrows + b.block - 1) / b.block;
	for (i = 0; i < 2; i++) {
		b.in[i] = in_floats ? emalloc(b.block * in_floats * sizeof(float)) : NULL;
		b.out[i] = out_floats ? emalloc(b.block * out_floats * sizeof(float)) : NULL;
	}
	pthread_mutex_init(&b.mu, NULL);
	pthread_cond_init(&b.cv, NULL);
	/* A file is mapped block by block and read where it lies: no
	 * reader, no copy.  Without a thread (none to be had) its side is
	 * done here, in turn. */
	n = block_rows(&b, 0, &y);
	src = NULL;
	if (in_floats && (rc = rf_reader_map_rows(io->reader, n, &src)) < 0) {
		b.read_rc = rc;
		b.read_errno = errno;
		return finish(&b, NULL, NULL);
	}
	mapping = src != NULL || !in_floats; /* no input: nothing to read */
	/* One block leaves nothing to overlap: a stream of many small frames
	 * would otherwise start two threads a frame. */
	threads = b.nblocks > 1;
	writing = threads && out_floats && pthread_create(&wt, NULL, writer, &b) == 0;
	if (threads && !mapping)
		reading = pthread_create(&rt, NULL, reader, &b) == 0;
	for (k = 0; k < b.nblocks; k++) {
		n = block_rows(&b, k, &y);
		if (!in_floats) {
			src = NULL;
		} else if (mapping && k > 0 &&
		           (rc = rf_reader_map_rows(io->reader, n, &src)) < 0) {
			b.read_rc = rc;
			b.read_errno = errno;
			break;
		}
		if (in_floats && !reading && (!mapping || !src)) {
			/* Not mappable (or ending early): read it, for the data
			 * or for the message. */
			if ((rc = rf_reader_read_rows(io->reader, b.in[k % 2], n)) < 0) {
				b.read_rc = rc;
				b.read_errno = errno;
				break;
			}
			src = b.in[k % 2];
		} else if (reading) {
			src = b.in[k % 2];
		}
		pthread_mutex_lock(&b.mu);
		go = (!reading || wait_past(&b, &b.read, k, &b.read_rc)) &&
		     (!writing || k < 2 || wait_past(&b, &b.written, k - 2, &b.write_rc));
		pthread_mutex_unlock(&b.mu);
		if (!go)
			break;
		if ((b.fn_rc = fn(arg, src, b.out[k % 2], y, n)) < 0)
			break;
		if (out_floats && !writing) {
			if ((rc = rf_writer_write_rows(io->writer, b.out[k % 2], n)) < 0) {
				b.write_rc = rc;
				b.write_errno = errno;
				break;
			}
		}
		pthread_mutex_lock(&b.mu);
		b.computed++;
		pthread_cond_broadcast(&b.cv);
		pthread_mutex_unlock(&b.mu);
		cli_progress_rows(y + n);
	}
	/* The writer finishes its blocks before it sees stop. */
	if (writing) {
		pthread_mutex_lock(&b.mu);
		while (b.written < b.computed && !b.write_rc)
			pthread_cond_wait(&b.cv, &b.mu);
		pthread_mutex_unlock(&b.mu);
	}
	return finish(&b, reading ? &rt : NULL, writing ? &wt : NULL);
}

struct stage_block {
	rf_stage *stage;
	int failed;  /* the stage refused a pixel (rf_stage_error says why) */
	int gave_up; /* the mode failed in run() (rf_stage_error says why) */
};

static int
stage_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	struct stage_block *sb = arg;
	int rc = rf_stage_run(sb->stage, in, out, y, n);

	sb->failed = rc == RF_EINVAL && *rf_stage_error(sb->stage);
	sb->gave_up = rc == RF_EPLUGIN;
	if (rc < 0 && !sb->failed && !sb->gave_up)
		die_status(rc, NULL);
	return rc;
}

void
cli_stage_rows(struct cli_io *io, rf_stage *stage, const rf_header *in, const rf_header *out)
{
	struct stage_block sb = { stage, 0, 0 };
	size_t rows = rf_block_rows(rf_header_ncols(out), rf_header_nchannels(out),
	                            CLI_BLOCK_BYTES);
	char err[1024];
	int rc;

	cli_io_begin(io, out);
	if (rows > rf_header_nrows(in))
		rows = rf_header_nrows(in);
	rc = cli_blocks(io, rf_header_nrows(in), rows,
	                rf_header_ncols(in) * rf_header_nchannels(in),
	                rf_header_ncols(out) * rf_header_nchannels(out), stage_block, &sb);
	if (sb.failed || sb.gave_up)
		snprintf(err, sizeof(err), "%s", rf_stage_error(stage));
	cli_io_invalid_note(io, rf_stage_invalid_count(stage));
	mode_invalid_note(io, rf_stage_invalid_output_count(stage));
	rf_stage_destroy(stage);
	if (sb.gave_up)
		cli_io_plugin_failed(io, err);
	if (sb.failed)
		cli_io_invalid_failed(io, err);
	if (rc < 0)
		cli_io_read_failed(io, rc);
	cli_io_end_frame(io);
}
