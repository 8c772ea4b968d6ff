/* Broken on purpose: a mode that writes, at one pixel, a value its
 * kind's output contract forbids (NaN, +-inf, -1 or 2) into one of its
 * outputs, and valid values everywhere else.  Built once for each kind
 * (BAD_KIND, the number of its RF_KIND_*: the preprocessor cannot read
 * an enum), as KIND-bad_out.so, and as shade-bad_spec.so for a shade
 * mode that writes radiance. */
#include <math.h>
#include <string.h>

#include "reflect/plugin.h"

static const struct rf_param params[] = {
	{ "x", "the pixel's column", 0, 1e6, 0, RF_PARAM_INTEGER, NULL },
	{ "y", "the pixel's row", 0, 1e6, 0, RF_PARAM_INTEGER, NULL },
	{ "out", "which output (a filter's or accumulator's value: its slot)", 0, 16, 0,
	  RF_PARAM_INTEGER, NULL },
	{ "value", "what it writes there", 0, 4, 0, RF_PARAM_CHOICE, "nan|inf|-inf|-1|2" },
};

struct bad {
	uint32_t x, y, out;
	float value;
};

static struct bad modes[1];

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	static const float bad[] = { NAN, INFINITY, -INFINITY, -1.0f, 2.0f };

	(void)host;
	(void)err;
	(void)errlen;
	/* every instance has the same parameters: one shared, read-only */
	modes[0].x = (uint32_t)values[0];
	modes[0].y = (uint32_t)values[1];
	modes[0].out = (uint32_t)values[2];
	modes[0].value = bad[(int)values[3]];
	*state = &modes[0];
	return 0;
}

static void
destroy(void *state)
{
	(void)state;
}

#if BAD_KIND == 1 /* RF_KIND_PROJECTION */
#define NAME "bad_out"
#define SUMMARY "test: writes a projection output its contract forbids at a pixel"
#define FLAGS 0
static const char *const inputs[] = { "N.X", "N.Y", "N.Z", NULL };
static const char *const outputs[] = { "R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z",
	                                "hit.dist", "probe.dist", NULL };
#define NOUT 8
static void
fill(const float *in, float *out)
{
	out[0] = out[3] = in[0];
	out[1] = out[4] = in[1];
	out[2] = out[5] = in[2];
	out[6] = out[7] = INFINITY;
}
#elif BAD_KIND == 2 /* RF_KIND_SHADE */ && !defined(BAD_SPEC)
#define NAME "bad_out"
#define SUMMARY "test: writes a roughness.eff its contract forbids at a pixel"
#define FLAGS 0
static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { RF_SHADE_ROUGHNESS, NULL };
#define NOUT 1
static void
fill(const float *in, float *out)
{
	out[0] = in[0];
}
#elif BAD_KIND == 2 /* RF_KIND_SHADE */
#define NAME "bad_spec"
#define SUMMARY "test: writes a radiance its contract forbids at a pixel"
#define FLAGS RF_PLUGIN_RADIANCE
static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B,
	                                NULL };
#define NOUT 3
static void
fill(const float *in, float *out)
{
	out[0] = out[1] = out[2] = in[0];
}
#elif BAD_KIND == 3 /* RF_KIND_OCCLUSION */
#define NAME "bad_out"
#define SUMMARY "test: writes an occlusion its contract forbids at a pixel"
#define FLAGS 0
static const char *const inputs[] = { "roughness", NULL };
static const char *const outputs[] = { RF_OCCLUSION, NULL };
#define NOUT 1
static void
fill(const float *in, float *out)
{
	out[0] = 1.0f - 0.5f * in[0];
}
#elif BAD_KIND == 4 /* RF_KIND_ACCUMULATE */
#define NAME "bad_out"
#define SUMMARY "test: leaves a state its contract forbids at a pixel"
#define FLAGS 0
static const char *const inputs[] = { NULL };
static const char *const outputs[] = { RF_ACCUMULATE_VALUE, RF_ACCUMULATE_VARIANCE, NULL };
#elif BAD_KIND == 5 /* RF_KIND_FILTER */
#define NAME "bad_out"
#define SUMMARY "test: filters to a value its contract forbids at a pixel"
#define FLAGS 0
static const char *const inputs[] = { NULL };
static const char *const outputs[] = { NULL };
#endif

static void
run(void *state, const struct rf_span *span)
{
	const struct bad *b = state;

#if BAD_KIND == 4 /* RF_KIND_ACCUMULATE */
	uint32_t i;

	/* the last frame's value, variance 0; slot out of value v at the pixel */
	for (i = 0; i < span->npix * span->nvalues; i++) {
		span->out[2 * i] = span->in[i];
		span->out[2 * i + 1] = 0.0f;
	}
	if (span->y == b->y && b->x >= span->x && b->x - span->x < span->npix)
		span->out[2 * (b->x - span->x) * span->nvalues + (b->out & 1)] = b->value;
#elif BAD_KIND == 5 /* RF_KIND_FILTER */
	/* a copy: value v of pixel i at out[v npix + i], as in[] has it */
	memcpy(span->out, span->in, (size_t)span->npix * span->nvalues * sizeof(float));
	if (span->y == b->y && b->x >= span->x && b->x - span->x < span->npix)
		span->out[(b->out % span->nvalues) * span->npix + (b->x - span->x)] = b->value;
#else
	const size_t nin = sizeof(inputs) / sizeof(inputs[0]) - 1;
	uint32_t i;

	for (i = 0; i < span->npix; i++)
		fill(span->in + i * nin, span->out + i * NOUT);
	if (span->y == b->y && b->x >= span->x && b->x - span->x < span->npix)
		span->out[(b->x - span->x) * NOUT + b->out % NOUT] = b->value;
#endif
}

static const struct rf_plugin descriptor = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	BAD_KIND, FLAGS, NAME, SUMMARY, "1.0", "reflect tests", "MIT",
	sizeof(params) / sizeof(params[0]), params, inputs, outputs,
	create, run, destroy, NULL
};

RF_PLUGIN_DEFINE(descriptor)
