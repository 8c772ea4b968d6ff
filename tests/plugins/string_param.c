/* A working test plugin with string parameters (ABI 1.1): table=FILE is
 * opened in create() (relative to the working directory), its first
 * number written as echo.table; label=TEXT's length as echo.label.  A
 * file that cannot be opened or read is create()'s error. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/plugin.h"

static const struct rf_param params[] = {
	{ "table", "a file with one number", 0, 0, 0, RF_PARAM_STRING, NULL },
	{ "label", "a text", 0, 0, 0, RF_PARAM_STRING, "abc" },
};
static const char *const inputs[] = { "N.X", NULL };
static const char *const outputs[] = { "echo.table", "echo.label", NULL };

struct strings {
	float table, label;
};

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct strings *s;
	const char *table, *label;
	FILE *fp;

	if (host->size < offsetof(struct rf_host, param_string) + sizeof(host->param_string) ||
	    !host->param_string) {
		snprintf(err, errlen, "no param_string");
		return -1;
	}
	table = host->param_string(host->ctx, values[0]);
	label = host->param_string(host->ctx, values[1]);
	if (!(s = calloc(1, sizeof(*s)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	s->label = (float)strlen(label);
	if (*table) {
		if (!(fp = fopen(table, "r"))) {
			snprintf(err, errlen, "cannot open '%s': %s", table, strerror(errno));
			free(s);
			return -1;
		}
		if (fscanf(fp, "%f", &s->table) != 1) {
			snprintf(err, errlen, "'%s': no number in it", table);
			fclose(fp);
			free(s);
			return -1;
		}
		fclose(fp);
	}
	*state = s;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct strings *s = state;
	uint32_t i;

	for (i = 0; i < span->npix; i++) {
		span->out[2 * i] = s->table;
		span->out[2 * i + 1] = s->label;
	}
}

static void
destroy(void *state)
{
	free(state);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_PROJECTION,
	.name = "string_param",
	.summary = "test: string parameters",
	.version = "1.0",
	.author = "reflect tests",
	.license = "MIT",
	.nparams = 2,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
