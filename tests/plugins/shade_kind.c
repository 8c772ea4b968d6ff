/* A valid plugin of the wrong kind for reflect-project: a shade mode. */
#include "testplugin.h"

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, 0, "shade_kind", TEST_REST("test: a shade mode")
};

RF_PLUGIN_DEFINE(descriptor)
