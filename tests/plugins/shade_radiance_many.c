/* A shade mode that reads its radiance through the host's batch service
 * (sample_many, plugin ABI 1.1): a span's directions and lods in one
 * call.  The tests compare it with none, byte for byte. */
#include <stddef.h>
#include <stdlib.h>

#include "reflect/plugin.h"

static const char *const inputs[] = { "roughness", "D.X", "D.Y", "D.Z", NULL };
static const char *const outputs[] = { "spec.R", "spec.G", "spec.B", NULL };

struct many {
	const struct rf_host *host;
	float *buf; /* 8 floats a pixel: x y z lod, then rgba */
	uint32_t cap;
};

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	struct many *m;

	(void)values;
	(void)err;
	(void)errlen;
	if (host->size < offsetof(struct rf_host, sample_many) + sizeof(host->sample_many) ||
	    !host->sample_many || !host->roughness_to_lod || !(m = calloc(1, sizeof(*m))))
		return -1;
	m->host = host;
	*state = m;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	struct many *m = state;
	const struct rf_host *host = m->host;
	const float *in = span->in;
	uint32_t i, n = span->npix;
	float *x, *y, *z, *lod, *rgba;

	if (n > m->cap) {
		free(m->buf);
		m->cap = 0;
		if (!(m->buf = malloc((size_t)n * 8 * sizeof(float))))
			return;
		m->cap = n;
	}
	x = m->buf;
	y = x + n;
	z = y + n;
	lod = z + n;
	rgba = lod + n;
	for (i = 0; i < n; i++, in += 4) {
		x[i] = in[1];
		y[i] = in[2];
		z[i] = in[3];
		lod[i] = host->roughness_to_lod(host->ctx, in[0]);
	}
	host->sample_many(host->ctx, n, x, y, z, lod, rgba);
	for (i = 0; i < n; i++) {
		span->out[3 * i] = rgba[4 * i];
		span->out[3 * i + 1] = rgba[4 * i + 1];
		span->out[3 * i + 2] = rgba[4 * i + 2];
	}
}

static void
destroy(void *state)
{
	struct many *m = state;

	if (m)
		free(m->buf);
	free(m);
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_SHADE, RF_PLUGIN_RADIANCE, "shade_radiance_many",
	"test: radiance from the host's batch service, like none",
	"1.0", "reflect developers", "MIT",
	0, NULL, inputs, outputs, create, run, destroy,
};

RF_PLUGIN_DEFINE(descriptor)
