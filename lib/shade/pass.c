/* The sampling pass of reflect-shade: effective roughness -> lod -> the
 * environment, per row, on several threads. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "envmap/rgba_levels.h"
#include "envmap/rgba_levels_simd.h"
#include "shade/blend-pass.h"
#include "shade/shade-internal.h"
#include "surface/surface-internal.h"
#include "plugin/plugin-internal.h"
#include "util/invalid.h"
#include "util/pixels.h"
#include "util/pool.h"
#include "reflect/shading.h"
#include "reflect/plugin.h"
#include "probe/shape.h"


/* Input channels; -1 when absent (only the optional ones may be). */
enum {
	IN_REFF, IN_DX, IN_DY, IN_DZ, /* always */
	IN_MASK, IN_PX, IN_PY, IN_PZ, /* walls */
	IN_ROUGH, IN_NX, IN_NY, IN_NZ, IN_VX, IN_VY, IN_VZ, /* --final */
	IN_METAL, IN_AR, IN_AG, IN_AB, /* --final, optional */
	IN_SR, IN_SG, IN_SB, /* radiance a mode wrote itself */
	IN_ER, IN_EG, IN_EB, /* what the surface emits, optional */
	IN_COUNT
};

static const char *const in_names[IN_COUNT] = {
	RF_SHADE_ROUGHNESS, "D.X", "D.Y", "D.Z",
	"mask", "P.X", "P.Y", "P.Z",
	"roughness", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z",
	"metallic", "albedo.R", "albedo.G", "albedo.B",
	RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B,
	"emission.R", "emission.G", "emission.B"
};

/* What a mode that traces the reflection writes. */
static const char *const spec_names[] = { RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B,
                                          NULL };

enum { OUT_SR, OUT_SG, OUT_SB, OUT_R, OUT_G, OUT_B, OUT_DR, OUT_DG, OUT_DB, OUT_COUNT };

static const char *const out_names[OUT_COUNT] = {
	RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B, "R", "G", "B",
	"diffuse.R", "diffuse.G", "diffuse.B"
};

struct rf_shade {
	int final, nthreads, mode_radiance;
	int force_lod, unprojected;
	float lod;
	/* The diffuse light: the environment's irradiance coefficients, and
	 * the probe box it is box-projected in (diffuse_box). */
	int diffuse, diffuse_box, has_box;
	float sh[27];
	float shq[3][9];  /* the same as a quadratic in N */
	int sh_known;     /* sh holds the environment's (given or projected) */
	struct rf__proxy proxy; /* the probe's, for the diffuse lookups */
	int in[IN_COUNT];
	/* The stream says what its walls emit (a scene's G-buffer): walls
	 * show it, and --final adds it to reflective pixels, instead of
	 * looking the walls up in the environment. */
	int emission;
	int out[OUT_COUNT];
	size_t nout;
	/* Probe blending (rf__shade_set_blend): its probes and environments,
	 * the pass made from them at the first block, the channels it reads
	 * and the weight channels it writes after the nout others. */
	int blending;
	struct rf_blend blend;
	const rf_cubemap *blend_env[RF_PROBES_MAX + 1]; /* and the sky's */
	enum rf_mapping blend_mapping[RF_PROBES_MAX + 1];
	float blend_steps[RF_PROBES_MAX + 1];
	enum rf_blend_fallback blend_fallback;
	struct rf__blend_pass *bp;
	int blend_ch[RF__BLEND_CHANNELS];
	char weight_names[RF_PROBES_MAX + 1][24];
	int out_weight[RF_PROBES_MAX + 1];
	/* A mode that traces its own rays: a stage per probe after the
	 * first, each with that probe for its host, run on the rows where
	 * the probe has weight; per thread a row of its output, a row of
	 * weights. */
	rf_stage *blend_stage[RF_PROBES_MAX];
	float *blend_rows;
	size_t blend_rows_cols;
	float center[3];
	rf_header *out_h;
	size_t ncols, in_ncomp, out_ncomp;
	const rf_cubemap *env;
	/* The same levels as RGBA vectors: one aligned load a texel, the
	 * prefilter's fast sampler; the pass spends most of its time here. */
	struct rf__rgba_levels levels;
	/* A turned probe's environment is in its box's frame (env_turned):
	 * every read, the irradiance's too, takes its direction there. */
	int env_turned;
	float env_turn[9];
	enum rf_mapping mapping;
	float steps;
	struct rf__pool *pool;
	/* The block rf_shade_run is running, and the stage before the pass
	 * when rf__shade_run_stage runs both. */
	const float *block_in;
	float *block_out;
	rf_stage *stage;
	size_t block_y, stage_in_ncomp;
	/* Each thread's reads of a row, gathered and made in one go; vector:
	 * made eight at a time. */
	struct reads *reads;
	size_t reads_cols;
	int vector;
	/* Invalid input (reflect.h's rules) in the pass's own reads: under
	 * RF_INVALID_ERROR the first is an error; under CLAMP a value is
	 * clamped (in a copy of the row), under ZERO the pixel's outputs are
	 * 0; a D or P that is not finite reads black under both.  The rules
	 * of every pixel (always), of a pixel the mirror shows (mirror: the
	 * final colour's material, a mode's radiance), and of one the wall
	 * shows (wall), and their union for the fast test of a row (check),
	 * with D and P. */
	enum rf_invalid invalid;
	size_t rows_done;
	char error[320];
	struct rf__check check, always, mirror, wall;
	size_t fixed; /* pixels of the frame clamped or zeroed */
};

