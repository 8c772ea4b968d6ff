/* No plugin at all: a library that lies beside the plugins (libfoo.so
 * a plugin links with, say).  Its constructor says on standard error
 * that it ran, which no tool may make it do: it exports no
 * rf_plugin_entry, so it is never loaded. */
#include <unistd.h>

#include "reflect/plugin.h"

__attribute__((constructor)) static void
announce(void)
{
	static const char msg[] = "not_plugin: constructor ran\n";

	if (write(STDERR_FILENO, msg, sizeof(msg) - 1) < 0) {
		/* nowhere to tell */
	}
}

RF_PLUGIN_EXPORT int not_plugin_helper(int x);

int
not_plugin_helper(int x)
{
	return x + 1;
}
