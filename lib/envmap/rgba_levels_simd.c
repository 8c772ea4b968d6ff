/*
 * The RGBA levels' inner loops with AVX2: the prefilter's lobe sum and the
 * shading pass's reads.  Eight directions' faces, texel coordinates and
 * bilinear weights are found in one pass of vector arithmetic, then each
 * one's eight texels are added with a multiply-add per pair.  The scalar
 * loops spend most of their time choosing the face and computing
 * addresses one direction at a time; here eight share that work, which
 * roughly halves the instructions per read.
 */
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "envmap/rgba_levels_simd.h"

#if defined(__x86_64__) && defined(__GNUC__)
#define PYRAMID_AVX2 1
#include <immintrin.h>
#endif

int
rf__lobe_table_alloc(struct rf__lobe_table *t, size_t n)
{
	/* Thirteen columns of n, each rounded up to whole vectors. */
	size_t stride = (n + 7) & ~(size_t)7;
	char *b;

	memset(t, 0, sizeof(*t));
	if (stride > SIZE_MAX / 13 / 4)
		return RF_ENOMEM;
	if (!(t->block = b = aligned_alloc(32, 13 * stride * 4)))
		return RF_ENOMEM;
	memset(b, 0, 13 * stride * 4);
	t->n = n;
	t->lx = (float *)b;
	t->ly = t->lx + stride;
	t->lz = t->ly + stride;
	t->scale0 = t->lz + stride;
	t->scale1 = t->scale0 + stride;
	t->w0 = t->scale1 + stride;
	t->w1 = t->w0 + stride;
	t->base0 = (int32_t *)(t->w1 + stride);
	t->base1 = t->base0 + stride;
	t->face0 = t->base1 + stride;
	t->face1 = t->face0 + stride;
	t->row0 = t->face1 + stride;
	t->row1 = t->row0 + stride;
	return 0;
}

void
rf__lobe_table_destroy(struct rf__lobe_table *t)
{
	free(t->block);
	memset(t, 0, sizeof(*t));
}

void
rf__lobe_table_set(struct rf__lobe_table *t, size_t i, const float l[3],
                   const struct rf__lod *lod, const struct rf__rgba_levels *p)
{
	t->lx[i] = l[0];
	t->ly[i] = l[1];
	t->lz[i] = l[2];
	t->scale0[i] = lod->scale[0];
	t->scale1[i] = lod->scale[2];
	t->w0[i] = lod->w0;
	t->w1[i] = lod->w1;
	t->base0[i] = (int32_t)(lod->base[0] - p->data);
	t->base1[i] = (int32_t)(lod->base[1] - p->data);
	t->face0[i] = (int32_t)lod->face_stride[0];
	t->face1[i] = (int32_t)lod->face_stride[1];
	t->row0[i] = (int32_t)lod->row[0];
	t->row1[i] = (int32_t)lod->row[1];
}

static size_t
levels_texels(const struct rf__rgba_levels *p)
{
	size_t l, total = 0;

	for (l = 0; l < p->nlevels; l++)
		total += 6 * p->face_stride[l];
	return total;
}

#ifdef PYRAMID_AVX2

int
rf__rgba_levels_simd_usable(const struct rf__rgba_levels *p)
{
	const char *env = getenv("REFLECT_SIMD");

	if (env && (!strcmp(env, "off") || !strcmp(env, "0")))
		return 0;
	__builtin_cpu_init();
	return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
	       levels_texels(p) < (size_t)INT32_MAX;
}

#define AVX2 __attribute__((target("avx2,fma")))

/* One level's texel offsets and four bilinear weights for eight samples:
 * the same arithmetic as rf__rgba_levels_fetch, lane by lane.  sc: face
 * widths, lw: the level's weights, base, face_stride, row: as in the
 * levels' tables. */
