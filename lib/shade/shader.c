/*
 * reflect-shade's frames, built here from a description of the shading:
 * the probe, the environments (loaded, prefiltered, kept while frames
 * name them), a plugin host for every probe, the mode's stages and the
 * sampling pass, set up in the one order that makes their rows line up.
 * A tool parses options into the description and streams rows; a second
 * caller does the same and copies none of this.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shade/shade-internal.h"
#include "util/util.h"
#include "reflect/host.h"
#include "reflect/shading.h"

/* An environment in use, kept across frames while they name the same. */
struct environment {
	char *name; /* as given: a path, or "default" */
	rf_cubemap *cube;
	enum rf_mapping mapping;
	float steps;
	int fresh;   /* loaded since the pass last took it */
	int has_sh9; /* the chain kept its irradiance coefficients */
	float sh9[27];
};

struct rf_shader {
	struct rf_shader_options o;
	int nthreads;
	rf_shade *pass;
	/* The first probe's host, for every frame: a mode tracing rays reads
	 * the plain levels it makes once per environment. */
	rf_plugin_host *host;
	struct environment env[RF_PROBES_MAX + 1]; /* the probes', the sky's */
	/* The frame's: the mode's stage, and with blending for a mode that
	 * traces its own rays a host and a stage for each probe after the
	 * first. */
	rf_stage *stage;
	rf_plugin_host *hosts[RF_PROBES_MAX];
	rf_stage *stages[RF_PROBES_MAX];
	struct rf_blend blend;
	/* What the prefilter about to start prefilters, for progress. */
	char line[4400];
};

void
rf_shader_options_init(struct rf_shader_options *o)
{
	memset(o, 0, sizeof(*o));
	rf_envmap_options_init(&o->envmap);
	o->diffuse = 1; /* with final, the probe's diffuse light too */
	o->blend = 1;
	o->max_probes = 2;
}

/* An error that has no message of its own (the caller says rf_strerror). */
static int
bare(int rc, char *err, size_t errlen)
{
	if (errlen)
		*err = '\0';
	return rc;
}

static void
note(const rf_shader *s, const char *fmt, ...) RF__PRINTF(2, 3);

static void
note(const rf_shader *s, const char *fmt, ...)
{
	char msg[4400];
	va_list ap;

	if (!s->o.note)
		return;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	rf__printable(msg);
	s->o.note(s->o.note_arg, msg);
}

/* The prefilter's progress, its line as it starts. */
static void
progress(void *arg, double done, double total)
{
	const rf_shader *s = arg;

	s->o.progress(s->o.progress_arg, done == 0.0 && *s->line ? s->line : NULL, done,
	              total);
}

static int
default_load(const rf_shader *s, rf_cubemap **c, struct rf_chain_info *info,
             const char *name, const struct rf_envmap_options *eo, char *err,
             size_t errlen)
{
	size_t bad = 0;
	int rc;

	if ((rc = rf_envmap_load(c, info, name, eo, &bad, err, errlen)) < 0)
		return rc;
	if (bad)
		note(s, "'%s': replaced %zu NaN, infinite or out-of-range texel values with 0",
		     name, bad);
	return 0;
}

