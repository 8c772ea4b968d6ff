/*
 * The vector code of raytraced.c, written once for LANES lanes:
 * raytraced.c includes it for 4 (SSE, every x86-64) and, where the
 * compiler can target it, for 8 (AVX2, chosen when an instance is made).
 * Each function does lanes of whole vectors from ray i on and returns
 * where it stopped; the caller finishes with the narrower width and then
 * one ray at a time.  The same operations lane by lane, in the same
 * order, and no fused multiply-add: the same bits at either width and in
 * the scalar loops.  Included by lanes-widths.h (see lanes.h).
 */

#include "maths/lanes.h"
#if LANES == 8
#include <immintrin.h>
#endif

/* Heitz's sampler (sample_vndf_one), LANES rays at a time. */
LANES_ATTR static size_t
NAME(vndf_lanes)(const struct vndf_view *s, size_t i, size_t n, const float *restrict u0,
                 const float *restrict u1, float *restrict hx, float *restrict hy,
                 float *restrict hz)
{
	const VF one = NAME(v_splat)(1.0f), half = NAME(v_splat)(0.5f);
	const VF w = NAME(v_splat)(s->w), alpha = NAME(v_splat)(s->alpha);

	for (; i + LANES <= n; i += LANES) {
		VF a = NAME(v_load)(u0 + i), b = NAME(v_load)(u1 + i), r, m, x, x2, sign, sn, cs;
		VF p1, p2, q, lh, nx, ny, nz, len;
		VI k;

		r = NAME(v_sqrt)(a);
		/* sincos_turn, lane by lane the same operations */
		k = __builtin_convertvector(b * 2.0f + half, VI);
		m = __builtin_convertvector(k, VF);
		x = (b - half * m) * 6.28318530718f;
		x2 = x * x;
		sign = __builtin_convertvector(1 - 2 * (k & 1), VF);
		sn = x * (one + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 +
		     x2 * (1.0f / 362880 - x2 * (1.0f / 39916800))))));
		cs = one + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 +
		     x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800 + x2 * (1.0f / 479001600))))));
		sn = sign * sn;
		cs = sign * cs;
		p1 = r * cs;
		p2 = r * sn;
		q = one - p1 * p1;
		p2 = (one - w) * NAME(v_sqrt)(NAME(v_max0)(q)) + w * p2;
		q = one - p1 * p1 - p2 * p2;
		lh = NAME(v_sqrt)(NAME(v_max0)(q));
		nx = alpha * (p1 * s->t1[0] + p2 * s->t2[0] + lh * s->vh[0]);
		ny = alpha * (p1 * s->t1[1] + p2 * s->t2[1] + lh * s->vh[1]);
		nz = NAME(v_max0)(p1 * s->t1[2] + p2 * s->t2[2] + lh * s->vh[2]);
		len = one / NAME(v_sqrt)(nx * nx + ny * ny + nz * nz);
		NAME(v_store)(hx + i, nx * len);
		NAME(v_store)(hy + i, ny * len);
		NAME(v_store)(hz + i, nz * len);
	}
	return i;
}

/* trace_lobe's loop of the exact estimator, LANES rays at a time: each
 * microfacet normal's direction, weight and pdf, gathered for the rays
 * that count at *count. */
