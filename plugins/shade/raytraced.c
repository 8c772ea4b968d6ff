/*
 * raytraced: the write-up's Monte-Carlo mode (spec 7), rays of the GGX
 * lobe each taken through the probe box, and reflect's exact estimator.
 *
 * Every sample is a direction L drawn from the GGX distribution of
 * visible normals about N seen from V (Heitz's sampler, spec 7.3), taken
 * to where it leaves the box (the host's project_rays) and read there
 * (the host's sample_radiance, box-filtered levels).
 *
 * estimator=exact: the pdf of L is G1(V) D(H) / (4 N.V), so with F = 1
 * the sample's share of  I = integral of f(V,L) (N.L) L(P,L) dL  is
 *   f N.L / pdf = D G2 / (4 N.V N.L) * N.L * 4 N.V / (G1(V) D) = G2 / G1(V),
 * which is G1(L) with separable masking (G2 = G1(V) G1(L), as Cycles 3.4)
 * and (1 + Lambda(V)) / (1 + Lambda(V) + Lambda(L)) height-correlated.
 * I is the mean over all K samples (one below the surface counts as 0);
 * spec is I divided by the directional albedo A + B that the host's
 * --final multiplies by, so that R G B comes out as I itself.  A sample
 * reads the level whose texel, seen through the box from P, covers the
 * solid angle 1 / (K pdf) that the sample stands for (filtered
 * importance sampling): few samples blur instead of aliasing, and as K
 * grows every read goes to level 0.  Frames to be averaged later
 * (frames=F) count: the footprint is that of K F rays.
 *
 * estimator=original: the write-up's unweighted mean of the samples with
 * N.L >= 0.001, read at level 0 (or mipoffset's level); the mirror
 * direction when none is valid, where the original divided 0 by 0.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/plugin.h"

/* Two 64 x 64 blue-noise masks, made at build time by bluenoise-gen.c. */
#include "bluenoise.h"

enum { SAMPLES, PATTERN, ANIMATE, SAMPLER, ESTIMATOR, MASKING, MIPOFFSET, SEED, FRAMES,
       NPARAMS };
enum { PATTERN_WHITE, PATTERN_BLUE, PATTERN_DETERMINISTIC };
enum { ESTIMATOR_EXACT, ESTIMATOR_ORIGINAL };
enum { MASKING_CORRELATED, MASKING_SEPARABLE };

static const struct rf_param params[NPARAMS] = {
	{ "samples", "rays per pixel", 1, 65536, 64, RF_PARAM_INTEGER, NULL },
	{ "pattern", "where each ray's two random numbers come from: a hash of "
	  "pixel, ray and seed; a Hammersley set shifted per pixel by blue noise; "
	  "or one Hammersley set for every pixel",
	  0, 2, 1, RF_PARAM_CHOICE, "white|blue|deterministic" },
	{ "animate", "the stream's FRAME moves the pattern (frames decorrelated)",
	  0, 1, 0, RF_PARAM_BOOL, NULL },
	{ "sampler", "how rays are drawn: GGX visible normals", 0, 0, 0, RF_PARAM_CHOICE,
	  "vndf" },
	{ "estimator", "exact: weighted to the GGX integral; original: the "
	  "write-up's mean of valid rays", 0, 1, 0, RF_PARAM_CHOICE, "exact|original" },
	{ "masking", "Smith masking of the exact estimator: height-correlated, or "
	  "separable G1(V) G1(L) as Cycles", 0, 1, 0, RF_PARAM_CHOICE,
	  "correlated|separable" },
	{ "mipoffset", "the write-up's cheat: every ray reads the level pr * "
	  "clamp(d, 0, 6) of the mirror ray's hit distance d", 0, 1, 0, RF_PARAM_BOOL,
	  NULL },
	{ "seed", "added to --seed", 0, 4294967295.0, 0, RF_PARAM_INTEGER, NULL },
	{ "frames", "frames the output will be averaged over (reflect-accumulate): "
	  "each ray's footprint is that of samples x frames rays", 1, 1e6, 1,
	  RF_PARAM_INTEGER, NULL },
};

