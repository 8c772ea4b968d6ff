/* Broken on purpose: built for plugin ABI 1.99, a minor version newer
 * than any host of this test knows; its descriptor has the fields a 1.99
 * header would have appended. */
#include "testplugin.h"

struct abi1_99_descriptor {
	struct rf_plugin base;
	const char *added_in_1_99;
};

static const struct abi1_99_descriptor descriptor = {
	{ 1, 99, sizeof(struct abi1_99_descriptor), RF_KIND_PROJECTION, 0,
	  "bad_minor", TEST_REST("test: ABI 1.99") },
	"a field this host has never heard of",
};

RF_PLUGIN_DEFINE(descriptor.base)