/* Loads `name` into e, as the chain the pass samples. */
static int
load_environment(rf_shader *s, const char *name, int from_header, struct environment *e,
                 char *err, size_t errlen)
{
	const struct rf_shader_options *o = &s->o;
	struct rf_envmap_options eo = o->envmap;
	struct rf_shade_env_options so;
	struct rf_chain_info info;
	rf_cubemap *c = NULL;
	int rc;

	s->line[0] = '\0';
	rf_cubemap_destroy(e->cube);
	e->cube = NULL;
	free(e->name);
	e->name = NULL;
	eo.from_header = from_header;
	eo.nthreads = s->nthreads;
	memset(&info, 0, sizeof(info));
	if (errlen)
		*err = '\0';
	rc = o->load ? o->load(o->load_arg, &c, &info, name, &eo, err, errlen)
	             : default_load(s, &c, &info, name, &eo, err, errlen);
	if (rc < 0)
		return rc;
	memset(&so, 0, sizeof(so));
	/* A mode tracing its own rays reads level 0: nothing to prefilter. */
	so.raw_ok = rf_plugin_traces_raw(o->mode);
	if (!info.prefiltered && !so.raw_ok) {
		size_t size = rf_cubemap_size(c), levels;
		char what[4200] = "", why[256];

		if (strcmp(name, "default"))
			snprintf(what, sizeof(what), " '%s'", name);
		if (rf_cubemap_levels(c) > 1 && o->verbose)
			note(s, "'%s' has box-filtered levels, not GGX ones: prefiltering its "
			     "level 0 (--prefiltered takes them as they are)", name);
		/* Worth a line: it is the slow part of a short pipeline.  Said
		 * when the prefilter starts, which a cached chain skips. */
		if (rf_chain_levels(size, 0, 1, &levels, why, sizeof(why)) == 0 && levels > 1)
			snprintf(s->line, sizeof(s->line), "prefiltering the environment%s "
			         "(%zux%zu per face, %zu levels)", what, size, size, levels);
	}
	so.mapping_set = o->mapping_set;
	so.mapping = o->mapping;
	so.steps = o->steps;
	so.samples = o->samples;
	so.as_given = o->envmap.prefiltered;
	so.nthreads = s->nthreads;
	if (o->progress) {
		so.progress = progress;
		so.progress_arg = s;
	}
	so.cache_dir = o->cache_dir;
	so.cache_bytes = o->cache_bytes;
	so.note = o->note;
	so.note_arg = o->note_arg;
	if ((rc = rf_shade_environment(&e->cube, &e->mapping, &e->steps, c, &info, name, &so,
	                               err, errlen)) < 0)
		return rc;
	if (!(e->name = strdup(name)))
		return bare(RF_ENOMEM, err, errlen);
	e->fresh = 1;
	e->has_sh9 = info.has_sh9;
	memcpy(e->sh9, info.sh9, sizeof(e->sh9));
	if (o->verbose)
		note(s, "environment '%s': %zu texels, %zu levels, mapping %s, steps %g", name,
		     rf_cubemap_size(e->cube), rf_cubemap_levels(e->cube),
		     rf_mapping_name(e->mapping), (double)e->steps);
	return 0;
}

int
rf_shader_create(rf_shader **sp, const struct rf_shader_options *o, char *err,
                 size_t errlen)
{
	struct rf_shade_options po;
	rf_shader *s;
	int rc;

	*sp = NULL;
	if (errlen)
		*err = '\0';
	if (!o->mode || o->mode->kind != RF_KIND_SHADE ||
	    (o->fallback == RF_BLEND_SKY && !o->sky)) {
		rf__format(err, errlen, "a shader needs a shade mode%s",
		           o->mode && o->mode->kind == RF_KIND_SHADE ? ", and a sky to fall "
		                                                       "back to" : "");
		return RF_EINVAL;
	}
	if (!(s = calloc(1, sizeof(*s))))
		return RF_ENOMEM;
	s->o = *o;
	if (!s->o.spec)
		s->o.spec = o->mode->name;
	s->nthreads = o->nthreads > 1 ? o->nthreads : 1;
	/* Loaded before the first frame: a sky that cannot be read is
	 * refused even where every frame has one probe and reads none. */
	if (o->fallback == RF_BLEND_SKY &&
	    (rc = load_environment(s, o->sky, 0, &s->env[RF_PROBES_MAX], err, errlen)) < 0) {
		rf_shader_destroy(s);
		return rc;
	}
	memset(&po, 0, sizeof(po));
	po.final = o->final;
	po.diffuse = o->diffuse;
	po.diffuse_box = o->diffuse_box;
	po.force_lod = o->force_lod;
	po.lod = o->lod;
	po.mode_radiance = rf_plugin_writes_radiance(o->mode);
	po.nthreads = s->nthreads;
	if ((rc = rf_shade_create(&s->pass, &po)) < 0 ||
	    (rc = rf_plugin_host_create(&s->host)) < 0) {
		rf_shader_destroy(s);
		return bare(rc, err, errlen);
	}
	*sp = s;
	return 0;
}

void
rf_shader_end_frame(rf_shader *s)
{
	uint32_t k;

	rf_stage_destroy(s->stage);
	s->stage = NULL;
	for (k = 1; k < RF_PROBES_MAX; k++) {
		rf_stage_destroy(s->stages[k]);
		rf_plugin_host_destroy(s->hosts[k]);
		s->stages[k] = NULL;
		s->hosts[k] = NULL;
	}
}

void
rf_shader_destroy(rf_shader *s)
{
	size_t k;

	if (!s)
		return;
	rf_shader_end_frame(s);
	/* its threads joined before the stages' environments go */
	rf_shade_destroy(s->pass);
	rf_plugin_host_destroy(s->host);
	for (k = 0; k <= RF_PROBES_MAX; k++) {
		rf_cubemap_destroy(s->env[k].cube);
		free(s->env[k].name);
	}
	free(s);
}

