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
 *     G-buffer channel shows;
 *   - luminance, with variance=auto (SVGF's): exp(-|l_p - l_q| /
 *     (luminance sqrt(g3x3(var_p)) + 1e-10)), var_p the variance of l_p:
 *     in the first pass from the standard errors reflect-accumulate
 *     --stats writes, else the spread of l over the pass's taps under
 *     the weights above; each pass filters it along (sum w^2 var_q /
 *     (sum w)^2) and hands it to the next in the host's carried row, so
 *     the stop tightens as the noise goes.  A step the noise cannot
 *     make is an edge, whatever the G-buffer says.
 * The weights multiply into one exponential a tap (the luminance stop
 * after the others: the spread it needs is taken under them).
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

enum { PASSES, NORMAL, PLANE, ROUGHNESS, COLOR, LOBE, VARIANCE, LUMINANCE, NPARAMS };

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
	{ "variance", "stop at luminance steps larger than the noise's spread (off: the "
	  "G-buffer's stops alone)", 0, 1, 1, RF_PARAM_CHOICE, "off|auto" },
	{ "luminance", "the luminance step, in standard deviations of the noise, that weighs "
	  "1/e", 0.01, 1000, 8, 0, NULL },
};

/* Guides: the inputs, then the optional inputs. */
static const char *const inputs[] = { "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z",
                                      "roughness", "objid", NULL };
static const char *const optional_inputs[] = { "mask", "hit.dist", "depth", "spec.R.se",
                                               "spec.G.se", "spec.B.se", NULL };
enum { NX, NY, NZ, PX, PY, PZ, ROUGH, OBJID, MASK, HIT, DEPTH, SER, SEG, SEB, NGUIDES };
/* State carried from pass to pass, after the values: the variance of
 * the luminance (the values' mean) as the pass left it. */
static const char *const carried[] = { "variance", NULL };

struct atrous {
	uint32_t passes, normal;
	float inv_plane, inv_rough, inv_color, lobe, sigma_l;
	int variance;
	float *scratch; /* run()'s scratch, ncap floats (grown, not per span) */
	size_t ncap;
	int wide; /* eight lanes (AVX2) */
	const struct rf_host *host; /* for fail() */
};

/* Guide f of pixel x of a planar band row. */
#define AT(row, f, x) ((row)[(size_t)(f) * w + (x)])

/* ok[x] = 1 where pixel x of a planar band row is usable: its geometry
 * finite and on the mask (or no mask: NaN).  Four pixels at a time, on
 * the bits: a test a pixel, as scalar code, cost a fifth of a pass. */
static void
usable_row(const float *row, size_t w, unsigned char *ok)
{
	typedef uint32_t v4u __attribute__((vector_size(16)));
	static const int fields[] = { NX, NY, NZ, PX, PY, PZ, ROUGH };
	const size_t nf = sizeof(fields) / sizeof(fields[0]);
	const float *m = row + (size_t)MASK * w;
	size_t x, k;

	for (x = 0; x + 4 <= w; x += 4) {
		v4u all = { 0, 0, 0, 0 }, bits;
		float mask[4];

		for (k = 0; k < nf; k++) {
			memcpy(&bits, row + (size_t)fields[k] * w + x, sizeof(bits));
			all |= (v4u)((bits & 0x7F800000u) == 0x7F800000u);
		}
		memcpy(mask, m + x, sizeof(mask));
		for (k = 0; k < 4; k++)
			ok[x + k] = !all[k] && !(mask[k] < 0.5f);
	}
	for (; x < w; x++) {
		ok[x] = !(m[x] < 0.5f);
		for (k = 0; k < nf; k++)
			ok[x] &= (unsigned char)isfinite(row[(size_t)fields[k] * w + x]);
	}
}

/* The pixel's size on its surface: the distance to the nearest
 * neighbour of the same object in the row, or in the rows above and
 * below, +inf when it has none.  A neighbour whose position is not
 * finite gives a distance of NaN, which is never the nearest: the pixels
 * around need no test of their own. */
