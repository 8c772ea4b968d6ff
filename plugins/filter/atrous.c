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
	float *soa; /* run()'s scratch, ncap floats (grown, not per span) */
	size_t ncap;
};

/* Guide f of pixel x of a planar band row. */
#define AT(row, f, x) ((row)[(size_t)(f) * w + (x)])

static inline int
usable(const float *row, size_t w, size_t x)
{
	return isfinite(AT(row, NX, x)) && isfinite(AT(row, NY, x)) && isfinite(AT(row, NZ, x)) &&
	       isfinite(AT(row, PX, x)) && isfinite(AT(row, PY, x)) && isfinite(AT(row, PZ, x)) &&
	       isfinite(AT(row, ROUGH, x)) && !(AT(row, MASK, x) < 0.5f);
}

/* The pixel's size on its surface: the distance to the nearest usable
 * neighbour of the same object in the row, or in the rows above and
 * below; +inf when it has none. */
static float
pixel_size(const struct rf_span *span, size_t x)
{
	const size_t w = span->width;
	const float *c = span->band[span->radius];
	float best = INFINITY;
	int k;

	for (k = 0; k < 4; k++) {
		const float *row = span->band[span->radius + (k == 2 ? -1 : k == 3 ? 1 : 0)];
		long qx = (long)x + (k == 0 ? -1 : k == 1 ? 1 : 0);
		float dx, dy, dz, d;

		if (!row || qx < 0 || qx >= (long)w)
			continue;
		if (AT(row, OBJID, qx) != AT(c, OBJID, x) || !usable(row, w, (size_t)qx))
			continue;
		dx = AT(row, PX, qx) - AT(c, PX, x);
		dy = AT(row, PY, qx) - AT(c, PY, x);
		dz = AT(row, PZ, qx) - AT(c, PZ, x);
		d = dx * dx + dy * dy + dz * dz;
		best = d < best ? d : best;
	}
	return sqrtf(best);
}

/* Four pixels at a time, straight from the planar band rows: every pixel
 * goes through the same vector code, the same bits wherever it lies.  A
 * tap off the row's ends reads lanes one by one, an objid of NaN for the
 * lanes outside (which then weigh nothing). */
typedef float v4f __attribute__((vector_size(16)));
typedef int32_t v4i __attribute__((vector_size(16)));

static inline v4f
v4_splat(float x)
{
	v4f v = { x, x, x, x };

	return v;
}

static inline v4f
v4_select(v4i m, v4f a, v4f b)
{
	return (v4f)(((v4i)a & m) | ((v4i)b & ~m));
}

static inline v4f
v4_sqrt(v4f x)
{
	v4f r;
	int i;

	for (i = 0; i < 4; i++)
		r[i] = sqrtf(x[i]);
	return r;
}

/* exp_neg, lane by lane the same operations */
static inline v4f
v4_exp_neg(v4f x)
{
	const v4f t = x * 1.44269504f;
	v4i ok = t < v4_splat(126.0f), i;
	v4f ti = v4_select(ok, t, v4_splat(0.0f)), f, r;

	i = __builtin_convertvector(ti, v4i);
	f = ti - __builtin_convertvector(i, v4f);
	r = 1.0f + f * (-0.69314718f + f * (0.24022651f + f * (-0.05550411f)));
	r = (v4f)((v4i)r - (i << 23));
	return v4_select(ok, r, v4_splat(0.0f));
}

static inline v4f
v4_ipow(v4f x, uint32_t n)
{
	v4f r = v4_splat(1.0f);

	while (n) {
		if (n & 1)
			r *= x;
		x *= x;
		n >>= 1;
	}
	return r;
}

/* Field f of pixels x .. x + 3 of a planar row of width w. */
static inline v4f
lanes(const float *row, size_t w, size_t f, long x)
{
	const float *a = row + f * w;
	v4f v;
	int k;

	if (x >= 0 && x + 4 <= (long)w) {
		memcpy(&v, a + x, sizeof(v));
		return v;
	}
	for (k = 0; k < 4; k++)
		v[k] = x + k >= 0 && x + k < (long)w ? a[x + k] : (f == OBJID ? NAN : 0.0f);
	return v;
}

/* The 25 taps of pixels x .. x + 3: the sum of their weights, and in
 * vsum the weighted sums of (v_q - v_p) for values v0 .. v1 - 1. */