static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", "roughness", NULL
};
/* The geometric normal, when the stream has it: rays below it count 0. */
static const char *const optional_inputs[] = { "Ng.X", "Ng.Y", "Ng.Z", NULL };
static const char *const outputs[] = { RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B,
                                       NULL };

/* One instance (one thread): the parameters and the scratch of a pixel's
 * rays, in the structure-of-arrays form the host's batch services take. */
struct raytraced {
	const struct rf_host *host;
	uint32_t samples, frame, seed;
	float rays; /* samples x frames: how many rays share the lobe */
	float *ham0, *ham1; /* the Hammersley set of `samples` points */
	int pattern, animate, estimator, masking, mipoffset;
	float *dir, *lookup, *dist, *jac, *x, *y, *z, *lod, *rgba, *weight, *pdf;
};

/* ---- random numbers ------------------------------------------------------ */

/* Jarzynski and Olano's pcg4d: four 32-bit keys, four well-mixed words. */
static inline void
pcg4d(uint32_t v[4])
{
	int i;

	for (i = 0; i < 4; i++)
		v[i] = v[i] * 1664525u + 1013904223u;
	v[0] += v[1] * v[3];
	v[1] += v[2] * v[0];
	v[2] += v[0] * v[1];
	v[3] += v[1] * v[2];
	for (i = 0; i < 4; i++)
		v[i] ^= v[i] >> 16;
	v[0] += v[1] * v[3];
	v[1] += v[2] * v[0];
	v[2] += v[0] * v[1];
	v[3] += v[1] * v[2];
}

/* The top 24 bits: [0, 1), never 1. */
static inline float
unit_float(uint32_t h)
{
	return (float)(h >> 8) * (1.0f / 16777216.0f);
}

static inline float
radical_inverse(uint32_t i)
{
	i = (i << 16) | (i >> 16);
	i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
	i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
	i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
	i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
	return unit_float(i);
}

static inline float
max0(float x)
{
	return x > 0.0f ? x : 0.0f;
}

static inline float
fract(float x)
{
	float f = x - floorf(x);

	return f < 1.0f ? f : 0.0f;
}

/* Ray i's (u1, u2) at pixel (px, py).  Animated frames are decorrelated:
 * the frame is a key of the hash, and the Hammersley sets move by the R2
 * sequence's step (Roberts 2018), so no frame reuses another's numbers.
 * blue shifts the set by the pixel's values of two blue-noise masks
 * (Cranley-Patterson rotation, Georgiev and Fajardo's dithered sampling):
 * every pixel converges as fast as Hammersley, without the structured
 * aliasing of one set for all, and what error is left is spread as blue
 * noise, fine grained, which the eye and any later blur forgive. */
static void
random_pairs(const struct raytraced *rt, uint32_t px, uint32_t py, uint32_t n,
             float *restrict u0, float *restrict u1)
{
	uint32_t frame = rt->animate ? rt->frame : 0, i;
	float b0 = 0.0f, b1 = 0.0f, f0 = 0.0f, f1 = 0.0f;

	if (rt->pattern == PATTERN_WHITE) {
		for (i = 0; i < n; i++) {
			uint32_t v[4] = { px, py, i, rt->seed ^ (frame * 0x9E3779B9u) };

			pcg4d(v);
			u0[i] = unit_float(v[0]);
			u1[i] = unit_float(v[1]);
		}
		return;
	}
	if (rt->pattern == PATTERN_BLUE) {
		uint32_t sx = (px + rt->seed * 23u) % BLUENOISE_SIZE;
		uint32_t sy = (py + rt->seed * 41u) % BLUENOISE_SIZE;
		uint32_t c = sy * BLUENOISE_SIZE + sx;

		b0 = ((float)bluenoise_rank[0][c] + 0.5f) / (float)(BLUENOISE_SIZE * BLUENOISE_SIZE);
		b1 = ((float)bluenoise_rank[1][c] + 0.5f) / (float)(BLUENOISE_SIZE * BLUENOISE_SIZE);
	}
	if (frame) {
		f0 = (float)frame * 0.7548776662f;
		f1 = (float)frame * 0.5698402910f;
	}
	/* The Hammersley set is the instance's (rt->ham0, rt->ham1); the
	 * shifts are the pixel's and the frame's. */
	for (i = 0; i < n; i++) {
		float a = rt->ham0[i], b = rt->ham1[i];

		if (rt->pattern == PATTERN_BLUE) {
			a = fract(a + b0);
			b = fract(b + b1);
		}
		if (frame) {
			a = fract(a + f0);
			b = fract(b + f1);
		}
		u0[i] = a;
		u1[i] = b;
	}
}

