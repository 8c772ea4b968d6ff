/* Broken on purpose: a parameter sets flag bit 0x10, which plugin ABI 1.0
 * does not define. */
#include "testplugin.h"

static const struct rf_param params[] = {
	{ "gain", "a gain", 0, 10, 1, RF_PARAM_INTEGER | 0x10u, NULL },
};

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "bad_param_flags",
	"test: unknown parameter flags", "1.0", "reflect tests", "MIT",
	1, params, test_inputs, test_outputs, test_create, test_run, test_destroy
};

RF_PLUGIN_DEFINE(descriptor)