/* The mode's inputs, checked before the environment is loaded, so that a
 * stream that cannot be shaded fails at once, not after a prefilter. */
static int
check_frame(rf_shader *s, const rf_header *in, const float *center, char *err,
            size_t errlen)
{
	const struct rf_plugin *p = s->o.mode;
	rf_header *h, *out;
	size_t i;
	int rc;

	for (i = 0; p->inputs[i]; i++)
		if (rf_header_find_channel(in, p->inputs[i]) < 0) {
			char list[512] = "";
			size_t k = 0, j;

			for (j = 0; p->inputs[j] && k + 2 < sizeof(list); j++)
				k += (size_t)snprintf(list + k, sizeof(list) - k, "%s%s",
				                      j ? " " : "", p->inputs[j]);
			rf__format(err, errlen, "input has no channel '%s' (mode '%s' reads %s)",
			           p->inputs[i], p->name, list);
			return RF_EINVAL;
		}
	if (rf_header_find_channel(in, "mask") >= 0 && !center) {
		rf__format(err, errlen, "pixels with mask 0 show the environment seen from "
		           "the probe centre: give --center=X,Y,Z or a stream with "
		           "PROBE_CENTER");
		return RF_EINVAL;
	}
	if ((rc = rf_header_dup(&h, in)) < 0)
		return bare(rc, err, errlen);
	for (i = 0; p->outputs[i]; i++)
		if (rf_header_find_channel(h, p->outputs[i]) < 0)
			rf_header_add_channel(h, p->outputs[i]);
	rc = rf_shade_begin_frame(s->pass, h, center, &out, err, errlen);
	rf_header_destroy(h);
	return rc;
}

/* The frame's other probes, each with its environment (PROBEk_ENV), for
 * the pass to blend into s->blend; *n 0 when the frame has one probe or
 * blending is off, else how many. */
static int
set_blend(rf_shader *s, const rf_header *in, const struct rf_probe *first, uint32_t *n,
          char *err, size_t errlen)
{
	const struct rf_shader_options *o = &s->o;
	struct rf_blend *b = &s->blend;
	const rf_cubemap *envs[RF_PROBES_MAX + 1] = { NULL };
	enum rf_mapping mappings[RF_PROBES_MAX + 1];
	float steps[RF_PROBES_MAX + 1];
	char why[512], key[32];
	uint32_t k;
	int nb, rc;

	*n = 0;
	nb = o->blend ? rf_blend_read(b, in, why, sizeof(why)) : 0;
	if (nb < 0) {
		rf__format(err, errlen, "%s", why);
		return nb;
	}
	if (nb < 2 || !first) {
		rf__shade_set_blend(s->pass, NULL, NULL, NULL, NULL, o->fallback);
		return 0;
	}
	/* the first probe as the options made it */
	b->probes[0] = *first;
	b->max_probes = o->max_probes;
	b->normal_fade = o->normal_fade;
	rf_blend_order(b);
	for (k = 0; k < b->nprobes; k++) {
		struct environment *e = &s->env[k];
		const char *name = NULL;

		if (k) {
			snprintf(key, sizeof(key), "PROBE%u_ENV", (unsigned)k + 1);
			name = rf_header_get(in, key);
			if (!name || !*name)
				name = "default";
			if ((!e->name || strcmp(e->name, name)) &&
			    (rc = load_environment(s, name, 1, e, err, errlen)) < 0)
				return rc;
		}
		envs[k] = e->cube;
		mappings[k] = e->mapping;
		steps[k] = e->steps;
	}
	if (o->fallback == RF_BLEND_SKY) {
		struct environment *sky = &s->env[RF_PROBES_MAX];

		if (!sky->name && (rc = load_environment(s, o->sky, 0, sky, err, errlen)) < 0)
			return rc;
		envs[k] = sky->cube;
		mappings[k] = sky->mapping;
		steps[k] = sky->steps;
	}
	if ((rc = rf__shade_set_blend(s->pass, b, envs, mappings, steps, o->fallback)) < 0)
		return bare(rc, err, errlen);
	*n = b->nprobes;
	return 0;
}

/* For a mode that traces its own rays, a stage for each probe after the
 * first, its host holding that probe and its environment, begun as the
 * first stage was so that their rows line up. */