/* ---- the lobe ------------------------------------------------------------ */

static inline float
dot3(const float a[3], const float b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline int
normalize3(float v[3])
{
	float len = sqrtf(dot3(v, v));

	if (!(len > 0.0f) || !(len < INFINITY))
		return -1;
	v[0] /= len;
	v[1] /= len;
	v[2] /= len;
	return 0;
}

/* A frame about n (HDRP's GetLocalFrame, Duff et al. 2017), right handed:
 * the write-up's orientation, so that its deterministic pattern lands
 * where it did. */
static inline void
local_frame(const float n[3], float x[3], float y[3])
{
	float s = n[2] >= 0.0f ? 1.0f : -1.0f, a = 1.0f / (s + n[2]);
	float b = n[0] * n[1] * a, c = n[0] * s;

	x[0] = c * n[0] * a - 1.0f;
	x[1] = s * b;
	x[2] = c;
	y[0] = b;
	y[1] = n[1] * n[1] * a - s;
	y[2] = n[1];
}

/* What Heitz's sampler (spec 7.3) works out once for a view: the
 * stretched view vh and its frame t1, t2 in the local frame (z up). */
struct vndf_view {
	float vh[3], t1[3], t2[3], w, alpha;
};

static inline void
vndf_view(const float v[3], float alpha, struct vndf_view *s)
{
	float *vh = s->vh, *t1 = s->t1, *t2 = s->t2, len;

	vh[0] = alpha * v[0];
	vh[1] = alpha * v[1];
	vh[2] = v[2];
	len = sqrtf(dot3(vh, vh));
	vh[0] /= len;
	vh[1] /= len;
	vh[2] /= len;
	if (vh[2] < 0.9999f) {
		float l = sqrtf(vh[0] * vh[0] + vh[1] * vh[1]);

		t1[0] = -vh[1] / l;
		t1[1] = vh[0] / l;
		t1[2] = 0.0f;
	} else {
		t1[0] = 1.0f;
		t1[1] = t1[2] = 0.0f;
	}
	t2[0] = vh[1] * t1[2] - vh[2] * t1[1];
	t2[1] = vh[2] * t1[0] - vh[0] * t1[2];
	t2[2] = vh[0] * t1[1] - vh[1] * t1[0];
	s->w = 0.5f * (1.0f + vh[2]);
	s->alpha = alpha;
}

/* sin and cos of 2 pi t for t in [0, 1), to 2e-7: t folded onto
 * [-1/4, 1/4] of a turn about the nearest half turn, then odd and even
 * Taylor polynomials.  Written without calls or branches, so that the
 * batch loop below becomes vector code. */
static inline void
sincos_turn(float t, float *s, float *c)
{
	int m = (int)(t * 2.0f + 0.5f);               /* nearest half turn */
	float x = (t - 0.5f * (float)m) * 6.28318530718f; /* in [-pi/2, pi/2] */
	float x2 = x * x, sign = (float)(1 - 2 * (m & 1));
	float sn = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 +
	           x2 * (1.0f / 362880 - x2 * (1.0f / 39916800))))));
	float cs = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 +
	           x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800 + x2 * (1.0f / 479001600))))));

	*s = sign * sn;
	*c = sign * cs;
}

