/*
 * hdrp: Frostbite's distance-based roughness as the write-up's
 * "ApproximatedHDRP" mode computes it (spec 5.1), with t the hit
 * distance along R and |R'| the distance from the capture point to the
 * hit:
 *   c   = clamp(pr t / |R'|, 0, pr)
 *   pr' = lerp(c, pr, pr)
 * Scale invariant; never rougher than pr; pr = 1 is unchanged.  Edge
 * cases (spec 5.2, Part A #3): pr = 0 gives 0 (also where |R'| = 0, the
 * original's 0 * inf = NaN); |R'| = 0 with pr > 0 gives the limit c = pr;
 * t <= 0 gives c = 0, so pr' = pr^2; no hit gives pr.
 */
#include "shade_mode.h"

static const char *const inputs[] = { "roughness", "hit.dist", "probe.dist", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };

static double
hdrp(double pr, double t, double r_len)
{
	double c;

	pr = sat(pr);
	if (pr == 0.0)
		return 0.0;
	if (no_hit(t))
		return pr;
	if (!(t > 0.0))
		c = 0.0; /* contact, or behind (a point outside the box) */
	else if (!(r_len > 0.0))
		c = pr; /* the hit is the capture point: pr t / 0 = inf */
	else
		c = pr * (t / r_len);
	if (c >= pr)
		return pr; /* exactly, not c + pr (pr - c) rounded */
	/* lerp(c, pr, pr) = c + pr (pr - c), written so that pr = 1 gives
	 * exactly 1. */
	return sat(pr * pr + c * (1.0 - pr));
}

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	return shade_mode_create(host, values, 0, state, err, errlen);
}

static void
run(void *state, const struct rf_span *span)
{
	const float *in = span->in;
	uint32_t i;

	(void)state;
	for (i = 0; i < span->npix; i++, in += 3)
		span->out[i] = (float)hdrp(in[0], in[1], in[2]);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.name = "hdrp",
	.summary = "frostbite/hdrp distance-based roughness: pr t / |R'|, faded by roughness",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = shade_mode_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
