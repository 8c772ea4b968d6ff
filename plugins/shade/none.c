/* none: classic box projection; the lod comes from roughness only. */
#include "shade_mode.h"

static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	return shade_mode_create(host, values, 0, state, err, errlen);
}

static void
run(void *state, const struct rf_span *span)
{
	uint32_t i;

	(void)state;
	for (i = 0; i < span->npix; i++)
		span->out[i] = (float)sat(span->in[i]);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.name = "none",
	.summary = "classic box projection: the material's roughness, no contact hardening",
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