AVX2 static inline __m256i
corners(__m256 u, __m256 v, __m256i face, __m256 sc, __m256 lw, __m256i base,
        __m256i face_stride, __m256i row, float w[4][8])
{
	const __m256 half = _mm256_set1_ps(0.5f);
	__m256 s = _mm256_fmadd_ps(u, sc, half), t = _mm256_fmadd_ps(v, sc, half);
	__m256i is = _mm256_cvttps_epi32(s), it = _mm256_cvttps_epi32(t);
	__m256 a = _mm256_sub_ps(s, _mm256_cvtepi32_ps(is));
	__m256 b = _mm256_sub_ps(t, _mm256_cvtepi32_ps(it));
	__m256 wb1 = _mm256_mul_ps(lw, b), wb0 = _mm256_sub_ps(lw, wb1);
	__m256i at = _mm256_add_epi32(
		base, _mm256_add_epi32(_mm256_mullo_epi32(face, face_stride),
		                       _mm256_add_epi32(_mm256_mullo_epi32(it, row), is)));
	__m256 w10 = _mm256_mul_ps(wb0, a), w11 = _mm256_mul_ps(wb1, a);

	_mm256_store_ps(w[0], _mm256_sub_ps(wb0, w10));
	_mm256_store_ps(w[1], w10);
	_mm256_store_ps(w[2], _mm256_sub_ps(wb1, w11));
	_mm256_store_ps(w[3], w11);
	return at;
}

AVX2 static inline __m256i
level_corners(__m256 u, __m256 v, __m256i face, const float *scale, const float *weight,
              const int32_t *base, const int32_t *face_stride, const int32_t *row,
              float w[4][8])
{
	return corners(u, v, face, _mm256_load_ps(scale), _mm256_load_ps(weight),
	               _mm256_load_si256((const __m256i *)base),
	               _mm256_load_si256((const __m256i *)face_stride),
	               _mm256_load_si256((const __m256i *)row), w);
}

/* The face of each of eight directions (as rf__cube_face chooses it, ties
 * to x, then y) and the position on it. */
AVX2 static inline __m256i
cube_face8(__m256 dx, __m256 dy, __m256 dz, __m256 *u, __m256 *v)
{
	const __m256 half = _mm256_set1_ps(0.5f), sign = _mm256_set1_ps(-0.0f);
	const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
	__m256 ax = _mm256_andnot_ps(sign, dx), ay = _mm256_andnot_ps(sign, dy);
	__m256 az = _mm256_andnot_ps(sign, dz);
	__m256 on_x = _mm256_and_ps(_mm256_cmp_ps(ax, ay, _CMP_GE_OQ),
	                            _mm256_cmp_ps(ax, az, _CMP_GE_OQ));
	__m256 on_y = _mm256_andnot_ps(on_x, _mm256_cmp_ps(ay, az, _CMP_GE_OQ));
	__m256 major = _mm256_blendv_ps(_mm256_blendv_ps(az, ay, on_y), ax, on_x);
	__m256 along = _mm256_blendv_ps(_mm256_blendv_ps(dz, dy, on_y), dx, on_x);
	__m256 pos = _mm256_cmp_ps(along, zero, _CMP_GT_OQ);
	__m256 flip = _mm256_and_ps(pos, sign), keep = _mm256_andnot_ps(pos, sign);
	/* across: +-X faces z (negated on +X), Y faces x, Z faces x
	 * (negated on +Z); down: Y faces z (negated on +Y), else -y. */
	__m256 across = _mm256_blendv_ps(
		_mm256_blendv_ps(_mm256_xor_ps(dx, flip), dx, on_y),
		_mm256_xor_ps(dz, keep), on_x);
	__m256 down = _mm256_blendv_ps(_mm256_xor_ps(dy, sign), _mm256_xor_ps(dz, flip), on_y);
	/* As rf__cube_face: a denormal major axis scaled up first, 0 for
	 * zero and NaN (the compare is false), u and v clamped (max and min
	 * return their second operand on NaN). */
	__m256 scale = _mm256_blendv_ps(_mm256_set1_ps(1.0f), _mm256_set1_ps(0x1p24f),
	                                _mm256_cmp_ps(major, _mm256_set1_ps(0x1p-126f), _CMP_LT_OQ));
	__m256 inv = _mm256_and_ps(_mm256_div_ps(half, _mm256_mul_ps(major, scale)),
	                           _mm256_cmp_ps(major, zero, _CMP_GT_OQ));
	/* Face 2 axis + (negative): masks are -1 where true. */
	__m256i axis = _mm256_add_epi32(_mm256_set1_epi32(2),
	                                _mm256_add_epi32(_mm256_slli_epi32(_mm256_castps_si256(on_x), 1),
	                                                 _mm256_castps_si256(on_y)));

	*u = _mm256_min_ps(_mm256_max_ps(_mm256_fmadd_ps(_mm256_mul_ps(across, scale), inv, half),
	                                 zero), one);
	*v = _mm256_min_ps(_mm256_max_ps(_mm256_fmadd_ps(_mm256_mul_ps(down, scale), inv, half),
	                                 zero), one);
	return _mm256_add_epi32(_mm256_slli_epi32(axis, 1),
	                        _mm256_add_epi32(_mm256_set1_epi32(1), _mm256_castps_si256(pos)));
}

