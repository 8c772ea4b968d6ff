/* A valid plugin of the wrong kind for reflect-project: a shade mode
 * (a roughness model that keeps the roughness as it is). */
#include "testplugin.h"

static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };

static void
run(void *state, const struct rf_span *span)
{
	uint32_t i;

	(void)state;
	for (i = 0; i < span->npix; i++)
		span->out[i] = span->in[i];
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, 0, "shade_kind", "test: a shade mode", "1.0", "reflect tests",
	"MIT", 0, NULL, inputs, outputs, test_create, run, test_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
