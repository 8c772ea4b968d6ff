/*
 * atrous: an edge-avoiding a-trous wavelet filter (Dammertz et al. 2010)
 * guided by the G-buffer, for the noise of the raytraced mode.
 *
 * Pass i (from 0) blurs with the 5 x 5 B3-spline taps (1/16, 1/4, 3/8,
 * 1/4, 1/16 per axis) spread 2^i pixels apart, each pass over the one
 * before: five passes reach 62 pixels at 25 taps a pixel a pass.  Each
 * tap q of pixel p is weighted, besides the spline, by
 *   - objid and mask: 0 across objects and off reflective pixels, so no
 *     colour leaks over a silhouette;
 *   - normals: max(0, N_p.N_q)^normal (SVGF's weight);
 *   - the plane: exp(-|N_p.(P_q - P_p)| / (plane |P_q - P_p|)), the sine
 *     of the angle at which q leaves p's tangent plane, so creases and
 *     depth steps stop the blur whatever the scale;
 *   - roughness: exp(-|r_p - r_q| / (roughness max(r_p, 0.05)));
 *   - colour, when color > 0: exp(-|l_p - l_q| / (color (l_p + l_q) / 2)),
 *     l the values' mean: box corners and probe seams are edges that no
 *     G-buffer channel shows.
 * The weights multiply into one exponential a tap.
 *
 * The radius follows the lobe: the reflection is itself blurred, on the
 * surface, over about 2 alpha hit.dist d / (d + hit.dist) (the lobe's
 * spread of reflected directions, 2 alpha, carried to the hit and seen
 * back on the surface from the eye at distance d, the virtual image's
 * parallax; without depth, d is taken as infinite), and pass i is applied
 * to a pixel only while its reach, 2 x 2^i pixels of the pixel's size on
 * the surface, stays within lobe times that: a mirror keeps every
 * detail, a blurry floor is smoothed wide, contact hardening survives.
 * Without hit.dist there is no such limit.
 *
 * A pixel's result is v_p + sum w (v_q - v_p) / sum w: exactly v_p where
 * every neighbour equals it, so a constant image comes out unchanged.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/plugin.h"

enum { PASSES, NORMAL, PLANE, ROUGHNESS, COLOR, LOBE, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "passes", "passes, the tap spacing doubling each (radius 2^(passes+1) - 2)",
	  1, 9, 5, RF_PARAM_INTEGER, NULL },
	{ "normal", "exponent of the normals' weight max(0, Np.Nq)^normal", 0, 1024, 64,
	  RF_PARAM_INTEGER, NULL },
	{ "plane", "sine of the angle off the tangent plane that weighs 1/e", 0.001, 10,
	  0.05, 0, NULL },
	{ "roughness", "relative roughness difference that weighs 1/e", 0.001, 100, 0.25, 0,
	  NULL },
	{ "color", "relative colour difference that weighs 1/e; 0: no colour weight", 0, 100,
	  0, 0, NULL },
	{ "lobe", "the reach allowed, in widths of the reflection's own blur; 0: no limit", 0, 100, 0.5,
	  0, NULL },
};

/* Guides: the inputs, then the optional inputs. */
static const char *const inputs[] = { "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z",
                                      "roughness", "objid", NULL };
static const char *const optional_inputs[] = { "mask", "hit.dist", "depth", NULL };
static const char *const none[] = { NULL };
enum { NX, NY, NZ, PX, PY, PZ, ROUGH, OBJID, MASK, HIT, DEPTH, NGUIDES };

struct atrous {
	uint32_t passes, normal;
	float inv_plane, inv_rough, inv_color, lobe;
	float *sum; /* nsum values' running sums (grown in run, not per pixel) */
	uint32_t nsum;
};

/* e^-x for x >= 0, to 2e-4 relative: 2^(-x log2 e) from the exponent
 * bits and a cubic for the fraction; 0 past 87 and for NaN. */
