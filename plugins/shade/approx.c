/*
 * approx: the write-up's contact hardening ("Approximated"), spec 4.1.
 * In mips it is lerp(0, 6 pr, d / 6); read linearly (pr' = mip / 6,
 * spec Part A #1) and with the 6 metres a parameter (Part A #2):
 *   pr' = pr * clamp(d, 0, distance) / distance      (clamp=1)
 *   pr' = clamp(pr * d / distance, 0, 1)             (clamp=0)
 * so a reflection is sharp at contact and reaches the material's
 * roughness `distance` metres away.
 */
#include "shade_mode.h"

enum { CLAMP, DISTANCE, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "clamp", "never rougher than the material (the original's toggle)",
	  0, 1, 1, RF_PARAM_BOOL, NULL },
	{ "distance", "hit distance in world units at which the material's "
	  "roughness is reached", 1e-6, 1e6, 6, 0, NULL },
};

static const char *const inputs[] = { "roughness", "hit.dist", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };

static double
approx(double pr, double d, int clamp, double distance)
{
	pr = sat(pr);
	if (no_hit(d))
		return pr;
	if (clamp)
		d = d > 0.0 ? (d < distance ? d : distance) : 0.0;
	/* d / distance is exactly 1 at d = distance: pr comes back as is. */
	return sat(pr * (d / distance));
}

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	return shade_mode_create(host, values, NPARAMS, state, err, errlen);
}

static void
run(void *state, const struct rf_span *span)
{
	const struct shade_mode *m = state;
	const float *in = span->in;
	int clamp = m->p[CLAMP] != 0.0;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 2)
		span->out[i] = (float)approx(in[0], in[1], clamp, m->p[DISTANCE]);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.name = "approx",
	.summary = "the write-up's contact hardening: roughness grows with the hit distance",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = shade_mode_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