/* Rows of eight weights (one weight of eight samples each) to eight
 * rows of one sample's weights. */
AVX2 static inline void
transpose8(float a[4][8], float b[4][8], float out[8][8])
{
	__m256 r0 = _mm256_load_ps(a[0]), r1 = _mm256_load_ps(a[1]);
	__m256 r2 = _mm256_load_ps(a[2]), r3 = _mm256_load_ps(a[3]);
	__m256 r4 = _mm256_load_ps(b[0]), r5 = _mm256_load_ps(b[1]);
	__m256 r6 = _mm256_load_ps(b[2]), r7 = _mm256_load_ps(b[3]);
	__m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
	__m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
	__m256 t4 = _mm256_unpacklo_ps(r4, r5), t5 = _mm256_unpackhi_ps(r4, r5);
	__m256 t6 = _mm256_unpacklo_ps(r6, r7), t7 = _mm256_unpackhi_ps(r6, r7);
	__m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xEE);
	__m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xEE);
	__m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xEE);
	__m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xEE);

	_mm256_store_ps(out[0], _mm256_permute2f128_ps(u0, u4, 0x20));
	_mm256_store_ps(out[1], _mm256_permute2f128_ps(u1, u5, 0x20));
	_mm256_store_ps(out[2], _mm256_permute2f128_ps(u2, u6, 0x20));
	_mm256_store_ps(out[3], _mm256_permute2f128_ps(u3, u7, 0x20));
	_mm256_store_ps(out[4], _mm256_permute2f128_ps(u0, u4, 0x31));
	_mm256_store_ps(out[5], _mm256_permute2f128_ps(u1, u5, 0x31));
	_mm256_store_ps(out[6], _mm256_permute2f128_ps(u2, u6, 0x31));
	_mm256_store_ps(out[7], _mm256_permute2f128_ps(u3, u7, 0x31));
}

AVX2 static rf__v4
lobe_sum_avx2(const struct rf__lobe_table *tb, size_t count, const struct rf__rgba_levels *p,
              const float n[3], const float tg[3], const float bt[3])
{
	const __m256 tx = _mm256_set1_ps(tg[0]), ty = _mm256_set1_ps(tg[1]), tz = _mm256_set1_ps(tg[2]);
	const __m256 bx = _mm256_set1_ps(bt[0]), by = _mm256_set1_ps(bt[1]), bz = _mm256_set1_ps(bt[2]);
	const __m256 nx = _mm256_set1_ps(n[0]), ny = _mm256_set1_ps(n[1]), nz = _mm256_set1_ps(n[2]);
	const float *data = (const float *)p->data;
	/* Each sample's weight pairs: (w00 x4, w10 x4), (w01 x4, w11 x4) of
	 * the first level, then the same of the second. */
	const __m256i pick[4] = {
		_mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1), _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3),
		_mm256_setr_epi32(4, 4, 4, 4, 5, 5, 5, 5), _mm256_setr_epi32(6, 6, 6, 6, 7, 7, 7, 7),
	};
	/* One accumulator per pair of texels read, so no add waits on the last. */
	__m256 acc[4];
	__attribute__((aligned(32))) int32_t at0[8], at1[8];
	__attribute__((aligned(32))) float w0[4][8], w1[4][8], wt[8][8];
	size_t s, k;
	rf__v4 sum;

	for (k = 0; k < 4; k++)
		acc[k] = _mm256_setzero_ps();
	for (s = 0; s < count; s += 8) {
		__m256 lx = _mm256_load_ps(tb->lx + s), ly = _mm256_load_ps(tb->ly + s);
		__m256 lz = _mm256_load_ps(tb->lz + s);
		__m256 dx = _mm256_fmadd_ps(lz, nx, _mm256_fmadd_ps(ly, bx, _mm256_mul_ps(lx, tx)));
		__m256 dy = _mm256_fmadd_ps(lz, ny, _mm256_fmadd_ps(ly, by, _mm256_mul_ps(lx, ty)));
		__m256 dz = _mm256_fmadd_ps(lz, nz, _mm256_fmadd_ps(ly, bz, _mm256_mul_ps(lx, tz)));
		__m256 u, v;
		__m256i face = cube_face8(dx, dy, dz, &u, &v);

		_mm256_store_si256((__m256i *)at0,
		                   level_corners(u, v, face, tb->scale0 + s, tb->w0 + s, tb->base0 + s,
		                                 tb->face0 + s, tb->row0 + s, w0));
		_mm256_store_si256((__m256i *)at1,
		                   level_corners(u, v, face, tb->scale1 + s, tb->w1 + s, tb->base1 + s,
		                                 tb->face1 + s, tb->row1 + s, w1));
		transpose8(w0, w1, wt);
		for (k = 0; k < 8; k++) {
			const float *q0 = data + 4 * (size_t)at0[k], *q1 = data + 4 * (size_t)at1[k];
			size_t r0 = 4 * (size_t)tb->row0[s + k], r1 = 4 * (size_t)tb->row1[s + k];
			__m256 w = _mm256_load_ps(wt[k]);

			/* A texel and its right-hand neighbour are one 32-byte load. */
			acc[0] = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pick[0]), _mm256_loadu_ps(q0), acc[0]);
			acc[1] = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pick[1]), _mm256_loadu_ps(q0 + r0), acc[1]);
			acc[2] = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pick[2]), _mm256_loadu_ps(q1), acc[2]);
			acc[3] = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pick[3]), _mm256_loadu_ps(q1 + r1), acc[3]);
		}
	}
	acc[0] = _mm256_add_ps(_mm256_add_ps(acc[0], acc[1]), _mm256_add_ps(acc[2], acc[3]));
	_mm_storeu_ps((float *)&sum, _mm_add_ps(_mm256_castps256_ps128(acc[0]),
	                                        _mm256_extractf128_ps(acc[0], 1)));
	return sum;
}