static inline float
exp_neg(float x)
{
	union { float f; uint32_t u; } v;
	float t = x * 1.44269504f, f;
	int32_t i;

	if (!(t < 126.0f))
		return 0.0f;
	i = (int32_t)t;
	f = t - (float)i;
	/* 2^-f on [0, 1] */
	v.f = 1.0f + f * (-0.69314718f + f * (0.24022651f + f * (-0.05550411f)));
	v.u -= (uint32_t)i << 23;
	return v.f;
}

static inline float
ipow(float x, uint32_t n)
{
	float r = 1.0f;

	while (n) {
		if (n & 1)
			r *= x;
		x *= x;
		n >>= 1;
	}
	return r;
}

static inline int
usable(const float *g)
{
	return isfinite(g[NX]) && isfinite(g[NY]) && isfinite(g[NZ]) && isfinite(g[PX]) &&
	       isfinite(g[PY]) && isfinite(g[PZ]) && isfinite(g[ROUGH]) && !(g[MASK] < 0.5f);
}

/* The pixel's size on its surface: the distance to the nearest usable
 * neighbour of the same object in the row, or in the rows above and
 * below; +inf when it has none. */
static float
pixel_size(const struct rf_span *span, uint32_t x, size_t stride)
{
	const float *c = span->band[span->radius] + (size_t)x * stride;
	float best = INFINITY;
	int k;

	for (k = 0; k < 4; k++) {
		const float *row = span->band[span->radius + (k == 2 ? -1 : k == 3 ? 1 : 0)];
		long qx = (long)x + (k == 0 ? -1 : k == 1 ? 1 : 0);
		const float *q;
		float dx, dy, dz, d;

		if (!row || qx < 0 || qx >= (long)span->width)
			continue;
		q = row + (size_t)qx * stride;
		if (q[OBJID] != c[OBJID] || !usable(q))
			continue;
		dx = q[PX] - c[PX];
		dy = q[PY] - c[PY];
		dz = q[PZ] - c[PZ];
		d = dx * dx + dy * dy + dz * dz;
		best = d < best ? d : best;
	}
	return sqrtf(best);
}

