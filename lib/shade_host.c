/* The sampling pass of reflect-shade: effective roughness -> lod -> the
 * environment, per row, on several threads. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "pixels.h"
#include "pool.h"
#include "pyramid.h"
#include "reflect/shading.h"

#define THREADS_MAX 256

/* Input channels; -1 when absent (only the optional ones may be). */
enum {
	IN_REFF, IN_DX, IN_DY, IN_DZ, /* always */
	IN_MASK, IN_PX, IN_PY, IN_PZ, /* walls */
	IN_ROUGH, IN_NX, IN_NY, IN_NZ, IN_VX, IN_VY, IN_VZ, /* --final */
	IN_METAL, IN_AR, IN_AG, IN_AB, /* --final, optional */
	IN_SR, IN_SG, IN_SB, /* radiance a mode wrote itself */
	IN_COUNT
};

static const char *const in_names[IN_COUNT] = {
	RF_SHADE_ROUGHNESS, "D.X", "D.Y", "D.Z",
	"mask", "P.X", "P.Y", "P.Z",
	"roughness", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z",
	"metallic", "albedo.R", "albedo.G", "albedo.B",
	"spec.R", "spec.G", "spec.B"
};

enum { OUT_SR, OUT_SG, OUT_SB, OUT_R, OUT_G, OUT_B, OUT_COUNT };

static const char *const out_names[OUT_COUNT] = {
	"spec.R", "spec.G", "spec.B", "R", "G", "B"
};

struct rf_shade {
	int final, nthreads, mode_radiance;
	int in[IN_COUNT];
	int out[OUT_COUNT];
	size_t nout;
	float center[3];
	rf_header *out_h;
	size_t ncols, in_ncomp, out_ncomp;
	const rf_cubemap *env;
	/* The same levels as RGBA vectors: one aligned load a texel, the
	 * prefilter's fast sampler; the pass spends most of its time here. */
	struct rf__pyramid pyramid;
	enum rf_mapping mapping;
	float steps;
	struct rf__pool *pool;
	/* The block rf_shade_run is running, and the stage before the pass
	 * when rf_shade_run_stage runs both. */
	const float *block_in;
	float *block_out;
	rf_stage *stage;
	size_t block_y, stage_in_ncomp;
};

int
rf_shade_create(rf_shade **sp, const struct rf_shade_options *o)
{
	rf_shade *s;

	*sp = NULL;
	if (!(s = calloc(1, sizeof(*s))))
		return RF_ENOMEM;
	s->final = o && o->final;
	s->mode_radiance = o && o->mode_radiance;
	s->nthreads = o && o->nthreads > 1 ? o->nthreads : 1;
	if (s->nthreads > THREADS_MAX)
		s->nthreads = THREADS_MAX;
	s->nout = s->final ? OUT_COUNT : OUT_R;
	if (rf__pool_new(&s->pool, s->nthreads) < 0) {
		free(s);
		return RF_ENOMEM;
	}
	*sp = s;
	return 0;
}

void
rf_shade_destroy(rf_shade *s)
{
	if (!s)
		return;
	rf__pool_free(s->pool);
	rf_header_free(s->out_h);
	rf__pyramid_free(&s->pyramid);
	free(s);
}

int
rf_shade_set_environment(rf_shade *s, const rf_cubemap *env, enum rf_mapping mapping,
                         float steps)
{
	int rc;

	rf__pyramid_free(&s->pyramid);
	s->env = NULL;
	if ((rc = rf__pyramid_from_cube(&s->pyramid, env)) < 0)
		return rc;
	s->env = env;
	s->mapping = mapping;
	s->steps = steps;
	return 0;
}

/* Finds channels first..last; why names what needs them. */
static int
require(rf_shade *s, const rf_header *h, int first, int last, const char *why,
        char *err, size_t errlen)
{
	int i;

	for (i = first; i <= last; i++)
		if ((s->in[i] = rf_header_find_channel(h, in_names[i])) < 0) {
			rf__format(err, errlen, "input has no channel '%s' (%s)",
			           in_names[i], why);
			return RF_ECHANNEL;
		}
	return 0;
}

