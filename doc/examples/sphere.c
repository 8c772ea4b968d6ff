/*
 * sphere: a projection mode for reflect-project(1) that uses a sphere,
 * not the probe box, as the proxy of the surroundings.
 *
 * The reflected ray from the pixel's position P is intersected with a
 * sphere of radius `radius` around the probe's capture point C; the
 * environment is looked up in the direction from C to that hit.  Rooms
 * that are round, or open scenes with a distant horizon, look better
 * with a sphere than with a box.
 *
 * Outputs are those of the built-in box mode:
 *   R.X R.Y R.Z   the unit reflection vector 2 (N.V) N - V
 *   D.X D.Y D.Z   the unit lookup direction, from C to the hit
 *   hit.dist      distance from P to the hit along R
 *   probe.dist    distance from C to the hit (the radius)
 * A pixel outside the sphere, or any pixel when box projection is off,
 * gets D = R and infinite distances, as the box mode does.
 *
 * It needs only <reflect/plugin.h> and the C library:
 *   cc -std=c11 -fPIC -shared $(pkg-config --cflags reflect-plugin) \
 *       sphere.c -o sphere.so -lm
 *   REFLECT_PLUGIN_PATH=$PWD reflect-project -m sphere:radius=8 gbuf.rfl
 * or install it where reflect looks by default:
 *   cp sphere.so "$(pkg-config --variable=plugindir reflect-plugin)"
 *
 * This file is in the public domain: copy it to start a plugin.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <reflect/plugin.h>

/* Parameters: the values reach create() in this order, already checked
 * against min and max by the host. */
enum { RADIUS, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "radius", "radius of the proxy sphere around the capture point",
	  0.001, 1e6, 5, 0, NULL },
};

/* Channels by name: the host finds these in the stream, in any order,
 * and hands them to run() interleaved in exactly this order. */
static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", NULL
};
static const char *const outputs[] = {
	"R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z", "hit.dist", "probe.dist", NULL
};

/* One instance per thread: everything run() needs, copied out of the
 * host's structures so that it depends on nothing the host may free. */
struct sphere {
	float center[3];
	float radius;
	int projection; /* 0: the probe says not to project (D = R) */
};

static int
create(const struct rf_host *host, const double *values, void **state,
       char *err, size_t errlen)
{
	struct sphere *s;
	int i;

	if (!host->probe) {
		snprintf(err, errlen, "no probe: give --box and --center, or a "
		         "stream with PROBE_BOX and PROBE_CENTER");
		return -1;
	}
	if (!(s = malloc(sizeof(*s)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	for (i = 0; i < 3; i++)
		s->center[i] = host->probe->center[i];
	s->radius = (float)values[RADIUS];
	s->projection = host->probe->box_projection;
	*state = s;
	return 0;
}

/* R = 2 (N.V) N - V, made unit length; 0 when it is the zero vector. */
static int
reflect_vector(const float n[3], const float v[3], float r[3])
{
	float d = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
	float len;
	int i;

	for (i = 0; i < 3; i++)
		r[i] = 2.0f * d * n[i] - v[i];
	len = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
	if (!(len > 0.0f))
		return 0;
	for (i = 0; i < 3; i++)
		r[i] /= len;
	return 1;
}

/*
 * Where the ray p + t r (r unit) leaves the sphere |x - c| = radius, for
 * p inside it.  With o = p - c, b = o.r and k = o.o - radius^2 <= 0:
 *   t^2 + 2 b t + k = 0,   t = -b + sqrt(b^2 - k) >= 0.
 * When b > 0 the same root is written -k / (b + sqrt(b^2 - k)), which
 * does not lose digits to cancellation.  Returns 0 when p is outside.
 */
static int
sphere_exit(const struct sphere *s, const float p[3], const float r[3],
            float *t)
{
	float o[3], b, k, root;
	int i;

	for (i = 0; i < 3; i++)
		o[i] = p[i] - s->center[i];
	b = o[0] * r[0] + o[1] * r[1] + o[2] * r[2];
	k = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - s->radius * s->radius;
	if (k > 0.0f)
		return 0;
	root = sqrtf(b * b - k);
	if (b > 0.0f)
		*t = -k / (b + root);
	else
		*t = root - b;
	return 1;
}

/* A span is npix pixels of one row; in and out are interleaved in the
 * order of inputs[] and outputs[]. */
static void
run(void *state, const struct rf_span *span)
{
	const struct sphere *s = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 9, out += 8) {
		const float *p = in, *n = in + 3, *v = in + 6;
		float *r = out, *d = out + 3, h[3], t, len;
		int j;

		if (!reflect_vector(n, v, r) || !s->projection ||
		    !sphere_exit(s, p, r, &t)) {
			d[0] = r[0];
			d[1] = r[1];
			d[2] = r[2];
			out[6] = out[7] = INFINITY;
			continue;
		}
		for (j = 0; j < 3; j++)
			h[j] = p[j] + r[j] * t - s->center[j];
		len = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
		for (j = 0; j < 3; j++)
			d[j] = len > 0.0f ? h[j] / len : r[j];
		out[6] = t;
		out[7] = len;
	}
}

static void
destroy(void *state)
{
	free(state);
}

/* The descriptor: the ABI version and size first, as the header says. */
static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_PROJECTION,
	.name = "sphere", /* equal to the file name, sphere.so */
	.summary = "sphere proxy: look up where the reflected ray leaves a sphere "
	           "around the capture point",
	.version = "1.0",
	.author = "reflect developers",
	.license = "public domain",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
