/*
 * mean: the running mean of every frame since the start (or the last
 * reset), each frame weighted by the samples it is the mean of (its
 * SAMPLES key, 1 without), and the variance of that mean from the
 * frames' own spread.  A frame of 4 rays and one of 12 so make the mean
 * of the 16, as one frame of 16 rays would.
 *
 * The sum (of weight x value) is compensated (Neumaier's variant of
 * Kahan's summation): a plain float sum of frames of 1 +- 0.1 drifts
 * from the exact sum by 1.8e-6 of its value after 65536 frames and
 * 1.2e-5 after 2^20, the compensated one by 2e-8 and 3e-8; and the mean
 * of frames whose sum is exact (the tests' small integers) is exactly
 * sum / W, W the weights' sum, kept in a slot (exact to 2^24 samples).
 * The spread is West's (1979) weighted form of Welford's M2,
 *   M2 <- M2 + w (x - mean before) (x - mean after),
 * and with frames whose values have variance s^2 / w (means of w
 * samples of variance s^2), M2 / (n - 1) estimates s^2, so the mean's
 * variance is M2 / ((n - 1) W) for n frames: M2 / (n (n - 1)) when
 * every weight is 1; +inf for one frame (no spread to tell).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

static const char *const inputs[] = { NULL };
static const char *const slots[] = { RF_ACCUMULATE_VALUE, RF_ACCUMULATE_VARIANCE, "sum",
                                     "compensation", "m2", "weight", NULL };
enum { VALUE, VARIANCE, SUM, COMPENSATION, M2, WEIGHT, NSLOTS };

struct mean {
	const struct rf_host *host;
	uint32_t frame; /* the frame `weight` is of */
	int known;      /* 0: weight not read yet */
	float weight;
};

/* The frame's SAMPLES, read once a frame: reflect-accumulate has checked
 * it (a whole number from 1 up), and 1 stands for a stream without it. */
static float
frame_weight(struct mean *m, uint32_t frame)
{
	const char *v;

	if (m->known && m->frame == frame)
		return m->weight;
	v = m->host->header_get ? m->host->header_get(m->host->ctx, "SAMPLES") : NULL;
	m->weight = v ? (float)strtod(v, NULL) : 1.0f;
	if (!(m->weight >= 1.0f))
		m->weight = 1.0f;
	m->frame = frame;
	m->known = 1;
	return m->weight;
}

static void
run(void *state, const struct rf_span *span)
{
	const float *x = span->in;
	float *s = span->out;
	const float n = (float)span->count, w = frame_weight(state, span->frame);
	const size_t nv = (size_t)span->npix * span->nvalues;
	size_t i;

	if (span->count == 1) {
		for (i = 0; i < nv; i++, s += NSLOTS) {
			s[VALUE] = x[i];
			s[SUM] = w * x[i];
			s[COMPENSATION] = s[M2] = 0.0f;
			s[WEIGHT] = w;
			s[VARIANCE] = INFINITY;
		}
		return;
	}
	for (i = 0; i < nv; i++, s += NSLOTS) {
		float wx = w * x[i], sum = s[SUM], t = sum + wx, before = s[VALUE], after, m2;
		float total = s[WEIGHT] + w;

		/* Neumaier: what the addition lost, from the larger operand */
		s[COMPENSATION] += fabsf(sum) >= fabsf(wx) ? (sum - t) + wx : (wx - t) + sum;
		s[SUM] = t;
		s[WEIGHT] = total;
		after = (t + s[COMPENSATION]) / total;
		m2 = s[M2] + w * ((x[i] - before) * (x[i] - after));
		s[M2] = m2 > 0.0f ? m2 : 0.0f;
		s[VALUE] = after;
		s[VARIANCE] = s[M2] / (total * (n - 1.0f));
	}
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct mean *m = calloc(1, sizeof(*m));

	(void)values;
	if (!m) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	m->host = host;
	*state = m;
	return 0;
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
	.kind = RF_KIND_ACCUMULATE,
	.name = "mean",
	.summary = "the mean of every frame so far, with its standard error",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = 0,
	.params = NULL,
	.inputs = inputs,
	.outputs = slots,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
