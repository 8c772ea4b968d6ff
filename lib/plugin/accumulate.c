/*
 * Running an accumulate mode over the frames of a stream (plugin.h: the
 * accumulate kind).  The accumulator owns each value's state between
 * frames, whole frames of it: what a mode combines over time has to be
 * kept for every pixel, so memory is the state (slots x values x pixels)
 * and, when the result is asked for at the end, the last frame's rows.
 * Rows are spread over the pool's threads, one instance of the mode on
 * each; a value's update depends on nothing but its own state and the
 * frame's count, so the bytes do not depend on the thread count.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "plugin/plugin-internal.h"
#include "util/pool.h"
#include "reflect/plugin.h"

struct worker {
	void *state;   /* the mode's instance */
	float *values; /* one row of the frame's values, gathered */
	/* The first bad value this worker met in the batch, by row. */
	size_t bad_row, bad_col;
	int bad_value;
	float bad;
	/* The first value whose state run() left broken, by row: out_row
	 * SIZE_MAX for none; out_slot 0 the value, 1 its variance. */
	size_t out_row, out_col, out_value;
	int out_slot;
	float out_bad;
};

struct rf_accumulator {
	const struct rf_plugin *p;
	struct rf__call_site site; /* for a crash report */
	const struct rf_host *host;
	int nthreads;
	struct worker *workers;
	struct rf__pool *pool;
	struct rf_accumulate_options o;
	char *channels, *reset; /* copies of the options' lists */
	size_t nslots, nvalues;
	int value_col[RF_CHANNELS_MAX]; /* stream channel of each value */
	int se_col[RF_CHANNELS_MAX];    /* its .se channel in the output, or -1 */
	rf_header *first;  /* frame 0's header: what every frame must match */
	rf_header *last;   /* the previous frame's, for the reset keys */
	rf_header *out_h;
	size_t ncols, nrows, in_ncomp, out_ncomp;
	size_t frames; /* begun so far */
	uint32_t count; /* frames in the state, this one included */
	uint64_t samples; /* their SAMPLES summed: the result's */
	float *state;   /* nrows x ncols x nvalues x nslots */
	float *kept;    /* the last frame's rows, output layout (keep) */
	/* The batch rf_accumulator_run or _result is running. */
	const float *in;
	float *out;
	size_t y;
	int result_only;
	char error[320];
};

static size_t
list_length(const char *const *list)
{
	size_t n = 0;

	while (list[n])
		n++;
	return n;
}

int
rf_accumulator_create(rf_accumulator **ap, const struct rf_plugin *p,
                      const double *values, const struct rf_host *host, int nthreads,
                      const struct rf_accumulate_options *o, char *err, size_t errlen)
{
	rf_accumulator *a;
	int i;

	*ap = NULL;
	if (nthreads < 1)
		nthreads = 1;
	if (nthreads > RF__THREADS_MAX)
		nthreads = RF__THREADS_MAX;
	if (p->kind != RF_KIND_ACCUMULATE) {
		rf__format(err, errlen, "mode '%s' is a %s mode, not an accumulate mode",
		           p->name, rf_plugin_kind_name(p->kind));
		return RF_EPLUGIN;
	}
	if (!(a = calloc(1, sizeof(*a))))
		return RF_ENOMEM;
	a->p = p;
	rf__call_site_init(&a->site, p);
	a->host = host;
	a->nthreads = nthreads;
	a->nslots = list_length(p->outputs);
	if (o)
		a->o = *o;
	if ((a->o.channels && !(a->channels = strdup(a->o.channels))) ||
	    (a->o.reset && !(a->reset = strdup(a->o.reset))) ||
	    !(a->workers = calloc((size_t)nthreads, sizeof(*a->workers))) ||
	    rf__pool_create(&a->pool, nthreads) < 0) {
		rf_accumulator_destroy(a);
		return RF_ENOMEM;
	}
	for (i = 0; i < nthreads; i++)
		if (rf__plugin_instance(p, &a->site, host, values, &a->workers[i].state, err,
		                        errlen) < 0) {
			rf_accumulator_destroy(a);
			return RF_EPLUGIN;
		}
	*ap = a;
	return 0;
}

void
rf_accumulator_destroy(rf_accumulator *a)
{
	int i;

	if (!a)
		return;
	rf__pool_destroy(a->pool);
	for (i = 0; a->workers && i < a->nthreads; i++) {
		if (a->workers[i].state)
			rf__plugin_destroy(a->p, &a->site, a->workers[i].state);
		free(a->workers[i].values);
	}
	free(a->workers);
	free(a->channels);
	free(a->reset);
	rf_header_destroy(a->first);
	rf_header_destroy(a->last);
	rf_header_destroy(a->out_h);
	free(a->state);
	free(a->kept);
	rf__call_site_fini(&a->site);
	free(a);
}

