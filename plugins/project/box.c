/* box: the classic box projection of the reflection vector. */
#include <math.h>

#include "reflect/plugin.h"

#include "probe/shape.h"

static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", NULL
};
static const char *const outputs[] = {
	"R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z", "hit.dist", "probe.dist", NULL
};

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	return rf__reflection_create(host, state, err, errlen);
}

static void
run(void *state, const struct rf_span *span)
{
	const struct rf_probe *probe = state;
	const struct rf__proxy proxy = rf__proxy_of_probe(probe);
	const int projecting = probe->box_projection;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 9, out += 8) {
		float p[3] = { in[0], in[1], in[2] }, r[3], d[3], hit = 0.0f, reach = 0.0f;
		int ok;

		rf__reflection_vector(in + 3, in + 6, r);
		ok = projecting ? rf__proxy_exit(&proxy, p, r, &hit) : -1;
		if (ok == 0)
			rf__lookup_from_hit(&proxy.box, p, r, hit, d, &reach);
		rf__projection_out(out, ok, r, d, hit, reach);
	}
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
	.kind = RF_KIND_PROJECTION,
	.name = "box",
	.summary = "box projection: look up where the reflected ray leaves the probe box",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