static float
pixel_size(const struct rf_span *span, size_t x)
{
	const size_t w = span->width;
	const float *c = span->band[span->radius];
	float best = INFINITY;
	int k;

	for (k = 0; k < 4; k++) {
		const int dy = k == 2 ? -1 : k == 3 ? 1 : 0;
		const float *row = span->band[span->radius + dy];
		long qx = (long)x + (k == 0 ? -1 : k == 1 ? 1 : 0);
		float dx, ddy, dz, d;

		if (!row || qx < 0 || qx >= (long)w || AT(row, OBJID, qx) != AT(c, OBJID, x))
			continue;
		dx = AT(row, PX, qx) - AT(c, PX, x);
		ddy = AT(row, PY, qx) - AT(c, PY, x);
		dz = AT(row, PZ, qx) - AT(c, PZ, x);
		d = dx * dx + ddy * ddy + dz * dz;
		best = d < best ? d : best;
	}
	return sqrtf(best);
}

/* Whether a pass of spacing step stays within the lobe at pixel x: the
 * same test for the pixels whose hit distance is known, else yes. */
static inline int
within_lobe(const struct atrous *a, float step, float r, float hit, float d, float size)
{
	float blur = 2.0f * r * r * hit;

	if (hit != hit)
		return 1;
	if (d > 0.0f && hit < INFINITY)
		blur *= d / (d + hit);
	return 2.0f * step * size <= a->lobe * blur;
}

/* act[x] = 0 where the pass would reach beyond the lobe.  The pixel's
 * size four pixels at a time inside the row (as pixel_size, the same
 * operations in the same order), pixel_size at its ends: a pixel at a
 * time it cost a tenth of the filter. */
static void
lobe_limit(const struct atrous *a, const struct rf_span *span, float *act)
{
	typedef float v4 __attribute__((vector_size(16)));
	typedef int32_t v4m __attribute__((vector_size(16)));
	const size_t w = span->width, x0 = span->x, x1 = span->x + span->npix;
	const float step = (float)(1u << span->pass);
	const float *c = span->band[span->radius];
	const float *up = span->band[span->radius - 1], *down = span->band[span->radius + 1];
	const float *const rows[4] = { c, c, up, down };
	const long shift[4] = { -1, 1, 0, 0 };
	size_t x = x0;

	for (; x < x1 && (x < 1 || x + 5 > w || (x - x0) % 4); x++)
		if (act[x] != 0.0f &&
		    !within_lobe(a, step, AT(c, ROUGH, x), AT(c, HIT, x), AT(c, DEPTH, x),
		                 pixel_size(span, x)))
			act[x] = 0.0f;
	for (; x + 4 <= x1 && x + 5 <= w; x += 4) {
		v4 cp[3], co, best = { INFINITY, INFINITY, INFINITY, INFINITY }, size;
		int k, f;

		for (f = 0; f < 3; f++)
			memcpy(&cp[f], c + (size_t)(PX + f) * w + x, sizeof(v4));
		memcpy(&co, c + (size_t)OBJID * w + x, sizeof(v4));
		for (k = 0; k < 4; k++) {
			const float *row = rows[k];
			v4 qp[3], qo, d;
			v4m same;

			if (!row)
				continue;
			for (f = 0; f < 3; f++)
				memcpy(&qp[f], row + (size_t)(PX + f) * w + x + shift[k], sizeof(v4));
			memcpy(&qo, row + (size_t)OBJID * w + x + shift[k], sizeof(v4));
			qp[0] -= cp[0];
			qp[1] -= cp[1];
			qp[2] -= cp[2];
			d = qp[0] * qp[0] + qp[1] * qp[1] + qp[2] * qp[2];
			same = (qo == co) & (d < best);
			best = (v4)(((v4m)d & same) | ((v4m)best & ~same));
		}
		for (k = 0; k < 4; k++) {
			size[k] = sqrtf(best[k]);
			if (act[x + k] != 0.0f &&
			    !within_lobe(a, step, AT(c, ROUGH, x + k), AT(c, HIT, x + k),
			                 AT(c, DEPTH, x + k), size[k]))
				act[x + k] = 0.0f;
		}
	}
	for (; x < x1; x++)
		if (act[x] != 0.0f &&
		    !within_lobe(a, step, AT(c, ROUGH, x), AT(c, HIT, x), AT(c, DEPTH, x),
		                 pixel_size(span, x)))
			act[x] = 0.0f;
}

/* Four pixels at a time, or eight where AVX2 is (atrous-taps.h),
 * straight from the planar band rows: every pixel goes through the same
 * vector code, the same bits wherever it lies and at either width.  A
 * tap off the row's ends reads lanes one by one, an objid of NaN for the
 * lanes outside (which then weigh nothing). */
