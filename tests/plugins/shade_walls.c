/* A radiance mode that reads the mask, to see where the host runs it:
 * spec is the pixel's x, y and 1.  Built once with spec outputs only,
 * which reflect-shade need not run on walls (mask 0), so a wall fails
 * the run; and once as shade_walls_extra with an output of its own,
 * walls.seen, which must be written everywhere, walls too. */
#include <stddef.h>

#include "reflect/plugin.h"

static const char *const inputs[] = { "mask", NULL };
#ifdef WALLS_EXTRA
#define NAME "shade_walls_extra"
#define NOUT 4
static const char *const outputs[] = { "spec.R", "spec.G", "spec.B", "walls.seen", NULL };
#else
#define NAME "shade_walls"
#define NOUT 3
static const char *const outputs[] = { "spec.R", "spec.G", "spec.B", NULL };
#endif

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	(void)values;
	(void)err;
	(void)errlen;
	*state = (void *)host;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct rf_host *host = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in++, out += NOUT) {
		out[0] = (float)(span->x + i);
		out[1] = (float)span->y;
		out[2] = 1.0f;
#ifdef WALLS_EXTRA
		out[3] = in[0] == 0.0f ? 1.0f : 0.0f;
#else
		if (in[0] == 0.0f)
			host->fail(host->ctx, "run on a wall");
#endif
	}
}

static void
destroy(void *state)
{
	(void)state;
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, RF_PLUGIN_RADIANCE, NAME,
	"test: where the host runs a radiance mode",
	"1.0", "reflect developers", "MIT",
	0, NULL, inputs, outputs, create, run, destroy,
};

RF_PLUGIN_DEFINE(descriptor)
