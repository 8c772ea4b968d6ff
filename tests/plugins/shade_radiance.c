/* A shade mode that computes radiance itself through the host's
 * services (roughness_to_lod, sample), as a Monte-Carlo mode would: the
 * tests compare it with `none`, which the host samples.  Built a second
 * time with TEST_ABI_1_0 as shade_radiance_1_0: a mode of ABI 1.0, which
 * had no RF_PLUGIN_RADIANCE and said so by its outputs alone, and must
 * still work. */
#include <stddef.h>

#include "reflect/plugin.h"

static const char *const inputs[] = { "roughness", "D.X", "D.Y", "D.Z", NULL };
static const char *const outputs[] = { "spec.R", "spec.G", "spec.B", NULL };

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	(void)values;
	(void)err;
	(void)errlen;
	if (!host->sample || !host->roughness_to_lod)
		return -1;
	*state = (void *)host;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct rf_host *host = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 4, out += 3)
		host->sample(host->ctx, in + 1, host->roughness_to_lod(host->ctx, in[0]),
		             out);
}

static void
destroy(void *state)
{
	(void)state;
}

#ifdef TEST_ABI_1_0
#define MINOR 0
#define FLAGS 0
#define NAME "shade_radiance_1_0"
#else
#define MINOR RF_PLUGIN_ABI_MINOR
#define FLAGS RF_PLUGIN_RADIANCE
#define NAME "shade_radiance"
#endif

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, FLAGS, NAME,
	"test: radiance from the host's services, like none",
	"1.0", "reflect developers", "MIT",
	0, NULL, inputs, outputs, create, run, destroy,
};

RF_PLUGIN_DEFINE(descriptor)