rf__v4
rf__lobe_sum8(const struct rf__lobe_table *t, size_t count, const struct rf__rgba_levels *p,
              const float n[3], const float tg[3], const float bt[3])
{
	return lobe_sum_avx2(t, count, p, n, tg, bt);
}

/* Rows of four weights of eight samples to each sample's four, sample k
 * at out[k % 4] + 4 (k / 4). */
AVX2 static inline void
transpose4(float a[4][8], float out[4][8])
{
	__m256 r0 = _mm256_load_ps(a[0]), r1 = _mm256_load_ps(a[1]);
	__m256 r2 = _mm256_load_ps(a[2]), r3 = _mm256_load_ps(a[3]);
	__m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
	__m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);

	_mm256_store_ps(out[0], _mm256_shuffle_ps(t0, t2, 0x44));
	_mm256_store_ps(out[1], _mm256_shuffle_ps(t0, t2, 0xEE));
	_mm256_store_ps(out[2], _mm256_shuffle_ps(t1, t3, 0x44));
	_mm256_store_ps(out[3], _mm256_shuffle_ps(t1, t3, 0xEE));
}

/* Eight reads whose lods are all whole (filtering=stochastic, or clamped
 * to level 0): the first level's texels only.  The two-level kernel
 * would add the second's at weight +0, which changes no sum: the same
 * bits at half the loads. */
AVX2 static inline void
fetch_one_level8(const struct rf__rgba_levels *p, __m256 u, __m256 v, __m256i face, __m256i l0,
                 rf__v4 *rgb)
{
	const __m256i pick[2] = {
		_mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1), _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3),
	};
	const float *data = (const float *)p->data;
	__attribute__((aligned(32))) int32_t at0[8], r0[8];
	__attribute__((aligned(32))) float w0[4][8], wt[4][8];
	__m256i row0 = _mm256_i32gather_epi32(p->lvl_row, l0, 4);
	size_t k;

	_mm256_store_si256((__m256i *)at0,
	                   corners(u, v, face, _mm256_i32gather_ps(p->lvl_scale, l0, 4),
	                           _mm256_set1_ps(1.0f), _mm256_i32gather_epi32(p->lvl_base, l0, 4),
	                           _mm256_i32gather_epi32(p->lvl_face, l0, 4), row0, w0));
	_mm256_store_si256((__m256i *)r0, _mm256_slli_epi32(row0, 2));
	transpose4(w0, wt);
	for (k = 0; k < 8; k++) {
		const float *q0 = data + 4 * (size_t)at0[k];
		__m256 w = _mm256_broadcast_ps((const __m128 *)(const void *)(wt[k & 3] + 4 * (k >> 2)));
		__m256 a = _mm256_mul_ps(_mm256_permutevar8x32_ps(w, pick[0]), _mm256_loadu_ps(q0));
		__m256 b = _mm256_mul_ps(_mm256_permutevar8x32_ps(w, pick[1]),
		                         _mm256_loadu_ps(q0 + r0[k]));

		a = _mm256_add_ps(a, b);
		_mm_storeu_ps((float *)&rgb[k], _mm_add_ps(_mm256_castps256_ps128(a),
		                                           _mm256_extractf128_ps(a, 1)));
	}
}

