/* Broken on purpose: descriptor flags 0x4, which plugin ABI 1.0 does not
 * define (it defines none). */
#include "testplugin.h"

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0x4u, "bad_flags", TEST_REST("test: unknown flags")
};

RF_PLUGIN_DEFINE(descriptor)
