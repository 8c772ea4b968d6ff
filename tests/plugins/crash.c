/* Broken on purpose: a projection mode that crashes in run() at a row
 * (or in create()), in the way `how` says: a write through NULL, a
 * stack that runs out, an illegal instruction, abort(), or SIGBUS and
 * SIGFPE as the kernel would send them.  The tool must name the mode,
 * its file, the frame and the row, and die of the same signal. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>

#include "testplugin.h"

enum { SEGV, STACK, ILL, ABORT, BUS, FPE, NONE };

static const struct rf_param params[] = {
	{ "how", "the way it crashes", 0, 6, 0, RF_PARAM_CHOICE,
	  "segv|stack|ill|abort|bus|fpe|none" },
	{ "row", "the row whose run() crashes", 0, 1e6, 0, RF_PARAM_INTEGER, NULL },
	{ "in_create", "crash in create() instead", 0, 1, 0, RF_PARAM_BOOL, NULL },
};

struct crash {
	int how;
	uint32_t row;
};

static int nowhere_depth;

/* Not a tail call, and a frame the compiler cannot drop. */
static int
recurse(volatile char *above)
{
	volatile char frame[256];

	frame[0] = above ? above[0] : 1;
	nowhere_depth++;
	return recurse(frame) + frame[0];
}

static void
crash_now(int how)
{
	switch (how) {
	case SEGV:
		*(volatile int *)(uintptr_t)8 = 1;
		break;
	case STACK:
		nowhere_depth = recurse(NULL);
		break;
	case ILL:
		__builtin_trap();
		break;
	case ABORT:
		abort();
		break;
	case BUS:
		raise(SIGBUS);
		break;
	case FPE:
		raise(SIGFPE);
		break;
	}
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct crash *c;

	(void)host;
	if (values[2] != 0.0)
		crash_now((int)values[0]);
	if (!(c = malloc(sizeof(*c)))) {
		snprintf(err, errlen, "out of memory");
		return 1;
	}
	c->how = (int)values[0];
	c->row = (uint32_t)values[1];
	*state = c;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct crash *c = state;

	if (span->y == c->row)
		crash_now(c->how);
	test_run(NULL, span);
}

static void
destroy(void *state)
{
	free(state);
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "crash", "test: crashes in run() at a row",
	"1.0", "reflect tests", "MIT", 3, params, test_inputs, test_outputs,
	create, run, destroy, NULL
};

RF_PLUGIN_DEFINE(descriptor)