/* One row's environment reads: directions and lods as columns, their
 * results, and for each pixel which reads are its own (-1: none). */
struct reads {
	float *mask; /* each pixel's mask, clamped (1 without a mask channel) */
	rf__v4 *blended; /* each pixel's mirror read, blended over the probes */
	float *x, *y, *z, *lod;
	rf__v4 *rgb;
	int32_t *mirror, *wall;
	struct rf__first_invalid first; /* under RF_INVALID_ERROR */
	float *row;          /* a row whose input breaks a rule, as repaired */
	size_t row_cap;      /* floats */
	unsigned char *zero; /* its pixels whose outputs are 0 */
	size_t fixed;        /* pixels repaired in the block */
};

int
rf_shade_create(rf_shade **sp, const struct rf_shade_options *o)
{
	rf_shade *s;

	*sp = NULL;
	if (!(s = calloc(1, sizeof(*s))))
		return RF_ENOMEM;
	s->final = o && o->final ? (o->final >= RF_FINAL_SPLIT_SUM && o->final <= RF_FINAL_HDRP
	                                ? o->final : RF_FINAL_SPLIT_SUM)
	                         : RF_FINAL_NONE;
	s->mode_radiance = o && o->mode_radiance;
	s->force_lod = o && o->force_lod;
	s->lod = o ? o->lod : 0.0f;
	s->nthreads = o && o->nthreads > 1 ? o->nthreads : 1;
	if (s->nthreads > RF__THREADS_MAX)
		s->nthreads = RF__THREADS_MAX;
	s->diffuse = s->final && o->diffuse;
	s->diffuse_box = s->diffuse && o->diffuse_box;
	s->nout = s->final ? (s->diffuse ? OUT_COUNT : OUT_DR) : OUT_R;
	if (rf__pool_create(&s->pool, s->nthreads) < 0) {
		free(s);
		return RF_ENOMEM;
	}
	*sp = s;
	return 0;
}

static void
free_reads(rf_shade *s)
{
	int t;

	for (t = 0; s->reads && t < s->nthreads; t++) {
		struct reads *r = &s->reads[t];

		free(r->mask);
		free(r->x);
		free(r->y);
		free(r->z);
		free(r->lod);
		free(r->rgb);
		free(r->mirror);
		free(r->wall);
		free(r->blended);
		free(r->row);
		free(r->zero);
	}
	free(s->reads);
	s->reads = NULL;
	s->reads_cols = 0;
}

/* Room for two reads a pixel (the mirror and the wall behind a partial
 * mask) on every thread, and for a row of ncomp channels. */
static int
alloc_reads(rf_shade *s, size_t ncols, size_t ncomp)
{
	size_t n = 2 * ncols;
	int t;

	if (ncols <= s->reads_cols) {
		for (t = 0; t < s->nthreads; t++) {
			struct reads *r = &s->reads[t];
			float *grown;

			if (ncols * ncomp <= r->row_cap)
				continue;
			if (!(grown = realloc(r->row, ncols * ncomp * sizeof(float))))
				return RF_ENOMEM;
			r->row = grown;
			r->row_cap = ncols * ncomp;
		}
		return 0;
	}
	free_reads(s);
	if (!(s->reads = calloc((size_t)s->nthreads, sizeof(*s->reads))))
		return RF_ENOMEM;
	for (t = 0; t < s->nthreads; t++) {
		struct reads *r = &s->reads[t];

		r->mask = malloc(ncols * sizeof(float));
		r->x = malloc(n * sizeof(float));
		r->y = malloc(n * sizeof(float));
		r->z = malloc(n * sizeof(float));
		r->lod = malloc(n * sizeof(float));
		r->rgb = aligned_alloc(16, n * sizeof(rf__v4));
		r->mirror = malloc(ncols * sizeof(int32_t));
		r->wall = malloc(ncols * sizeof(int32_t));
		r->blended = aligned_alloc(16, ncols * sizeof(rf__v4));
		r->row = malloc(ncols * ncomp * sizeof(float));
		r->row_cap = ncols * ncomp;
		r->zero = malloc(ncols);
		if (!r->mask || !r->x || !r->y || !r->z || !r->lod || !r->rgb || !r->mirror ||
		    !r->wall || !r->blended || !r->row || !r->zero) {
			free_reads(s);
			return RF_ENOMEM;
		}
	}
	s->reads_cols = ncols;
	return 0;
}

void
rf_shade_destroy(rf_shade *s)
{
	if (!s)
		return;
	rf__pool_destroy(s->pool);
	free_reads(s);
	rf_header_destroy(s->out_h);
	rf__blend_pass_destroy(s->bp);
	rf__rgba_levels_destroy(&s->levels);
	free(s->blend_rows);
	free(s);
}