/* count reads, eight at a time; what is left over goes the scalar way. */
AVX2 static size_t
fetch_many_avx2(const struct rf__rgba_levels *p, size_t count, const float *x, const float *y,
                const float *z, const float *lod, rf__v4 *rgb)
{
	const __m256i pick[4] = {
		_mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1), _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3),
		_mm256_setr_epi32(4, 4, 4, 4, 5, 5, 5, 5), _mm256_setr_epi32(6, 6, 6, 6, 7, 7, 7, 7),
	};
	const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
	const __m256 top = _mm256_set1_ps((float)(p->nlevels - 1));
	const __m256i top_level = _mm256_set1_epi32((int)p->nlevels - 1);
	const __m256i next = _mm256_set1_epi32(1);
	const float *data = (const float *)p->data;
	__attribute__((aligned(32))) int32_t at0[8], at1[8], r0[8], r1[8];
	__attribute__((aligned(32))) float w0[4][8], w1[4][8], wt[8][8];
	size_t s, k;

	for (s = 0; s + 8 <= count; s += 8) {
		__m256 u, v;
		__m256i face = cube_face8(_mm256_loadu_ps(x + s), _mm256_loadu_ps(y + s),
		                          _mm256_loadu_ps(z + s), &u, &v);
		/* The lod clamped to the levels (NaN to 0: max returns its
		 * second operand), split into two levels and a weight. */
		__m256 l = _mm256_min_ps(_mm256_max_ps(_mm256_loadu_ps(lod + s), zero), top);
		__m256i l0 = _mm256_cvttps_epi32(l);
		__m256i l1 = _mm256_min_epi32(_mm256_add_epi32(l0, next), top_level);
		__m256 f1 = _mm256_andnot_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(l1, l0)),
		                             _mm256_sub_ps(l, _mm256_cvtepi32_ps(l0)));
		__m256i row0, row1;

		if (!_mm256_movemask_ps(_mm256_cmp_ps(f1, zero, _CMP_NEQ_UQ))) {
			fetch_one_level8(p, u, v, face, l0, rgb + s);
			continue;
		}
		row0 = _mm256_i32gather_epi32(p->lvl_row, l0, 4);
		row1 = _mm256_i32gather_epi32(p->lvl_row, l1, 4);

		_mm256_store_si256((__m256i *)at0,
		                   corners(u, v, face, _mm256_i32gather_ps(p->lvl_scale, l0, 4),
		                           _mm256_sub_ps(one, f1),
		                           _mm256_i32gather_epi32(p->lvl_base, l0, 4),
		                           _mm256_i32gather_epi32(p->lvl_face, l0, 4), row0, w0));
		_mm256_store_si256((__m256i *)at1,
		                   corners(u, v, face, _mm256_i32gather_ps(p->lvl_scale, l1, 4), f1,
		                           _mm256_i32gather_epi32(p->lvl_base, l1, 4),
		                           _mm256_i32gather_epi32(p->lvl_face, l1, 4), row1, w1));
		_mm256_store_si256((__m256i *)r0, _mm256_slli_epi32(row0, 2));
		_mm256_store_si256((__m256i *)r1, _mm256_slli_epi32(row1, 2));
		transpose8(w0, w1, wt);
		for (k = 0; k < 8; k++) {
			const float *q0 = data + 4 * (size_t)at0[k], *q1 = data + 4 * (size_t)at1[k];
			__m256 w = _mm256_load_ps(wt[k]);
			__m256 a = _mm256_mul_ps(_mm256_permutevar8x32_ps(w, pick[0]), _mm256_loadu_ps(q0));
			__m256 b = _mm256_mul_ps(_mm256_permutevar8x32_ps(w, pick[1]),
			                         _mm256_loadu_ps(q0 + r0[k]));

			a = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pick[2]), _mm256_loadu_ps(q1), a);
			b = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pick[3]),
			                    _mm256_loadu_ps(q1 + r1[k]), b);
			a = _mm256_add_ps(a, b);
			_mm_storeu_ps((float *)&rgb[s + k], _mm_add_ps(_mm256_castps256_ps128(a),
			                                               _mm256_extractf128_ps(a, 1)));
		}
	}
	return s;
}

