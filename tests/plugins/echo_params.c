/* A valid test mode with one parameter of every type.  It writes the
 * values it was created with into its output channels, so a test can read
 * back with -fa what reached the plugin, and fails in create() on
 * request (shape=fail) to show how a plugin reports an error. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

enum { SCALE, OFFSET, COUNT, INVERT, SHAPE, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "scale", "a number with a range", 0.5, 4, 1, 0, NULL },
	{ "offset", "a number without bounds", -HUGE_VAL, HUGE_VAL, 0, 0, NULL },
	{ "count", "an integer", 1, 8, 3, RF_PARAM_INTEGER, NULL },
	{ "invert", "a switch", 0, 1, 0, RF_PARAM_BOOL, NULL },
	{ "shape", "a choice; fail makes create fail", 0, 2, 0, RF_PARAM_CHOICE,
	  "round|square|fail" },
};

static const char *const inputs[] = { "N.X", NULL };
static const char *const outputs[] = {
	"echo.scale", "echo.offset", "echo.count", "echo.invert", "echo.shape",
	"echo.nx", "echo.y", "echo.frame", NULL
};

struct state {
	double values[NPARAMS];
};

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	struct state *s;
	int i;

	(void)host;
	if (values[SHAPE] == 2) {
		/* The newline is on purpose: the host must keep it one line. */
		snprintf(err, errlen, "shape=fail asked for a failure\nin create");
		return -1;
	}
	if (!(s = malloc(sizeof(*s)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	for (i = 0; i < NPARAMS; i++)
		s->values[i] = values[i];
	*state = s;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct state *s = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 1, out += 8) {
		out[0] = (float)s->values[SCALE];
		out[1] = (float)s->values[OFFSET];
		out[2] = (float)s->values[COUNT];
		out[3] = (float)s->values[INVERT];
		out[4] = (float)s->values[SHAPE];
		out[5] = (float)(in[0] * s->values[SCALE] + s->values[OFFSET]);
		out[6] = (float)span->y;
		out[7] = (float)span->frame;
	}
}

static void
destroy(void *state)
{
	free(state);
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0,
	"echo_params",
	"test: echoes its parameters into its output channels",
	"1.0", "reflect tests", "MIT",
	NPARAMS, params, inputs, outputs,
	create, run, destroy,
};

RF_PLUGIN_DEFINE(descriptor)
