/* A projection mode built for plugin ABI 1.1, whose struct rf_probe was
 * 48 bytes: it reads the frame's probes at that stride, as such a mode
 * compiled against the 1.1 header would.  R.X R.Y R.Z get the first
 * probe's box_min x, the second's box_min x and box_max z, D.X the
 * number of probes: the host must hand it the 1.1 layout. */
#include "testplugin.h"

struct probe_1_1 {
	float center[3];
	float box_min[3];
	float box_max[3];
	int box_projection;
	float bevel;
	int bevel_grown;
};

static int
probes_create(const struct rf_host *host, const double *values, void **state, char *err,
              size_t errlen)
{
	(void)values;
	(void)err;
	(void)errlen;
	*state = (void *)host;
	return 0;
}

static void
probes_run(void *state, const struct rf_span *span)
{
	const struct rf_host *host = state;
	const struct probe_1_1 *probes = (const struct probe_1_1 *)(const void *)host->probes;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, out += 8) {
		out[0] = host->nprobes > 0 ? probes[0].box_min[0] : NAN;
		out[1] = host->nprobes > 1 ? probes[1].box_min[0] : NAN;
		out[2] = host->nprobes > 1 ? probes[1].box_max[2] : NAN;
		out[3] = (float)host->nprobes;
		out[4] = out[5] = out[6] = out[7] = 0.0f;
	}
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, 1, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "probes_abi_1_1",
	"test: a 1.1 mode reading the probes array", "1.0", "reflect tests", "MIT", 0, NULL,
	test_inputs, test_outputs, probes_create, probes_run, test_destroy, NULL,
};

RF_PLUGIN_DEFINE(descriptor)