#else

int
rf__rgba_levels_simd_usable(const struct rf__rgba_levels *p)
{
	(void)levels_texels;
	return 0;
}

/* Never called where rf__rgba_levels_simd_usable says no; kept correct anyway,
 * as the plain loop over the table. */
rf__v4
rf__lobe_sum8(const struct rf__lobe_table *t, size_t count, const struct rf__rgba_levels *p,
              const float n[3], const float tg[3], const float bt[3])
{
	rf__v4 acc = { 0, 0, 0, 0 };
	size_t i;

	for (i = 0; i < count; i++) {
		struct rf__lod lod;
		float d[3];

		d[0] = t->lx[i] * tg[0] + t->ly[i] * bt[0] + t->lz[i] * n[0];
		d[1] = t->lx[i] * tg[1] + t->ly[i] * bt[1] + t->lz[i] * n[1];
		d[2] = t->lx[i] * tg[2] + t->ly[i] * bt[2] + t->lz[i] * n[2];
		lod.scale[0] = lod.scale[1] = t->scale0[i];
		lod.scale[2] = lod.scale[3] = t->scale1[i];
		lod.base[0] = p->data + t->base0[i];
		lod.base[1] = p->data + t->base1[i];
		lod.face_stride[0] = (size_t)t->face0[i];
		lod.face_stride[1] = (size_t)t->face1[i];
		lod.row[0] = (size_t)t->row0[i];
		lod.row[1] = (size_t)t->row1[i];
		lod.w0 = t->w0[i];
		lod.w1 = t->w1[i];
		acc += rf__rgba_levels_fetch(d, &lod);
	}
	return acc;
}

#endif

/* Eight at a time where the kernel exists and was chosen; the rest, or
 * all of them, the plain way. */
static void
fetch_many(const struct rf__rgba_levels *p, int vector, size_t count, const float *x,
           const float *y, const float *z, const float *lod, rf__v4 *rgb)
{
	size_t i = 0;

#ifdef PYRAMID_AVX2
	if (vector) {
		i = fetch_many_avx2(p, count, x, y, z, lod, rgb);
		/* The last reads padded to eight, through the same kernel: a
		 * read gives the same bits wherever it falls in a batch (the
		 * kernel fuses multiply-adds, the plain path does not), so a
		 * mode reading one at a time through the host gets the pass's
		 * numbers exactly. */
		if (i < count) {
			float px[8], py[8], pz[8], pl[8];
			rf__v4 out[8];
			size_t k, n = count - i;

			for (k = 0; k < 8; k++) {
				size_t j = i + (k < n ? k : n - 1);

				px[k] = x[j];
				py[k] = y[j];
				pz[k] = z[j];
				pl[k] = lod[j];
			}
			fetch_many_avx2(p, 8, px, py, pz, pl, out);
			for (k = 0; k < n; k++)
				rgb[i + k] = out[k];
			i = count;
		}
	}
#else
	(void)vector;
#endif
	for (; i < count; i++) {
		float d[3] = { x[i], y[i], z[i] };
		struct rf__lod l = rf__rgba_levels_lod(p, lod[i]);

		rgb[i] = rf__rgba_levels_fetch(d, &l);
	}
}

/* A turned cube's directions taken into its frame a chunk at a time, on
 * the stack: the world's cube pays one test. */
void
rf__rgba_levels_fetch_many(const struct rf__rgba_levels *p, int vector, size_t count, const float *x,
                       const float *y, const float *z, const float *lod, rf__v4 *rgb)
{
	float tx[64], ty[64], tz[64], d[3];
	size_t i0, k, m;

	if (!p->turned) {
		fetch_many(p, vector, count, x, y, z, lod, rgb);
		return;
	}
	for (i0 = 0; i0 < count; i0 += m) {
		m = count - i0 < 64 ? count - i0 : 64;
		for (k = 0; k < m; k++) {
			rf__turn_in(p->turn, x[i0 + k], y[i0 + k], z[i0 + k], d);
			tx[k] = d[0];
			ty[k] = d[1];
			tz[k] = d[2];
		}
		fetch_many(p, vector, m, tx, ty, tz, lod + i0, rgb + i0);
	}
}