static void
run(void *state, const struct rf_span *span)
{
	static const float h[5] = { 1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16 };
	struct atrous *a = state;
	const uint32_t nv = span->nvalues, step = 1u << span->pass;
	const size_t stride = NGUIDES + nv;
	const float *row = span->band[span->radius];
	float *out = span->out, *sum;
	uint32_t i, v;

	if (nv > a->nsum) {
		float *grown = realloc(a->sum, nv * sizeof(float));

		if (!grown) {
			/* no room to filter: the values as they are */
			for (i = 0; i < span->npix; i++)
				memcpy(out + (size_t)i * nv, row + (size_t)(span->x + i) * stride + NGUIDES,
				       nv * sizeof(float));
			return;
		}
		a->sum = grown;
		a->nsum = nv;
	}
	sum = a->sum;
	for (i = 0; i < span->npix; i++, out += nv) {
		const uint32_t x = span->x + i;
		const float *p = row + (size_t)x * stride, *vp = p + NGUIDES;
		float wsum = 0.0f, lp = 0.0f, reach, inv_r;
		int dx, dy;

		memcpy(out, vp, nv * sizeof(float));
		if (!usable(p))
			continue; /* not reflective, or no geometry: as it is */
		if (a->lobe > 0.0f && p[HIT] == p[HIT]) {
			/* the reflection's own blur on the surface, against this
			 * pass's reach */
			float alpha = p[ROUGH] * p[ROUGH], blur = 2.0f * alpha * p[HIT];

			if (p[DEPTH] > 0.0f && p[HIT] < INFINITY)
				blur *= p[DEPTH] / (p[DEPTH] + p[HIT]);
			reach = 2.0f * (float)step * pixel_size(span, x, stride);
			if (!(reach <= a->lobe * blur))
				continue;
		}
		inv_r = a->inv_rough / (p[ROUGH] > 0.05f ? p[ROUGH] : 0.05f);
		for (v = 0; v < nv; v++) {
			sum[v] = 0.0f;
			lp += vp[v];
		}
		lp /= (float)nv;
		for (dy = -2; dy <= 2; dy++) {
			const float *qrow = span->band[(long)span->radius + dy * (long)step];

			if (!qrow)
				continue;
			for (dx = -2; dx <= 2; dx++) {
				long qx = (long)x + dx * (long)step;
				const float *q, *vq;
				float w, e, ddx, ddy, ddz, dist2, plane, dr, nd;

				if (qx < 0 || qx >= (long)span->width)
					continue;
				q = qrow + (size_t)qx * stride;
				vq = q + NGUIDES;
				/* a guide that is not finite makes w NaN, and the tap is
				 * dropped below */
				if (q[OBJID] != p[OBJID] || q[MASK] < 0.5f)
					continue;
				nd = p[NX] * q[NX] + p[NY] * q[NY] + p[NZ] * q[NZ];
				if (!(nd > 0.0f))
					continue;
				w = h[dx + 2] * h[dy + 2] * ipow(nd, a->normal);
				ddx = q[PX] - p[PX];
				ddy = q[PY] - p[PY];
				ddz = q[PZ] - p[PZ];
				dist2 = ddx * ddx + ddy * ddy + ddz * ddz;
				plane = p[NX] * ddx + p[NY] * ddy + p[NZ] * ddz;
				e = dist2 > 0.0f ? fabsf(plane) / sqrtf(dist2) * a->inv_plane : 0.0f;
				dr = fabsf(p[ROUGH] - q[ROUGH]);
				e += dr * inv_r;
				if (a->inv_color > 0.0f) {
					float lq = 0.0f, mean;

					for (v = 0; v < nv; v++)
						lq += vq[v];
					lq /= (float)nv;
					mean = 0.5f * (fabsf(lp) + fabsf(lq));
					e += mean > 0.0f ? fabsf(lp - lq) * a->inv_color / mean : 0.0f;
				}
				w *= exp_neg(e);
				if (!(w > 0.0f))
					continue;
				wsum += w;
				for (v = 0; v < nv; v++)
					sum[v] += w * (vq[v] - vp[v]);
			}
		}
		if (wsum > 0.0f)
			for (v = 0; v < nv; v++)
				out[v] = vp[v] + sum[v] / wsum;
	}
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct atrous *a;
	uint32_t radius[RF_FILTER_PASSES_MAX], i;

	if (host->size < offsetof(struct rf_host, filter_passes) + sizeof(host->filter_passes) ||
	    !host->filter_passes) {
		snprintf(err, errlen, "this host runs no filter passes (it needs "
		         "reflect-filter of plugin ABI 1.1 or later)");
		return -1;
	}
	if (!(a = calloc(1, sizeof(*a)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	a->passes = (uint32_t)values[PASSES];
	a->normal = (uint32_t)values[NORMAL];
	a->inv_plane = (float)(1.0 / values[PLANE]);
	a->inv_rough = (float)(1.0 / values[ROUGHNESS]);
	a->inv_color = values[COLOR] > 0.0 ? (float)(1.0 / values[COLOR]) : 0.0f;
	a->lobe = (float)values[LOBE];
	for (i = 0; i < a->passes; i++)
		radius[i] = 2u << i;
	if (host->filter_passes(host->ctx, a->passes, radius) < 0) {
		snprintf(err, errlen, "the host refused %u passes", a->passes);
		free(a);
		return -1;
	}
	*state = a;
	return 0;
}

static void
destroy(void *state)
{
	struct atrous *a = state;

	if (a)
		free(a->sum);
	free(a);
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_FILTER,
	.name = "atrous",
	.summary = "an edge-avoiding a-trous wavelet filter guided by the G-buffer, its "
	           "reach held to the lobe",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = none,
	.optional_inputs = optional_inputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
