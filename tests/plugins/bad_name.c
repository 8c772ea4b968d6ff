/* Broken on purpose: the file is bad_name.so, the descriptor says
 * "other_name". */
#include "testplugin.h"

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "other_name", TEST_REST("test: name mismatch")
};

RF_PLUGIN_DEFINE(descriptor)