/* Heitz's sampler for n rays at once: the microfacet normals of the
 * numbers u0, u1, in one loop of plain arithmetic over arrays; four rays
 * at a time in SSE vectors where the compiler has them, by the same
 * operations in the same order (the same bits as one at a time). */
static inline void
sample_vndf_one(const struct vndf_view *s, float u0, float u1, float *hx, float *hy,
                float *hz)
{
	const float *vh = s->vh, *t1 = s->t1, *t2 = s->t2, w = s->w, alpha = s->alpha;
	float r = sqrtf(u0), sn, cs, p1, p2, lh, nx, ny, nz, len, q;

	sincos_turn(u1, &sn, &cs);
	p1 = r * cs;
	p2 = r * sn;
	q = 1.0f - p1 * p1;
	p2 = (1.0f - w) * sqrtf(max0(q)) + w * p2;
	q = 1.0f - p1 * p1 - p2 * p2;
	lh = sqrtf(max0(q));
	nx = alpha * (p1 * t1[0] + p2 * t2[0] + lh * vh[0]);
	ny = alpha * (p1 * t1[1] + p2 * t2[1] + lh * vh[1]);
	nz = p1 * t1[2] + p2 * t2[2] + lh * vh[2];
	nz = max0(nz);
	len = 1.0f / sqrtf(nx * nx + ny * ny + nz * nz);
	*hx = nx * len;
	*hy = ny * len;
	*hz = nz * len;
}

#if defined(__SSE2__)
typedef float v4f __attribute__((vector_size(16)));
typedef int v4i __attribute__((vector_size(16)));

static inline v4f
v4_max0(v4f x)
{
	const v4f zero = { 0, 0, 0, 0 };

	/* as max0: NaN and -0 give 0 */
	return (v4f)((v4i)x & (x > zero));
}

static inline v4f
v4_sqrt(v4f x)
{
	return __builtin_ia32_sqrtps(x);
}
#endif

static void
sample_vndf_batch(const struct vndf_view *s, size_t n, const float *restrict u0,
                  const float *restrict u1, float *restrict hx, float *restrict hy,
                  float *restrict hz)
{
	size_t i = 0;

#if defined(__SSE2__)
	const v4f one = { 1, 1, 1, 1 }, half = { 0.5f, 0.5f, 0.5f, 0.5f };
	const v4f w = { s->w, s->w, s->w, s->w }, alpha = { s->alpha, s->alpha, s->alpha,
	                                                    s->alpha };

	for (; i + 4 <= n; i += 4) {
		v4f a, b, r, m, x, x2, sign, sn, cs, p1, p2, q, lh, nx, ny, nz, len;
		v4i k;
		int j;

		memcpy(&a, u0 + i, sizeof(a));
		memcpy(&b, u1 + i, sizeof(b));
		r = v4_sqrt(a);
		/* sincos_turn, lane by lane the same operations */
		k = __builtin_convertvector(b * 2.0f + half, v4i);
		m = __builtin_convertvector(k, v4f);
		x = (b - half * m) * 6.28318530718f;
		x2 = x * x;
		sign = __builtin_convertvector(1 - 2 * (k & 1), v4f);
		sn = x * (one + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 +
		     x2 * (1.0f / 362880 - x2 * (1.0f / 39916800))))));
		cs = one + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 +
		     x2 * (1.0f / 40320 + x2 * (-1.0f / 3628800 + x2 * (1.0f / 479001600))))));
		sn = sign * sn;
		cs = sign * cs;
		p1 = r * cs;
		p2 = r * sn;
		q = one - p1 * p1;
		p2 = (one - w) * v4_sqrt(v4_max0(q)) + w * p2;
		q = one - p1 * p1 - p2 * p2;
		lh = v4_sqrt(v4_max0(q));
		nx = alpha * (p1 * s->t1[0] + p2 * s->t2[0] + lh * s->vh[0]);
		ny = alpha * (p1 * s->t1[1] + p2 * s->t2[1] + lh * s->vh[1]);
		nz = v4_max0(p1 * s->t1[2] + p2 * s->t2[2] + lh * s->vh[2]);
		len = one / v4_sqrt(nx * nx + ny * ny + nz * nz);
		for (j = 0; j < 4; j++) {
			hx[i + j] = nx[j] * len[j];
			hy[i + j] = ny[j] * len[j];
			hz[i + j] = nz[j] * len[j];
		}
	}
