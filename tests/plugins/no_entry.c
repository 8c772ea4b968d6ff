/* Broken on purpose: a valid descriptor, exported under another name
 * than rf_plugin_entry. */
#include "testplugin.h"

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "no_entry", TEST_REST("test: no entry point")
};

RF_PLUGIN_EXPORT const struct rf_plugin *reflect_plugin_model(void);

const struct rf_plugin *
reflect_plugin_model(void)
{
	return &descriptor;
}