static v4f
taps(const struct atrous *a, const struct rf_span *span, long x, const float *lp,
     uint32_t v0, uint32_t v1, v4f *vsum)
{
	static const float h[5] = { 1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16 };
	const v4i magnitude = { 0x7FFFFFFF, 0x7FFFFFFF, 0x7FFFFFFF, 0x7FFFFFFF };
	const size_t w = span->width;
	const uint32_t nv = span->nvalues, step = 1u << span->pass;
	const float *c = span->band[span->radius];
	const v4f pr = lanes(c, w, ROUGH, x), po = lanes(c, w, OBJID, x);
	const v4f inv_r = a->inv_rough / v4_select(pr > 0.05f, pr, v4_splat(0.05f));
	v4f pn[3], pp[3], pv[64], plp, wsum = v4_splat(0.0f);
	uint32_t v, k;
	int dy, dx;

	memcpy(&plp, lp, sizeof(plp));
	for (k = 0; k < 3; k++) {
		pn[k] = lanes(c, w, NX + k, x);
		pp[k] = lanes(c, w, PX + k, x);
	}
	for (v = v0; v < v1; v++) {
		vsum[v - v0] = v4_splat(0.0f);
		pv[v - v0] = lanes(c, w, NGUIDES + v, x);
	}
	for (dy = -2; dy <= 2; dy++) {
		const float *q = span->band[(long)span->radius + dy * (long)step];

		if (!q)
			continue;
		for (dx = -2; dx <= 2; dx++) {
			const long qx = x + dx * (long)step;
			v4f nd, e, wt, ddx, ddy, ddz, dist2, plane;
			v4i keep;

			/* the same object, on the mask (or no mask: NaN) */
			keep = (lanes(q, w, OBJID, qx) == po) & ~(lanes(q, w, MASK, qx) < 0.5f);
			nd = pn[0] * lanes(q, w, NX, qx) + pn[1] * lanes(q, w, NY, qx) +
			     pn[2] * lanes(q, w, NZ, qx);
			keep &= nd > 0.0f;
			wt = h[dx + 2] * h[dy + 2] * v4_ipow(nd, a->normal);
			ddx = lanes(q, w, PX, qx) - pp[0];
			ddy = lanes(q, w, PY, qx) - pp[1];
			ddz = lanes(q, w, PZ, qx) - pp[2];
			dist2 = ddx * ddx + ddy * ddy + ddz * ddz;
			plane = (v4f)((v4i)(pn[0] * ddx + pn[1] * ddy + pn[2] * ddz) & magnitude);
			e = v4_select(dist2 > 0.0f, plane / v4_sqrt(dist2) * a->inv_plane,
			              v4_splat(0.0f));
			e += (v4f)((v4i)(lanes(q, w, ROUGH, qx) - pr) & magnitude) * inv_r;
			if (a->inv_color > 0.0f) {
				v4f lq = v4_splat(0.0f), mean, diff;

				for (v = 0; v < nv; v++)
					lq += lanes(q, w, NGUIDES + v, qx);
				lq /= (float)nv;
				mean = 0.5f * ((v4f)((v4i)plp & magnitude) + (v4f)((v4i)lq & magnitude));
				diff = (v4f)((v4i)(plp - lq) & magnitude);
				e += v4_select(mean > 0.0f, diff * a->inv_color / mean, v4_splat(0.0f));
			}
			wt *= v4_exp_neg(e);
			keep &= wt > 0.0f; /* and not NaN, from a guide that is not finite */
			wt = v4_select(keep, wt, v4_splat(0.0f));
			wsum += wt;
			for (v = v0; v < v1; v++)
				vsum[v - v0] += wt * (lanes(q, w, NGUIDES + v, qx) - pv[v - v0]);
		}
	}
	return wsum;
}

/* Per-instance scratch, grown in run() (once a size, not per pixel). */
static int
reserve(struct atrous *a, size_t floats)
{
	if (floats > a->ncap) {
		float *grown = realloc(a->soa, floats * sizeof(float));

		if (!grown)
			return -1;
		a->soa = grown;
		a->ncap = floats;
	}
	return 0;
}

static void
run(void *state, const struct rf_span *span)
{
	struct atrous *a = state;
	const uint32_t nv = span->nvalues, step = 1u << span->pass, n = span->npix;
	const size_t w = span->width;
	const float *row = span->band[span->radius];
	float *act, *lp;
	uint32_t i, v;

	/* the values as they are, for the pixels the pass leaves alone */
	for (v = 0; v < nv; v++)
		memcpy(span->out + (size_t)v * n, row + (NGUIDES + v) * w + span->x,
		       n * sizeof(float));
	if (reserve(a, 2 * ((size_t)w + 4)) < 0)
		return; /* no room to filter: the values as they are */
	act = a->soa;
	lp = act + w + 4;
	/* Which pixels this pass touches: reflective, with geometry, and (the
	 * lobe) whose reach stays within the reflection's own blur. */
	for (i = 0; i < w + 4; i++)
		act[i] = lp[i] = 0.0f;
	for (i = span->x; i < span->x + n; i++) {
		if (!usable(row, w, i))
			continue;
		if (a->lobe > 0.0f && AT(row, HIT, i) == AT(row, HIT, i)) {
			float r = AT(row, ROUGH, i), hit = AT(row, HIT, i), d = AT(row, DEPTH, i);
			float blur = 2.0f * r * r * hit;

			if (d > 0.0f && hit < INFINITY)
				blur *= d / (d + hit);
			if (!(2.0f * (float)step * pixel_size(span, i) <= a->lobe * blur))
				continue;
		}
		act[i] = 1.0f;
		for (v = 0; v < nv; v++)
			lp[i] += AT(row, NGUIDES + v, i);
		lp[i] /= (float)nv;
	}
	for (i = span->x & ~3u; i < span->x + n; i += 4) {
		uint32_t v0, k;
		int any = 0;

		for (k = 0; k < 4; k++)
			any |= i + k < w && act[i + k] != 0.0f;
		if (!any)
			continue;
		/* 64 values at a time (the weights again for each 64 more) */
		for (v0 = 0; v0 < nv; v0 += 64) {
			uint32_t v1 = v0 + 64 < nv ? v0 + 64 : nv;
			v4f vsum[64], wsum = taps(a, span, (long)i, lp + i, v0, v1, vsum);

			for (k = 0; k < 4; k++) {
				uint32_t x = i + k;

				if (x < span->x || x >= span->x + n || act[x] == 0.0f || !(wsum[k] > 0.0f))
					continue;
				for (v = v0; v < v1; v++)
					span->out[(size_t)v * n + (x - span->x)] =
						AT(row, NGUIDES + v, x) + vsum[v - v0][k] / wsum[k];
			}
		}
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
		free(a->soa);
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