int
rf__shade_set_blend(rf_shade *s, const struct rf_blend *b, const rf_cubemap *const *envs,
                     const enum rf_mapping *mappings, const float *steps,
                     enum rf_blend_fallback fallback)
{
	uint32_t k;

	rf__blend_pass_destroy(s->bp);
	s->bp = NULL;
	memset(s->blend_stage, 0, sizeof(s->blend_stage));
	s->blending = b && b->nprobes > 1;
	if (!s->blending)
		return 0;
	s->blend = *b;
	s->blend_fallback = fallback;
	for (k = 0; k <= b->nprobes; k++) {
		if (k == b->nprobes && fallback != RF_BLEND_SKY)
			break;
		if (k && !s->mode_radiance && !envs[k])
			return RF_EINVAL;
		s->blend_env[k] = envs ? envs[k] : NULL;
		s->blend_mapping[k] = mappings ? mappings[k] : RF_MAPPING_DEFAULT;
		s->blend_steps[k] = steps ? steps[k] : 0.0f;
	}
	for (k = 0; k < b->nprobes; k++)
		snprintf(s->weight_names[k], sizeof(s->weight_names[k]), "weight.probe%u",
		         (unsigned)k + 1);
	snprintf(s->weight_names[k], sizeof(s->weight_names[k]), "weight.fallback");
	return 0;
}

int
rf_final_parse(const char *name, enum rf_final *final)
{
	static const char *const names[] = { "split-sum", "unity", "hdrp" };
	int i;

	for (i = 0; i < 3; i++)
		if (!strcmp(name, names[i])) {
			*final = (enum rf_final)(RF_FINAL_SPLIT_SUM + i);
			return 0;
		}
	return RF_EINVAL;
}

void
rf_shade_set_irradiance(rf_shade *s, const float sh9[27])
{
	memcpy(s->sh, sh9, sizeof(s->sh));
	rf__sh9_quadratic(s->sh, s->shq);
	s->sh_known = 1;
}

void
rf_shade_set_probe(rf_shade *s, const struct rf_probe *probe)
{
	s->has_box = probe != NULL;
	if (probe)
		s->proxy = rf__proxy_of_probe(probe);
}

void
rf__shade_set_env_frame(rf_shade *s, const float rotation[9])
{
	s->env_turned = rotation != NULL;
	if (rotation)
		memcpy(s->env_turn, rotation, sizeof(s->env_turn));
	rf__rgba_levels_turn(&s->levels, rotation);
}

void
rf__shade_set_unprojected(rf_shade *s, int unprojected)
{
	s->unprojected = unprojected;
}

int
rf__shade_set_blend_stages(rf_shade *s, rf_stage *const *stages)
{
	uint32_t k;

	if (!s->blending || !s->mode_radiance)
		return RF_EINVAL;
	for (k = 1; k < s->blend.nprobes; k++) {
		if (!stages[k] || rf__stage_threads(stages[k]) < s->nthreads)
			return RF_EINVAL;
		s->blend_stage[k] = stages[k];
	}
	return 0;
}

const char *
rf_shade_channel(const rf_shade *s, size_t i)
{
	if (i < s->nout)
		return out_names[i];
	if (s->blending && i - s->nout <= s->blend.nprobes)
		return s->weight_names[i - s->nout];
	return NULL;
}

