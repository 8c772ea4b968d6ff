/* Broken on purpose: a plugin of ABI 1.0 with a string parameter, which
 * came with ABI 1.1. */
#include "testplugin.h"

static const struct rf_param params[] = {
	{ "table", "a file", 0, 0, 0, RF_PARAM_STRING, NULL },
};

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, 0, 120, RF_KIND_PROJECTION, 0, "string_abi_1_0",
	"test: a string parameter in ABI 1.0", "1.0", "reflect tests", "MIT",
	1, params, test_inputs, test_outputs, test_create, test_run, test_destroy, NULL
};

RF_PLUGIN_DEFINE(descriptor)
