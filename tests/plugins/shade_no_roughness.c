/* Broken on purpose: a shade mode that writes neither roughness.eff nor
 * (with RF_PLUGIN_RADIANCE) spec.R spec.G spec.B. */
#include "testplugin.h"

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, 0, "shade_no_roughness", TEST_REST("test: no shade output")
};

RF_PLUGIN_DEFINE(descriptor)
