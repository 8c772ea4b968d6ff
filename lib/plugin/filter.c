/*
 * Running a filter mode over the frames of a stream (plugin.h: the filter
 * kind), a band of rows at a time.
 *
 * A mode runs in passes, each over the output of the one before, and a
 * pass needs the rows radius above and below the row it writes: the
 * passes form a cascade of ring buffers, level p the input of pass p
 * (each row planar: an array of the row for each of the mode's inputs,
 * the guides, then for each value), level P the result.  Rows are read as the rings have room, each level computes
 * what its band allows, and a result row leaves as soon as it is done,
 * with the other channels of its input row (held in a ring of whole input
 * rows until then).  Memory is a few bands: at 1920x1080 with 34
 * channels, a-trous's five passes (radius 2 to 32) run in 55 MB where
 * the frame is 282 MB, and a frame of any height in the same.  The rows of a step are spread over the
 * pool's threads; a row depends only on the rows of its band, so the
 * bytes do not depend on the thread count.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "plugin/plugin-internal.h"
#include "util/invalid.h"
#include "util/pool.h"
#include "reflect/plugin.h"

struct worker {
	void *state;        /* the mode's instance */
	const float **band; /* 2 radius + 1 row pointers */
	/* The first value of the step that run() wrote not finite, by row:
	 * bad_y SIZE_MAX for none. */
	size_t bad_y, bad_x, bad_value;
	uint32_t bad_pass;
	float bad;
};

struct level {
	float *rows; /* cap rows of ncols x (ng + nv) floats, row y at y % cap */
	size_t cap;
	size_t avail; /* rows 0 .. avail - 1 have been written */
	size_t done;  /* rows of the next level computed from this one */
};

struct rf_filter {
	const struct rf_plugin *p;
	struct rf__call_site site; /* for a crash report */
	const struct rf_host *host;
	int nthreads;
	struct worker *workers;
	struct rf__pool *pool;
	char *channels;
	size_t ninputs, ng, nv; /* required inputs; guides with the optional */
	/* The mode's own rows a pixel (its outputs), after the values in
	 * every level: state a pass hands the next (a variance the filter
	 * carries), NaN into the first pass, never written out. */
	size_t ns;
	int guide_col[RF_CHANNELS_MAX];
	/* The guides' rules: their directions (N, Ng, V) are made unit as
	 * they are read, so that a mode's dot products hold whatever their
	 * length (1e20 overflowed to NaN); one without a direction is NaN,
	 * as a guide the stream lacks. */
	struct rf__check rules;
	const char *guide_names[RF_CHANNELS_MAX];
	int value_col[RF_CHANNELS_MAX];
	uint32_t npasses, radius[RF_FILTER_PASSES_MAX];
	rf_header *out_h;
	size_t ncols, nrows, ncomp, frames;
	/* The output's channels as input columns: every one but the
	 * standard errors (NAME.se) of the values filtered, which were the
	 * errors of the values before the filter. */
	int out_col[RF_CHANNELS_MAX];
	size_t out_ncomp;
	int out_value_col[RF_CHANNELS_MAX]; /* value_col's in the output */
	struct level level[RF_FILTER_PASSES_MAX + 1];
	float *full; /* whole input rows, from the next output row on */
	size_t full_cap;
	float *block; /* rows as read or written, block of them */
	size_t block_rows;
	/* The step pass_row is running: for each pass, its first row and
	 * where its tasks begin among the step's (task_start[npasses], all). */
	size_t step_y0[RF_FILTER_PASSES_MAX];
	size_t task_start[RF_FILTER_PASSES_MAX + 1];
	char error[320];
};

static size_t
list_length(const char *const *list)
{
	size_t n = 0;

	while (list && list[n])
		n++;
	return n;
}

static const char *
guide_name(const rf_filter *f, size_t i)
{
	return i < f->ninputs ? f->p->inputs[i]
	                      : rf_plugin_optional_inputs(f->p)[i - f->ninputs];
}

