/*
 * ema: the exponential moving average, the history a TAA keeps:
 *   mu <- mu + a_n (x - mu),  a_n = max(weight, 1 / n)
 * for the n-th frame since the start (or the last reset).  With warmup
 * (the default) the first 1 / weight frames are their plain mean, as
 * Falcor's SVGF does, so that the first frame's noise does not linger
 * for 1 / weight frames; without it a_1 = 1 and then a_n = weight, the
 * textbook average.  The steady state averages (2 - weight) / weight
 * frames' worth: 19 at the default 0.1.
 *
 * The variance of the average: the frames' spread from the weighted
 * variance S <- (1 - a)(S + a d^2), d = x - mu before the update (Finch
 * 2009), made unbiased by 1 / (1 - W2), times W2, the sum of the
 * squared weights the frames have in mu (W2 <- (1 - a)^2 W2 + a^2).  W2
 * is the same for every pixel: each instance works it out once for a
 * count.  One frame (W2 = 1): +inf.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

enum { WEIGHT, WARMUP, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "weight", "the new frame's share of the average", 0.001, 1, 0.1, 0, NULL },
	{ "warmup", "the first 1/weight frames are their plain mean", 0, 1, 1,
	  RF_PARAM_BOOL, NULL },
};

static const char *const inputs[] = { NULL };
static const char *const slots[] = { RF_ACCUMULATE_VALUE, RF_ACCUMULATE_VARIANCE,
                                     "spread", NULL };
enum { VALUE, VARIANCE, SPREAD, NSLOTS };

struct ema {
	double weight;
	int warmup;
	uint32_t count; /* of w2 below, 0: none yet */
	double w2;
};

/* a_n for frame n. */
static double
share(const struct ema *e, uint32_t n)
{
	double a = e->warmup ? 1.0 / n : (n == 1 ? 1.0 : e->weight);

	return a > e->weight ? a : e->weight;
}

static void
run(void *state, const struct rf_span *span)
{
	struct ema *e = state;
	const float *x = span->in;
	float *s = span->out;
	const size_t nv = (size_t)span->npix * span->nvalues;
	float a, keep, factor;
	size_t i;

	if (e->count != span->count) {
		/* W2 from the start: a few thousand steps at most, once a frame */
		uint32_t n;

		if (e->count > span->count || e->count == 0) {
			e->count = 0;
			e->w2 = 0.0;
		}
		for (n = e->count + 1; n <= span->count; n++) {
			double an = share(e, n);

			e->w2 = (1.0 - an) * (1.0 - an) * e->w2 + an * an;
		}
		e->count = span->count;
	}
	a = (float)share(e, span->count);
	keep = 1.0f - a;
	factor = e->w2 < 1.0 ? (float)(e->w2 / (1.0 - e->w2)) : INFINITY;
	if (span->count == 1) {
		for (i = 0; i < nv; i++, s += NSLOTS) {
			s[VALUE] = x[i];
			s[SPREAD] = 0.0f;
			s[VARIANCE] = INFINITY;
		}
		return;
	}
	for (i = 0; i < nv; i++, s += NSLOTS) {
		float d = x[i] - s[VALUE];

		s[VALUE] += a * d;
		s[SPREAD] = keep * (s[SPREAD] + a * d * d);
		s[VARIANCE] = s[SPREAD] * factor;
	}
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct ema *e = calloc(1, sizeof(*e));

	(void)host;
	if (!e) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	e->weight = values[WEIGHT];
	e->warmup = values[WARMUP] != 0.0;
	*state = e;
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
	.name = "ema",
	.summary = "an exponential moving average of the frames, as a TAA's history",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = slots,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
