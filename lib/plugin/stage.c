/* Running a per-pixel plugin over blocks of rows, on several threads. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plugin/plugin-internal.h"
#include "probe/probe-internal.h"
#include "util/invalid.h"
#include "util/pixels.h"
#include "util/pool.h"
#include "reflect/plugin.h"

/* What each thread has of its own. */
struct worker {
	void *state;    /* the plugin's instance */
	float *gather;  /* one row of the plugin's inputs */
	float *scatter; /* one row of the plugin's outputs */
	unsigned char *zero; /* pixels of the row written as 0 */
	/* Invalid input the worker met in the block: how many pixels were
	 * fixed, and the first under RF_INVALID_ERROR. */
	size_t fixed, fixed_out;
	struct rf__first_invalid first;
};

struct rf_stage {
	const struct rf_plugin *p;
	struct rf__call_site site; /* for a crash report */
	const struct rf_host *host; /* for a run() that failed (fail()) */
	int distant; /* a projection without parallax (rf__host_take_distant) */
	int nthreads;
	struct worker *workers;
	size_t nin, nout;
	size_t nrequired;      /* inputs; nin adds the optional ones */
	const char **in_names; /* nin: every input, "" for an absent optional one */
	size_t *absent, nabsent; /* the optional inputs the stream lacks */
	int *in_map, *out_map; /* plugin channel -> stream channel, -1 absent */
	/* The same maps as runs of adjacent channels, copied as blocks. */
	struct rf__run *in_runs, *out_runs;
	size_t nin_runs, nout_runs;
	rf_header *out_h;
	size_t ncols, nrows, in_ncomp, out_ncomp, row_cap;
	/* A tile's place in its full frame (REGION): the modes see the full
	 * frame's pixel positions and size, so a tile's pixels are the full
	 * frame's, noise seeds and camera rays alike. */
	struct rf_region region;
	uint32_t frame;
	size_t frames;
	struct rf__pool *pool;
	/* The block rf_stage_run is running. */
	const float *block_in;
	float *block_out;
	size_t block_y;
	enum rf_invalid invalid;
	struct rf__check check; /* on the plugin's inputs, as gathered */
	struct rf__check out_check; /* on its outputs, as it wrote them */
	int mask_col;           /* the stream's mask, or -1 */
	int skip_walls;         /* run() only between walls (rf__stage_skip_walls) */
	/* An occlusion mode's factor: its output column, the input's own
	 * occlusion (-1: none) and the channels it multiplies, named. */
	int occ_col, occ_prev, occ_targets[6], nocc_targets;
	const char *occ_names[6];
	/* Inputs given one value for every pixel (rf_stage_set_input_value). */
	size_t nfixed, fixed_at[4];
	float fixed_value[4];
	size_t fixed;           /* pixels of the frame clamped or zeroed */
	size_t fixed_out;       /* those for the plugin's outputs */
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

/* A plugin's message as one line: terminated even when the plugin filled
 * the whole buffer, control characters (newlines) made spaces. */
static void
one_line(char *msg, size_t size)
{
	char *c;

	msg[size - 1] = '\0';
	for (c = msg; *c; c++)
		if ((unsigned char)*c < 0x20 || *c == 0x7f)
			*c = ' ';
}

int
rf__plugin_instance(const struct rf_plugin *p, const struct rf__call_site *site,
                    const struct rf_host *host, const double *values, void **state,
                    char *err, size_t errlen)
{
	char msg[400] = "";
	int failed;

	*state = NULL;
	if (!(host = rf__host_for_plugin(host, p, err, errlen)))
		return RF_EPLUGIN;
	rf__call_enter(site, "create", 0, 0, 0);
	failed = p->create(host, values, state, msg, sizeof(msg));
	rf__call_leave();
	if (failed) {
		one_line(msg, sizeof(msg));
		rf__format(err, errlen, "mode '%s': %s", p->name,
		           *msg ? msg : "cannot create an instance");
		*state = NULL;
		return RF_EPLUGIN;
	}
	return 0;
}

void
rf__plugin_destroy(const struct rf_plugin *p, const struct rf__call_site *site, void *state)
{
	rf__call_enter(site, "destroy", 0, 0, 0);
	p->destroy(state);
	rf__call_leave();
}

/* Whether mode p reads the surface's position, which parallax needs. */
static int
reads_position(const struct rf_plugin *p)
{
	const char *const *lists[2] = { p->inputs, rf_plugin_optional_inputs(p) };
	size_t k, i;

	for (k = 0; k < 2; k++)
		for (i = 0; lists[k] && lists[k][i]; i++)
			if (!strncmp(lists[k][i], "P.", 2))
				return 1;
	return 0;
}

int
rf_stage_create(rf_stage **sp, const struct rf_plugin *p, const double *values,
                const struct rf_host *host, int nthreads, char *err, size_t errlen)
{
	rf_stage *s;
	int i;

	*sp = NULL;
	if (nthreads < 1)
		nthreads = 1;
	if (nthreads > RF__THREADS_MAX)
		nthreads = RF__THREADS_MAX;
	if (!(s = calloc(1, sizeof(*s))))
		return RF_ENOMEM;
	s->p = p;
	rf__call_site_init(&s->site, p);
	s->host = host;
	s->nthreads = nthreads;
	s->nrequired = list_length(p->inputs);
	s->nin = s->nrequired + (rf_plugin_optional_inputs(p)
	                             ? list_length(rf_plugin_optional_inputs(p)) : 0);
	s->nout = list_length(p->outputs);
	s->in_names = calloc(s->nin + 1, sizeof(*s->in_names));
	s->absent = calloc(s->nin + 1, sizeof(*s->absent));
	s->in_map = calloc(s->nin + 1, sizeof(int));
	s->out_map = calloc(s->nout + 1, sizeof(int));
	s->in_runs = calloc(s->nin + 1, sizeof(struct rf__run));
	s->out_runs = calloc(s->nout + 1, sizeof(struct rf__run));
	s->workers = calloc((size_t)nthreads, sizeof(struct worker));
	if (!s->in_names || !s->absent || !s->in_map || !s->out_map || !s->in_runs ||
	    !s->out_runs || !s->workers ||
	    rf__pool_create(&s->pool, nthreads) < 0) {
		rf_stage_destroy(s);
		return RF_ENOMEM;
	}
	for (i = 0; i < nthreads; i++)
		if (rf__plugin_instance(p, &s->site, host, values, &s->workers[i].state, err,
		                        errlen) < 0) {
			rf_stage_destroy(s);
			return RF_EPLUGIN;
		}
	if (p->kind == RF_KIND_PROJECTION && !reads_position(p)) {
		s->distant = 1;
		rf__host_take_distant(host);
	}
	*sp = s;
	return 0;
}

void
rf_stage_destroy(rf_stage *s)
{
	int i;

	if (!s)
		return;
	rf__pool_destroy(s->pool);
	for (i = 0; s->workers && i < s->nthreads; i++) {
		if (s->workers[i].state)
			rf__plugin_destroy(s->p, &s->site, s->workers[i].state);
		free(s->workers[i].gather);
		free(s->workers[i].scatter);
		free(s->workers[i].zero);
	}
	free(s->workers);
	free(s->in_names);
	free(s->absent);
	free(s->in_map);
	free(s->out_map);
	free(s->in_runs);
	free(s->out_runs);
	rf_header_destroy(s->out_h);
	rf__call_site_fini(&s->site);
	free(s);
}

static int
frame_number(const rf_header *h, size_t fallback, uint32_t *out)
{
	const char *v = rf_header_get(h, "FRAME");
	unsigned long n;
	char *end;

	if (!v) {
		*out = (uint32_t)fallback;
		return 0;
	}
	errno = 0;
	n = strtoul(v, &end, 10);
	if (end == v || *end || errno || n > UINT32_MAX)
		return -1;
	*out = (uint32_t)n;
	return 0;
}

/* The runs of the inputs the stream has: absent optional ones are no
 * part of any run (they read as NaN). */
static size_t
gather_runs(rf_stage *s)
{
	int map[RF_CHANNELS_MAX];
	size_t slot[RF_CHANNELS_MAX], i, n = 0, k, r;

	for (i = 0; i < s->nin && n < RF_CHANNELS_MAX; i++)
		if (s->in_map[i] >= 0) {
			map[n] = s->in_map[i];
			slot[n++] = i;
		}
	if (n == s->nin)
		return rf__channel_runs(s->in_map, s->nin, 0, s->in_runs);
	/* With gaps, one run per input: simple, and only for such streams. */
	for (k = 0, r = 0; k < n; k++, r++) {
		s->in_runs[r].src = (unsigned)map[k];
		s->in_runs[r].dst = (unsigned)slot[k];
		s->in_runs[r].len = 1;
	}
	return r;
}

int
rf_stage_begin_frame(rf_stage *s, const rf_header *in, rf_header **out,
                     char *err, size_t errlen)
{
	size_t i;
	int c, t;

	*out = NULL;
	/* a frame may bring a probe that an old mode cannot see */
	if (!rf__host_for_plugin(s->host, s->p, err, errlen))
		return RF_EPLUGIN;
	rf_header_destroy(s->out_h);
	if (rf_header_dup(&s->out_h, in) < 0)
		return RF_ENOMEM;
	/* every probe's, not the first's only: the blend after it takes
	 * each probe's key for its own */
	if (s->distant && (c = rf__header_probes_distant(s->out_h)) < 0) {
		rf__format(err, errlen, "cannot turn the probes' box projection off: %s",
		           rf_strerror(c));
		return c;
	}
	s->nabsent = 0;
	for (i = s->nrequired; i < s->nin; i++) {
		const char *name = rf_plugin_optional_inputs(s->p)[i - s->nrequired];

		s->in_map[i] = rf_header_find_channel(in, name);
		s->in_names[i] = s->in_map[i] >= 0 ? name : "";
		if (s->in_map[i] < 0)
			s->absent[s->nabsent++] = i;
	}
	for (i = 0; i < s->nrequired; i++) {
		s->in_names[i] = s->p->inputs[i];
		if ((c = rf_header_find_channel(in, s->p->inputs[i])) < 0) {
			char list[512] = "";
			size_t k = 0, j;

			for (j = 0; j < s->nrequired && k + 2 < sizeof(list); j++)
				k += (size_t)snprintf(list + k, sizeof(list) - k, "%s%s",
				                      j ? " " : "", s->p->inputs[j]);
			rf__format(err, errlen, "input has no channel '%s' (mode '%s' "
			           "reads %s)", s->p->inputs[i], s->p->name, list);
			return RF_ECHANNEL;
		}
		s->in_map[i] = c;
	}
	for (i = 0; i < s->nout; i++) {
		if ((c = rf_header_find_channel(s->out_h, s->p->outputs[i])) < 0 &&
		    (c = rf_header_add_channel(s->out_h, s->p->outputs[i])) < 0) {
			rf__format(err, errlen, "cannot add channel '%s': %s",
			           s->p->outputs[i], rf_strerror(c));
			return c;
		}
		s->out_map[i] = c;
	}
	rf__check_plan(&s->check, s->in_names, s->nin);
	rf__check_plan_outputs(&s->out_check, s->p->outputs, s->nout);
	s->mask_col = rf_header_find_channel(in, "mask");
	s->nocc_targets = 0;
	s->occ_col = s->occ_prev = -1;
	if (s->p->kind == RF_KIND_OCCLUSION) {
		static const char *const targets[] = { RF_SHADE_SPEC_R, RF_SHADE_SPEC_G,
		                                       RF_SHADE_SPEC_B, "R", "G", "B" };

		s->occ_col = rf_header_find_channel(s->out_h, RF_OCCLUSION);
		s->occ_prev = rf_header_find_channel(in, RF_OCCLUSION);
		for (i = 0; i < 6; i++)
			if ((c = rf_header_find_channel(in, targets[i])) >= 0) {
				s->occ_names[s->nocc_targets] = targets[i];
				s->occ_targets[s->nocc_targets++] = c;
			} else if (i < 3) {
				rf__format(err, errlen, "input has no channel '%s': occlusion "
				           "darkens a shaded reflection; run reflect-shade first",
				           targets[i]);
				return RF_ECHANNEL;
			}
	}
	s->fixed = s->fixed_out = 0;
	s->error[0] = '\0';
	s->nin_runs = gather_runs(s);
	s->nout_runs = rf__channel_runs(s->out_map, s->nout, 1, s->out_runs);
	if (frame_number(in, s->frames, &s->frame) < 0) {
		rf__format(err, errlen, "FRAME='%s' is not a frame number",
		           rf_header_get(in, "FRAME"));
		return RF_EFORMAT;
	}
	if (rf_header_region(in, &s->region) < 0) {
		rf__format(err, errlen, RF_KEY_REGION "='%s' is not X0 Y0 WIDTH HEIGHT of a "
		           "full frame that holds this one", rf_header_get(in, RF_KEY_REGION));
		return RF_EFORMAT;
	}
	s->frames++;
	s->ncols = rf_header_ncols(in);
	s->nrows = rf_header_nrows(in);
	s->in_ncomp = rf_header_nchannels(in);
	s->out_ncomp = rf_header_nchannels(s->out_h);
	if (s->ncols * s->out_ncomp * sizeof(float) > RF_ROW_BYTES_MAX) {
		rf__format(err, errlen, "output rows of %zu channels are too large",
		           s->out_ncomp);
		return RF_ETOOBIG;
	}
	if (s->ncols > s->row_cap) {
		for (t = 0; t < s->nthreads; t++) {
			struct worker *w = &s->workers[t];

			free(w->gather);
			free(w->scatter);
			free(w->zero);
			w->gather = malloc(s->ncols * (s->nin + 1) * sizeof(float));
			w->scatter = malloc(s->ncols * s->nout * sizeof(float));
			w->zero = malloc(s->ncols);
			if (!w->gather || !w->scatter || !w->zero) {
				s->row_cap = 0;
				return RF_ENOMEM;
			}
		}
		s->row_cap = s->ncols;
	}
	*out = s->out_h;
	return 0;
}

int
rf_stage_reserve_channel(rf_stage *s, const char *name)
{
	int c;

	if (!s->out_h)
		return RF_EINVAL;
	if ((c = rf_header_find_channel(s->out_h, name)) >= 0)
		return c;
	if ((c = rf_header_add_channel(s->out_h, name)) < 0)
		return c;
	s->out_ncomp = rf_header_nchannels(s->out_h);
	if (s->ncols * s->out_ncomp * sizeof(float) > RF_ROW_BYTES_MAX)
		return RF_ETOOBIG;
	return c;
}

/* The gathered row's pixels checked, clamped, or marked in w->zero;
 * whether any is to be written as 0. */
static int
check_row(rf_stage *s, struct worker *w, const float *in, size_t y)
{
	size_t x;
	int any = 0, r;

	if (rf__check_row(&s->check, w->gather, s->nin, s->ncols))
		return 0;
	for (x = 0; x < s->ncols; x++) {
		int wall = s->mask_col >= 0 && in[x * s->in_ncomp + (size_t)s->mask_col] == 0.0f;
		char why[200];

		r = rf__check_pixel(&s->check, w->gather + x * s->nin, wall, s->invalid, why,
		                    sizeof(why));
		w->zero[x] = r == 2;
		any |= r == 2;
		if (r > 0)
			w->fixed++;
		if (r < 0)
			rf__first_invalid_keep(&w->first, y * s->ncols + x, "%s", why);
	}
	return any;
}

/*
 * What the plugin wrote, checked as its inputs are (rf__check_plan_outputs
 * says the rules): a mode's bug is never a silent wrong image.  The row
 * is tested in one pass first (a few adds a value), pixel by pixel only
 * when something broke a rule.  Walls (mask 0) reflect nothing and the
 * pass does not read what a mode wrote there; pixels already zeroed for
 * their input are left so.  Whether any pixel is now to be zeroed.
 */
static int
check_outputs(rf_stage *s, struct worker *w, const float *in, size_t y, int zeroed)
{
	size_t x;
	int any = 0, r;

	if (!zeroed)
		memset(w->zero, 0, s->ncols);
	for (x = 0; x < s->ncols; x++) {
		char why[200];

		if (w->zero[x] ||
		    (s->mask_col >= 0 && in[x * s->in_ncomp + (size_t)s->mask_col] == 0.0f))
			continue;
		r = rf__check_pixel(&s->out_check, w->scatter + x * s->nout, 0, s->invalid, why,
		                    sizeof(why));
		w->zero[x] = r == 2;
		any |= r == 2;
		if (r > 0)
			w->fixed_out++;
		if (r < 0)
			rf__first_invalid_keep(&w->first, y * s->ncols + x, "mode '%s' broke its "
			                       "output contract: %s", s->p->name, why);
	}
	return zeroed | any;
}

void
rf__stage_block_begin(rf_stage *s)
{
	int t;

	for (t = 0; t < s->nthreads; t++) {
		s->workers[t].fixed = s->workers[t].fixed_out = 0;
		rf__first_invalid_clear(&s->workers[t].first);
	}
}

int
rf__stage_block_end(rf_stage *s)
{
	int t;

	for (t = 0; t < s->nthreads; t++) {
		s->fixed += s->workers[t].fixed;
		s->fixed_out += s->workers[t].fixed_out;
	}
	if (rf__host_take_failure(s->host, s->p->name, s->error, sizeof(s->error)))
		return RF_EPLUGIN;
	return rf__first_invalid_report(&s->workers[0].first, (size_t)s->nthreads,
	                                sizeof(struct worker), s->ncols, s->error,
	                                sizeof(s->error));
}

int
rf_stage_set_input_value(rf_stage *s, const char *name, float value)
{
	const char *const *opt = rf_plugin_optional_inputs(s->p);
	size_t i, k;

	if (!name) {
		s->nfixed = 0;
		return 0;
	}
	for (i = 0; i < s->nin; i++) {
		const char *in = i < s->nrequired ? s->p->inputs[i] : opt[i - s->nrequired];

		if (strcmp(in, name))
			continue;
		for (k = 0; k < s->nfixed && s->fixed_at[k] != i; k++)
			;
		if (k == s->nfixed) {
			if (s->nfixed == sizeof(s->fixed_at) / sizeof(s->fixed_at[0]))
				return RF_ETOOBIG;
			s->nfixed++;
		}
		s->fixed_at[k] = i;
		s->fixed_value[k] = value;
		return 0;
	}
	return RF_ENOTFOUND;
}

void
rf_stage_set_invalid(rf_stage *s, enum rf_invalid policy)
{
	s->invalid = policy;
}

const char *
rf_stage_error(const rf_stage *s)
{
	return s->error;
}

size_t
rf_stage_invalid_count(const rf_stage *s)
{
	return s->fixed;
}

size_t
rf_stage_invalid_output_count(const rf_stage *s)
{
	return s->fixed_out;
}

/* Whether the reflection pixel po darkens, and the occlusion prev it
 * had, keep the rules (finite; in [0, 1]): 0, or -1 with why, or (not
 * under ERROR) 1 after clamping them (CLAMP) or zeroing the pixel's
 * outputs (ZERO). */
static int
occlusion_inputs(const rf_stage *s, float *po, float *prev, char *why, size_t len)
{
	int k, bad = !(*prev >= 0.0f && *prev <= 1.0f);

	for (k = 0; k < s->nocc_targets && !bad; k++)
		bad = !isfinite(po[s->occ_targets[k]]);
	if (!bad)
		return 0;
	if (s->invalid == RF_INVALID_ERROR) {
		if (!(*prev >= 0.0f && *prev <= 1.0f))
			snprintf(why, len, "channel '%s' is %g, outside [0, 1]", RF_OCCLUSION,
			         (double)*prev);
		else
			snprintf(why, len, "channel '%s' is %g", s->occ_names[k - 1],
			         (double)po[s->occ_targets[k - 1]]);
		return -1;
	}
	for (k = 0; k < s->nocc_targets; k++) {
		float *v = &po[s->occ_targets[k]];

		if (s->invalid == RF_INVALID_ZERO || *v != *v)
			*v = 0.0f;
		else if (!isfinite(*v))
			*v = *v > 0.0f ? FLT_MAX : -FLT_MAX;
	}
	*prev = *prev > 0.0f ? (*prev < 1.0f ? *prev : 1.0f) : 0.0f;
	if (s->invalid == RF_INVALID_ZERO)
		po[s->occ_col] = *prev = 0.0f;
	return 1;
}

/* An occlusion mode's factor on the reflection: the channels it darkens
 * (in place: their columns are the input's, widened), and the product
 * with the input's own occlusion; those inputs held to the rules as the
 * plugin's are (a NaN spec went through as NaN). */
static void
apply_occlusion(const rf_stage *s, struct worker *w, const float *in, float *out, size_t y)
{
	char why[200];
	size_t x;
	int k, r;

	for (x = 0; x < s->ncols; x++) {
		float *po = out + x * s->out_ncomp, f = po[s->occ_col];
		float prev = s->occ_prev >= 0 ? in[x * s->in_ncomp + (size_t)s->occ_prev] : 1.0f;

		if ((r = occlusion_inputs(s, po, &prev, why, sizeof(why))) < 0)
			rf__first_invalid_keep(&w->first, y * s->ncols + x, "%s", why);
		else if (r > 0)
			w->fixed++;
		f = po[s->occ_col];
		for (k = 0; k < s->nocc_targets; k++)
			po[s->occ_targets[k]] *= f;
		if (s->occ_prev >= 0)
			po[s->occ_col] = f * prev;
	}
}

void
rf__stage_skip_walls(rf_stage *s, const char *const *names)
{
	size_t i, k;

	s->skip_walls = 0;
	if (s->mask_col < 0 || s->occ_col >= 0)
		return;
	for (i = 0; i < s->nout; i++) {
		for (k = 0; names[k] && strcmp(names[k], s->p->outputs[i]); k++)
			;
		if (!names[k])
			return;
	}
	s->skip_walls = 1;
}

/* run() over the row's runs of pixels that are not walls (mask 0): a
 * wall's outputs are written 0.  Walls are half the default scene's
 * pixels, and a ray-traced mode's time is its pixels'. */
static void
run_between_walls(rf_stage *s, struct worker *w, struct rf_span *span, const float *in,
                  size_t y)
{
	const size_t nc = s->in_ncomp, mc = (size_t)s->mask_col;
	size_t x = 0, x0;

	while (x < s->ncols) {
		for (; x < s->ncols && in[x * nc + mc] == 0.0f; x++)
			memset(w->scatter + x * s->nout, 0, s->nout * sizeof(float));
		for (x0 = x; x < s->ncols && in[x * nc + mc] != 0.0f; x++)
			;
		if (x == x0)
			break;
		span->npix = (uint32_t)(x - x0);
		span->x = (uint32_t)(s->region.x0 + x0);
		span->in = w->gather + x0 * s->nin;
		span->out = w->scatter + x0 * s->nout;
		rf__call_enter(&s->site, "run", s->frames, y, 1);
		s->p->run(w->state, span);
		rf__call_leave();
	}
}

/* One row (row y of the frame) on thread `thread`: its input passed
 * through, the plugin's inputs gathered, run, its outputs scattered. */
void
rf__stage_row(rf_stage *s, const float *in, float *out, size_t y, int thread)
{
	struct worker *w = &s->workers[thread];
	struct rf_span span;
	size_t x, i;
	int zeroed;

	memset(&span, 0, sizeof(span));
	span.size = sizeof(span);
	span.width = (uint32_t)s->region.width;
	span.height = (uint32_t)s->region.height;
	span.frame = s->frame;
	span.npix = (uint32_t)s->ncols;
	span.in = w->gather;
	span.out = w->scatter;
	span.x = (uint32_t)s->region.x0;
	span.y = (uint32_t)(s->region.y0 + y);
	rf__widen_pixels(out, s->out_ncomp, in, s->in_ncomp, s->ncols);
	for (x = 0; x < s->ncols; x++) {
		const float *pi = in + x * s->in_ncomp;
		float *g = w->gather + x * s->nin;

		for (i = 0; i < s->nin_runs; i++)
			rf__copy_run(g + s->in_runs[i].dst, pi + s->in_runs[i].src,
			             s->in_runs[i].len);
		for (i = 0; i < s->nabsent; i++)
			g[s->absent[i]] = NAN;
		for (i = 0; i < s->nfixed; i++)
			g[s->fixed_at[i]] = s->fixed_value[i];
	}
	zeroed = s->check.n ? check_row(s, w, in, y) : 0;
	if (s->skip_walls) {
		run_between_walls(s, w, &span, in, y);
	} else {
		rf__call_enter(&s->site, "run", s->frames, y, 1);
		s->p->run(w->state, &span);
		rf__call_leave();
	}
	if (s->out_check.n && !rf__check_row(&s->out_check, w->scatter, s->nout, s->ncols))
		zeroed = check_outputs(s, w, in, y, zeroed);
	for (x = 0; x < s->ncols; x++) {
		float *po = out + x * s->out_ncomp;
		const float *q = w->scatter + x * s->nout;

		if (zeroed && w->zero[x])
			memset(w->scatter + x * s->nout, 0, s->nout * sizeof(float));
		for (i = 0; i < s->nout_runs; i++)
			rf__copy_run(po + s->out_runs[i].dst, q + s->out_runs[i].src,
			             s->out_runs[i].len);
	}
	if (s->occ_col >= 0)
		apply_occlusion(s, w, in, out, y);
}

int
rf__stage_threads(const rf_stage *s)
{
	return s->nthreads;
}

int
rf__stage_ready(const rf_stage *s, size_t y, size_t nrows, size_t *in_ncomp,
                size_t *out_ncomp)
{
	if (!s->out_h || y + nrows > s->nrows || y + nrows < y)
		return RF_EINVAL;
	*in_ncomp = s->in_ncomp;
	*out_ncomp = s->out_ncomp;
	return 0;
}

static void
run_row(void *arg, size_t r, int thread)
{
	rf_stage *s = arg;

	rf__stage_row(s, s->block_in + r * s->ncols * s->in_ncomp,
	              s->block_out + r * s->ncols * s->out_ncomp, s->block_y + r, thread);
}

int
rf_stage_run(rf_stage *s, const float *in, float *out, size_t y, size_t nrows)
{
	size_t in_ncomp, out_ncomp;
	int rc;

	if ((rc = rf__stage_ready(s, y, nrows, &in_ncomp, &out_ncomp)) < 0)
		return rc;
	s->block_in = in;
	s->block_out = out;
	s->block_y = y;
	rf__stage_block_begin(s);
	/* A row is a task: threads that start late or run slow take fewer. */
	rf__pool_run(s->pool, nrows, run_row, s);
	return rf__stage_block_end(s);
}
