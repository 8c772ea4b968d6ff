/*
 * The vector code of footprint.c, written once for LANES lanes:
 * footprint.c includes it for 4 (SSE, every x86-64, and the compiler's
 * generic vectors elsewhere) and, where the compiler can target it, for
 * 8 (AVX2, chosen when an instance is made; REFLECT_SIMD=off keeps 4).
 * A pixel's eight width rays, its log map and its taps are eight lanes
 * (taps: four, the rest unused); at 4 lanes each is two vectors.  The
 * same operations lane by lane in the same order and no fused
 * multiply-add, so either width gives the same bits.
 */

#include "maths/lanes.h"

#if LANES == 8
#include <immintrin.h>
#endif

/* Unit direction ca d + sa par + tb across, stored as xyz triples. */
LANES_ATTR static inline void
NAME(fv_direction)(VF ca, VF sa, VF tb, const float d[3], const float par[3],
                   const float across[3], float *out)
{
	VF r[3], len;
	int k, j;

	for (j = 0; j < 3; j++)
		r[j] = ca * d[j] + sa * par[j] + tb * across[j];
	len = NAME(v_splat)(1.0f) / NAME(v_sqrt)(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
	for (j = 0; j < 3; j++)
		r[j] = r[j] * len;
	for (k = 0; k < LANES; k++)
		for (j = 0; j < 3; j++)
			out[3 * k + j] = r[j][k];
}

/* sin and cos of x: x less the nearest multiple of pi / 2 (in two
 * parts), then Taylor to the 12th power on [-pi / 4, pi / 4] (error
 * below 1e-10, far under float's). */
LANES_ATTR static inline void
NAME(fv_sincos)(VF x, VF *s, VF *c)
{
	const VF zero = NAME(v_splat)(0.0f), half = NAME(v_splat)(0.5f);
	VI q = __builtin_convertvector(x * (float)(2.0 / M_PI) +
	                               NAME(v_select)(x < zero, -half, half), VI), swap, neg_s, neg_c;
	VF k = __builtin_convertvector(q, VF), r, r2, sr, cr, t;

	r = (x - k * 1.5703125f) - k * 4.838267948965580e-4f;
	r2 = r * r;
	sr = r + r * r2 * (-1.0f / 6 + r2 * (1.0f / 120 + r2 * (-1.0f / 5040 + r2 *
	     (1.0f / 362880 + r2 * (-1.0f / 39916800)))));
	cr = 1.0f + r2 * (-0.5f + r2 * (1.0f / 24 + r2 * (-1.0f / 720 + r2 * (1.0f / 40320 +
	     r2 * (-1.0f / 3628800 + r2 * (1.0f / 479001600))))));
	swap = (q & 1) != 0;
	neg_s = (q & 2) != 0;
	neg_c = ((q + 1) & 2) != 0;
	t = NAME(v_select)(swap, cr, sr);
	cr = NAME(v_select)(swap, sr, cr);
	sr = t;
	*s = NAME(v_select)(neg_s, -sr, sr);
	*c = NAME(v_select)(neg_c, -cr, cr);
}

/* atan2(s, z) for s >= 0: to [0, 1] by the smaller over the larger,
 * past tan(pi / 12) by atan t = pi / 6 + atan((sqrt(3) t - 1) /
 * (t + sqrt(3))), then Taylor to the 15th power (error below 1e-9). */
LANES_ATTR static inline VF
NAME(fv_atan2p)(VF s, VF z)
{
	const VF zero = NAME(v_splat)(0.0f), sqrt3 = NAME(v_splat)(1.7320508075688772f);
	VF az = NAME(v_select)(z < zero, -z, z), lo, hi, t, u, u2, a;
	VI big = s > az, far;

	lo = NAME(v_select)(big, az, s);
	hi = NAME(v_select)(big, s, az);
	t = lo / NAME(v_select)(hi > zero, hi, NAME(v_splat)(1.0f));
	far = t > 0.2679491924311227f;
	u = NAME(v_select)(far, (sqrt3 * t - 1.0f) / (t + sqrt3), t);
	u2 = u * u;
	a = u + u * u2 * (-1.0f / 3 + u2 * (1.0f / 5 + u2 * (-1.0f / 7 + u2 * (1.0f / 9 +
	    u2 * (-1.0f / 11 + u2 * (1.0f / 13 + u2 * (-1.0f / 15)))))));
	a = NAME(v_select)(far, a + (float)(M_PI / 6.0), a);
	a = NAME(v_select)(big, (float)M_PI_2 - a, a);
	return NAME(v_select)(z < zero, (float)M_PI - a, a);
}

/* The eight width rays: lane i turns by the angle whose cos, sin and
 * tan are ca[i], sa[i], tb[i]; out gets 24 floats. */
LANES_ATTR static void
NAME(fp_rays)(const float *ca, const float *sa, const float *tb, const float d[3],
              const float par[3], const float across[3], float *out)
{
	int i;

	for (i = 0; i < 8; i += LANES)
		NAME(fv_direction)(NAME(v_load)(ca + i), NAME(v_load)(sa + i),
		                   NAME(v_load)(tb + i), d, par, across, out + 3 * i);
}

/* Up to eight taps at in-plane angle ia and across angle ib: out gets
 * 24 floats. */
LANES_ATTR static void
NAME(fp_taps)(const float *ia, const float *ib, const float d[3], const float par[3],
              const float across[3], float *out)
{
	int i;

	for (i = 0; i < 8; i += LANES) {
		VF sa, ca, sb, cb;

		NAME(fv_sincos)(NAME(v_load)(ia + i), &sa, &ca);
		NAME(fv_sincos)(NAME(v_load)(ib + i), &sb, &cb);
		NAME(fv_direction)(ca, sa, sb / cb, d, par, across, out + 3 * i);
	}
}

/* The log map (log_map) of eight looked-up directions (24 floats) in
 * the tangent plane at unit c, t1 t2: gx, gy. */
LANES_ATTR static void
NAME(fp_log)(const float *look, const float c[3], const float t1[3], const float t2[3],
             float *gx, float *gy)
{
	int i, k;

	for (i = 0; i < 8; i += LANES) {
		const VF zero = NAME(v_splat)(0.0f);
		VF v[3], inv, x, y, z, s, ang, f;

		for (k = 0; k < LANES; k++) {
			v[0][k] = look[3 * (i + k)];
			v[1][k] = look[3 * (i + k) + 1];
			v[2][k] = look[3 * (i + k) + 2];
		}
		inv = NAME(v_splat)(1.0f) / NAME(v_sqrt)(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
		v[0] = v[0] * inv;
		v[1] = v[1] * inv;
		v[2] = v[2] * inv;
		x = v[0] * t1[0] + v[1] * t1[1] + v[2] * t1[2];
		y = v[0] * t2[0] + v[1] * t2[1] + v[2] * t2[2];
		z = v[0] * c[0] + v[1] * c[1] + v[2] * c[2];
		s = NAME(v_sqrt)(x * x + y * y);
		ang = NAME(fv_atan2p)(s, z);
		f = NAME(v_select)(s > zero, ang / NAME(v_select)(s > zero, s, NAME(v_splat)(1.0f)),
		                 zero);
		NAME(v_store)(gx + i, x * f);
		NAME(v_store)(gy + i, y * f);
	}
}
