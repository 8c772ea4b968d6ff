/*
 * project_rays' loop for p inside the box, written once for LANES lanes:
 * host.c includes it for 4 (SSE, every x86-64) and, where the compiler
 * can target it, for 8 (AVX2, chosen when the host is set up).  The same
 * operations lane by lane in the same order as the scalar loop, and no
 * fused multiply-add: the same bits at either width.  Before including,
 * define LANES, VF and VI (vector types of LANES floats and int32s),
 * NAME(x) (x with a suffix) and LANES_ATTR (the target attribute, or
 * nothing).
 */

LANES_ATTR static inline VF
NAME(p_splat)(float x)
{
	VF v;
	int k;

	for (k = 0; k < LANES; k++)
		v[k] = x;
	return v;
}

/* Lane by lane: a where mask is set (all ones), else b. */
LANES_ATTR static inline VF
NAME(p_select)(VI mask, VF a, VF b)
{
	return (VF)(((VI)a & mask) | ((VI)b & ~mask));
}

/* LANES xyz triples to three vectors and back, four at a time by
 * soa.h's shuffles, joined and split in registers. */
LANES_ATTR static inline void
NAME(p_aos_to_soa)(const float *in, VF v[3])
{
#if LANES == 4
	aos_to_soa(in, v);
#else
	soa_v4 a[3], b[3];
	int j;

	aos_to_soa(in, a);
	aos_to_soa(in + 12, b);
	for (j = 0; j < 3; j++)
		v[j] = __builtin_shufflevector(a[j], b[j], 0, 1, 2, 3, 4, 5, 6, 7);
#endif
}

LANES_ATTR static inline void
NAME(p_soa_to_aos)(const VF v[3], float *out)
{
#if LANES == 4
	soa_to_aos(v, out);
#else
	soa_v4 a[3], b[3];
	int j;

	for (j = 0; j < 3; j++) {
		a[j] = __builtin_shufflevector(v[j], v[j], 0, 1, 2, 3);
		b[j] = __builtin_shufflevector(v[j], v[j], 4, 5, 6, 7);
	}
	soa_to_aos(a, out);
	soa_to_aos(b, out + 12);
#endif
}

/* Rays i and on, LANES at a time; returns where it stopped. */
LANES_ATTR static uint32_t
NAME(project_lanes)(const struct box *b, uint32_t i, uint32_t n, const float p[3],
                    const float *dirs, float *lookup, float *dist, float *jacobian)
{
	const VF inf = NAME(p_splat)(INFINITY), zero = NAME(p_splat)(0.0f);
	const VF one = NAME(p_splat)(1.0f);

	for (; i + LANES <= n; i += LANES) {
		VF dv[3], t = inf, lk[3], hx, hy, hz, len, inv, num, den, jac, da, la;
		VI axis = (VI)zero, hit, pos;
		int k;

		NAME(p_aos_to_soa)(dirs + 3 * i, dv);
		for (k = 0; k < 3; k++) {
			const VF hi = NAME(p_splat)(b->hi[k]), lo = NAME(p_splat)(b->lo[k]);
			VF wall = NAME(p_select)(dv[k] > zero, hi, lo), tk, ad;
			VI take;

			tk = (wall - p[k]) / dv[k];
			ad = (VF)((VI)dv[k] & 0x7FFFFFFF);
			take = (ad > AXIS_EPSILON) & (tk < t);
			t = NAME(p_select)(take, tk, t);
			axis = (k & take) | (axis & ~take);
		}
		hit = t < inf;
		t = NAME(p_select)(t < zero, zero, t);
		hx = p[0] + dv[0] * t - b->center[0];
		hy = p[1] + dv[1] * t - b->center[1];
		hz = p[2] + dv[2] * t - b->center[2];
		len = hx * hx + hy * hy + hz * hz;
		for (k = 0; k < LANES; k++)
			len[k] = sqrtf(len[k]);
		inv = one / len;
		pos = len > zero;
		lk[0] = NAME(p_select)(pos, hx * inv, dv[0]);
		lk[1] = NAME(p_select)(pos, hy * inv, dv[1]);
		lk[2] = NAME(p_select)(pos, hz * inv, dv[2]);
		/* the lookup's and the ray's components on the wall's axis */
		la = NAME(p_select)(axis == 0, lk[0], NAME(p_select)(axis == 1, lk[1], lk[2]));
		da = NAME(p_select)(axis == 0, dv[0], NAME(p_select)(axis == 1, dv[1], dv[2]));
		la = (VF)((VI)la & 0x7FFFFFFF);
		da = (VF)((VI)da & 0x7FFFFFFF);
		num = t * t * la;
		den = len * len * da;
		jac = NAME(p_select)(pos, num / den, one);
		for (k = 0; k < 3; k++)
			lk[k] = NAME(p_select)(hit, lk[k], dv[k]);
		jac = NAME(p_select)(hit, jac, one);
		t = NAME(p_select)(hit, t, inf);
		NAME(p_soa_to_aos)(lk, lookup + 3 * i);
		memcpy(dist + i, &t, sizeof(t));
		memcpy(jacobian + i, &jac, sizeof(jac));
	}
	return i;
}
