/* Broken on purpose: built for plugin ABI 2.0.  Its descriptor is only
 * the three leading fields, as a 2.x descriptor may look like anything
 * after them: the host must stop after reading those three. */
#include <stdint.h>

#include "reflect/plugin.h"

struct abi2_descriptor {
	uint32_t abi_major, abi_minor, size;
};

static const struct abi2_descriptor descriptor = {
	2, 0, sizeof(struct abi2_descriptor)
};

RF_PLUGIN_EXPORT const void *rf_plugin_entry(void);

const void *
rf_plugin_entry(void)
{
	return &descriptor;
}
