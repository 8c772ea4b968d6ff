/* Broken on purpose: claims ABI 1.0 but was built with a hand-made
 * header whose descriptor ends after `flags`: size says 20 bytes.  The
 * host must not read name, summary or anything else past size. */
#include <stdint.h>

#include "reflect/plugin.h"

struct short_descriptor {
	uint32_t abi_major, abi_minor, size, kind, flags;
};

static const struct short_descriptor descriptor = {
	RF_PLUGIN_ABI_MAJOR, 0, sizeof(struct short_descriptor),
	RF_KIND_PROJECTION, 0
};

RF_PLUGIN_EXPORT const void *rf_plugin_entry(void);

const void *
rf_plugin_entry(void)
{
	return &descriptor;
}
