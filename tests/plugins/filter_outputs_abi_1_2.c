/* Broken on purpose: a filter mode built for plugin ABI 1.2, whose filter
 * modes name no outputs, yet it names a row carried from pass to pass
 * (ABI 1.3). */
#include "testplugin.h"

static const char *const none[] = { NULL };
static const char *const carried[] = { "variance", NULL };

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, 2, sizeof(struct rf_plugin),
	RF_KIND_FILTER, 0, "filter_outputs_abi_1_2",
	"test: a 1.3 carried row in a 1.2 filter", "1.0", "reflect tests", "MIT", 0, NULL,
	none, carried, test_create, test_run, test_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
