/*
 * horizon: specular occlusion by the geometric horizon, for normal-mapped
 * and bumped surfaces: the share of the lobe's albedo that comes from
 * above the surface's real horizon (horizon.h).  Where N = Ng it is
 * exactly 1: flat and smooth objects are untouched, and a grazing view
 * is not darkened twice (the DFG term already took what falls below N's
 * horizon).  As roughness goes to 0 it becomes a path tracer's test: 1
 * for R above Ng's horizon, 0 below.  Only angles: scale invariant.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

#include "horizon.h"

enum { INTENSITY, SAMPLES, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "intensity", "how much of the occlusion is applied: lerp(1, so, intensity)", 0, 1, 1,
	  0, NULL },
	{ "samples", "points of the lobe a pixel whose N and Ng differ", 4, 4096, 128,
	  RF_PARAM_INTEGER, NULL },
};

static const char *const inputs[] = { "N.X", "N.Y", "N.Z", "Ng.X", "Ng.Y", "Ng.Z",
                                      "V.X", "V.Y", "V.Z", "roughness", NULL };
static const char *const outputs[] = { RF_OCCLUSION, NULL };

struct horizon {
	float intensity;
	int samples;
};

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct horizon *h;

	(void)host;
	if (!(h = malloc(sizeof(*h)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	h->intensity = (float)values[INTENSITY];
	h->samples = (int)values[SAMPLES];
	*state = h;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct horizon *h = state;
	const float *in = span->in;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 10) {
		double so = 1.0;

		if (in[9] == in[9] && !(in[0] == in[3] && in[1] == in[4] && in[2] == in[5]))
			so = horizon_share(in, in + 3, in + 6, in[9], h->samples);
		span->out[i] = (float)(1.0 - h->intensity * (1.0 - so));
	}
}

static void
destroy(void *state)
{
	free(state);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_OCCLUSION,
	.name = "horizon",
	.summary = "occlusion by the geometric horizon: the share of the lobe's albedo "
	           "from above Ng's horizon",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
