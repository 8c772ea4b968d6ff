/*
 * ratio: a shade mode for reflect-shade(1), an effective-roughness model
 * of contact hardening.
 *
 * A reflection blurs with the lobe's width where it meets the wall, but
 * the probe was captured from C: seen from C, the same blur on the wall
 * spans an angle d / L times the lobe's, d the distance from the surface
 * to the hit and L from C to it.  So the probe is read with the lobe
 * narrowed by that ratio:
 *   alpha' = alpha lerp(1, min(1, d / L), strength),   alpha = r^2,
 * r the material's perceptual roughness, and the mode writes
 * roughness.eff = sqrt(alpha'), which the host turns into a lod with the
 * environment's own roughness-to-lod mapping.  Scale invariant (a ratio
 * of distances); at contact (d = 0) a mirror; where the hit is farther
 * from the surface than from C the lobe is kept as it is.
 *
 * Inputs: roughness, hit.dist and probe.dist (from reflect-project).
 * Build and run (doc/examples/Makefile does the first):
 *   cc -std=c11 -fPIC -shared $(pkg-config --cflags reflect-plugin) \
 *       ratio.c -o ratio.so -lm
 *   REFLECT_PLUGIN_PATH=$PWD reflect-shade -m ratio:strength=0.5 scene.rfl
 *
 * This file is in the public domain: copy it to start a plugin.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <reflect/plugin.h>

enum { STRENGTH, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "strength", "how much of the narrowing is applied (0: the material's roughness)",
	  0, 1, 1, 0, NULL },
};

/* A shade mode writes roughness.eff (RF_SHADE_ROUGHNESS); the host then
 * samples the environment along D at its lod. */
static const char *const inputs[] = { "roughness", "hit.dist", "probe.dist", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	float *strength;

	(void)host;
	if (!(strength = malloc(sizeof(*strength)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	*strength = (float)values[STRENGTH];
	*state = strength;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const float k = *(const float *)state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 3) {
		float r = in[0], d = in[1], l = in[2], ratio = 1.0f, alpha;

		/* +inf distances (no box, box projection off): no parallax */
		if (d >= 0.0f && l > 0.0f && d < INFINITY && l < INFINITY)
			ratio = d < l ? d / l : 1.0f;
		alpha = r * r * (1.0f + k * (ratio - 1.0f));
		out[i] = sqrtf(alpha > 0.0f ? alpha : 0.0f);
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
	.kind = RF_KIND_SHADE,
	.name = "ratio",
	.summary = "example: the lobe narrowed by the ratio of the hit's distances",
	.version = "1.0",
	.author = "reflect developers",
	.license = "public domain",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
