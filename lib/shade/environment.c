/*
 * The environment a shading pass samples: a GGX chain, with the mapping
 * and steps it was made with.  A raw environment, or a chain of plain
 * box-filtered levels, is prefiltered here first; a chain made with one
 * mapping is never sampled with another, which would pick the wrong
 * levels, unless the caller says the options describe a chain another
 * tool made (reflect-shade --prefiltered).
 */
#include <stdio.h>
#include <string.h>

#include "shade/cache.h"
#include "util/util.h"
#include "reflect/shading.h"

/* " 'name'", or nothing for the embedded room. */
static void
quoted(char *buf, size_t size, const char *name)
{
	if (name && strcmp(name, "default"))
		snprintf(buf, size, " '%s'", name);
	else if (size)
		*buf = '\0';
}

static int
prefilter(rf_cubemap **env, float *steps, const rf_cubemap *src, const char *name,
          enum rf_mapping mapping, const struct rf_shade_env_options *o, char *err,
          size_t errlen)
{
	struct rf_prefilter_options pf;
	size_t size = rf_cubemap_size(src), levels;
	uint64_t key = 0;
	char what[4200];
	int rc;

	quoted(what, sizeof(what), name);
	if ((rc = rf_chain_levels(size, 0, 1, &levels, err, errlen)) < 0)
		return rc;
	if (levels < 2) {
		rf__format(err, errlen, "the environment%s is %zu texels a face: too small "
		           "to prefilter into levels", what, size);
		return RF_EINVAL;
	}
	rf_prefilter_defaults(&pf);
	pf.mapping = mapping;
	pf.steps = o->steps > 0.0f ? o->steps : (float)(levels - 1);
	if (o->samples)
		pf.samples = o->samples;
	pf.nthreads = o->nthreads;
	pf.progress = o->progress;
	pf.progress_arg = o->progress_arg;
	if ((rc = rf_cubemap_check_size(size, levels, err, errlen)) < 0)
		return rc;
	if (o->cache_dir) {
		struct rf_chain_info want;
		char why[1024], note[1200];

		memset(&want, 0, sizeof(want));
		want.mapping = mapping;
		want.steps = pf.steps;
		want.samples = pf.samples;
		key = rf__env_cache_key(src, mapping, pf.steps, pf.samples, levels);
		rc = rf__env_cache_get(o->cache_dir, key, src, levels, &want, env, why,
		                       sizeof(why));
		if (rc == 0) {
			*steps = pf.steps;
			return 0;
		}
		/* made again below, and written over the bad one */
		if (rc == RF_EINVAL && o->note) {
			rf__format(note, sizeof(note), "cache entry %s; prefiltering%s again",
			           why, what);
			o->note(o->note_arg, note);
		}
	}
	if ((rc = rf_cubemap_create(env, size, levels)) < 0)
		return rc;
	/* done 0 of 1: the prefilter starts (a cache hit never says so) */
	if (o->progress)
		o->progress(o->progress_arg, 0.0, 1.0);
	if ((rc = rf_prefilter(src, *env, &pf, err, errlen)) < 0) {
		rf_cubemap_destroy(*env);
		*env = NULL;
		return rc;
	}
	*steps = pf.steps;
	if (o->cache_dir) {
		struct rf_chain_info info;

		memset(&info, 0, sizeof(info));
		info.prefiltered = 1;
		info.mapping = mapping;
		info.steps = pf.steps;
		info.samples = pf.samples;
		info.base_copied = 1;
		/* a cache that cannot be written is no reason to fail */
		(void)rf__env_cache_put(o->cache_dir, key, *env, &info,
		                        o->cache_bytes ? o->cache_bytes : (size_t)256 << 20);
	}
	return 0;
}

int
rf_shade_environment(rf_cubemap **env, enum rf_mapping *mapping, float *steps,
                     rf_cubemap *loaded, const struct rf_chain_info *info,
                     const char *name, const struct rf_shade_env_options *o,
                     char *err, size_t errlen)
{
	size_t levels = rf_cubemap_levels(loaded);
	float chain_steps;
	int rc;

	*env = NULL;
	*mapping = o->mapping_set ? o->mapping : RF_MAPPING_DEFAULT;
	if (!info->prefiltered && o->raw_ok) {
		*env = loaded;
		*steps = (float)(levels - 1);
		return 0;
	}
	if (!info->prefiltered) {
		rc = prefilter(env, steps, loaded, name, *mapping, o, err, errlen);
		rf_cubemap_destroy(loaded);
		return rc;
	}
	chain_steps = info->steps > 0.0f ? info->steps : (float)(levels - 1);
	if (!o->as_given && ((o->mapping_set && o->mapping != info->mapping) ||
	                     (o->steps > 0.0f && o->steps != chain_steps))) {
		rf__format(err, errlen, "'%s' was prefiltered with mapping %s and steps %g; "
		           "--mapping and --steps must agree (or give --prefiltered to "
		           "override them)", name ? name : "default",
		           rf_mapping_name(info->mapping), (double)chain_steps);
		rf_cubemap_destroy(loaded);
		return RF_EINVAL;
	}
	*mapping = o->as_given && o->mapping_set ? o->mapping : info->mapping;
	*steps = o->as_given && o->steps > 0.0f ? o->steps : chain_steps;
	*env = loaded;
	return 0;
}