static int
blend_stages(rf_shader *s, const rf_header *in, char *err, size_t errlen)
{
	const struct rf_shader_options *o = &s->o;
	const struct rf_blend *b = &s->blend;
	const char *channel;
	rf_header *mid;
	uint32_t k;
	size_t c;
	int rc;

	for (k = 1; k < b->nprobes; k++) {
		const struct environment *e = &s->env[k];

		if ((rc = rf_plugin_host_create(&s->hosts[k])) < 0)
			return bare(rc, err, errlen);
		rf_plugin_host_set_frame(s->hosts[k], in);
		rf_plugin_host_set_probe(s->hosts[k], &b->probes[k]);
		if ((rc = rf_plugin_host_set_environment(s->hosts[k], e->cube, e->mapping,
		                                         e->steps)) < 0 ||
		    (rf_plugin_traces_raw(o->mode) &&
		     (rc = rf_plugin_host_set_radiance(s->hosts[k], e->cube)) < 0))
			return bare(rc, err, errlen);
		rf_plugin_host_set_seed(s->hosts[k], o->seed);
		if (errlen)
			*err = '\0';
		if ((rc = rf_stage_create(&s->stages[k], o->mode, o->values,
		                          rf_plugin_host_table(s->hosts[k]), s->nthreads, err,
		                          errlen)) < 0 ||
		    (rc = rf_stage_begin_frame(s->stages[k], in, &mid, err, errlen)) < 0)
			return rc;
		for (c = 0; (channel = rf_shade_channel(s->pass, c)); c++)
			if ((rc = rf_stage_reserve_channel(s->stages[k], channel)) < 0)
				return bare(rc, err, errlen);
	}
	if ((rc = rf__shade_set_blend_stages(s->pass, s->stages)) < 0)
		return bare(rc, err, errlen);
	return 0;
}

/* The SAMPLES the output's values are means of: a mode's whole-number
 * parameter samples= (reflect-plugin(7)), so that reflect-accumulate
 * weighs its frames by it; 0 for a mode without one, whose values are
 * no estimate to weigh. */
static uint64_t
mode_samples(const struct rf_shader_options *o)
{
	uint32_t i;

	for (i = 0; o->mode && o->values && i < o->mode->nparams; i++)
		if (!strcmp(o->mode->params[i].name, "samples") &&
		    (o->mode->params[i].flags & RF_PARAM_INTEGER) && o->values[i] >= 1.0 &&
		    o->values[i] <= (double)RF_SAMPLES_MAX)
			return (uint64_t)o->values[i];
	return 0;
}

/* What the output's header says of the shading, after the caller's keys. */
static int
set_keys(rf_shader *s, rf_header *out, const struct rf_probe *probe, char *err,
         size_t errlen)
{
	const struct rf_shader_options *o = &s->o;
	uint64_t samples = mode_samples(o);
	char steps[64], count[32];
	int rc;

	if (o->header && (rc = o->header(o->header_arg, out)) < 0)
		return bare(rc, err, errlen);
	snprintf(steps, sizeof(steps), "%.9g", (double)s->env[0].steps);
	snprintf(count, sizeof(count), "%llu", (unsigned long long)samples);
	if ((rc = samples ? rf_header_set(out, RF_KEY_SAMPLES, count)
	                  : rf_header_unset(out, RF_KEY_SAMPLES)) < 0 ||
	    (rc = rf_header_set(out, RF_KEY_SHADE, o->spec)) < 0 ||
	    (rc = rf_header_set(out, RF_KEY_ENV_MAPPING,
	                        rf_mapping_name(s->env[0].mapping))) < 0 ||
	    (rc = rf_header_set(out, RF_KEY_ENV_STEPS, steps)) < 0 ||
	    (o->env && (rc = rf_header_set(out, RF_KEY_PROBE_ENV, o->env)) < 0) ||
	    (probe && (rc = rf_probe_to_header(probe, out)) < 0)) {
		if (rc == RF_ENOMEM)
			return bare(rc, err, errlen);
		rf__format(err, errlen, "cannot write the output's header: a value is longer "
		           "than a header line (%d bytes)", RF_HEADER_LINE_MAX);
		return RF_EINVAL;
	}
	return 0;
}

