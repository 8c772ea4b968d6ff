/* infinite: no parallax; the environment is taken as infinitely far. */
#include <math.h>

#include "reflect/plugin.h"

#include "probe/projection.h"

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
		rf__reflection_vector(in, in + 3, out);
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
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_PROJECTION,
	.name = "infinite",
	.summary = "no parallax: look up the reflection vector itself (distant environment)",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