static void
free_frame(rf_filter *f)
{
	uint32_t p;

	for (p = 0; p <= RF_FILTER_PASSES_MAX; p++) {
		free(f->level[p].rows);
		f->level[p].rows = NULL;
	}
	free(f->full);
	free(f->block);
	f->full = f->block = NULL;
}

int
rf_filter_create(rf_filter **fp, const struct rf_plugin *p, const double *values,
                 const struct rf_host *host, int nthreads,
                 const struct rf_filter_options *o, char *err, size_t errlen)
{
	rf_filter *f;
	uint32_t rmax = 0, i;
	int t;

	*fp = NULL;
	if (nthreads < 1)
		nthreads = 1;
	if (nthreads > RF__THREADS_MAX)
		nthreads = RF__THREADS_MAX;
	if (p->kind != RF_KIND_FILTER) {
		rf__format(err, errlen, "mode '%s' is a %s mode, not a filter mode", p->name,
		           rf_plugin_kind_name(p->kind));
		return RF_EPLUGIN;
	}
	/* a filter mode declares its passes to the host in create(): a
	 * caller's own table would take them where the filter cannot see */
	if (!rf__host_is_own(host)) {
		rf__format(err, errlen, "a filter runs with the table of an rf_plugin_host "
		           "(rf_plugin_host_table), which its mode declares its passes to");
		return RF_EINVAL;
	}
	if (!(f = calloc(1, sizeof(*f))))
		return RF_ENOMEM;
	f->p = p;
	rf__call_site_init(&f->site, p);
	f->host = host;
	f->nthreads = nthreads;
	f->ninputs = list_length(p->inputs);
	f->ng = f->ninputs + list_length(rf_plugin_optional_inputs(p));
	f->ns = list_length(p->outputs);
	if ((o && o->channels && !(f->channels = strdup(o->channels))) ||
	    !(f->workers = calloc((size_t)nthreads, sizeof(*f->workers))) ||
	    rf__pool_create(&f->pool, nthreads) < 0) {
		rf_filter_destroy(f);
		return RF_ENOMEM;
	}
	rf__host_filter_reset(host);
	for (t = 0; t < nthreads; t++)
		if (rf__plugin_instance(p, &f->site, host, values, &f->workers[t].state, err,
		                        errlen) < 0) {
			rf_filter_destroy(f);
			return RF_EPLUGIN;
		}
	f->npasses = rf__host_filter_passes(host, f->radius);
	for (i = 0; i < f->npasses; i++)
		rmax = f->radius[i] > rmax ? f->radius[i] : rmax;
	for (t = 0; t < nthreads; t++)
		if (!(f->workers[t].band = calloc(2 * (size_t)rmax + 1, sizeof(float *)))) {
			rf_filter_destroy(f);
			return RF_ENOMEM;
		}
	*fp = f;
	return 0;
}

void
rf_filter_destroy(rf_filter *f)
{
	int t;

	if (!f)
		return;
	rf__pool_destroy(f->pool);
	for (t = 0; f->workers && t < f->nthreads; t++) {
		if (f->workers[t].state)
			rf__plugin_destroy(f->p, &f->site, f->workers[t].state);
		free(f->workers[t].band);
	}
	free(f->workers);
	free(f->channels);
	rf_header_destroy(f->out_h);
	free_frame(f);
	rf__call_site_fini(&f->site);
	free(f);
}

/* Whether input channel c is the standard error of a value filtered
 * (and not filtered itself, as --channels may ask). */
static int
stale_error(const rf_filter *f, const rf_header *in, size_t c)
{
	const char *name = rf_header_channel(in, c);
	size_t len = strlen(name), i;

	if (len <= 3 || strcmp(name + len - 3, ".se"))
		return 0;
	for (i = 0; i < f->nv; i++)
		if ((size_t)f->value_col[i] == c)
			return 0;
	for (i = 0; i < f->nv; i++) {
		const char *v = rf_header_channel(in, (size_t)f->value_col[i]);

		if (strlen(v) == len - 3 && !strncmp(v, name, len - 3))
			return 1;
	}
	return 0;
}

/* f->out_col and the output header's channels: the input's, less the
 * standard errors the filter made stale. */