int
rf_shader_begin_frame(rf_shader *s, const rf_header *in, rf_header **out, char *err,
                      size_t errlen)
{
	const struct rf_shader_options *o = &s->o;
	struct environment *env = &s->env[0];
	struct rf_probe probe;
	float centre[3], *center = NULL;
	char why[512];
	const char *name, *channel;
	rf_header *mid, *h;
	uint32_t nblend;
	size_t k;
	int rc, prc;

	*out = NULL;
	if (errlen)
		*err = '\0';
	rf_shader_end_frame(s);
	prc = rf_probe_resolve(&probe, in, o->box, o->center, o->projection, why,
	                       sizeof(why));
	if (prc < 0 && prc != RF_ENOTFOUND) {
		rf__format(err, errlen, "%s", why);
		return prc;
	}
	if (prc == 0) {
		center = probe.center;
	} else if (o->center) {
		double v[3];

		if (rf__scan_doubles(o->center, v, 3) < 0) {
			rf__format(err, errlen, "--center: '%s' needs 3 comma-separated numbers",
			           o->center);
			return RF_EINVAL;
		}
		for (k = 0; k < 3; k++)
			centre[k] = (float)v[k];
		center = centre;
	}
	/* Box projection off: the classic lookup along R for every mode, the
	 * distances infinite as for a probe without box projection. */
	rf__shade_set_unprojected(s->pass, prc == 0 && !probe.box_projection);
	rf__shade_set_env_frame(s->pass, prc == 0 && probe.rotated ? probe.rotation : NULL);
	rf_shade_set_probe(s->pass, prc == 0 && probe.box_projection ? &probe : NULL);
	if ((rc = check_frame(s, in, center, err, errlen)) < 0)
		return rc;

	name = o->env ? o->env : rf_header_get(in, RF_KEY_PROBE_ENV);
	if (!name || !*name)
		name = "default";
	if ((!env->name || strcmp(env->name, name)) &&
	    (rc = load_environment(s, name, !o->env, env, err, errlen)) < 0)
		return rc;
	if ((rc = set_blend(s, in, prc == 0 ? &probe : NULL, &nblend, err, errlen)) < 0)
		return rc;

	rf_plugin_host_set_frame(s->host, in);
	rf_plugin_host_set_probe(s->host, prc == 0 ? &probe : NULL);
	if ((rc = rf_plugin_host_set_environment(s->host, env->cube, env->mapping,
	                                         env->steps)) < 0 ||
	    /* the plain levels, made once per environment */
	    (env->fresh && rf_plugin_traces_raw(o->mode) &&
	     (rc = rf_plugin_host_set_radiance(s->host, env->cube)) < 0))
		return bare(rc, err, errlen);
	rf_plugin_host_set_seed(s->host, o->seed);
	if ((rc = rf_stage_create(&s->stage, o->mode, o->values, rf_plugin_host_table(s->host),
	                          s->nthreads, err, errlen)) < 0)
		return rc;
	if (prc == 0 && !probe.box_projection) {
		rf_stage_set_input_value(s->stage, "hit.dist", INFINITY);
		rf_stage_set_input_value(s->stage, "probe.dist", INFINITY);
	}
	rf_stage_set_invalid(s->stage, o->invalid);
	rf_shade_set_invalid(s->pass, o->invalid);
	if ((rc = rf_stage_begin_frame(s->stage, in, &mid, err, errlen)) < 0)
		return rc;
	/* The pass's channels, in the order it would append them, so that
	 * it shades the stage's rows in place. */
	for (k = 0; (channel = rf_shade_channel(s->pass, k)); k++)
		if ((rc = rf_stage_reserve_channel(s->stage, channel)) < 0)
			return bare(rc, err, errlen);
	if ((rc = rf_shade_begin_frame(s->pass, mid, center, &h, err, errlen)) < 0)
		return rc;
	if (nblend && rf_plugin_writes_radiance(o->mode) &&
	    (rc = blend_stages(s, in, err, errlen)) < 0)
		return rc;
	/* The pass keeps a copy of the levels: made once per environment. */
	if (env->fresh &&
	    (rc = rf_shade_set_environment(s->pass, env->cube, env->mapping, env->steps)) < 0)
		return bare(rc, err, errlen);
	if (env->fresh && env->has_sh9)
		rf_shade_set_irradiance(s->pass, env->sh9);
	env->fresh = 0;
	if ((rc = set_keys(s, h, prc == 0 ? &probe : NULL, err, errlen)) < 0)
		return rc;
	*out = h;
	return 0;
}

int
rf_shader_run(rf_shader *s, const float *in, float *out, size_t y, size_t nrows)
{
	if (!s->stage)
		return RF_EINVAL;
	return rf__shade_run_stage(s->pass, s->stage, in, out, y, nrows);
}

const char *
rf_shader_error(const rf_shader *s)
{
	if (s->stage && *rf_stage_error(s->stage))
		return rf_stage_error(s->stage);
	return rf_shade_error(s->pass);
}

size_t
rf_shader_invalid_count(const rf_shader *s)
{
	return (s->stage ? rf_stage_invalid_count(s->stage) : 0) +
	       rf_shade_invalid_count(s->pass);
}

size_t
rf_shader_invalid_output_count(const rf_shader *s)
{
	return s->stage ? rf_stage_invalid_output_count(s->stage) : 0;
}
