/* Broken on purpose: a parameter whose default lies outside its range. */
#include "testplugin.h"

static const struct rf_param params[] = {
	{ "gain", "a gain", 0, 10, 12, 0, NULL },
};

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "bad_param_range",
	"test: a default outside the range", "1.0", "reflect tests", "MIT",
	1, params, test_inputs, test_outputs, test_create, test_run, test_destroy
};

RF_PLUGIN_DEFINE(descriptor)
