/* Broken on purpose: an accumulate mode that reads channels by name and
 * whose state does not start with value and variance. */
#include "testplugin.h"

static const char *const inputs[] = { "spec.R", NULL };
static const char *const outputs[] = { "sum", NULL };

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_ACCUMULATE, 0, "accumulate_channels",
	"test: an accumulate mode breaking its contract", "1.0", "reflect tests", "MIT", 0,
	NULL, inputs, outputs, test_create, test_run, test_destroy,
};

RF_PLUGIN_DEFINE(descriptor)
