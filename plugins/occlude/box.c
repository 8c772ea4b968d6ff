/*
 * box: the write-up's box-based specular occlusion.  The reflection
 * darkens where the reflected ray meets the probe's shape close by:
 * so = sat(multiplier (d / unit)^power), the reflection times
 * lerp(1, so, intensity), d the stream's hit.dist, so it follows
 * whatever projection made it (the bevel too, where the write-up always
 * used the plain box).  unit is 1 world unit (the write-up's, so a room
 * twice as large darkens half as wide), or with scale=box the smallest
 * half extent of the shape the lookups leave by (the probe's proxy: its
 * box, turned or not, or a sphere's radius): the same picture at any
 * scale.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

#include "probe/shape.h"

enum { INTENSITY, MULTIPLIER, POWER, SCALE, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "intensity", "how much of the occlusion is applied: lerp(1, so, intensity)", 0, 1, 1,
	  0, NULL },
	{ "multiplier", "so = sat(multiplier (d / unit)^power)", 0, HUGE_VAL, 1, 0, NULL },
	{ "power", "the exponent of the distance", 0, HUGE_VAL, 1, 0, NULL },
	{ "scale", "the unit of d: a world unit (the write-up's), or the box's smallest half "
	  "extent (scale invariant)", 0, 1, 0, RF_PARAM_CHOICE, "world|box" },
};

static const char *const inputs[] = { "hit.dist", NULL };
static const char *const outputs[] = { RF_OCCLUSION, NULL };

struct box_occlusion {
	float intensity, multiplier, power, inv_unit;
};

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct box_occlusion *o;
	float unit = 1.0f;

	if (values[SCALE] != 0.0) {
		struct rf_probe proxy;
		struct rf__frame frame;
		int i, rotated;

		if (!host->probe) {
			snprintf(err, errlen, "scale=box needs the probe box: give a stream with "
			         "PROBE_BOX (reflect-project writes it)");
			return -1;
		}
		if (rf__probe_proxy_aligned(host->probe, &proxy, &frame, &rotated) ==
		    RF_SHAPE_INFINITE) {
			snprintf(err, errlen, "scale=box needs a size, and the probe's proxy is "
			         "infinite: give scale=world");
			return -1;
		}
		unit = INFINITY;
		for (i = 0; i < 3; i++) {
			float h = 0.5f * (proxy.box_max[i] - proxy.box_min[i]);

			unit = h < unit ? h : unit;
		}
	}
	if (!(o = calloc(1, sizeof(*o)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	o->intensity = (float)values[INTENSITY];
	o->multiplier = (float)values[MULTIPLIER];
	o->power = (float)values[POWER];
	o->inv_unit = 1.0f / unit;
	*state = o;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct box_occlusion *o = state;
	uint32_t i;

	for (i = 0; i < span->npix; i++) {
		float d = span->in[i], so = 1.0f;

		/* behind the point (outside the box) counts as touching it;
		 * nothing ahead (+inf) occludes nothing */
		if (!(d > 0.0f))
			d = 0.0f;
		if (d < INFINITY) {
			/* a product past the float range is 0 x inf where one
			 * factor is 0 (multiplier=0, or d = 0 with a multiplier too
			 * large for a float), NaN, and so 0 as its limit is */
			so = o->multiplier * powf(d * o->inv_unit, o->power);
			so = so > 0.0f ? (so < 1.0f ? so : 1.0f) : 0.0f;
		}
		span->out[i] = 1.0f - o->intensity * (1.0f - so);
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
	.name = "box",
	.summary = "the write-up's occlusion: darker where the reflected ray meets the box "
	           "close by",
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
