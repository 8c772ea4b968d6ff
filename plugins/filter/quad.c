/*
 * quad: the write-up's 2x2 blur (spec 10), to reproduce its pictures:
 * every pixel becomes the mean of the aligned quad it belongs to,
 * pixels (2 floor(x/2) + {0, 1}, 2 floor(y/2) + {0, 1}), as a GPU's
 * quad of fragments shares values.  Blocky and not centred, and blind
 * to edges, as the original is; at an odd frame's last row or column a
 * quad is the pixels it has.  The four members of a quad add in one
 * order, so they get the same bits.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

static const char *const none[] = { NULL };

static void
run(void *state, const struct rf_span *span)
{
	const uint32_t nv = span->nvalues, r = span->radius, y = span->y, w = span->width;
	/* the quad's rows: this one and the one below (even y) or above */
	const float *rows[2] = { span->band[r - (y & 1)], span->band[r + 1 - (y & 1)] };
	uint32_t i, k, v;

	(void)state;
	for (v = 0; v < nv; v++) {
		float *out = span->out + (size_t)v * span->npix;

		for (i = 0; i < span->npix; i++) {
			uint32_t x0 = (span->x + i) & ~1u, x1 = x0 + 1 < w ? x0 + 1 : x0;
			float count = (float)((x1 > x0 ? 2 : 1) * (rows[1] ? 2 : 1)), sum = 0.0f;

			for (k = 0; k < 2; k++)
				if (rows[k]) {
					const float *vals = rows[k] + (size_t)v * w;

					sum += vals[x0];
					if (x1 > x0)
						sum += vals[x1];
				}
			out[i] = sum / count;
		}
	}
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	static const uint32_t radius = 1;

	(void)values;
	*state = NULL;
	if (host->size < offsetof(struct rf_host, filter_passes) + sizeof(host->filter_passes) ||
	    !host->filter_passes || host->filter_passes(host->ctx, 1, &radius) < 0) {
		snprintf(err, errlen, "this host runs no filter passes (it needs "
		         "reflect-filter of plugin ABI 1.1 or later)");
		return -1;
	}
	return 0;
}

static void
destroy(void *state)
{
	(void)state;
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_FILTER,
	.name = "quad",
	.summary = "the write-up's aligned 2x2 average, blind to edges",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = 0,
	.params = NULL,
	.inputs = none,
	.outputs = none,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