#endif
	for (; i < n; i++)
		sample_vndf_one(s, u0[i], u1[i], hx + i, hy + i, hz + i);
}

/* sqrt(alpha^2 + (1 - alpha^2) c^2): with it 1 + 2 Lambda = a / c and
 * G1 = 2c / (c + a), with no tan^2 to overflow at grazing angles. */
static inline float
smith_a(float alpha2, float c)
{
	return sqrtf(alpha2 + (1.0f - alpha2) * c * c);
}

static inline float
ggx_d(float alpha2, float c)
{
	float t = c * c * (alpha2 - 1.0f) + 1.0f;

	return alpha2 / (3.14159265359f * t * t);
}

/* ---- a pixel --------------------------------------------------------------- */

/* log2 of a positive x to 2e-5 (a lod needs no more): the exponent,
 * and for the mantissa m in [1, 2) 2 atanh(t) / ln 2 with
 * t = (m - 1) / (m + 1) in [0, 1/3], four terms of its series.  0,
 * below and NaN give a large negative number, +inf a large positive one;
 * the caller clamps. */
static inline float
fast_log2(float x)
{
	union { float f; uint32_t u; } v = { x };
	float e = (float)(int32_t)((v.u >> 23) & 0xFF) - 127.0f, t, t2;

	if (!(x > 0.0f))
		return -1e30f;
	v.u = (v.u & 0x007FFFFFu) | 0x3F800000u;
	t = (v.f - 1.0f) / (v.f + 1.0f);
	t2 = t * t;
	return e + 2.88539008f * t * (1.0f + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7))));
}

/* The lod at which a read at unit lookup direction d covers the solid
 * angle omega at the capture point: half the log2 of its ratio to a
 * level-0 texel there, (2 / N)^2 |d_major|^3. */
static inline float
footprint_lod(const struct rf_host *host, const float d[3], float omega)
{
	float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]), texel, lod;
	float m = ax > ay ? (ax > az ? ax : az) : (ay > az ? ay : az);
	float top = (float)(host->env_levels - 1);

	texel = 4.0f / ((float)host->env_size * (float)host->env_size) * m * m * m;
	lod = 0.5f * fast_log2(omega / texel);
	return lod > 0.0f ? (lod < top ? lod : top) : 0.0f; /* NaN: 0 */
}

/* The write-up's mipoffset level: pr * clamp(d, 0, 6) for the mirror
 * ray's hit distance d. */
static float
mipoffset_lod(const struct raytraced *rt, const float p[3], const float r[3], float pr)
{
	float d[3], dist = INFINITY, jac, top = (float)(rt->host->env_levels - 1), lod;

	if (rt->host->project_rays)
		rt->host->project_rays(rt->host->ctx, 1, p, r, d, &dist, &jac);
	dist = dist > 0.0f ? (dist < 6.0f ? dist : 6.0f) : 0.0f;
	lod = pr * dist;
	return lod < top ? lod : top;
}

/* Where n rays (rt->dir) from p leave the box: rt->lookup, rt->jac. */
static void
project(struct raytraced *rt, const float p[3], uint32_t n)
{
	const struct rf_host *host = rt->host;
	uint32_t i;

	if (host->project_rays) {
		host->project_rays(host->ctx, n, p, rt->dir, rt->lookup, rt->dist, rt->jac);
		return;
	}
	memcpy(rt->lookup, rt->dir, 3 * n * sizeof(float));
	for (i = 0; i < n; i++)
		rt->jac[i] = 1.0f;
}