LANES_ATTR static uint32_t
NAME(lobe_lanes)(struct raytraced *rt, const struct lobe *lb, uint32_t i, uint32_t n,
                 const float *hxs, const float *hys, const float *hzs, uint32_t *count)
{
	const float *v = lb->v, *x = lb->x, *y = lb->y, *nn = lb->n, *ng = lb->ng;
	const float alpha2 = lb->alpha2, nv = lb->nv, av = lb->av, g1v = lb->g1v;
	const VF zero = NAME(v_splat)(0.0f), one = NAME(v_splat)(1.0f);
	const int has_ng = lb->has_ng, separable = rt->masking == MASKING_SEPARABLE;
	uint32_t c = *count;

	for (; i + LANES <= n; i += LANES) {
		VF hx = NAME(v_load)(hxs + i), hy = NAME(v_load)(hys + i), hz = NAME(v_load)(hzs + i);
		VF cv, lx, ly, lz, wx, wy, wz, cl, gl, al, wt, pd, t;
		VI ok;
		int j;

		cv = v[0] * hx + v[1] * hy + v[2] * hz;
		cv = NAME(v_max0)(cv);
		ok = cv < one; /* as sat(): NaN and below 0 give 0, above 1 gives 1 */
		cv = (VF)(((VI)cv & ok) | ((VI)one & ~ok));
		lx = 2.0f * cv * hx - v[0];
		ly = 2.0f * cv * hy - v[1];
		lz = 2.0f * cv * hz - v[2];
		wx = lx * x[0] + ly * y[0] + lz * nn[0];
		wy = lx * x[1] + ly * y[1] + lz * nn[1];
		wz = lx * x[2] + ly * y[2] + lz * nn[2];
		cl = nn[0] * wx + nn[1] * wy + nn[2] * wz;
		gl = ng[0] * wx + ng[1] * wy + ng[2] * wz;
		ok = cl > zero;
		if (has_ng)
			ok &= gl > zero;
		al = NAME(v_sqrt)(alpha2 + (1.0f - alpha2) * cl * cl);
		wt = separable ? 2.0f * cl / (cl + al) : cl * (nv + av) / (av * cl + al * nv);
		t = hz * hz * (alpha2 - 1.0f) + 1.0f;
		pd = g1v * (alpha2 / (3.14159265359f * t * t)) / (4.0f * nv);
#if LANES == 8
		/* The lanes that count packed to the front by one permutation
		 * (pack_lanes: their indices, four bits each) and written whole
		 * at the count: what follows them is overwritten later or never
		 * read.  The count never passes the vector's first ray, so every
		 * write is inside the arrays.  The lanes one by one took 18 % of
		 * the mode's instructions. */
		{
			const __m256i shifts = _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28);
			int m = _mm256_movemask_ps((__m256)ok);
			__m256i at = _mm256_and_si256(
				_mm256_srlv_epi32(_mm256_set1_epi32((int)pack_lanes[m]), shifts),
				_mm256_set1_epi32(15));
			VF d[3];

			_mm256_storeu_ps(rt->weight + c, _mm256_permutevar8x32_ps((__m256)wt, at));
			_mm256_storeu_ps(rt->pdf + c, _mm256_permutevar8x32_ps((__m256)pd, at));
			_mm256_storeu_si256((__m256i *)(void *)(rt->index + c),
			                    _mm256_add_epi32(at, _mm256_set1_epi32((int)i)));
			d[0] = (VF)_mm256_permutevar8x32_ps((__m256)wx, at);
			d[1] = (VF)_mm256_permutevar8x32_ps((__m256)wy, at);
			d[2] = (VF)_mm256_permutevar8x32_ps((__m256)wz, at);
			NAME(v_soa_to_aos)(d, rt->dir + 3 * c);
			c += (uint32_t)__builtin_popcount((unsigned)m);
		}
		(void)j;
#else
		/* Every lane is written where the next ray that counts goes,
		 * and the count moves by those that do: no branch to mispredict
		 * on rays that fall below the surface at random.  The count
		 * never passes the lane's own ray, so every write is inside
		 * the arrays. */
		for (j = 0; j < LANES; j++) {
			rt->weight[c] = wt[j];
			rt->pdf[c] = pd[j];
			rt->index[c] = i + (uint32_t)j;
			rt->dir[3 * c] = wx[j];
			rt->dir[3 * c + 1] = wy[j];
			rt->dir[3 * c + 2] = wz[j];
			c += (uint32_t)ok[j] & 1u;
		}
#endif
	}
	*count = c;
	return i;
}

