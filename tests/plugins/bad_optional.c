/* Broken on purpose: an optional input (ABI 1.1) that is also one of its
 * inputs. */
#include "testplugin.h"

static const char *const optional[] = { "Ng.X", "N.X", NULL };

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "bad_optional", TEST_REST("test: an input twice"), optional
};

RF_PLUGIN_DEFINE(descriptor)