/* Reads the n projected rays at rt->lod: rgba. */
static void
read_rays(struct raytraced *rt, uint32_t n)
{
	const struct rf_host *host = rt->host;
	uint32_t i;

	for (i = 0; i < n; i++) {
		rt->x[i] = rt->lookup[3 * i];
		rt->y[i] = rt->lookup[3 * i + 1];
		rt->z[i] = rt->lookup[3 * i + 2];
	}
	host->sample_radiance(host->ctx, n, rt->x, rt->y, rt->z, rt->lod, rt->rgba);
}

static void
shade_pixel(struct raytraced *rt, const float *in, uint32_t px, uint32_t py, float out[3])
{
	const struct rf_host *host = rt->host;
	float p[3] = { in[0], in[1], in[2] }, n[3] = { in[3], in[4], in[5] };
	float vw[3] = { in[6], in[7], in[8] }, ng[3] = { in[10], in[11], in[12] };
	float pr = in[9], alpha, alpha2, x[3], y[3], v[3], r[3], nv, fixed_lod = 0.0f;
	float sum[3] = { 0, 0, 0 }, g1v = 1.0f, av = 0.0f;
	struct vndf_view view;
	int has_ng, original = rt->estimator == ESTIMATOR_ORIGINAL;
	uint32_t i, count = 0;

	out[0] = out[1] = out[2] = 0.0f;
	if (normalize3(n) < 0 || normalize3(vw) < 0 || !(pr >= 0.0f))
		return;
	pr = pr < 1.0f ? pr : 1.0f;
	has_ng = normalize3(ng) == 0;
	nv = dot3(n, vw);
	if (!(nv > 0.0f) && !original)
		return; /* seen from below its surface: no light, as in Cycles */
	for (i = 0; i < 3; i++)
		r[i] = 2.0f * nv * n[i] - vw[i];
	if (rt->mipoffset)
		fixed_lod = mipoffset_lod(rt, p, r, pr);
	alpha = pr * pr;
	alpha2 = alpha * alpha;
	local_frame(n, x, y);
	v[0] = dot3(x, vw);
	v[1] = dot3(y, vw);
	v[2] = nv;
	vndf_view(v, alpha, &view);
	if (!original) {
		av = smith_a(alpha2, nv);
		g1v = 2.0f * nv / (nv + av);
	}
	/* A mirror (pbrt's threshold): one ray, whole. */
	if (alpha < 1e-3f && !original) {
		float a, b;

		if (has_ng && !(dot3(ng, r) > 0.0f))
			return;
		memcpy(rt->dir, r, sizeof(r));
		rt->lod[0] = fixed_lod;
		project(rt, p, 1);
		read_rays(rt, 1);
		host->dfg(host->ctx, nv, pr, &a, &b);
		if (a + b > 1e-6f)
			for (i = 0; i < 3; i++)
				out[i] = rt->rgba[i] / (a + b);
		return;
	}
	/* The numbers, then the microfacet normals of all rays at once (into
	 * scratch that the reads use later). */
	{
		float *hx = rt->lookup, *hy = hx + rt->samples, *hz = hy + rt->samples;

		random_pairs(rt, px, py, rt->samples, rt->x, rt->y);
		sample_vndf_batch(&view, rt->samples, rt->x, rt->y, hx, hy, hz);
	}
	i = 0;
#if defined(__SSE2__)
	/* Four rays at a time, as the loop below does one: the same
	 * operations, so the same bits. */
	for (; !original && i + 4 <= rt->samples; i += 4) {
		const float *hxs = rt->lookup, *hys = hxs + rt->samples, *hzs = hys + rt->samples;
		const v4f zero = { 0, 0, 0, 0 }, one = { 1, 1, 1, 1 };
		v4f hx, hy, hz, c, lx, ly, lz, wx, wy, wz, cl, gl, al, wt, pd, t;
		v4i ok;
		int j;

		memcpy(&hx, hxs + i, sizeof(hx));
		memcpy(&hy, hys + i, sizeof(hy));
		memcpy(&hz, hzs + i, sizeof(hz));
		c = v[0] * hx + v[1] * hy + v[2] * hz;
		c = v4_max0(c);
		ok = c < one; /* as sat(): NaN and below 0 give 0, above 1 gives 1 */
		c = (v4f)(((v4i)c & ok) | ((v4i)one & ~ok));
		lx = 2.0f * c * hx - v[0];
		ly = 2.0f * c * hy - v[1];
		lz = 2.0f * c * hz - v[2];
		wx = lx * x[0] + ly * y[0] + lz * n[0];
		wy = lx * x[1] + ly * y[1] + lz * n[1];
		wz = lx * x[2] + ly * y[2] + lz * n[2];
		cl = n[0] * wx + n[1] * wy + n[2] * wz;
		gl = ng[0] * wx + ng[1] * wy + ng[2] * wz;
		ok = cl > zero;
		if (has_ng)
			ok &= gl > zero;
		al = v4_sqrt(alpha2 + (1.0f - alpha2) * cl * cl);
		wt = rt->masking == MASKING_SEPARABLE ? 2.0f * cl / (cl + al)
		                                     : cl * (nv + av) / (av * cl + al * nv);
		t = hz * hz * (alpha2 - 1.0f) + 1.0f;
		pd = g1v * (alpha2 / (3.14159265359f * t * t)) / (4.0f * nv);
		for (j = 0; j < 4; j++) {
			if (!ok[j])
				continue;
			rt->weight[count] = wt[j];
			rt->pdf[count] = pd[j];
			rt->dir[3 * count] = wx[j];
			rt->dir[3 * count + 1] = wy[j];
			rt->dir[3 * count + 2] = wz[j];
			count++;
		}
	}
#endif
	for (; i < rt->samples; i++) {
		const float *hx = rt->lookup;
		float h[3] = { hx[i], hx[rt->samples + i], hx[2 * rt->samples + i] };
		float l[3], lw[3], c, cl;
		int k;

		c = dot3(v, h);
		c = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
		for (k = 0; k < 3; k++)
			l[k] = 2.0f * c * h[k] - v[k];
		for (k = 0; k < 3; k++)
			lw[k] = l[0] * x[k] + l[1] * y[k] + l[2] * n[k];
		cl = dot3(n, lw);
		if (original) {
			if (!(cl >= 0.001f))
				continue;
			rt->weight[count] = 1.0f;
			rt->lod[count] = fixed_lod;
		} else {
			float al;

			/* Below the surface, or the geometry: worth nothing. */
			if (!(cl > 0.0f) || (has_ng && !(dot3(ng, lw) > 0.0f)))
				continue;
			al = smith_a(alpha2, cl);
			rt->weight[count] = rt->masking == MASKING_SEPARABLE
			                        ? 2.0f * cl / (cl + al)
			                        : cl * (nv + av) / (av * cl + al * nv);
			/* The ray's pdf, G1(V) D(H) / (4 N.V), for its footprint. */
			rt->pdf[count] = g1v * ggx_d(alpha2, h[2]) / (4.0f * nv);
		}
		memcpy(rt->dir + 3 * count, lw, sizeof(lw));
		count++;
	}
	if (original && count == 0) {
		/* No valid ray: the mirror direction (spec Part A #3). */
		memcpy(rt->dir, r, sizeof(r));
		rt->lod[0] = fixed_lod;
		project(rt, p, 1);
		read_rays(rt, 1);
		for (i = 0; i < 3; i++)
			out[i] = rt->rgba[i];
		return;
	}
	if (!count)
		return;
	project(rt, p, count);
	if (!original && !rt->mipoffset) {
		const float k = rt->rays;

		for (i = 0; i < count; i++)
			rt->lod[i] = footprint_lod(host, rt->lookup + 3 * i,
			                           rt->jac[i] / (k * rt->pdf[i]));
	} else if (!original) {
		for (i = 0; i < count; i++)
			rt->lod[i] = fixed_lod;
	}
	read_rays(rt, count);
	for (i = 0; i < count; i++) {
		const float *c = rt->rgba + 4 * i;
		float w = rt->weight[i];

		sum[0] += w * c[0];
		sum[1] += w * c[1];
		sum[2] += w * c[2];
	}
	if (original) {
		for (i = 0; i < 3; i++)
			out[i] = sum[i] / (float)count;
	} else {
		float a, b, e;

		host->dfg(host->ctx, nv, pr, &a, &b);
		e = (a + b) * (float)rt->samples;
		if (e > 1e-6f)
			for (i = 0; i < 3; i++)
				out[i] = sum[i] / e;
	}
}

