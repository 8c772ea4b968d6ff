/* Broken on purpose: the descriptor has no summary. */
#include "testplugin.h"

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "no_summary", TEST_REST(NULL)
};

RF_PLUGIN_DEFINE(descriptor)
