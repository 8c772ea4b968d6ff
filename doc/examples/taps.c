/*
 * taps: a shade mode for reflect-shade(1) that reads the environment
 * itself (RF_PLUGIN_RADIANCE), in four taps across the GGX lobe.
 *
 * The lobe's median cone (half-angle atan alpha, alpha = r^2) is sampled
 * at four directions, D tilted by half that angle toward +-t and +-b
 * (t, b a frame about D), each standing for a quarter of the cone: a
 * cone of half the half-angle.  The chain sample_many reads is
 * GGX-prefiltered: its lod for roughness r' holds the environment
 * already blurred by the GGX lobe of r', so a tap reads at the lod of
 * the lobe as wide as its share, not at a lod picked from texel sizes:
 * alpha' = tan(atan(alpha) / 2), lod = roughness_to_lod(sqrt(alpha')).
 * (texel_solid_angle is for a chain of plain box-filtered levels, the
 * host's sample_radiance, where a texel is all the blur a level adds.)
 * The four reads of a whole span go to the host in one call
 * (sample_many), and the mode writes their mean as spec.R spec.G
 * spec.B.  At roughness 0 the taps meet at D and the lod is 0: a
 * mirror read.
 *
 * Build and run (doc/examples/Makefile does the first):
 *   cc -std=c11 -fPIC -shared $(pkg-config --cflags reflect-plugin) \
 *       taps.c -o taps.so -lm
 *   REFLECT_PLUGIN_PATH=$PWD reflect-shade -m taps --final scene.rfl
 *
 * This file is in the public domain: copy it to start a plugin.
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>

#include <reflect/plugin.h>

static const char *const inputs[] = { "roughness", "D.X", "D.Y", "D.Z", NULL };
static const char *const outputs[] = { RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B,
                                       NULL };

struct taps {
	const struct rf_host *host;
	float *buf; /* 4 taps a pixel: x, y, z, lod, then rgba */
	uint32_t cap;
};

/* The services this mode needs came with plugin ABI 1.1: read a member
 * only when the host's table is long enough to have it. */
#define HAS(host, member)                                                    \
	((host)->size >= offsetof(struct rf_host, member) + sizeof((host)->member) && \
	 (host)->member)

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct taps *t;

	(void)values;
	if (!HAS(host, sample_many) || !host->roughness_to_lod) {
		snprintf(err, errlen, "the host has no sample_many or roughness_to_lod "
		         "(it needs reflect-shade with an environment, plugin ABI 1.1)");
		return -1;
	}
	if (!(t = calloc(1, sizeof(*t)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	t->host = host;
	*state = t;
	return 0;
}

/* A unit frame t, b about the unit vector d. */
static void
frame(const float d[3], float t[3], float b[3])
{
	const float s = d[2] >= 0.0f ? 1.0f : -1.0f, a = -1.0f / (s + d[2]);
	const float c = d[0] * d[1] * a;

	t[0] = 1.0f + s * d[0] * d[0] * a;
	t[1] = s * c;
	t[2] = -s * d[0];
	b[0] = c;
	b[1] = s + d[1] * d[1] * a;
	b[2] = -d[1];
}

static void
run(void *state, const struct rf_span *span)
{
	struct taps *tp = state;
	const struct rf_host *host = tp->host;
	const uint32_t n = span->npix, m = 4 * n;
	const float *in = span->in;
	float *x, *y, *z, *lod, *rgba;
	uint32_t i, k, c;

	if (m > tp->cap) {
		float *grown = realloc(tp->buf, (size_t)m * 8 * sizeof(float));

		if (!grown) {
			host->fail(host->ctx, "out of memory for the taps");
			return;
		}
		tp->buf = grown;
		tp->cap = m;
	}
	x = tp->buf;
	y = x + m;
	z = y + m;
	lod = z + m;
	rgba = lod + m;
	for (i = 0; i < n; i++, in += 4) {
		const float alpha = in[0] * in[0], half = 0.5f * atanf(alpha);
		/* the lobe as wide as a tap's quarter of the cone, on the chain */
		const float tap_lod = host->roughness_to_lod(host->ctx, sqrtf(tanf(half)));
		float d[3] = { in[1], in[2], in[3] }, t[3], b[3], len;

		len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
		if (len > 0.0f)
			for (c = 0; c < 3; c++)
				d[c] /= len;
		frame(d, t, b);
		for (k = 0; k < 4; k++) {
			const float *axis = k < 2 ? t : b, sign = k & 1 ? -1.0f : 1.0f;
			const uint32_t j = 4 * i + k;
			float dir[3];

			for (c = 0; c < 3; c++)
				dir[c] = cosf(half) * d[c] + sign * sinf(half) * axis[c];
			x[j] = dir[0];
			y[j] = dir[1];
			z[j] = dir[2];
			lod[j] = tap_lod;
		}
	}
	host->sample_many(host->ctx, m, x, y, z, lod, rgba);
	for (i = 0; i < n; i++)
		for (c = 0; c < 3; c++)
			span->out[3 * i + c] = 0.25f * (rgba[16 * i + c] + rgba[16 * i + 4 + c] +
			                                rgba[16 * i + 8 + c] + rgba[16 * i + 12 + c]);
}

static void
destroy(void *state)
{
	struct taps *t = state;

	if (t)
		free(t->buf);
	free(t);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.flags = RF_PLUGIN_RADIANCE | RF_PLUGIN_PREFILTERED,
	.name = "taps",
	.summary = "example: four taps across the lobe, read through the host in one call",
	.version = "1.0",
	.author = "reflect developers",
	.license = "public domain",
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