int
rf_shade_begin_frame(rf_shade *s, const rf_header *in, const float center[3],
                     rf_header **out, char *err, size_t errlen)
{
	size_t i;
	int c, rc;

	*out = NULL;
	for (i = 0; i < IN_COUNT; i++)
		s->in[i] = rf_header_find_channel(in, in_names[i]);
	if (s->mode_radiance) {
		if ((rc = require(s, in, IN_SR, IN_SB, "the radiance the shade mode "
		                  "writes", err, errlen)) < 0)
			return rc;
	} else if ((rc = require(s, in, IN_REFF, IN_REFF, "the effective "
	                         "roughness a shade mode writes", err, errlen)) < 0 ||
	           (rc = require(s, in, IN_DX, IN_DZ, "the lookup direction that "
	                         "reflect-project writes", err, errlen)) < 0) {
		return rc;
	}
	if (s->in[IN_MASK] >= 0) {
		if ((rc = require(s, in, IN_PX, IN_PZ, "pixels with mask 0 show the "
		                  "environment seen from the probe centre toward P",
		                  err, errlen)) < 0)
			return rc;
		if (!center) {
			rf__format(err, errlen, "pixels with mask 0 show the environment "
			           "seen from the probe centre, and there is none");
			return RF_EINVAL;
		}
		memcpy(s->center, center, sizeof(s->center));
	}
	if (s->final &&
	    (rc = require(s, in, IN_ROUGH, IN_VZ, "the final colour's environment "
	                  "BRDF reads roughness, N and V", err, errlen)) < 0)
		return rc;
	rf_header_free(s->out_h);
	if (!(s->out_h = rf_header_dup(in)))
		return RF_ENOMEM;
	for (i = 0; i < s->nout; i++) {
		if ((c = rf_header_find_channel(s->out_h, out_names[i])) < 0 &&
		    (c = rf_header_add_channel(s->out_h, out_names[i])) < 0) {
			rf__format(err, errlen, "cannot add channel '%s': %s",
			           out_names[i], rf_strerror(c));
			return c;
		}
		s->out[i] = c;
	}
	s->ncols = rf_header_ncols(in);
	s->in_ncomp = rf_header_nchannels(in);
	s->out_ncomp = rf_header_nchannels(s->out_h);
	if (s->ncols * s->out_ncomp * sizeof(float) > RF_ROW_BYTES_MAX) {
		rf__format(err, errlen, "output rows of %zu channels are too large",
		           s->out_ncomp);
		return RF_ETOOBIG;
	}
	*out = s->out_h;
	return 0;
}

static float
sat(float x)
{
	return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
}