static int
drop_stale_errors(rf_filter *f, const rf_header *in)
{
	size_t c, i, len = 0;
	char *names;
	int rc;

	f->out_ncomp = 0;
	for (c = 0; c < f->ncomp; c++)
		if (!stale_error(f, in, c)) {
			for (i = 0; i < f->nv; i++)
				if ((size_t)f->value_col[i] == c)
					f->out_value_col[i] = (int)f->out_ncomp;
			f->out_col[f->out_ncomp++] = (int)c;
			len += strlen(rf_header_channel(in, c)) + 1;
		}
	if (f->out_ncomp == f->ncomp)
		return 0;
	if (!(names = malloc(len + 1)))
		return RF_ENOMEM;
	names[0] = '\0';
	for (c = 0; c < f->out_ncomp; c++) {
		strcat(names, rf_header_channel(in, (size_t)f->out_col[c]));
		strcat(names, " ");
	}
	rc = rf_header_set_channels(f->out_h, names);
	free(names);
	return rc;
}

int
rf_filter_begin_frame(rf_filter *f, const rf_header *in, rf_header **out, char *err,
                      size_t errlen)
{
	size_t i, stride, rsum = 0, nv;
	uint32_t p;
	int rc;

	for (i = 0; i < f->ng; i++) {
		f->guide_col[i] = rf_header_find_channel(in, guide_name(f, i));
		if (f->guide_col[i] < 0 && i < f->ninputs) {
			rf__format(err, errlen, "frame %zu has no channel '%s', which mode '%s' "
			           "is guided by", f->frames + 1, guide_name(f, i), f->p->name);
			return RF_ECHANNEL;
		}
		f->guide_names[i] = f->guide_col[i] >= 0 ? guide_name(f, i) : "";
	}
	rf__check_plan(&f->rules, f->guide_names, f->ng);
	if ((rc = rf__choose_values(in, f->channels, "filter", f->value_col, &nv, err,
	                            errlen)) < 0)
		return rc;
	free_frame(f);
	f->nv = nv;
	f->ncols = rf_header_ncols(in);
	f->nrows = rf_header_nrows(in);
	f->ncomp = rf_header_nchannels(in);
	stride = f->ncols * (f->ng + f->nv + f->ns);
	for (p = 0; p < f->npasses; p++)
		rsum += f->radius[p];
	/* Rows a step reads and writes: enough for the threads to share and
	 * to pay for a step's wait, few enough that the rings stay bands (at
	 * 1920x1080 x 34 channels, 4 rows a step: 25.5 Mpixel/s a pass of
	 * atrous in 41 MB; 16 rows: 31-32 in 55 MB). */
	f->block_rows = rf_block_rows(f->ncols, f->ncomp, (size_t)4 << 20);
	if (f->block_rows > 16)
		f->block_rows = 16;
	for (p = 0; p <= f->npasses; p++) {
		struct level *l = &f->level[p];
		size_t cap = (p < f->npasses ? 2 * (size_t)f->radius[p] + 1 : 0) + f->block_rows + 1;

		l->cap = cap < f->nrows ? cap : f->nrows;
		l->avail = l->done = 0;
		if (f->nrows && !(l->rows = malloc(l->cap * stride * sizeof(float) + 1)))
			goto nomem;
	}
	f->full_cap = rsum + f->block_rows + 2;
	if (f->full_cap > f->nrows)
		f->full_cap = f->nrows;
	if (f->nrows && (!(f->full = malloc(f->full_cap * f->ncols * f->ncomp * sizeof(float))) ||
	                 !(f->block = malloc(f->block_rows * f->ncols * f->ncomp *
	                                     sizeof(float)))))
		goto nomem;
	rf_header_destroy(f->out_h);
	f->out_h = NULL;
	if ((rc = rf_header_dup(&f->out_h, in)) < 0 || (rc = drop_stale_errors(f, in)) < 0)
		return rc;
	*out = f->out_h;
	f->frames++;
	return 0;
nomem:
	rf__format(err, errlen, "out of memory for the bands of %zux%zu pixels", f->ncols,
	           f->nrows);
	return RF_ENOMEM;
}