/* The first frame decides the values: --channels, or the default selection. */
static int
choose_values(rf_accumulator *a, const rf_header *in, char *err, size_t errlen)
{
	return rf__choose_values(in, a->channels, "accumulate", a->value_col, &a->nvalues, err,
	                         errlen);
}

/* Why frame `in` cannot join frame 0, or 0. */
static int
same_shape(const rf_accumulator *a, const rf_header *in, char *err, size_t errlen)
{
	const rf_header *f = a->first;
	size_t i, n = rf_header_nchannels(in), m = rf_header_nchannels(f);

	if (rf_header_ncols(in) != rf_header_ncols(f) || rf_header_nrows(in) != rf_header_nrows(f)) {
		rf__format(err, errlen, "frame %zu is %zux%zu, the first frame was %zux%zu: "
		           "frames accumulate pixel by pixel, so they must have one size",
		           a->frames + 1,
		           rf_header_ncols(in), rf_header_nrows(in), rf_header_ncols(f),
		           rf_header_nrows(f));
		return RF_EFORMAT;
	}
	for (i = 0; i < n && i < m; i++)
		if (strcmp(rf_header_channel(in, i), rf_header_channel(f, i)))
			break;
	if (i == n && n == m)
		return 0;
	if (i < n && i < m)
		rf__format(err, errlen, "frame %zu's channel %zu is '%s', the first frame's "
		           "was '%s': frames must have one channel list", a->frames + 1, i + 1,
		           rf_header_channel(in, i), rf_header_channel(f, i));
	else if (i < n)
		rf__format(err, errlen, "frame %zu has a channel the first frame had not "
		           "('%s'): frames must have one channel list", a->frames + 1,
		           rf_header_channel(in, i));
	else
		rf__format(err, errlen, "frame %zu lacks the first frame's channel '%s': "
		           "frames must have one channel list", a->frames + 1,
		           rf_header_channel(f, i));
	return RF_EFORMAT;
}

/* Has one of the reset keys changed since the previous frame? */
static int
reset_due(const rf_accumulator *a, const rf_header *in)
{
	char *list, *key, *save = NULL;
	int due = 0;

	if (!a->reset || !a->last || !(list = strdup(a->reset)))
		return 0;
	for (key = strtok_r(list, ", ", &save); key && !due; key = strtok_r(NULL, ", ", &save)) {
		const char *now = rf_header_get(in, key), *before = rf_header_get(a->last, key);

		due = (now == NULL) != (before == NULL) || (now && strcmp(now, before));
	}
	free(list);
	return due;
}

static int
first_frame(rf_accumulator *a, const rf_header *in, char *err, size_t errlen)
{
	size_t i, floats, pixels;
	int rc;

	if ((rc = choose_values(a, in, err, errlen)) < 0)
		return rc;
	a->ncols = rf_header_ncols(in);
	a->nrows = rf_header_nrows(in);
	a->in_ncomp = rf_header_nchannels(in);
	pixels = a->ncols * a->nrows;
	if (pixels && a->nvalues * a->nslots > SIZE_MAX / sizeof(float) / pixels) {
		rf__format(err, errlen, "the state of %zux%zu pixels of %zu values is more "
		           "than this machine can address", a->ncols, a->nrows, a->nvalues);
		return RF_ENOMEM;
	}
	floats = pixels * a->nvalues * a->nslots;
	if (!(a->state = malloc(floats ? floats * sizeof(float) : 1))) {
		rf__format(err, errlen, "out of memory for the state of %zux%zu pixels "
		           "(%zu MB)", a->ncols, a->nrows, floats * sizeof(float) >> 20);
		return RF_ENOMEM;
	}
	for (i = 0; i < (size_t)a->nthreads; i++)
		if (!(a->workers[i].values = malloc((a->ncols * a->nvalues + 1) * sizeof(float))))
			return RF_ENOMEM;
	return rf_header_dup(&a->first, in);
}