static int
finite3(const float v[3])
{
	return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* Radiance at dir and lod; a direction that is not finite (never from
 * reflect-project) reads black rather than spreading NaN. */
static void
sample(const rf_shade *s, const float dir[3], float lod, float rgb[3])
{
	struct rf__lod l;
	rf__v4 c;

	if (!finite3(dir)) {
		rgb[0] = rgb[1] = rgb[2] = 0.0f;
		return;
	}
	/* What rf_cubemap_sample computes (trilinear, the lod clamped to
	 * the levels), on the RGBA copy. */
	l = rf__pyramid_lod(&s->pyramid, lod);
	c = rf__pyramid_fetch(dir, &l);
	rgb[0] = c[0];
	rgb[1] = c[1];
	rgb[2] = c[2];
}

/* The optional channel c of pixel p, or 1 when the stream lacks it. */
static float
or_one(const rf_shade *s, const float *p, int c)
{
	return s->in[c] >= 0 ? p[s->in[c]] : 1.0f;
}

static void
shade_pixel(const rf_shade *s, const float *p, float *o)
{
	float rgb[3], d[3], m = 1.0f, wall[3] = { 0, 0, 0 };
	int k;

	if (s->in[IN_MASK] >= 0)
		m = sat(p[s->in[IN_MASK]]);
	if (m > 0.0f && s->mode_radiance) {
		for (k = 0; k < 3; k++)
			rgb[k] = p[s->in[IN_SR + k]];
	} else if (m > 0.0f) {
		float lod = rf_roughness_to_lod(s->mapping, s->steps, p[s->in[IN_REFF]]);

		d[0] = p[s->in[IN_DX]];
		d[1] = p[s->in[IN_DY]];
		d[2] = p[s->in[IN_DZ]];
		sample(s, d, lod, rgb);
	} else {
		rgb[0] = rgb[1] = rgb[2] = 0.0f;
	}
	if (m < 1.0f) {
		/* A wall is what the probe saw there: the environment at lod 0
		 * from the capture point toward P. */
		for (k = 0; k < 3; k++)
			d[k] = p[s->in[IN_PX + k]] - s->center[k];
		sample(s, d, 0.0f, wall);
	}
	for (k = 0; k < 3; k++)
		o[s->out[OUT_SR + k]] = m * rgb[k] + (1.0f - m) * wall[k];
	if (!s->final)
		return;
	if (m > 0.0f) {
		float nv = p[s->in[IN_NX]] * p[s->in[IN_VX]] +
		           p[s->in[IN_NY]] * p[s->in[IN_VY]] +
		           p[s->in[IN_NZ]] * p[s->in[IN_VZ]];
		float metal = sat(or_one(s, p, IN_METAL)), a, b;

		rf_dfg_lookup(nv, p[s->in[IN_ROUGH]], &a, &b);
		for (k = 0; k < 3; k++) {
			float albedo = sat(or_one(s, p, IN_AR + k));
			float f0 = 0.04f + (albedo - 0.04f) * metal;

			rgb[k] *= f0 * a + b;
		}
	}
	/* Walls are light sources here, not reflectors: no BRDF. */
	for (k = 0; k < 3; k++)
		o[s->out[OUT_R + k]] = m * rgb[k] + (1.0f - m) * wall[k];
}

/* Row r of the block, on any thread: the pass keeps no state per thread. */
static void
shade_row(void *arg, size_t r, int thread)
{
	const rf_shade *s = arg;
	const float *in = s->block_in + r * s->ncols * s->in_ncomp;
	float *out = s->block_out + r * s->ncols * s->out_ncomp;
	size_t x;

	(void)thread;
	if (in != out)
		rf__widen_pixels(out, s->out_ncomp, in, s->in_ncomp, s->ncols);
	for (x = 0; x < s->ncols; x++)
		shade_pixel(s, in + x * s->in_ncomp, out + x * s->out_ncomp);
}

/* Row r: the stage into out, then the pass over it in place, while the
 * row is still in this core's cache. */
static void
stage_and_shade_row(void *arg, size_t r, int thread)
{
	const rf_shade *s = arg;
	const float *in = s->block_in + r * s->ncols * s->stage_in_ncomp;
	float *out = s->block_out + r * s->ncols * s->out_ncomp;
	size_t x;

	rf__stage_row(s->stage, in, out, s->block_y + r, thread);
	for (x = 0; x < s->ncols; x++)
		shade_pixel(s, out + x * s->out_ncomp, out + x * s->out_ncomp);
}

int
rf_shade_run_stage(rf_shade *s, rf_stage *stage, const float *in, float *out, size_t y,
                   size_t nrows)
{
	size_t sin, sout;
	int rc;

	if (!s->out_h || !s->env)
		return RF_EINVAL;
	if ((rc = rf__stage_ready(stage, y, nrows, &sin, &sout)) < 0)
		return rc;
	/* The stage's output must be the pass's input, with its channels. */
	if (sout != s->in_ncomp || s->in_ncomp != s->out_ncomp ||
	    rf__stage_threads(stage) < rf__pool_threads(s->pool))
		return RF_EINVAL;
	s->block_in = in;
	s->block_out = out;
	s->block_y = y;
	s->stage = stage;
	s->stage_in_ncomp = sin;
	rf__pool_run(s->pool, nrows, stage_and_shade_row, s);
	return 0;
}

int
rf_shade_run(rf_shade *s, const float *in, float *out, size_t nrows)
{
	if (!s->out_h || !s->env || (in == out && s->in_ncomp != s->out_ncomp))
		return RF_EINVAL;
	s->block_in = in;
	s->block_out = out;
	rf__pool_run(s->pool, nrows, shade_row, s);
	return 0;
}
