/* Broken on purpose: a shade mode that says it writes radiance
 * (RF_PLUGIN_RADIANCE) but outputs roughness.eff. */
#include "testplugin.h"

static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, RF_PLUGIN_RADIANCE, "radiance_no_spec",
	"test: radiance flag without spec", "1.0", "reflect tests", "MIT", 0, NULL,
	inputs, outputs, test_create, test_run, test_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