int
rf_accumulator_begin_frame(rf_accumulator *a, const rf_header *in, rf_header **out,
                           char *err, size_t errlen)
{
	char count[32];
	uint64_t samples;
	size_t i;
	int rc;

	if (!a->first)
		rc = first_frame(a, in, err, errlen);
	else
		rc = same_shape(a, in, err, errlen);
	if (rc < 0)
		return rc;
	/* The mode reads the key itself (header_get); what it reads is
	 * checked here, once, with a message for a person. */
	if (rf_header_samples(in, &samples) < 0) {
		rf__format(err, errlen, "frame %zu: header key %s='%s' is not a whole number "
		           "from 1 to %u (how many samples each value is the mean of)",
		           a->frames + 1, RF_KEY_SAMPLES, rf_header_get(in, RF_KEY_SAMPLES),
		           RF_SAMPLES_MAX);
		return RF_EFORMAT;
	}
	if (reset_due(a, in)) {
		a->count = 0;
		a->samples = 0;
	}
	if (a->count == UINT32_MAX) {
		rf__format(err, errlen, "frame %zu: more frames than an accumulator counts",
		           a->frames + 1);
		return RF_EINVAL;
	}
	a->count++;
	a->samples += samples; /* 2^32 frames of 2^32 samples at most: no overflow */
	rf_header_destroy(a->last);
	a->last = NULL;
	if ((rc = rf_header_dup(&a->last, in)) < 0)
		return rc;
	rf_header_destroy(a->out_h);
	a->out_h = NULL;
	if ((rc = rf_header_dup(&a->out_h, in)) < 0)
		return rc;
	for (i = 0; i < a->nvalues; i++) {
		char name[RF_CHANNEL_NAME_MAX + 8];
		int c;

		a->se_col[i] = -1;
		if (!a->o.stats)
			continue;
		snprintf(name, sizeof(name), "%s.se", rf_header_channel(in, (size_t)a->value_col[i]));
		if (strlen(name) > RF_CHANNEL_NAME_MAX) {
			rf__format(err, errlen, "channel '%s': its standard error's name '%s' "
			           "is longer than %d bytes", rf_header_channel(in,
			           (size_t)a->value_col[i]), name, RF_CHANNEL_NAME_MAX);
			return RF_ECHANNEL;
		}
		if ((c = rf_header_find_channel(a->out_h, name)) < 0 &&
		    (c = rf_header_add_channel(a->out_h, name)) < 0)
			return c;
		a->se_col[i] = c;
	}
	snprintf(count, sizeof(count), "%u", a->count);
	if ((rc = rf_header_set(a->out_h, RF_KEY_ACCUMULATED, count)) < 0)
		return rc;
	snprintf(count, sizeof(count), "%llu", (unsigned long long)a->samples);
	if ((rc = rf_header_set(a->out_h, RF_KEY_SAMPLES, count)) < 0)
		return rc;
	a->out_ncomp = rf_header_nchannels(a->out_h);
	if (a->o.keep && !a->kept &&
	    !(a->kept = malloc((a->ncols * a->nrows * a->out_ncomp + 1) * sizeof(float)))) {
		rf__format(err, errlen, "out of memory for the last frame (%zux%zu pixels)",
		           a->ncols, a->nrows);
		return RF_ENOMEM;
	}
	*out = a->out_h;
	a->frames++;
	return 0;
}

/* What run() left in a row's state: the value finite, its variance not
 * NaN and not negative (+inf: not known yet), as plugin.h has them, or
 * a mode's bug would be a silent wrong image.  One pass of adds, a
 * search only on a failure. */
static void
check_state_row(const rf_accumulator *a, struct worker *w, const float *state, size_t y)
{
	const size_t n = a->ncols * a->nvalues;
	float finite = 0.0f;
	int negative = 0;
	size_t k;

	for (k = 0; k < n; k++) {
		const float *s = state + k * a->nslots;

		finite += s[0] * 0.0f;
		negative |= !(s[1] >= 0.0f);
	}
	if ((finite == 0.0f && !negative) || y >= w->out_row)
		return;
	for (k = 0; k < n; k++) {
		const float *s = state + k * a->nslots;

		if (!isfinite(s[0]) || !(s[1] >= 0.0f)) {
			w->out_row = y;
			w->out_col = k / a->nvalues;
			w->out_value = k % a->nvalues;
			w->out_slot = isfinite(s[0]) ? 1 : 0;
			w->out_bad = s[w->out_slot];
			return;
		}
	}
}

/* One output row: the input row's channels (in_ncomp of every stride
 * floats), the values and their standard errors from the state. */
static void
emit_row(const rf_accumulator *a, const float *in, size_t stride, const float *state,
         float *out)
{
	size_t x, i;

	for (x = 0; x < a->ncols; x++, in += stride, out += a->out_ncomp) {
		const float *s = state + x * a->nvalues * a->nslots;

		memcpy(out, in, a->in_ncomp * sizeof(float));
		for (i = 0; i < a->nvalues; i++, s += a->nslots) {
			out[a->value_col[i]] = s[0];
			if (a->se_col[i] >= 0)
				out[a->se_col[i]] = sqrtf(s[1]);
		}
	}
}