#define RF__LANES_BODY "atrous-taps.h"
#include "maths/lanes-widths.h"

/* Per-instance scratch, grown in run() (once a size, not per pixel). */
static int
reserve(struct atrous *a, size_t floats)
{
	if (floats > a->ncap) {
		float *grown = realloc(a->scratch, floats * sizeof(float));

		if (!grown)
			return -1;
		a->scratch = grown;
		a->ncap = floats;
	}
	return 0;
}

/* The variance of pixel x's luminance as the pass gets it: from the
 * first pass's standard errors (spec.R.se G B, from reflect-accumulate
 * --stats; NaN without them, +inf when not known yet), else the state
 * the pass before left. */
static inline float
in_var(const struct rf_span *span, const float *row, size_t x)
{
	const size_t w = span->width;
	float r, g, b;

	if (span->pass)
		return AT(row, NGUIDES + span->nvalues, x);
	r = AT(row, SER, x);
	g = AT(row, SEG, x);
	b = AT(row, SEB, x);
	/* the reflection's channels move together: the mean of their
	 * variances, not a third of it */
	return (r * r + g * g + b * b) / 3.0f;
}

/* The variance at x through a 3x3 binomial blur over the same object
 * (SVGF's prefilter, so that one noisy estimate does not stop the
 * blur); NaN where the pixel's own is not finite. */
static float
var_3x3(const struct rf_span *span, const float *vin, size_t x)
{
	static const float k[3] = { 0.25f, 0.5f, 0.25f };
	const size_t w = span->width;
	const float *c = span->band[span->radius];
	float sum = 0.0f, wsum = 0.0f;
	int dx, dy;

	if (!(vin[x] < INFINITY))
		return NAN;
	for (dy = -1; dy <= 1; dy++) {
		const float *row = span->band[(long)span->radius + dy];

		if (!row)
			continue;
		for (dx = -1; dx <= 1; dx++) {
			long qx = (long)x + dx;
			float v;

			if (qx < 0 || qx >= (long)w || AT(row, OBJID, qx) != AT(c, OBJID, x) ||
			    AT(row, MASK, qx) < 0.5f)
				continue;
			v = dy ? in_var(span, row, (size_t)qx) : vin[qx];
			if (!(v < INFINITY))
				continue;
			sum += k[dx + 1] * k[dy + 1] * v;
			wsum += k[dx + 1] * k[dy + 1];
		}
	}
	return sum / wsum;
}

/* A standard error that is NaN (in a stream that has the channel: a
 * neighbour in the row is not NaN) or negative: the variance it gives
 * would be silently wrong, so the run stops. */
static int
check_se(const struct atrous *a, const struct rf_span *span, const float *row)
{
	static const char *const names[3] = { "spec.R.se", "spec.G.se", "spec.B.se" };
	const size_t w = span->width;
	char msg[200];
	size_t x;
	int c;

	for (c = 0; c < 3; c++) {
		const float *se = row + (size_t)(SER + c) * w;
		size_t nan = w, present = 0;

		for (x = 0; x < w; x++) {
			if (se[x] != se[x]) {
				nan = nan < w ? nan : x;
				continue;
			}
			present = 1;
			if (se[x] < 0.0f) {
				nan = x;
				break;
			}
		}
		if (!present || nan == w)
			continue;
		snprintf(msg, sizeof(msg), "row %u, pixel %zu: channel '%s' is %g, not a "
		         "standard error (0 or more, inf when not known); give it as "
		         "reflect-accumulate --stats writes it, or drop it", span->y + 1,
		         nan + 1, names[c], (double)se[nan]);
		if (a->host->fail)
			a->host->fail(a->host->ctx, msg);
		return -1;
	}
	return 0;
}

static void group(const struct atrous *a, const struct rf_span *span, uint32_t i,
                  const float *act, const float *lp, const float *den, const float *vin);

