/* Broken on purpose: built for plugin ABI 1.0, which defines no
 * descriptor flags, yet it sets RF_PLUGIN_RADIANCE (a 1.1 flag). */
#include "testplugin.h"

static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { "spec.R", "spec.G", "spec.B", NULL };

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, 0, sizeof(struct rf_plugin),
	RF_KIND_SHADE, RF_PLUGIN_RADIANCE, "flags_abi_1_0",
	"test: a 1.1 flag in a 1.0 plugin", "1.0", "reflect tests", "MIT", 0, NULL,
	inputs, outputs, test_create, test_run, test_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