static void
run_row(void *arg, size_t task, int thread)
{
	rf_accumulator *a = arg;
	struct worker *w = &a->workers[thread];
	size_t y = a->y + task, x, i;
	float *state = a->state + y * a->ncols * a->nvalues * a->nslots;
	const float *in = a->in ? a->in + task * a->ncols * a->in_ncomp : NULL;

	if (!a->result_only) {
		struct rf_span span;
		float *v = w->values;

		for (x = 0; x < a->ncols; x++)
			for (i = 0; i < a->nvalues; i++) {
				float f = in[x * a->in_ncomp + (size_t)a->value_col[i]];

				if (!isfinite(f) && (w->bad_value < 0 || y < w->bad_row)) {
					w->bad_row = y;
					w->bad_col = x;
					w->bad_value = (int)i;
					w->bad = f;
					f = 0.0f;
				}
				*v++ = f;
			}
		memset(&span, 0, sizeof(span));
		span.size = sizeof(span);
		span.npix = (uint32_t)a->ncols;
		span.y = (uint32_t)y;
		span.width = (uint32_t)a->ncols;
		span.height = (uint32_t)a->nrows;
		span.frame = (uint32_t)(a->frames - 1);
		span.in = w->values;
		span.out = state;
		span.nvalues = (uint32_t)a->nvalues;
		span.count = a->count;
		if (a->ncols) {
			rf__call_enter(&a->site, "run", a->frames, y, 1);
			a->p->run(w->state, &span);
			rf__call_leave();
			check_state_row(a, w, state, y);
		}
		if (a->kept) {
			float *k = a->kept + y * a->ncols * a->out_ncomp;

			for (x = 0; x < a->ncols; x++)
				memcpy(k + x * a->out_ncomp, in + x * a->in_ncomp,
				       a->in_ncomp * sizeof(float));
		}
		if (a->out)
			emit_row(a, in, a->in_ncomp, state, a->out + task * a->ncols * a->out_ncomp);
	} else {
		float *k = a->kept + y * a->ncols * a->out_ncomp;

		emit_row(a, k, a->out_ncomp, state, a->out + task * a->ncols * a->out_ncomp);
	}
}

static int
run_rows(rf_accumulator *a, const float *in, float *out, size_t y, size_t nrows,
         int result_only)
{
	size_t i, best = SIZE_MAX;
	int wb = -1;

	if (!a->first || y > a->nrows || nrows > a->nrows - y)
		return RF_EINVAL;
	a->in = in;
	a->out = out;
	a->y = y;
	a->result_only = result_only;
	a->error[0] = '\0';
	for (i = 0; i < (size_t)a->nthreads; i++) {
		a->workers[i].bad_value = -1;
		a->workers[i].out_row = SIZE_MAX;
	}
	rf__pool_run(a->pool, nrows, run_row, a);
	if (rf__host_take_failure(a->host, a->p->name, a->error, sizeof(a->error)))
		return RF_EPLUGIN;
	for (i = 0; i < (size_t)a->nthreads; i++) {
		const struct worker *w = &a->workers[i];

		if (w->bad_value >= 0 && w->bad_row < best) {
			best = w->bad_row;
			wb = (int)i;
		}
	}
	if (wb >= 0) {
		const struct worker *w = &a->workers[wb];

		rf__format(a->error, sizeof(a->error), "row %zu, pixel %zu: channel '%s' is "
		           "%s", w->bad_row + 1, w->bad_col + 1,
		           rf_header_channel(a->first, (size_t)a->value_col[w->bad_value]),
		           isnan(w->bad) ? "nan" : w->bad > 0 ? "inf" : "-inf");
		return RF_EINVAL;
	}
	for (i = 0; i < (size_t)a->nthreads; i++) {
		const struct worker *w = &a->workers[i];

		if (w->out_row != SIZE_MAX && (wb < 0 || w->out_row < best)) {
			best = w->out_row;
			wb = (int)i;
		}
	}
	if (wb >= 0) {
		const struct worker *w = &a->workers[wb];
		const float v = w->out_bad;

		rf__format(a->error, sizeof(a->error), "row %zu, pixel %zu: mode '%s' broke "
		           "its output contract: the %s of channel '%s' is %s", w->out_row + 1,
		           w->out_col + 1, a->p->name, w->out_slot ? "variance" : "value",
		           rf_header_channel(a->first, (size_t)a->value_col[w->out_value]),
		           isnan(v) ? "nan" : isinf(v) ? (v > 0 ? "inf" : "-inf") : "negative");
		return RF_EINVAL;
	}
	return 0;
}

int
rf_accumulator_run(rf_accumulator *a, const float *in, float *out, size_t y, size_t nrows)
{
	if (!in)
		return RF_EINVAL;
	return run_rows(a, in, out, y, nrows, 0);
}

int
rf_accumulator_result(rf_accumulator *a, float *out, size_t y, size_t nrows)
{
	if (!a->kept || !out)
		return RF_EINVAL;
	return run_rows(a, NULL, out, y, nrows, 1);
}

size_t
rf_accumulator_count(const rf_accumulator *a)
{
	return a->count;
}

const char *
rf_accumulator_error(const rf_accumulator *a)
{
	return a->error;
}
