/*
 * godot: the fresnel-aware contact hardening Godot merged (spec 6.2, the
 * write-up's "ApproximatedGodot" 6.1), in perceptual roughness (Godot's
 * sqrt(roughness) is pr; its mip_min = r^2 LOD is pr^4):
 *   F   = (1 - max(N.V, 0))^power
 *   x   = sat(d (1 - F) / distance + (1 - F) pr)
 *   pr' = lerp(pr^4, pr, x)
 * Sharp at grazing angles and at contact; pr = 1 and pr = 0 are
 * unchanged; no hit gives pr.
 */
#include "shade_mode.h"

enum { POWER, DISTANCE, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "power", "exponent of the grazing factor (1 - N.V)^power (godot: 4; "
	  "the write-up's demo: 2)", 0, 64, 4, 0, NULL },
	{ "distance", "hit distance in world units over which hardening fades "
	  "(the original's 6)", 1e-6, 1e6, 6, 0, NULL },
};

static const char *const inputs[] = {
	"roughness", "hit.dist", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", NULL
};
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };

/* x^n for a whole n by squaring: the default power 4 is two multiplies
 * where pow() costs more than the rest of the mode. */
static double
whole_power(double x, unsigned n)
{
	double r = 1.0;

	for (; n; n >>= 1, x *= x)
		if (n & 1)
			r *= x;
	return r;
}

/* whole: the power as a whole number, or -1 when it has a fraction. */
static double
godot(const float *in, double power, int whole, double distance)
{
	double pr = sat(in[0]), d = in[1], nv, f, x, lo;

	if (no_hit(d))
		return pr;
	nv = sat((double)in[2] * in[5] + (double)in[3] * in[6] + (double)in[4] * in[7]);
	f = whole >= 0 ? whole_power(1.0 - nv, (unsigned)whole) : pow(1.0 - nv, power);
	x = sat(d * (1.0 - f) / distance + (1.0 - f) * pr);
	if (x >= 1.0)
		return pr; /* exactly, not lo + (pr - lo) rounded */
	lo = pr * pr * pr * pr;
	return sat(lo + (pr - lo) * x);
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
	const double power = m->p[POWER], distance = m->p[DISTANCE];
	const int whole = power == floor(power) ? (int)power : -1; /* once, not a pixel */
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 8)
		span->out[i] = (float)godot(in, power, whole, distance);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.name = "godot",
	.summary = "godot's fresnel-aware contact hardening, from pr^4 at contact to pr",
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