static void
run(void *state, const struct rf_span *span)
{
	struct atrous *a = state;
	const uint32_t nv = span->nvalues, n = span->npix;
	const size_t w = span->width;
	const float *row = span->band[span->radius];
	float *vout = span->out + (size_t)nv * n;
	unsigned char *ok;
	float *act, *lp, *den, *vin;
	uint32_t i, v;

	/* the values as they are, for the pixels the pass leaves alone */
	for (v = 0; v < nv; v++)
		memcpy(span->out + (size_t)v * n, row + (NGUIDES + v) * w + span->x,
		       n * sizeof(float));
	for (i = 0; i < n; i++)
		vout[i] = NAN;
	if (reserve(a, 4 * ((size_t)w + 8) + (w + 3) / sizeof(float) + 1) < 0)
		return; /* no room to filter: the values as they are */
	act = a->scratch;
	lp = act + w + 8;
	den = lp + w + 8;
	vin = den + w + 8;
	ok = (unsigned char *)(vin + w + 8);
	usable_row(row, w, ok);
	/* Which pixels this pass touches: reflective, with geometry, and (the
	 * lobe) whose reach stays within the reflection's own blur. */
	for (i = 0; i < w + 8; i++)
		act[i] = lp[i] = den[i] = vin[i] = 0.0f;
	for (i = span->x; i < span->x + n; i++)
		act[i] = ok[i];
	if (a->lobe > 0.0f)
		lobe_limit(a, span, act);
	if (a->variance) {
		if (!span->pass && check_se(a, span, row) < 0)
			return;
		/* the whole row: the 3x3 blur reads the neighbours' */
		for (i = 0; i < w; i++)
			vin[i] = in_var(span, row, i);
		for (i = span->x; i < span->x + n; i++) {
			vout[i - span->x] = vin[i];
			if (act[i] != 0.0f)
				den[i] = a->sigma_l * sqrtf(var_3x3(span, vin, i)) + 1e-10f;
		}
	}
	if (a->inv_color > 0.0f || a->variance) /* the luminance weights' only */
		for (i = span->x; i < span->x + n; i++) {
			if (act[i] == 0.0f)
				continue;
			for (v = 0; v < nv; v++)
				lp[i] += AT(row, NGUIDES + v, i);
			lp[i] /= (float)nv;
		}
	for (i = span->x & ~7u; i < span->x + n; i += 8)
		group(a, span, i, act, lp, den, vin);
}

/* Pixels i .. i + 7 (two groups of four, or one of eight). */
static void
group(const struct atrous *a, const struct rf_span *span, uint32_t i, const float *act,
      const float *lp, const float *den, const float *vin)
{
	const uint32_t nv = span->nvalues, n = span->npix;
	const size_t w = span->width;
	const float *row = span->band[span->radius];
	float wsum[8], vsum[64][8], varsum[8];
	uint32_t v0, v, k, half;
	int any = 0;

	for (k = 0; k < 8; k++)
		any |= i + k < w && act[i + k] != 0.0f;
	if (!any)
		return;
	/* 64 values at a time (the weights again for each 64 more) */
	for (v0 = 0; v0 < nv; v0 += 64) {
		uint32_t v1 = v0 + 64 < nv ? v0 + 64 : nv;

#if defined(RF__LANES_WIDE)
		if (a->wide) {
			taps_8(a, span, (long)i, lp + i, den + i, vin + i, v0, v1, wsum, vsum[0],
			       varsum);
		} else
#endif
		{
			float s4[64][4];

			for (half = 0; half < 8; half += 4) {
				taps_4(a, span, (long)(i + half), lp + i + half, den + i + half,
				       vin + i + half, v0, v1, wsum + half, s4[0], varsum + half);
				for (v = v0; v < v1; v++)
					memcpy(vsum[v - v0] + half, s4[v - v0], sizeof(s4[0]));
			}
		}
		for (k = 0; k < 8; k++) {
			uint32_t x = i + k;

			if (x < span->x || x >= span->x + n || act[x] == 0.0f || !(wsum[k] > 0.0f))
				continue;
			for (v = v0; v < v1; v++)
				span->out[(size_t)v * n + (x - span->x)] =
					AT(row, NGUIDES + v, x) + vsum[v - v0][k] / wsum[k];
			/* SVGF's: the weights squared carry the variance */
			if (a->variance)
				span->out[(size_t)nv * n + (x - span->x)] =
					varsum[k] / (wsum[k] * wsum[k]);
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
	a->variance = values[VARIANCE] > 0.5;
	a->sigma_l = (float)values[LUMINANCE];
	a->host = host;
	a->wide = rf__lanes_wide();
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
		free(a->scratch);
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
	.outputs = carried,
	.optional_inputs = optional_inputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
