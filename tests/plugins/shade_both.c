/* Broken on purpose: a shade mode writing roughness.eff and spec.R G B,
 * one of which the host would drop. */
#include "testplugin.h"

static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, RF_SHADE_SPEC_R, RF_SHADE_SPEC_G,
                                       RF_SHADE_SPEC_B, NULL };

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, 0, "shade_both",
	"test: roughness and radiance both", "1.0", "reflect tests", "MIT", 0, NULL,
	inputs, outputs, test_create, test_run, test_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