static void
run(void *state, const struct rf_span *span)
{
	struct raytraced *rt = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += 13, out += 3)
		shade_pixel(rt, in, span->x + i, span->y, out);
}

/* ---- instances ----------------------------------------------------------- */

static void
destroy(void *state)
{
	struct raytraced *rt = state;

	if (!rt)
		return;
	free(rt->dir);
	free(rt);
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	const char *frame;
	struct raytraced *rt;
	size_t k, i;
	float *block;

	/* The services of ABI 1.1; a host of 1.0 would have none of them. */
	if (host->size < offsetof(struct rf_host, dfg) + sizeof(host->dfg) ||
	    !host->sample_radiance || !host->dfg || !host->env_size) {
		snprintf(err, errlen, "this host offers no environment to trace rays into "
		         "(it needs reflect-shade of plugin ABI 1.1 or later)");
		return -1;
	}
	if (!(rt = calloc(1, sizeof(*rt)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	rt->host = host;
	rt->samples = (uint32_t)values[SAMPLES];
	rt->pattern = (int)values[PATTERN];
	rt->animate = values[ANIMATE] != 0.0;
	rt->estimator = (int)values[ESTIMATOR];
	rt->masking = (int)values[MASKING];
	rt->mipoffset = values[MIPOFFSET] != 0.0;
	rt->seed = (uint32_t)values[SEED] + host->seed;
	rt->rays = (float)(values[SAMPLES] * values[FRAMES]);
	if ((frame = host->header_get(host->ctx, "FRAME")))
		rt->frame = (uint32_t)strtoul(frame, NULL, 10);
	/* One block: per ray 3 + 3 + 1 + 1 + 3 + 1 + 4 + 1 + 1 + 2 floats. */
	k = rt->samples;
	if (!(block = malloc(k * 20 * sizeof(float)))) {
		free(rt);
		snprintf(err, errlen, "out of memory for %zu rays", k);
		return -1;
	}
	rt->dir = block;
	rt->lookup = rt->dir + 3 * k;
	rt->dist = rt->lookup + 3 * k;
	rt->jac = rt->dist + k;
	rt->x = rt->jac + k;
	rt->y = rt->x + k;
	rt->z = rt->y + k;
	rt->lod = rt->z + k;
	rt->rgba = rt->lod + k;
	rt->weight = rt->rgba + 4 * k;
	rt->pdf = rt->weight + k;
	rt->ham0 = rt->pdf + k;
	rt->ham1 = rt->ham0 + k;
	for (i = 0; i < k; i++) {
		rt->ham0[i] = ((float)i + 0.5f) / (float)rt->samples;
		rt->ham1[i] = radical_inverse((uint32_t)i);
	}
	*state = rt;
	return 0;
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.flags = RF_PLUGIN_RADIANCE,
	.name = "raytraced",
	.summary = "rays of the GGX lobe through the probe box, weighted to the exact "
	           "integral",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.optional_inputs = optional_inputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
