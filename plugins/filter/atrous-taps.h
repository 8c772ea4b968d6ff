/*
 * The vector code of atrous.c, written once for LANES lanes: atrous.c
 * includes it for 4 (SSE, every x86-64) and, where the compiler can
 * target it, for 8 (AVX2, chosen at run time).  The same operations lane
 * by lane, in the same order, and no fused multiply-add: the same bits
 * at either width.  Included by lanes-widths.h (see lanes.h).
 */

#include "maths/lanes.h"

/* exp_neg, lane by lane the same operations */
LANES_ATTR static inline VF
NAME(v_exp_neg)(VF x)
{
	const VF t = x * 1.44269504f;
	VI ok = t < NAME(v_splat)(126.0f), i;
	VF ti = NAME(v_select)(ok, t, NAME(v_splat)(0.0f)), f, r;

	i = __builtin_convertvector(ti, VI);
	f = ti - __builtin_convertvector(i, VF);
	r = 1.0f + f * (-0.69314718f + f * (0.24022651f + f * (-0.05550411f)));
	r = (VF)((VI)r - (i << 23));
	return NAME(v_select)(ok, r, NAME(v_splat)(0.0f));
}

LANES_ATTR static inline VF
NAME(v_ipow)(VF x, uint32_t n)
{
	VF r = NAME(v_splat)(1.0f);

	if (n && !(n & (n - 1))) { /* 2^k: k squarings, no tests a bit */
		for (; n > 1; n >>= 1)
			x *= x;
		return x;
	}

	while (n) {
		if (n & 1)
			r *= x;
		x *= x;
		n >>= 1;
	}
	return r;
}

/* Field f of pixels x .. x + LANES - 1 of a planar row of width w. */
LANES_ATTR static inline VF
NAME(lanes)(const float *row, size_t w, size_t f, long x)
{
	const float *a = row + f * w;
	VF v;
	int k;

	if (x >= 0 && x + LANES <= (long)w) {
		memcpy(&v, a + x, sizeof(v));
		return v;
	}
	for (k = 0; k < LANES; k++)
		v[k] = x + k >= 0 && x + k < (long)w ? a[x + k] : (f == OBJID ? NAN : 0.0f);
	return v;
}

/* The 25 taps of pixels x .. x + LANES - 1: the sum of their weights
 * (wsum_out, LANES floats), and the weighted sums of (v_q - v_p) for
 * values v0 .. v1 - 1 (vsum_out, LANES floats a value).  The weights
 * first, then each value's sum over them in a register: a value's sum
 * through memory, tap by tap, cost a fifth of the filter.  Through
 * memory, not vectors returned: the caller is not compiled for the wide
 * target. */
