/*
 * How far a long run is, on standard error (never on the stream's
 * standard output).  On a terminal one line, redrawn at most four times
 * a second once the run has lasted a second (a short run says nothing)
 * and erased at the end or before any message; with --progress plain
 * lines at most once a second and one at the end, for logs; with -q
 * nothing.  The tools call it between blocks of rows, from the thread
 * that computes them, so it costs a clock read a block and nothing when
 * off.
 */
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

static enum cli_progress_mode mode = CLI_PROGRESS_AUTO;
static int active = -1; /* decided on first use: the mode, and a terminal */
static int drawn;       /* a terminal line is showing */
static double start, last, frame_start;
/* The part of the run being made: frame `frame` (from 0) of `nframes`
 * made here (0: a stream of frames not known in advance), `nrows` rows a
 * frame, `rows` of this one done. */
static size_t frame, nframes, nrows, rows;
static int frame_started;
static int held;                 /* cli_progress_hold: nothing more counts */
static const char *unit = "row"; /* what rows are: cli_progress_unit */

static double
now(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int
cli_progress_option(int opt)
{
	if (opt == 'q')
		mode = CLI_PROGRESS_QUIET;
	else if (opt == CLI_OPT_PROGRESS)
		mode = CLI_PROGRESS_LINES;
	else
		return 0;
	return 1;
}

static int
is_active(void)
{
	if (active < 0) {
		active = mode == CLI_PROGRESS_LINES ||
		         (mode == CLI_PROGRESS_AUTO && isatty(STDERR_FILENO));
		start = last = now();
	}
	return active;
}

/* m:ss, or h:mm:ss past an hour. */
static void
put_time(char *buf, size_t size, double s)
{
	unsigned long t = s > 0 && s < 1e9 ? (unsigned long)(s + 0.5) : 0;

	if (t >= 3600)
		snprintf(buf, size, "%lu:%02lu:%02lu", t / 3600, t / 60 % 60, t % 60);
	else
		snprintf(buf, size, "%lu:%02lu", t / 60, t % 60);
}

static void
draw(int final)
{
	double t = now(), elapsed = t - start, done;
	char counts[128], el[32], eta[32];

	if (!final && t - last < (mode == CLI_PROGRESS_LINES ? 1.0 : 0.25))
		return;
	if (!final && mode != CLI_PROGRESS_LINES && elapsed < 1.0)
		return;
	last = t;
	done = nrows ? (double)rows / (double)nrows : 1.0;
	if (nframes == 1)
		snprintf(counts, sizeof(counts), "%s %zu/%zu", unit, rows, nrows);
	else if (nframes)
		snprintf(counts, sizeof(counts), "frame %zu/%zu, %s %zu/%zu", frame + 1,
		         nframes, unit, rows, nrows);
	else
		snprintf(counts, sizeof(counts), "frame %zu, %s %zu/%zu", frame + 1, unit, rows,
		         nrows);
	/* Frames to come are taken to cost what this run's did so far; in a
	 * stream of frames not known in advance, the ETA is this frame's. */
	if (nframes)
		done = ((double)frame + done) / (double)nframes;
	else
		elapsed = t - frame_start;
	put_time(eta, sizeof(eta), done > 0 ? elapsed * (1.0 - done) / done : 0);
	put_time(el, sizeof(el), t - start);
	if (mode == CLI_PROGRESS_LINES) {
		fprintf(stderr, "%s: %3.0f%%, %s, %s elapsed%s%s\n", argv0, 100.0 * done, counts,
		        el, done > 0 && done < 1 ? ", ETA " : "", done > 0 && done < 1 ? eta : "");
	} else {
		fprintf(stderr, "\r\033[K%s: %3.0f%%  %s  %s elapsed%s%s", argv0, 100.0 * done,
		        counts, el, done > 0 && done < 1 ? "  ETA " : "",
		        done > 0 && done < 1 ? eta : "");
		drawn = 1;
	}
	fflush(stderr);
}

int
cli_progress_quiet(void)
{
	return mode == CLI_PROGRESS_QUIET;
}

size_t
cli_progress_block(size_t block, size_t rows_a_frame)
{
	size_t most = rows_a_frame / 32 ? rows_a_frame / 32 : 1;

	return is_active() && block > most ? most : block;
}

void
cli_progress_frames(size_t count)
{
	nframes = count;
}

void
cli_progress_unit(const char *name)
{
	unit = name;
}

void
cli_progress_hold(void)
{
	held = 1;
}

void
cli_progress_frame(size_t rows_a_frame)
{
	if (held || !is_active())
		return;
	if (frame_started)
		frame++;
	frame_started = 1;
	frame_start = now();
	nrows = rows_a_frame;
	rows = 0;
}

void
cli_progress_rows(size_t done)
{
	/* not decided (no frame begun) or off */
	if (held || active <= 0)
		return;
	rows = done;
	draw(0);
}

void
cli_progress_clear(void)
{
	if (drawn) {
		fputs("\r\033[K", stderr);
		drawn = 0;
	}
}

void
cli_progress_end(void)
{
	if (active <= 0)
		return;
	if (mode == CLI_PROGRESS_LINES && frame_started)
		draw(1);
	cli_progress_clear();
}