static float *
level_row(const rf_filter *f, uint32_t p, size_t y)
{
	const struct level *l = &f->level[p];

	return l->rows + (y % l->cap) * f->ncols * (f->ng + f->nv + f->ns);
}

static float *
full_row(const rf_filter *f, size_t y)
{
	return f->full + (y % f->full_cap) * f->ncols * f->ncomp;
}

/* What run() wrote for a row of pass p (planar values): a filtered
 * value must be finite, as its input was, or a mode's bug would be a
 * silent wrong image.  One pass of adds, a search only on a failure. */
static void
check_pass_row(const rf_filter *f, struct worker *w, const float *out, size_t y, uint32_t p)
{
	const size_t n = f->nv * f->ncols;
	float sum = 0.0f;
	size_t i;

	for (i = 0; i < n; i++)
		sum += out[i] * 0.0f;
	if (sum == 0.0f || y >= w->bad_y)
		return;
	for (i = 0; i < n && isfinite(out[i]); i++)
		;
	w->bad_y = y;
	w->bad_x = i % f->ncols;
	w->bad_value = i / f->ncols;
	w->bad_pass = p;
	w->bad = out[i];
}

/* After a step: RF_EINVAL with f->error for the first value run() wrote
 * that is not finite, else 0. */
static int
pass_failure(rf_filter *f)
{
	const struct worker *b = NULL;
	int t;

	for (t = 0; t < f->nthreads; t++) {
		const struct worker *w = &f->workers[t];

		if (w->bad_y != SIZE_MAX && (!b || w->bad_y < b->bad_y))
			b = w;
	}
	if (!b)
		return 0;
	rf__format(f->error, sizeof(f->error), "row %zu, pixel %zu: mode '%s' broke its "
	           "output contract: pass %u wrote channel '%s' as %s", b->bad_y + 1,
	           b->bad_x + 1, f->p->name, b->bad_pass + 1,
	           rf_header_channel(f->out_h, (size_t)f->out_value_col[b->bad_value]),
	           isnan(b->bad) ? "nan" : b->bad > 0 ? "inf" : "-inf");
	return RF_EINVAL;
}

/* A task of the step: a row of one pass, from level pass into level
 * pass + 1. */
static void
pass_row(void *arg, size_t task, int thread)
{
	rf_filter *f = arg;
	struct worker *w = &f->workers[thread];
	uint32_t p = 0;
	size_t y, k, r;
	struct rf_span span;
	float *dst;
	const float *src;

	while (task >= f->task_start[p + 1])
		p++;
	r = f->radius[p];
	y = f->step_y0[p] + (task - f->task_start[p]);
	dst = level_row(f, p + 1, y);

	for (k = 0; k <= 2 * (size_t)r; k++) {
		long yy = (long)y + (long)k - (long)r;

		w->band[k] = yy >= 0 && (size_t)yy < f->nrows ? level_row(f, p, (size_t)yy) : NULL;
	}
	src = w->band[r];
	memset(&span, 0, sizeof(span));
	span.size = sizeof(span);
	span.npix = (uint32_t)f->ncols;
	span.y = (uint32_t)y;
	span.width = (uint32_t)f->ncols;
	span.height = (uint32_t)f->nrows;
	span.frame = (uint32_t)(f->frames - 1);
	span.in = src;
	span.out = dst + f->ng * f->ncols; /* planar values, then the mode's state */
	span.nvalues = (uint32_t)f->nv;
	span.band = w->band;
	span.radius = r;
	span.pass = p;
	if (f->ncols) {
		rf__call_enter(&f->site, "run", f->frames, y, 1);
		f->p->run(w->state, &span);
		rf__call_leave();
		check_pass_row(f, w, span.out, y, p);
	}
	/* the guides' arrays as they were, before the values', for the
	 * next pass (the result's are not read) */
	if (p + 1 < f->npasses)
		memcpy(dst, src, f->ng * f->ncols * sizeof(float));
}

