/*
 * mean: the running mean of every frame since the start (or the last
 * reset), and the variance of that mean from the frames' own spread.
 *
 * The sum is compensated (Neumaier's variant of Kahan's summation): a
 * plain float sum of frames of 1 +- 0.1 drifts from the exact sum by
 * 1.8e-6 of its value after 65536 frames and 1.2e-5 after 2^20, the
 * compensated one by 2e-8 and 3e-8; and the mean of frames whose sum is
 * exact (the tests' small integers) is exactly sum / n.  The spread is Welford's M2, updated with the mean before and
 * after the frame; the mean's variance is M2 / (n (n - 1)), +inf for one
 * frame (no spread to tell).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

static const char *const inputs[] = { NULL };
static const char *const slots[] = { RF_ACCUMULATE_VALUE, RF_ACCUMULATE_VARIANCE, "sum",
                                     "compensation", "m2", NULL };
enum { VALUE, VARIANCE, SUM, COMPENSATION, M2, NSLOTS };

static void
run(void *state, const struct rf_span *span)
{
	const float *x = span->in;
	float *s = span->out;
	const float n = (float)span->count;
	const size_t nv = (size_t)span->npix * span->nvalues;
	size_t i;

	(void)state;
	if (span->count == 1) {
		for (i = 0; i < nv; i++, s += NSLOTS) {
			s[VALUE] = s[SUM] = x[i];
			s[COMPENSATION] = s[M2] = 0.0f;
			s[VARIANCE] = INFINITY;
		}
		return;
	}
	for (i = 0; i < nv; i++, s += NSLOTS) {
		float sum = s[SUM], t = sum + x[i], before = s[VALUE], after, m2;

		/* Neumaier: what the addition lost, from the larger operand */
		s[COMPENSATION] += fabsf(sum) >= fabsf(x[i]) ? (sum - t) + x[i] : (x[i] - t) + sum;
		s[SUM] = t;
		after = (t + s[COMPENSATION]) / n;
		m2 = s[M2] + (x[i] - before) * (x[i] - after);
		s[M2] = m2 > 0.0f ? m2 : 0.0f;
		s[VALUE] = after;
		s[VARIANCE] = s[M2] / (n * (n - 1.0f));
	}
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	(void)host;
	(void)values;
	(void)err;
	(void)errlen;
	*state = NULL;
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
