/* box: the classic box projection of the reflection vector. */
#include <math.h>

#include "reflect/plugin.h"

#include "reflection.h"

static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", NULL
};
static const char *const outputs[] = {
	"R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z", "hit.dist", "probe.dist", NULL
};

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	return reflection_create(host, state, err, errlen);
}

static void
run(void *state, const struct rf_span *span)
{
	const struct rf_probe *probe = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 9, out += 8) {
		reflection_vector(in + 3, in + 6, out);
		if (!probe->box_projection ||
		    box_exit(probe, in, out, &out[6]) != 0) {
			out[3] = out[0];
			out[4] = out[1];
			out[5] = out[2];
			out[6] = out[7] = INFINITY;
			continue;
		}
		lookup_from_hit(probe, in, out, out[6], out + 3, &out[7]);
	}
}

static void
destroy(void *state)
{
	(void)state;
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0,
	"box",
	"box projection: look up where the reflected ray leaves the probe box",
	"1.0", "reflect developers", "MIT",
	0, NULL, inputs, outputs,
	create, run, destroy,
};

RF_PLUGIN_DEFINE(descriptor)
