/*
 * bevel_original: the write-up's bevel box projection as it is, to
 * picture its artefacts beside reflect's bevel (doc/pictures): the
 * rounded box centred on the capture point, grown by the radius beyond
 * the box (its offset off) or shrunk into it (offset on), exited by its
 * flipped intersector (tests/unit/bevel-original.h), and the lookup
 * o + t R even where that returned -1.  A test plugin, never installed.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

#include "../unit/bevel-original.h"

static const struct rf_param params[] = {
	{ "radius", "the write-up's bevel factor, world units", 0, HUGE_VAL, 0.7, 0, NULL },
	{ "offset", "the write-up's offset: shrink the box by the radius", 0, 1, 0,
	  RF_PARAM_BOOL, NULL },
};
static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", NULL
};
static const char *const outputs[] = {
	"R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z", "hit.dist", "probe.dist", NULL
};

struct original {
	float c[3], size[3], rad;
};

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct original *o;
	int i;

	if (!host->probe) {
		snprintf(err, errlen, "no probe box");
		return -1;
	}
	if (!(o = malloc(sizeof(*o)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	o->rad = (float)values[0];
	for (i = 0; i < 3; i++) {
		o->c[i] = host->probe->center[i];
		o->size[i] = 0.5f * (host->probe->box_max[i] - host->probe->box_min[i]);
		if (values[1] != 0.0)
			o->size[i] -= o->rad;
	}
	*state = o;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct original *o = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 9, out += 8) {
		const float *n = in + 3, *v = in + 6;
		float nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2], r[3], ro[3], d[3], t, len = 0;
		int k;

		for (k = 0; k < 3; k++) {
			r[k] = 2.0f * nv * n[k] - v[k];
			len += r[k] * r[k];
		}
		len = sqrtf(len);
		for (k = 0; k < 3; k++) {
			r[k] /= len;
			ro[k] = in[k] - o->c[k];
		}
		t = original_exit(o->size, o->rad, ro, r);
		len = 0;
		for (k = 0; k < 3; k++) {
			d[k] = ro[k] + r[k] * t; /* -1 used as a distance, as it was */
			len += d[k] * d[k];
		}
		len = sqrtf(len);
		for (k = 0; k < 3; k++) {
			out[k] = r[k];
			out[3 + k] = len > 0 ? d[k] / len : r[k];
		}
		out[6] = t;
		out[7] = len;
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
	.kind = RF_KIND_PROJECTION,
	.name = "bevel_original",
	.summary = "test: the write-up's bevel box projection, artefacts and all",
	.version = "1.0",
	.author = "reflect tests",
	.license = "MIT",
	.nparams = 2,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
