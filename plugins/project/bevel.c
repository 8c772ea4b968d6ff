/*
 * bevel: box projection onto the probe box with its edges and corners
 * rounded (bevel.h has the shape and its exact exit), so that a
 * reflection slides round a room's corner instead of folding at it.
 *
 * roughen=K grows the radius with the lobe: R_eff = R + K 2 alpha t,
 * 2 alpha t the width of the GGX lobe's median cone (2 atan alpha, about
 * 2 alpha wide) at t, the exit distance through the shape of radius R;
 * one step of that fixed point, R_eff at most the box's smallest half
 * extent.  A mirror keeps R, a rough floor sees soft room edges.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

#include "probe/bevel.h"
#include "probe/projection.h"
#include "probe/shape.h"

enum { RADIUS, OFFSET, ROUGHEN, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "radius", "rounding radius of the box's edges and corners, world units", 0, HUGE_VAL,
	  0.5, 0, NULL },
	{ "offset", "grow the rounded box beyond the probe box (the write-up's shape) instead "
	  "of keeping its faces on it", 0, 1, 0, RF_PARAM_BOOL, NULL },
	{ "roughen", "radius added per width of the lobe at the hit (0: a fixed radius)", 0,
	  HUGE_VAL, 0, 0, NULL },
};

static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", NULL
};
static const char *const optional_inputs[] = { "roughness", NULL };
static const char *const outputs[] = {
	"R.X", "R.Y", "R.Z", "D.X", "D.Y", "D.Z", "hit.dist", "probe.dist", NULL
};

struct bevel_mode {
	struct rf_probe probe; /* its box the proxy's, in the proxy's frame */
	struct rf__frame frame;
	int rotated;
	float radius, roughen, max_radius;
	int grown;
};

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct bevel_mode *m;
	struct rf_probe aligned;
	struct rf__frame frame;
	int rotated;

	if (!host->probe) {
		snprintf(err, errlen, "no probe box: give --box and --center or a "
		         "stream with PROBE_BOX and PROBE_CENTER");
		return -1;
	}
	if (rf__probe_proxy_aligned(host->probe, &aligned, &frame, &rotated) != RF_SHAPE_BOX) {
		snprintf(err, errlen, "the probe's proxy is %s, and bevel rounds a box: use "
		         "mode box", host->probe->proxy_shape == RF_SHAPE_INFINITE
		                         ? "infinite" : "a sphere");
		return -1;
	}
	if (values[RADIUS] > rf__bevel_max_radius(&aligned)) {
		snprintf(err, errlen, "radius %g is more than the probe box's smallest half "
		         "extent, %g: give radius=%g or less", values[RADIUS],
		         (double)rf__bevel_max_radius(&aligned),
		         (double)rf__bevel_max_radius(&aligned));
		return -1;
	}
	if (host->size < offsetof(struct rf_host, declare_bevel) + sizeof(host->declare_bevel) ||
	    !host->declare_bevel ||
	    host->declare_bevel(host->ctx, (float)values[RADIUS], values[OFFSET] != 0.0) < 0) {
		snprintf(err, errlen, "this host cannot record a bevel (it needs reflect-project "
		         "of plugin ABI 1.1 or later)");
		return -1;
	}
	if (!(m = calloc(1, sizeof(*m)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	m->probe = aligned;
	m->frame = frame;
	m->rotated = rotated;
	m->radius = (float)values[RADIUS];
	m->grown = values[OFFSET] != 0.0;
	m->roughen = (float)values[ROUGHEN];
	m->max_radius = rf__bevel_max_radius(&aligned);
	*state = m;
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct bevel_mode *m = state;
	const struct rf__bevel shape = rf__bevel_of_probe(&m->probe, m->radius, m->grown);
	const struct rf__box box = rf__box_of_probe(&m->probe);
	const int projecting = m->probe.box_projection;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 10, out += 8) {
		float p[3] = { in[0], in[1], in[2] }, r[3], d[3], hit = 0.0f, reach = 0.0f;
		float q[3], e[3]; /* p and r in the box's frame */
		int ok;

		rf__reflection_vector(in + 3, in + 6, r);
		if (m->rotated) {
			rf__frame_point_in(&m->frame, p, q);
			rf__frame_vector_in(&m->frame, r, e);
		} else {
			q[0] = p[0], q[1] = p[1], q[2] = p[2];
			e[0] = r[0], e[1] = r[1], e[2] = r[2];
		}
		if (!projecting)
			ok = -1;
		else if (m->radius == 0.0f && m->roughen == 0.0f)
			ok = rf__box_exit(&box, q, e, &hit); /* exactly box */
		else
			ok = rf__bevel_exit(&shape, q, e, &hit, NULL);
		if (ok == 0 && m->roughen > 0.0f && in[9] > 0.0f) {
			const float alpha = in[9] * in[9];
			float grown = m->radius + m->roughen * 2.0f * alpha * hit;
			struct rf__bevel wider;

			if (grown > m->max_radius)
				grown = m->max_radius;
			wider = rf__bevel_of_probe(&m->probe, grown, m->grown);
			ok = rf__bevel_exit(&wider, q, e, &hit, NULL);
		}
		if (ok == 0)
			rf__lookup_from_hit(&box, p, r, hit, d, &reach);
		rf__projection_out(out, ok, r, d, hit, reach);
	}
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
	.kind = RF_KIND_PROJECTION,
	.name = "bevel",
	.summary = "box projection onto the probe box with its edges and corners rounded",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
	.optional_inputs = optional_inputs,
};

RF_PLUGIN_DEFINE(descriptor)