int
rf_shade_set_environment(rf_shade *s, const rf_cubemap *env, enum rf_mapping mapping,
                         float steps)
{
	int rc;

	rf__rgba_levels_destroy(&s->levels);
	s->env = NULL;
	if ((rc = rf__rgba_levels_from_cube(&s->levels, env)) < 0)
		return rc;
	rf__rgba_levels_turn(&s->levels, s->env_turned ? s->env_turn : NULL);
	s->env = env;
	s->vector = rf__rgba_levels_simd_usable(&s->levels);
	/* Projected when the first block needs them, unless the chain's own
	 * coefficients come first (rf_shade_set_irradiance). */
	s->sh_known = 0;
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

/* A rule on input channel i (with i + 1 and i + 2 for a direction);
 * nothing when the stream lacks it. */
static void
add_rule(const rf_shade *s, struct rf__check *c, int kind, const char *name, int i)
{
	struct rf__check_item *it;
	int k;

	if (s->in[i] < 0 || c->n >= RF__CHECK_MAX)
		return;
	it = &c->item[c->n++];
	it->kind = kind;
	it->name = name;
	for (k = 0; k < (kind == RF__CHECK_DIRECTION ? 3 : 1); k++)
		it->at[k] = s->in[i + k];
}

/* The rules of what the pass reads itself: mask in [0, 1]; D finite
 * where the mirror shows (when the mode gives no radiance) and P where
 * the wall shows (when the stream has a mask); the emission a radiance
 * where it shows (walls, and with --final every pixel); with --final the
 * material (roughness, metallic, albedo in [0, 1]; N and V directions)
 * where the mirror shows, and so the radiance a mode wrote. */
static void
plan_check(rf_shade *s)
{
	static const int finite[6] = { IN_DX, IN_DY, IN_DZ, IN_PX, IN_PY, IN_PZ };
	struct rf__check *const plans[3] = { &s->always, &s->mirror, &s->wall };
	size_t j;
	int k;

	s->check.n = s->always.n = s->mirror.n = s->wall.n = 0;
	for (k = 0; k < 6; k++)
		if (k < 3 ? !s->mode_radiance : s->in[IN_MASK] >= 0)
			add_rule(s, &s->check, RF__CHECK_FINITE, in_names[finite[k]], finite[k]);
	add_rule(s, &s->always, RF__CHECK_UNIT, "mask", IN_MASK);
	for (k = 0; k < 3 && s->emission; k++)
		add_rule(s, s->final ? &s->always : &s->wall, RF__CHECK_RADIANCE,
		         in_names[IN_ER + k], IN_ER + k);
	if (s->final) {
		add_rule(s, &s->mirror, RF__CHECK_UNIT, "roughness", IN_ROUGH);
		add_rule(s, &s->mirror, RF__CHECK_UNIT, "metallic", IN_METAL);
		for (k = 0; k < 3; k++)
			add_rule(s, &s->mirror, RF__CHECK_UNIT, in_names[IN_AR + k], IN_AR + k);
		if (s->in[IN_NY] >= 0 && s->in[IN_NZ] >= 0)
			add_rule(s, &s->mirror, RF__CHECK_DIRECTION, "N", IN_NX);
		if (s->in[IN_VY] >= 0 && s->in[IN_VZ] >= 0)
			add_rule(s, &s->mirror, RF__CHECK_DIRECTION, "V", IN_VX);
	}
	for (k = 0; k < 3 && s->mode_radiance; k++)
		add_rule(s, &s->mirror, RF__CHECK_RADIANCE, in_names[IN_SR + k], IN_SR + k);
	for (k = 0; k < 3; k++)
		for (j = 0; j < plans[k]->n && s->check.n < RF__CHECK_MAX; j++)
			s->check.item[s->check.n++] = plans[k]->item[j];
}

int
rf_shade_begin_frame(rf_shade *s, const rf_header *in, const float center[3],
                     rf_header **out, char *err, size_t errlen)
{
	size_t i;
	int c, rc;

	*out = NULL;
	s->rows_done = 0;
	s->fixed = 0;
	s->error[0] = '\0';
	for (i = 0; i < IN_COUNT; i++)
		s->in[i] = rf_header_find_channel(in, in_names[i]);
	s->emission = s->in[IN_ER] >= 0 && s->in[IN_EG] >= 0 && s->in[IN_EB] >= 0;
	if (s->unprojected && !s->mode_radiance) {
		static const char *const r[3] = { "R.X", "R.Y", "R.Z" };

		for (i = 0; i < 3; i++)
			if ((s->in[IN_DX + i] = rf_header_find_channel(in, r[i])) < 0) {
				rf__format(err, errlen, "input has no channel '%s' (the reflection "
				           "vector reflect-project writes: with box projection off "
				           "it is the lookup direction)", r[i]);
				return RF_ECHANNEL;
			}
	}
	plan_check(s);
	if (s->mode_radiance) {
		if ((rc = require(s, in, IN_SR, IN_SB, "the radiance the shade mode "
		                  "writes", err, errlen)) < 0)
			return rc;
	} else if ((rc = require(s, in, IN_REFF, IN_REFF, "the effective "
	                         "roughness a shade mode writes", err, errlen)) < 0 ||
	           (!s->unprojected &&
	            (rc = require(s, in, IN_DX, IN_DZ, "the lookup direction that "
	                          "reflect-project writes", err, errlen)) < 0)) {
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
	if (s->blending) {
		static const char *const names[RF__BLEND_CHANNELS] = {
			"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "R.X", "R.Y", "R.Z",
			RF_SHADE_ROUGHNESS
		};

		for (i = 0; i < RF__BLEND_CHANNELS; i++) {
			s->blend_ch[i] = rf_header_find_channel(in, names[i]);
			/* N for the normal fade only; a traced mode reads no R */
			if (s->blend_ch[i] < 0 && !(i >= RF__BLEND_NX && i < RF__BLEND_RX) &&
			    !(s->mode_radiance && i >= RF__BLEND_RX)) {
				rf__format(err, errlen, "input has no channel '%s' (blending probes "
				           "reads P, the reflection R that reflect-project "
				           "writes, and %s)", names[i], RF_SHADE_ROUGHNESS);
				return RF_ECHANNEL;
			}
		}
		if (!s->blend.normal_fade || s->blend_ch[RF__BLEND_NX] < 0 ||
		    s->blend_ch[RF__BLEND_NX + 1] < 0 || s->blend_ch[RF__BLEND_NX + 2] < 0)
			s->blend_ch[RF__BLEND_NX] = -1;
	}
	rf_header_destroy(s->out_h);
	if (rf_header_dup(&s->out_h, in) < 0)
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
	for (i = 0; s->blending && i <= s->blend.nprobes; i++) {
		const char *name = s->weight_names[i];

		if ((c = rf_header_find_channel(s->out_h, name)) < 0 &&
		    (c = rf_header_add_channel(s->out_h, name)) < 0) {
			rf__format(err, errlen, "cannot add channel '%s': %s", name,
			           rf_strerror(c));
			return c;
		}
		s->out_weight[i] = c;
	}
	/* the blend pass is made at the first block, for the frame's size */
	rf__blend_pass_destroy(s->bp);
	s->bp = NULL;
	s->ncols = rf_header_ncols(in);
	if (s->blending && s->mode_radiance) {
		size_t need = (size_t)s->nthreads * (rf_header_nchannels(s->out_h) +
		                                     s->blend.nprobes + 1) * s->ncols;

		free(s->blend_rows);
		if (!(s->blend_rows = malloc(need * sizeof(float))))
			return RF_ENOMEM;
	}
	s->in_ncomp = rf_header_nchannels(in);
	s->out_ncomp = rf_header_nchannels(s->out_h);
	if (s->ncols * s->out_ncomp * sizeof(float) > RF_ROW_BYTES_MAX) {
		rf__format(err, errlen, "output rows of %zu channels are too large",
		           s->out_ncomp);
		return RF_ETOOBIG;
	}
	if ((rc = alloc_reads(s, s->ncols, s->in_ncomp)) < 0)
		return rc;
	*out = s->out_h;
	return 0;
}

static float
sat(float x)
{
	return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
}

/* The optional channel c of pixel p, or 1 when the stream lacks it. */
static float
or_one(const rf_shade *s, const float *p, int c)
{
	return s->in[c] >= 0 ? p[s->in[c]] : 1.0f;
}

/* Adds a read; a direction that is not finite (never from
 * reflect-project) reads nothing, so black rather than NaN. */
static inline int32_t
add_read(struct reads *r, size_t *n, float x, float y, float z, float lod)
{
	if (!isfinite(x) || !isfinite(y) || !isfinite(z))
		return -1;
	r->x[*n] = x;
	r->y[*n] = y;
	r->z[*n] = z;
	r->lod[*n] = lod;
	return (int32_t)(*n)++;
}

/* The pass's own reads of pixel x (row y, p a copy of it) checked: 0,
 * 1 clamped in place, 2 to be written as 0, or -1 (ERROR) kept in
 * r->first. */
static int
check_pixel(const rf_shade *s, float *p, size_t y, size_t x, struct reads *r)
{
	static const char *const names[2][6] = { { "D.X", "D.Y", "D.Z", "P.X", "P.Y", "P.Z" },
		                                 { "R.X", "R.Y", "R.Z", "P.X", "P.Y", "P.Z" } };
	const int at[6] = { s->in[IN_DX], s->in[IN_DY], s->in[IN_DZ],
		            s->in[IN_PX], s->in[IN_PY], s->in[IN_PZ] };
	char why[200];
	float m;
	int k, q, result;

	if ((q = rf__check_pixel(&s->always, p, 0, s->invalid, why, sizeof(why))) < 0)
		goto broken;
	if (q == 2)
		return 2;
	result = q;
	m = s->in[IN_MASK] >= 0 ? p[s->in[IN_MASK]] : 1.0f;
	if (m > 0.0f && (q = rf__check_pixel(&s->mirror, p, 0, s->invalid, why,
	                                     sizeof(why))) != 0) {
		if (q < 0)
			goto broken;
		if (q == 2)
			return 2;
		result = 1;
	}
	if (m < 1.0f && (q = rf__check_pixel(&s->wall, p, 1, s->invalid, why,
	                                     sizeof(why))) != 0) {
		if (q < 0)
			goto broken;
		if (q == 2)
			return 2;
		result = 1;
	}
	/* otherwise such a direction reads black (add_read) */
	for (k = 0; k < 6 && s->invalid == RF_INVALID_ERROR; k++)
		if (at[k] >= 0 && ((k < 3 && m > 0.0f && !s->mode_radiance) || (k >= 3 && m < 1.0f)) &&
		    !isfinite(p[at[k]])) {
			snprintf(why, sizeof(why), "channel '%s' is %g", names[s->unprojected][k],
			         (double)p[at[k]]);
			goto broken;
		}
	return result;
broken:
	rf__first_invalid_keep(&r->first, y * s->ncols + x, "%s", why);
	return -1;
}

/* The row as the pass reads it: in itself when every pixel keeps the
 * rules (the common case, one fast test), else a copy checked pixel by
 * pixel (clamped, its pixels to be zeroed marked in r->zero), with
 * *zeroed set when there are any. */
static const float *
checked_row(const rf_shade *s, const float *in, size_t in_ncomp, size_t y, struct reads *r,
            int *zeroed)
{
	size_t x;
	int q;

	*zeroed = 0;
	if (!s->check.n || rf__check_row(&s->check, in, in_ncomp, s->ncols))
		return in;
	memcpy(r->row, in, s->ncols * in_ncomp * sizeof(float));
	for (x = 0; x < s->ncols; x++) {
		q = check_pixel(s, r->row + x * in_ncomp, y, x, r);
		r->zero[x] = q == 2;
		*zeroed |= q == 2;
		r->fixed += q > 0;
	}
	return r->row;
}

/* The reads of a row's pixels: the mirror direction at the lod of its
 * effective roughness, and where the mask is partial or 0, the wall it
 * shows (the environment at lod 0 from the capture point toward P).
 * The channel numbers are held in locals: stores to the int tables
 * would otherwise make the compiler read them again for every pixel. */
static size_t
plan_reads(const rf_shade *s, const float *in, size_t in_ncomp, struct reads *r)
{
	const int cm = s->in[IN_MASK], cr = s->in[IN_REFF];
	const int cdx = s->in[IN_DX], cdy = s->in[IN_DY], cdz = s->in[IN_DZ];
	const int cpx = s->in[IN_PX], cpy = s->in[IN_PY], cpz = s->in[IN_PZ];
	const int mirror = !s->mode_radiance;
	const float ox = s->center[0], oy = s->center[1], oz = s->center[2];
	size_t x, n = 0;

	for (x = 0; x < s->ncols; x++, in += in_ncomp) {
		float m = cm >= 0 ? sat(in[cm]) : 1.0f;
		int32_t a = -1, b = -1;

		if (m > 0.0f && mirror)
			a = add_read(r, &n, in[cdx], in[cdy], in[cdz],
			             s->force_lod ? s->lod
			                          : rf_roughness_to_lod(s->mapping, s->steps, in[cr]));
		if (m < 1.0f && !s->emission)
			b = add_read(r, &n, in[cpx] - ox, in[cpy] - oy, in[cpz] - oz, 0.0f);
		r->mask[x] = m;
		r->mirror[x] = a;
		r->wall[x] = b;
	}
	return n;
}

/* Lambert's albedo (1 - metallic) E(N) / pi, E from the irradiance
 * coefficients at N, or with the box projection at the direction from
 * the capture point to where P + t N leaves the probe box. */
static void
diffuse_light(const rf_shade *s, const float *p, const float albedo[3], float metal,
              float e[3])
{
	float n[3] = { p[s->in[IN_NX]], p[s->in[IN_NY]], p[s->in[IN_NZ]] }, dir[3], t, reach;
	float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
	int k;

	if (!(len > 0.0f) || !(len < INFINITY)) {
		e[0] = e[1] = e[2] = 0.0f;
		return;
	}
	for (k = 0; k < 3; k++)
		dir[k] = n[k] / len;
	if (s->diffuse_box && s->has_box && s->in[IN_PX] >= 0) {
		const float pos[3] = { p[s->in[IN_PX]], p[s->in[IN_PY]], p[s->in[IN_PZ]] };
		float u[3] = { dir[0], dir[1], dir[2] }, l;

		if (rf__proxy_exit(&s->proxy, pos, u, &t) == 0) {
			rf__lookup_from_hit(&s->proxy.box, pos, u, t, dir, &reach);
			l = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
			if (!(l > 0.0f)) {
				e[0] = e[1] = e[2] = 0.0f;
				return;
			}
			for (k = 0; k < 3; k++)
				dir[k] /= l;
		}
	}
	if (s->env_turned) {
		float local[3];

		rf__turn_in(s->env_turn, dir[0], dir[1], dir[2], local);
		rf__surface_diffuse(s->shq, local, albedo, metal, e);
		return;
	}
	rf__surface_diffuse(s->shq, dir, albedo, metal, e);
}

/* The final colour's BRDF term of a reflective pixel, on rgb in place,
 * the engine's (s->final), and with the diffuse light into diffuse. */
static void
final_colour(const rf_shade *s, const float *p, float rgb[3], float diffuse[3])
{
	const float nx = p[s->in[IN_NX]], ny = p[s->in[IN_NY]], nz = p[s->in[IN_NZ]];
	const float vx = p[s->in[IN_VX]], vy = p[s->in[IN_VY]], vz = p[s->in[IN_VZ]];
	/* the cosine, whatever the vectors' lengths (the rules ask only that
	 * they normalise: each square sum within the float range, and so the
	 * dot product) */
	const float nn = nx * nx + ny * ny + nz * nz, vv = vx * vx + vy * vy + vz * vz;
	float nv = nn > 0.0f && vv > 0.0f
	                   ? (nx * vx + ny * vy + nz * vz) / (sqrtf(nn) * sqrtf(vv)) : 0.0f;
	float metal = sat(or_one(s, p, IN_METAL)), pr = sat(p[s->in[IN_ROUGH]]);
	float albedo[3], f0[3], w[3];
	int k;

	for (k = 0; k < 3; k++)
		albedo[k] = sat(or_one(s, p, IN_AR + k));
	rf__surface_f0(albedo, metal, f0);
	if (s->final == RF_FINAL_UNITY)
		rf__surface_unity(f0, nv, pr, metal, w);
	else
		rf__surface_split_sum(f0, nv, pr, s->final == RF_FINAL_HDRP, w);
	for (k = 0; k < 3; k++)
		rgb[k] *= w[k];
	if (s->diffuse) {
		diffuse_light(s, p, albedo, metal, diffuse);
		for (k = 0; k < 3; k++)
			rgb[k] += diffuse[k];
	}
}

/* A radiance as written: past the float range it is the largest float
 * (finite inputs can add up past it), and never NaN. */
static inline float
radiance_out(float v)
{
	return v < FLT_MAX ? (v > -FLT_MAX ? v : -FLT_MAX) : v == v ? FLT_MAX : 0.0f;
}

/* Pixel p's outputs into o (which may be p) from its reads. */
static void
shade_pixel(const rf_shade *s, const float *p, float *o, const struct reads *r, size_t x)
{
	float rgb[3] = { 0, 0, 0 }, wall[3] = { 0, 0, 0 }, spec[3], diffuse[3] = { 0, 0, 0 };
	float m = r->mask[x];
	int k;

	if (m > 0.0f && s->mode_radiance) {
		for (k = 0; k < 3; k++)
			rgb[k] = p[s->in[IN_SR + k]];
	} else if (r->mirror[x] >= 0) {
		for (k = 0; k < 3; k++)
			rgb[k] = r->rgb[r->mirror[x]][k];
	}
	if (s->emission)
		for (k = 0; k < 3; k++)
			wall[k] = p[s->in[IN_ER + k]];
	else if (r->wall[x] >= 0)
		for (k = 0; k < 3; k++)
			wall[k] = r->rgb[r->wall[x]][k];
	for (k = 0; k < 3; k++)
		spec[k] = rgb[k];
	if (s->final && m > 0.0f) {
		final_colour(s, p, rgb, diffuse);
		if (s->emission)
			for (k = 0; k < 3; k++)
				rgb[k] += wall[k];
	}
	/* Every input is read: now the outputs, which may overwrite them. */
	for (k = 0; k < 3; k++)
		o[s->out[OUT_SR + k]] = radiance_out(m * spec[k] + (1.0f - m) * wall[k]);
	/* Walls are light sources here, not reflectors: no BRDF. */
	if (s->final)
		for (k = 0; k < 3; k++)
			o[s->out[OUT_R + k]] = radiance_out(m * rgb[k] + (1.0f - m) * wall[k]);
	if (s->diffuse)
		for (k = 0; k < 3; k++)
			o[s->out[OUT_DR + k]] = radiance_out(m * diffuse[k]);
}

/* A row of ncols pixels: its reads gathered, made in one go (eight at a
 * time where the CPU allows), then the pixels finished. */
static void
shade_pixels(const rf_shade *s, const float *in, size_t in_ncomp, float *out, size_t y,
             struct reads *r)
{
	const float *w = NULL;
	uint32_t k, nw = 0;
	size_t x, n, c;
	int zeroed;

	in = checked_row(s, in, in_ncomp, y, r, &zeroed);
	n = plan_reads(s, in, in_ncomp, r);

	rf__rgba_levels_fetch_many(&s->levels, s->vector, n, r->x, r->y, r->z, r->lod, r->rgb);
	if (s->bp) {
		const rf__v4 zero = { 0, 0, 0, 0 };

		/* every input is read before the first output is written */
		for (x = 0; x < s->ncols; x++)
			r->blended[x] = r->mirror[x] >= 0 ? r->rgb[r->mirror[x]] : zero;
		w = rf__blend_pass_row(s->bp, (int)(r - s->reads), in, in_ncomp, s->blend_ch,
		                       r->mask, r->blended);
		nw = s->blend.nprobes + 1;
		for (x = 0; x < s->ncols; x++)
			if (r->mirror[x] >= 0)
				r->rgb[r->mirror[x]] = r->blended[x];
	}
	for (x = 0; x < s->ncols; x++) {
		float *o = out + x * s->out_ncomp;

		shade_pixel(s, in + x * in_ncomp, o, r, x);
		for (c = 0; zeroed && r->zero[x] && c < s->nout; c++)
			o[s->out[c]] = 0.0f;
		for (k = 0; k < nw; k++)
			o[s->out_weight[k]] = w[x * nw + k];
	}
}

/* Row r of the block, on thread `thread` (whose reads it uses). */
static void
shade_row(void *arg, size_t r, int thread)
{
	const rf_shade *s = arg;
	const float *in = s->block_in + r * s->ncols * s->in_ncomp;
	float *out = s->block_out + r * s->ncols * s->out_ncomp;

	if (in != out)
		rf__widen_pixels(out, s->out_ncomp, in, s->in_ncomp, s->ncols);
	shade_pixels(s, in, s->in_ncomp, out, s->block_y + r, &s->reads[thread]);
}

/* Row r: the stage into out, then the pass over it in place, while the
 * row is still in this core's cache. */
/* A traced row blended over the probes: each probe's stage traces the row
 * (the first's is the pass's own, in out already) where the probe has
 * weight, and spec becomes the weighted sum, the fallback's share the
 * first probe's (a traced ray has no probe-less lookup) or, with
 * RF_BLEND_NONE, the weights scaled to 1; then the row is shaded. */
static void
blend_traced_row(const rf_shade *s, const float *in, float *out, size_t y, int thread)
{
	const uint32_t np = s->blend.nprobes, stride = np + 1;
	const size_t n = s->ncols, nc = s->out_ncomp;
	float *row = s->blend_rows + (size_t)thread * (nc + stride) * n;
	float *w = row + nc * n;
	const int cs[3] = { s->in[IN_SR], s->in[IN_SG], s->in[IN_SB] };
	size_t x;
	uint32_t k;
	int c;

	for (x = 0; x < n; x++) {
		float *wx = w + x * stride;
		const float rest = rf__blend_pixel_weights(&s->blend, s->blend_fallback,
		                                           out + x * nc, s->blend_ch, wx);

		/* the first probe's share, the fallback's with it */
		for (c = 0; c < 3; c++)
			out[x * nc + (size_t)cs[c]] *= wx[0] + rest;
	}
	for (k = 1; k < np; k++) {
		int any = 0;

		for (x = 0; x < n && !any; x++)
			any = w[x * stride + k] > 0.0f;
		if (!any)
			continue;
		rf__stage_row(s->blend_stage[k], in, row, y, thread);
		for (x = 0; x < n; x++)
			for (c = 0; c < 3; c++)
				out[x * nc + (size_t)cs[c]] += w[x * stride + k] *
				                               row[x * nc + (size_t)cs[c]];
	}
	shade_pixels(s, out, nc, out, y, &s->reads[thread]);
	for (x = 0; x < n; x++)
		for (k = 0; k <= np; k++)
			out[x * nc + (size_t)s->out_weight[k]] = w[x * stride + k];
}

static void
stage_and_shade_row(void *arg, size_t r, int thread)
{
	const rf_shade *s = arg;
	const float *in = s->block_in + r * s->ncols * s->stage_in_ncomp;
	float *out = s->block_out + r * s->ncols * s->out_ncomp;

	rf__stage_row(s->stage, in, out, s->block_y + r, thread);
	if (s->blending && s->mode_radiance && s->blend_stage[1])
		blend_traced_row(s, in, out, s->block_y + r, thread);
	else
		shade_pixels(s, out, s->out_ncomp, out, s->block_y + r, &s->reads[thread]);
}

static int
block_begin(rf_shade *s)
{
	int t, rc;

	if (s->blending && !s->mode_radiance && !s->bp && s->env) {
		s->blend_mapping[0] = s->mapping;
		s->blend_steps[0] = s->steps;
		if ((rc = rf__blend_pass_create(&s->bp, &s->blend, s->blend_env,
		                                s->blend_mapping, s->blend_steps,
		                                s->blend_fallback, &s->levels, s->vector,
		                                s->nthreads, s->ncols)) < 0)
			return rc;
	}
	if (s->diffuse && !s->sh_known) {
		float sh[27];

		rf_cubemap_sh9(s->env, 0, sh);
		rf_shade_set_irradiance(s, sh);
	}
	for (t = 0; t < s->nthreads; t++) {
		rf__first_invalid_clear(&s->reads[t].first);
		s->reads[t].fixed = 0;
	}
	return 0;
}

/* RF_EINVAL with s->error for the block's first invalid pixel. */
static int
block_end(rf_shade *s)
{
	int t;

	for (t = 0; t < s->nthreads; t++)
		s->fixed += s->reads[t].fixed;
	return rf__first_invalid_report(&s->reads[0].first, (size_t)s->nthreads,
	                                sizeof(struct reads), s->ncols, s->error,
	                                sizeof(s->error));
}

size_t
rf_shade_invalid_count(const rf_shade *s)
{
	return s->fixed;
}

void
rf_shade_set_invalid(rf_shade *s, enum rf_invalid policy)
{
	s->invalid = policy;
}

const char *
rf_shade_error(const rf_shade *s)
{
	return s->error;
}

int
rf__shade_run_stage(rf_shade *s, rf_stage *stage, const float *in, float *out, size_t y,
                     size_t nrows)
{
	size_t sin, sout;
	uint32_t k;
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
	if ((rc = block_begin(s)) < 0)
		return rc;
	/* shade_pixel never reads a mode's radiance at a wall: the mode
	 * need not trace it there. */
	if (s->mode_radiance)
		rf__stage_skip_walls(stage, spec_names);
	rf__stage_block_begin(stage);
	for (k = 1; s->blending && s->mode_radiance && k < s->blend.nprobes; k++) {
		size_t ki, ko;

		if (!s->blend_stage[k])
			break;
		if ((rc = rf__stage_ready(s->blend_stage[k], y, nrows, &ki, &ko)) < 0)
			return rc;
		if (ko != s->out_ncomp)
			return RF_EINVAL;
		rf__stage_skip_walls(s->blend_stage[k], spec_names);
		rf__stage_block_begin(s->blend_stage[k]);
	}
	rf__pool_run(s->pool, nrows, stage_and_shade_row, s);
	if ((rc = rf__stage_block_end(stage)) < 0)
		return rc;
	for (k = 1; s->blending && s->mode_radiance && k < s->blend.nprobes; k++)
		if (s->blend_stage[k] && (rc = rf__stage_block_end(s->blend_stage[k])) < 0) {
			/* the tool reads the pass's message for a stage of its own */
			rf__format(s->error, sizeof(s->error), "%s",
			           rf_stage_error(s->blend_stage[k]));
			return rc;
		}
	return block_end(s);
}

int
rf_shade_run(rf_shade *s, const float *in, float *out, size_t nrows)
{
	int rc;

	if (!s->out_h || !s->env || (in == out && s->in_ncomp != s->out_ncomp))
		return RF_EINVAL;
	s->block_in = in;
	s->block_out = out;
	s->block_y = s->rows_done;
	s->rows_done += nrows;
	if ((rc = block_begin(s)) < 0)
		return rc;
	rf__pool_run(s->pool, nrows, shade_row, s);
	return block_end(s);
}
