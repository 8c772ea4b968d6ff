/* A projection mode that gives up in run() at one row (parameter row,
 * from 0) through the host's fail() (plugin ABI 1.1), its outputs
 * written all the same, as the ABI asks. */
#include <stdio.h>

#include "testplugin.h"

static const struct rf_param params[] = {
	{ "row", "the row it gives up at", 0, 1e6, 2, RF_PARAM_INTEGER, NULL },
};

struct fail_state {
	const struct rf_host *host;
	uint32_t row;
};

static struct fail_state states[64];

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	static unsigned next;
	struct fail_state *s = &states[__atomic_fetch_add(&next, 1, __ATOMIC_RELAXED) % 64];

	if (host->size < offsetof(struct rf_host, fail) + sizeof(host->fail) || !host->fail) {
		snprintf(err, errlen, "the host has no fail()");
		return -1;
	}
	s->host = host;
	s->row = (uint32_t)values[0];
	*state = s;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct fail_state *s = state;

	test_run(NULL, span);
	if (span->y == s->row) {
		char msg[80];

		snprintf(msg, sizeof(msg), "row %u is one it cannot take\nat all", span->y + 1);
		s->host->fail(s->host->ctx, msg);
	}
}

static void
destroy(void *state)
{
	(void)state;
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "bail_at_row",
	"test: gives up in run() at one row", "1.0", "reflect tests", "MIT",
	1, params, test_inputs, test_outputs, create, run, destroy,
};

RF_PLUGIN_DEFINE(descriptor)
