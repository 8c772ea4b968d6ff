/* Broken on purpose: RF_PLUGIN_RADIANCE on a projection mode, which
 * writes no radiance. */
#include "testplugin.h"

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, RF_PLUGIN_RADIANCE, "radiance_projection",
	TEST_REST("test: radiance flag on a projection")
};

RF_PLUGIN_DEFINE(descriptor)
