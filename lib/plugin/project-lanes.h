/*
 * project_rays' loop for p inside the box, written once for LANES lanes:
 * host.c includes it for 4 (SSE, every x86-64) and, where the compiler
 * can target it, for 8 (AVX2, chosen when the host is set up).  The same
 * operations lane by lane in the same order as the scalar loop, and no
 * fused multiply-add: the same bits at either width.  Included by
 * lanes-widths.h (see lanes.h).
 */

#include "maths/lanes.h"

/* Rays i and on, LANES at a time; returns where it stopped. */
LANES_ATTR static uint32_t
NAME(project_lanes)(const struct rf__box *b, uint32_t i, uint32_t n, const float p[3],
                    const float *dirs, float *lookup, float *dist, float *jacobian)
{
	const VF inf = NAME(v_splat)(INFINITY), zero = NAME(v_splat)(0.0f);
	const VF one = NAME(v_splat)(1.0f);

	for (; i + LANES <= n; i += LANES) {
		VF dv[3], t = inf, lk[3], hx, hy, hz, len, inv, num, den, jac, da, la;
		VI axis = (VI)zero, hit, pos;
		int k;

		NAME(v_aos_to_soa)(dirs + 3 * i, dv);
		for (k = 0; k < 3; k++) {
			const VF hi = NAME(v_splat)(b->hi[k]), lo = NAME(v_splat)(b->lo[k]);
			VF wall = NAME(v_select)(dv[k] > zero, hi, lo), tk, ad;
			VI take;

			tk = (wall - p[k]) / dv[k];
			ad = (VF)((VI)dv[k] & 0x7FFFFFFF);
			take = (ad > RF__AXIS_EPSILON) & (tk < t);
			t = NAME(v_select)(take, tk, t);
			axis = (k & take) | (axis & ~take);
		}
		hit = t < inf;
		t = NAME(v_select)(t < zero, zero, t);
		hx = p[0] + dv[0] * t - b->center[0];
		hy = p[1] + dv[1] * t - b->center[1];
		hz = p[2] + dv[2] * t - b->center[2];
		len = NAME(v_sqrt)(hx * hx + hy * hy + hz * hz);
		inv = one / len;
		pos = len > zero;
		lk[0] = NAME(v_select)(pos, hx * inv, dv[0]);
		lk[1] = NAME(v_select)(pos, hy * inv, dv[1]);
		lk[2] = NAME(v_select)(pos, hz * inv, dv[2]);
		/* the lookup's and the ray's components on the wall's axis */
		la = NAME(v_select)(axis == 0, lk[0], NAME(v_select)(axis == 1, lk[1], lk[2]));
		da = NAME(v_select)(axis == 0, dv[0], NAME(v_select)(axis == 1, dv[1], dv[2]));
		la = (VF)((VI)la & 0x7FFFFFFF);
		da = (VF)((VI)da & 0x7FFFFFFF);
		num = t * t * la;
		den = len * len * da;
		jac = NAME(v_select)(pos, num / den, one);
		for (k = 0; k < 3; k++)
			lk[k] = NAME(v_select)(hit, lk[k], dv[k]);
		jac = NAME(v_select)(hit, jac, one);
		t = NAME(v_select)(hit, t, inf);
		NAME(v_soa_to_aos)(lk, lookup + 3 * i);
		memcpy(dist + i, &t, sizeof(t));
		memcpy(jacobian + i, &jac, sizeof(jac));
	}
	return i;
}
