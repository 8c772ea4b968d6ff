/* infinite: no parallax; the environment is taken as infinitely far. */
#include <math.h>

#include "reflect/plugin.h"

#include "reflection.h"

static const char *const inputs[] = {
	"N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", NULL
};
static const char *const outputs[] = {
	"R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z", "hit.dist", "probe.dist", NULL
};

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	*state = NULL;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 6, out += 8) {
		reflection_vector(in, in + 3, out);
		out[3] = out[0];
		out[4] = out[1];
		out[5] = out[2];
		out[6] = out[7] = INFINITY;
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
	"infinite",
	"no parallax: look up the reflection vector itself (distant environment)",
	"1.0", "reflect developers", "MIT",
	0, NULL, inputs, outputs,
	create, run, destroy,
};

RF_PLUGIN_DEFINE(descriptor)