/* footprint_lod for LANES rays at a time (the largest of three
 * magnitudes is the same by max as by comparisons). */
LANES_ATTR static uint32_t
NAME(lod_lanes)(const struct rf_host *host, uint32_t i, uint32_t n,
                const float *restrict lookup, const float *restrict jac,
                const float *restrict pdf, float share, float *restrict lod)
{
	const float top = (float)(host->env_levels - 1);
	const float scale = 4.0f / ((float)host->env_size * (float)host->env_size);
	const VF zero = NAME(v_splat)(0.0f), one = NAME(v_splat)(1.0f), vtop = NAME(v_splat)(top);
	const VF lowest = NAME(v_splat)(-1e30f);

	for (; i + LANES <= n; i += LANES) {
		VF d[3], m, texel, omega, x, e, f, t, t2, l, r;
		VI bits, pos, ok;
		int j;

		NAME(v_aos_to_soa)(lookup + 3 * i, d);
		for (j = 0; j < 3; j++)
			d[j] = (VF)((VI)d[j] & 0x7FFFFFFF);
		/* maxps's rule, a > b ? a : b */
		m = NAME(v_select)(d[0] > d[1], d[0], d[1]);
		m = NAME(v_select)(m > d[2], m, d[2]);
		texel = scale * m * m * m;
		omega = NAME(v_load)(jac + i);
		t = NAME(v_load)(pdf + i);
		omega = omega / (share * t);
		x = omega / texel;
		/* fast_log2, lane by lane */
		bits = (VI)x;
		e = __builtin_convertvector((bits >> 23) & 0xFF, VF) - 127.0f;
		f = (VF)((bits & 0x007FFFFF) | 0x3F800000);
		t = (f - one) / (f + one);
		t2 = t * t;
		l = e + 2.88539008f * t * (one + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7))));
		pos = x > zero;
		l = (VF)(((VI)l & pos) | ((VI)lowest & ~pos));
		l = 0.5f * l;
		/* clamp to [0, top]; NaN: 0 */
		ok = l < vtop;
		r = (VF)(((VI)l & ok) | ((VI)vtop & ~ok));
		pos = l > zero;
		r = (VF)((VI)r & pos);
		NAME(v_store)(lod + i, r);
	}
	return i;
}

/* stochastic_lods, LANES rays at a time: the same integer hash and float
 * compare lane by lane, so the same levels. */
typedef unsigned NAME(vu) __attribute__((vector_size(4 * LANES)));

LANES_ATTR static uint32_t
NAME(round_lanes)(uint32_t key, uint32_t first, uint32_t i, uint32_t n,
                  const uint32_t *restrict index, float *restrict lod)
{
	const VF one = NAME(v_splat)(1.0f);

	for (; i + LANES <= n; i += LANES) {
		NAME(vu) k, h;
		VF l = NAME(v_load)(lod + i), f, u;
		VI up;

		memcpy(&k, index + i, sizeof(k));
		h = key + (first + k) * 0x9E3779B9u;
		f = __builtin_convertvector(__builtin_convertvector(l, VI), VF);
		u = __builtin_convertvector((VI)(h >> 8), VF) * (1.0f / 16777216.0f);
		up = u < l - f;
		NAME(v_store)(lod + i, f + (VF)((VI)one & up));
	}
	return i;
}

/* read_rays' copy of the lookups to three arrays, LANES rays at a time. */
LANES_ATTR static uint32_t
NAME(split_lanes)(uint32_t i, uint32_t n, const float *restrict lookup, float *restrict x,
                  float *restrict y, float *restrict z)
{
	for (; i + LANES <= n; i += LANES) {
		VF d[3];

		NAME(v_aos_to_soa)(lookup + 3 * i, d);
		NAME(v_store)(x + i, d[0]);
		NAME(v_store)(y + i, d[1]);
		NAME(v_store)(z + i, d[2]);
	}
	return i;
}
