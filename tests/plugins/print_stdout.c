/* Broken on purpose: a projection mode that prints to standard output,
 * as a printf left in from debugging does, in its constructor, create()
 * and run(), through stdio and through the descriptor (but with quiet=1,
 * for the clean run to compare with).  The stream must not carry a byte
 * of it. */
#include <stdio.h>
#include <unistd.h>

#include "testplugin.h"

__attribute__((constructor)) static void
loaded(void)
{
	printf("print_stdout: loaded\n");
	fflush(stdout);
}

static const struct rf_param params[] = {
	{ "quiet", "print nothing", 0, 1, 0, RF_PARAM_BOOL, NULL },
};

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	static int quiet = 1;

	test_create(host, values, state, err, errlen);
	if (values[0] == 0.0) {
		printf("print_stdout: create\n");
		fflush(stdout);
	}
	/* the state is the switch (test_create leaves it NULL) */
	*state = values[0] == 0.0 ? NULL : &quiet;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	static const char raw[] = "print_stdout: raw\n";

	if (!state) {
		printf("print_stdout: row %u\n", (unsigned)span->y);
		fflush(stdout);
		if (write(STDOUT_FILENO, raw, sizeof(raw) - 1) < 0) {
			/* nothing to do */
		}
	}
	test_run(NULL, span);
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "print_stdout", "test: prints to standard output",
	"1.0", "reflect tests", "MIT", 1, params, test_inputs, test_outputs,
	create, run, test_destroy, NULL
};

RF_PLUGIN_DEFINE(descriptor)
