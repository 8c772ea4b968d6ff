/* Shared parts of the test plugins: a valid projection mode that copies
 * N into R and D.  Each test plugin takes these and breaks exactly
 * one thing in its descriptor (or, for echo_params, breaks nothing). */
#ifndef REFLECT_TESTS_TESTPLUGIN_H
#define REFLECT_TESTS_TESTPLUGIN_H

#include <math.h>
#include <stddef.h>

#include "reflect/plugin.h"

static const char *const test_inputs[] = { "N.X", "N.Y", "N.Z", NULL };
static const char *const test_outputs[] = {
	"R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z", "hit.dist", "probe.dist", NULL
};

static int
test_create(const struct rf_host *host, const double *values, void **state,
            char *err, size_t errlen)
{
	(void)host;
	(void)values;
	(void)err;
	(void)errlen;
	*state = NULL;
	return 0;
}

static void
test_run(void *state, const struct rf_span *span)
{
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	(void)state;
	for (i = 0; i < span->npix; i++, in += 3, out += 8) {
		out[0] = out[3] = in[0];
		out[1] = out[4] = in[1];
		out[2] = out[5] = in[2];
		out[6] = out[7] = INFINITY;
	}
}

static void
test_destroy(void *state)
{
	(void)state;
}

/* The fields after abi_major, abi_minor, size, kind, flags and name. */
#define TEST_REST(summary)                                                \
	summary, "1.0", "reflect tests", "MIT", 0, NULL, test_inputs,     \
		test_outputs, test_create, test_run, test_destroy

#endif