/* The directions among the guides of a gathered row made unit, in
 * double; NaN where there is none. */
static void
unit_guides(const rf_filter *f, float *g)
{
	const size_t w = f->ncols;
	size_t i, x;

	for (i = 0; i < f->rules.n; i++) {
		const struct rf__check_item *it = &f->rules.item[i];
		float *a, *b, *c;

		if (it->kind != RF__CHECK_DIRECTION)
			continue;
		a = g + (size_t)it->at[0] * w;
		b = g + (size_t)it->at[1] * w;
		c = g + (size_t)it->at[2] * w;
		for (x = 0; x < w; x++) {
			double l = sqrt((double)a[x] * a[x] + (double)b[x] * b[x] +
			                (double)c[x] * c[x]);

			if (l > 0.0 && l < HUGE_VAL) {
				a[x] = (float)(a[x] / l);
				b[x] = (float)(b[x] / l);
				c[x] = (float)(c[x] / l);
			} else {
				a[x] = b[x] = c[x] = NAN;
			}
		}
	}
}

/* The largest value filtered: a mode takes differences of values and
 * sums of a few, with weights that add up to 1, and all must stay in
 * float's range (3e38 beside -3e38 made inf - inf, and NaN out). */
#define VALUE_MAX (FLT_MAX / 4)

/* Copies n rows just read (f->block) into the ring of whole rows and
 * gathers them into level 0; 0, or RF_EINVAL for a value that is not
 * finite or past VALUE_MAX (rf_filter_error says where). */
static int
take_rows(rf_filter *f, size_t y, size_t n)
{
	const size_t w = f->ncols;
	size_t k, x, i;

	for (k = 0; k < n; k++) {
		const float *in = f->block + k * w * f->ncomp;
		float *g = level_row(f, 0, y + k);

		memcpy(full_row(f, y + k), in, w * f->ncomp * sizeof(float));
		for (x = 0; x < w; x++, in += f->ncomp) {
			for (i = 0; i < f->ng; i++)
				g[i * w + x] = f->guide_col[i] >= 0 ? in[f->guide_col[i]] : NAN;
			for (i = 0; i < f->nv; i++) {
				float v = in[f->value_col[i]];

				if (!isfinite(v)) {
					rf__format(f->error, sizeof(f->error), "row %zu, pixel %zu: "
					           "channel '%s' is %s", y + k + 1, x + 1,
					           rf_header_channel(f->out_h, (size_t)f->out_value_col[i]),
					           isnan(v) ? "nan" : v > 0 ? "inf" : "-inf");
					return RF_EINVAL;
				}
				if (!(fabsf(v) <= VALUE_MAX)) {
					rf__format(f->error, sizeof(f->error), "row %zu, pixel %zu: "
					           "channel '%s' is %g, past a quarter of the float "
					           "range (%g), where a filter's sums overflow", y + k + 1,
					           x + 1,
					           rf_header_channel(f->out_h, (size_t)f->out_value_col[i]),
					           (double)v, (double)VALUE_MAX);
					return RF_EINVAL;
				}
				g[(f->ng + i) * w + x] = v;
			}
		}
		for (x = 0; x < f->ns * w; x++)
			g[(f->ng + f->nv) * w + x] = NAN;
		unit_guides(f, g);
	}
	return 0;
}

/* The first row a level still needs: the lowest of its next output
 * row's band, or the next result row. */
static size_t
level_low(const rf_filter *f, uint32_t p, size_t out_next)
{
	if (p == f->npasses)
		return out_next;
	return f->level[p].done > f->radius[p] ? f->level[p].done - f->radius[p] : 0;
}