LANES_ATTR static void
NAME(taps)(const struct atrous *a, const struct rf_span *span, long x, const float *lp,
           const float *den, const float *vin, uint32_t v0, uint32_t v1, float *wsum_out,
           float *vsum_out, float *varsum_out)
{
	static const float h[5] = { 1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16 };
	const VI magnitude = (VI)NAME(v_splat)(0.0f) | 0x7FFFFFFF;
	const size_t w = span->width;
	const uint32_t nv = span->nvalues, step = 1u << span->pass;
	const float *c = span->band[span->radius];
	const VF pr = NAME(lanes)(c, w, ROUGH, x), po = NAME(lanes)(c, w, OBJID, x);
	const VF inv_r = a->inv_rough / NAME(v_select)(pr > 0.05f, pr, NAME(v_splat)(0.05f));
	VF pn[3], pp[3], plp, wsum = NAME(v_splat)(0.0f), wts[25], lqs[25], vqs[25];
	const float *tap_row[25];
	long tap_x[25];
	int tap_inside[25], ntaps = 0, centre = -1, t;
	uint32_t v, k;
	int dy, dx;

	memcpy(&plp, lp, sizeof(plp));
	for (k = 0; k < 3; k++) {
		pn[k] = NAME(lanes)(c, w, NX + k, x);
		pp[k] = NAME(lanes)(c, w, PX + k, x);
	}
	for (dy = -2; dy <= 2; dy++) {
		const float *q = span->band[(long)span->radius + dy * (long)step];

		if (!q)
			continue;
		for (dx = -2; dx <= 2; dx++) {
			const long qx = x + dx * (long)step;
			/* lanes all inside the row: plain loads, else lane by lane */
			const int inside = qx >= 0 && qx + LANES <= (long)w;
#define LD(f) (inside ? NAME(v_load)(q + (size_t)(f) * w + qx) : NAME(lanes)(q, w, (f), qx))
			VF nd, e, wt, ddx, ddy, ddz, dist2, plane;
			VI keep;

			/* the same object, on the mask (or no mask: NaN) */
			keep = (LD(OBJID) == po) & ~(LD(MASK) < 0.5f);
			nd = pn[0] * LD(NX) + pn[1] * LD(NY) +
			     pn[2] * LD(NZ);
			keep &= nd > 0.0f;
			wt = h[dx + 2] * h[dy + 2] * NAME(v_ipow)(nd, a->normal);
			ddx = LD(PX) - pp[0];
			ddy = LD(PY) - pp[1];
			ddz = LD(PZ) - pp[2];
			dist2 = ddx * ddx + ddy * ddy + ddz * ddz;
			plane = (VF)((VI)(pn[0] * ddx + pn[1] * ddy + pn[2] * ddz) & magnitude);
			e = NAME(v_select)(dist2 > 0.0f, plane / NAME(v_sqrt)(dist2) * a->inv_plane,
			              NAME(v_splat)(0.0f));
			e += (VF)((VI)(LD(ROUGH) - pr) & magnitude) * inv_r;
			if (a->inv_color > 0.0f || a->variance) {
				VF lq = NAME(v_splat)(0.0f);

				for (v = 0; v < nv; v++)
					lq += LD(NGUIDES + v);
				lq /= (float)nv;
				lqs[ntaps] = lq;
				if (a->variance)
					vqs[ntaps] = span->pass ? LD(NGUIDES + nv)
					                        : (LD(SER) * LD(SER) + LD(SEG) * LD(SEG) +
					                           LD(SEB) * LD(SEB)) / 3.0f;
			}
			if (a->inv_color > 0.0f) {
				VF lq = lqs[ntaps], mean, diff;

				mean = 0.5f * ((VF)((VI)plp & magnitude) + (VF)((VI)lq & magnitude));
				diff = (VF)((VI)(plp - lq) & magnitude);
				e += NAME(v_select)(mean > 0.0f, diff * a->inv_color / mean, NAME(v_splat)(0.0f));
			}
			wt *= NAME(v_exp_neg)(e);
			keep &= wt > 0.0f; /* and not NaN, from a guide that is not finite */
			wt = NAME(v_select)(keep, wt, NAME(v_splat)(0.0f));
			wsum += wt;
			if (!dx && !dy)
				centre = ntaps;
			wts[ntaps] = wt;
			tap_row[ntaps] = q;
			tap_x[ntaps] = qx;
			tap_inside[ntaps++] = inside;
#undef LD
		}
	}
	if (a->variance) {
		/* SVGF's luminance stop, |l_p - l_q| / (luminance sqrt(var_p) + eps),
		 * var_p through a 3x3 blur (den, from run()); where no variance
		 * came (one frame, or none accumulated), the spread of the
		 * luminance over these taps under the G-buffer's weights, as
		 * SVGF does before it has frames. */
		const VF inf = NAME(v_splat)(INFINITY);
		VF pden, pvar, m = NAME(v_splat)(0.0f), s2 = NAME(v_splat)(0.0f), spread, vs;

		memcpy(&pden, den, sizeof(pden));
		memcpy(&pvar, vin, sizeof(pvar));
		for (t = 0; t < ntaps; t++)
			m += wts[t] * lqs[t];
		m /= wsum;
		for (t = 0; t < ntaps; t++) {
			VF d = lqs[t] - m;

			s2 += wts[t] * (d * d);
		}
		spread = s2 / wsum;
		pden = NAME(v_select)(pden == pden, pden,
		                      a->sigma_l * NAME(v_sqrt)(spread) + 1e-10f);
		vs = NAME(v_select)(pvar < inf, pvar, spread);
		wsum = NAME(v_splat)(0.0f);
		spread = NAME(v_splat)(0.0f);
		for (t = 0; t < ntaps; t++) {
			VF diff = (VF)((VI)(plp - lqs[t]) & magnitude);
			VF vq = NAME(v_select)(vqs[t] < inf, vqs[t], vs);

			wts[t] *= NAME(v_exp_neg)(diff / pden);
			wsum += wts[t];
			spread += (wts[t] * wts[t]) * vq;
		}
		memcpy(varsum_out, &spread, sizeof(spread));
	}
	memcpy(wsum_out, &wsum, sizeof(wsum));
	for (v = v0; v < v1; v++) {
		const size_t f = NGUIDES + v;
		const VF pv = NAME(lanes)(c, w, f, x);
		VF vsum = NAME(v_splat)(0.0f);

		/* the centre's difference is 0: not a term, the same sum */
		for (t = 0; t < ntaps; t++) {
			const float *q = tap_row[t];
			VF vq;

			if (t == centre)
				continue;
			vq = tap_inside[t] ? NAME(v_load)(q + f * w + tap_x[t])
			                   : NAME(lanes)(q, w, f, tap_x[t]);
			vsum += wts[t] * (vq - pv);
		}
		memcpy(vsum_out + (size_t)(v - v0) * LANES, &vsum, sizeof(vsum));
	}
}