int
rf_filter_frame(rf_filter *f, rf_filter_read_fn *read_rows, rf_filter_write_fn *write_rows,
                void *arg)
{
	size_t read_next = 0, out_next = 0;
	int rc;

	f->error[0] = '\0';
	while (out_next < f->nrows) {
		size_t n = f->nrows - read_next, progress = 0, low;
		uint32_t p;

		/* Read what the whole-row ring and level 0 have room for. */
		if (n > f->block_rows)
			n = f->block_rows;
		if (n > f->full_cap - (read_next - out_next))
			n = f->full_cap - (read_next - out_next);
		low = level_low(f, 0, out_next);
		if (n > f->level[0].cap - (read_next - low))
			n = f->level[0].cap - (read_next - low);
		if (n) {
			if ((rc = read_rows(arg, f->block, n)) < 0)
				return rc;
			if ((rc = take_rows(f, read_next, n)) < 0)
				return rc;
			read_next += n;
			f->level[0].avail = read_next;
			progress += n;
		}
		/* Each pass as far as its band and the next level's room allowed
		 * before the step, all passes in one step: a row of pass p + 1
		 * reads only rows of level p + 1 made in earlier steps, so the
		 * passes' rows are independent tasks, and the threads wait for
		 * each other once a step, not once a pass (at 1920x1080 five
		 * passes of atrous kept two threads busy 79 % of the time
		 * a pass at a time). */
		f->task_start[0] = 0;
		for (p = 0; p < f->npasses; p++) {
			struct level *l = &f->level[p], *next = &f->level[p + 1];
			size_t r = f->radius[p], last, room;

			last = l->avail == f->nrows ? f->nrows : (l->avail > r ? l->avail - r : 0);
			room = next->cap - (next->avail - level_low(f, p + 1, out_next));
			if (last > l->done + room)
				last = l->done + room;
			if (last < l->done)
				last = l->done;
			f->step_y0[p] = l->done;
			f->task_start[p + 1] = f->task_start[p] + (last - l->done);
		}
		if (f->task_start[f->npasses]) {
			int t;

			for (t = 0; t < f->nthreads; t++)
				f->workers[t].bad_y = SIZE_MAX;
			rf__pool_run(f->pool, f->task_start[f->npasses], pass_row, f);
			if (rf__host_take_failure(f->host, f->p->name, f->error, sizeof(f->error)))
				return RF_EPLUGIN;
			if ((rc = pass_failure(f)) < 0)
				return rc;
			progress += f->task_start[f->npasses];
			for (p = 0; p < f->npasses; p++) {
				size_t made = f->task_start[p + 1] - f->task_start[p];

				f->level[p].done += made;
				f->level[p + 1].avail = f->level[p].done;
			}
		}
		/* The result rows done, with their input rows' other channels. */
		while (out_next < f->level[f->npasses].avail) {
			size_t m = f->level[f->npasses].avail - out_next, k, x, i;

			if (m > f->block_rows)
				m = f->block_rows;
			for (k = 0; k < m; k++) {
				const float *res = level_row(f, f->npasses, out_next + k);
				const float *row = full_row(f, out_next + k);
				float *o = f->block + k * f->ncols * f->out_ncomp;

				if (f->out_ncomp == f->ncomp) {
					memcpy(o, row, f->ncols * f->ncomp * sizeof(float));
				} else {
					for (x = 0; x < f->ncols; x++, row += f->ncomp)
						for (i = 0; i < f->out_ncomp; i++)
							o[x * f->out_ncomp + i] = row[f->out_col[i]];
				}
				for (x = 0; x < f->ncols; x++, o += f->out_ncomp)
					for (i = 0; i < f->nv; i++)
						o[f->out_value_col[i]] = res[(f->ng + i) * f->ncols + x];
			}
			if ((rc = write_rows(arg, f->block, m)) < 0)
				return rc;
			out_next += m;
			progress += m;
		}
		if (!progress) {
			rf__format(f->error, sizeof(f->error), "the bands stalled at row %zu "
			           "(a bug: please report it)", out_next);
			return RF_EINVAL;
		}
	}
	return 0;
}

uint32_t
rf_filter_passes(const rf_filter *f)
{
	return f->npasses;
}

size_t
rf_filter_reach(const rf_filter *f)
{
	size_t reach = 0;
	uint32_t i;

	for (i = 0; i < f->npasses; i++)
		reach += f->radius[i];
	return reach;
}

const char *
rf_filter_error(const rf_filter *f)
{
	return f->error;
}
