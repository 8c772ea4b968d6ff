/*
 * The prefilter's bright part: texels far above a source's mean (a sun,
 * a lamp) taken out of what the importance samples read and integrated
 * exactly against each lobe instead.
 *
 * A few hundred texels of a 256 cube can hold a fifth of its energy: a
 * sun of 1.5 degrees at 4000 over a sky near 1.  Importance samples of
 * GGX find it by chance, one sample in a texel's set landing on it or
 * not, and a filtered read spreads it over the read's footprint; at 64
 * samples the texels of its halo are off by half (relative RMS).  The
 * sum over the lobe is linear in the radiance, so the source splits:
 * L = min(L, T) + (L - min(L, T)) per channel, with T a multiple of the
 * mean.  The first part has no contrast past T and the samples converge
 * on it; the second is zero but for a sparse set of texels, and is
 * integrated as the brute-force reference integrates the whole source
 * (the same points, weights and bilinear reconstruction), over the
 * exact integral of the lobe.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "envmap/prefilter_bright.h"
#include "envmap/rgba_levels.h"
#include "reflect/envmap.h"

/* A texel is bright past BRIGHT_FACTOR times the mean of the source (of
 * its largest channel).  A lower factor makes the sampled part smoother
 * and the sparse set larger; at 16 the sampled part of a sky with a sun
 * is within 0.5% RMS at 64 samples. */
#define BRIGHT_FACTOR 16.0

/* At most this many integration points of the bright part at level 1
 * (where they are densest: brute_subdivision), counted as the points of
 * the texels next to a bright one; past it the threshold rises until
 * they fit.  Each output texel visits every point: a sun 1.5 degrees
 * across at 256 texels a face takes 224 there, and the bright part in
 * all adds some 30% to the time of the samples. */
#define BRIGHT_POINTS_MAX 2048

static float
max3(const float *p)
{
	float m = p[0] > p[1] ? p[0] : p[1];

	return m > p[2] ? m : p[2];
}

static int
cmp_desc(const void *a, const void *b)
{
	float x = *(const float *)a, y = *(const float *)b;

	return x > y ? -1 : x < y;
}

/* Texels within one of a texel above t on the same face (the ones
 * across an edge are few and left out of this estimate). */
static size_t
near_count(const rf_cubemap *c, float t, unsigned char *mark)
{
	size_t n = rf_cubemap_size(c), i, j, a, b, count = 0;
	int f;

	memset(mark, 0, 6 * n * n);
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				if (!(max3(rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j)) > t))
					continue;
				for (b = j ? j - 1 : 0; b <= j + 1 && b < n; b++)
					for (a = i ? i - 1 : 0; a <= i + 1 && a < n; a++) {
						unsigned char *m = mark + ((size_t)f * n + b) * n + a;

						count += !*m;
						*m = 1;
					}
			}
	return count;
}

int
rf__bright_split(rf_cubemap *c, size_t sub, rf_cubemap **resid, size_t *count)
{
	size_t n = rf_cubemap_size(c), i, j, above = 0, k = 0, keep;
	double sum = 0.0;
	float t, *vals;
	unsigned char *mark;
	int f, ch;

	*resid = NULL;
	*count = 0;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++)
				sum += max3(rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j));
	t = (float)(BRIGHT_FACTOR * sum / (6.0 * (double)n * (double)n));
	if (!(t > 0.0f))
		return 0; /* black, or negative texels: nothing stands out */
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++)
				above += max3(rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j)) > t;
	if (!above)
		return 0;
	vals = malloc(above * sizeof(float));
	mark = malloc(6 * n * n);
	if (!vals || !mark) {
		free(vals);
		free(mark);
		return RF_ENOMEM;
	}
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float m = max3(rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j));

				if (m > t)
					vals[k++] = m;
			}
	qsort(vals, above, sizeof(float), cmp_desc);
	/* The brightest `keep`, fewer while their points are too many; ties
	 * with the first left out stay in the sampled part. */
	for (keep = above; near_count(c, t, mark) * sub * sub > BRIGHT_POINTS_MAX;) {
		keep /= 2;
		if (!keep)
			break;
		t = vals[keep];
	}
	free(vals);
	free(mark);
	if (!keep || !(t > 0.0f))
		return 0;
	if (rf_cubemap_create(resid, n, 1) < 0)
		return RF_ENOMEM;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float *p = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);
				float *r = rf_cubemap_texel(*resid, 0, (enum rf_face)f, i, j);

				r[0] = r[1] = r[2] = 0.0f;
				if (!(max3(p) > t))
					continue;
				for (ch = 0; ch < 3; ch++)
					if (p[ch] > t) {
						r[ch] = p[ch] - t;
						p[ch] = t;
					}
				++*count;
			}
	if (!*count) {
		rf_cubemap_destroy(*resid);
		*resid = NULL;
		return 0;
	}
	rf_cubemap_seal_level(c, 0);
	rf_cubemap_seal_level(*resid, 0);
	return 0;
}

static void
normalize3(float v[3])
{
	float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);

	v[0] /= len;
	v[1] /= len;
	v[2] /= len;
}

/* Whether a bilinear read inside texel (i, j) of a face reaches a
 * non-zero texel of the residual: its 3 x 3 neighbours, across the
 * face's edges through the border. */
static int
near_bright(const float *face, size_t n, size_t i, size_t j)
{
	size_t a, b, stride = (n + 2) * 3;

	for (b = j; b < j + 3; b++)
		for (a = i; a < i + 3; a++) {
			const float *p = face + b * stride + a * 3;

			if (p[0] != 0.0f || p[1] != 0.0f || p[2] != 0.0f)
				return 1;
		}
	return 0;
}

/* Room for twice the points (columns moved up), a multiple of 4 and one
 * block more, for the padding of the last block. */
static int
grow(struct rf__bright *b, size_t *cap)
{
	size_t want = *cap ? 2 * *cap : 256, col;
	float *p = realloc(b->p, 6 * want * sizeof(float));

	if (!p)
		return RF_ENOMEM;
	for (col = 6; col-- > 1;)
		memmove(p + col * want, p + col * *cap, *cap * sizeof(float));
	b->p = p;
	*cap = want;
	return 0;
}

int
rf__bright_points(struct rf__bright *b, const rf_cubemap *resid, size_t sub)
{
	size_t n = rf_cubemap_size(resid), m = n * sub, i, j, si, sj, cap = b->stride;
	int f;

	b->count = 0;
	b->sub = sub;
	for (f = 0; f < 6; f++) {
		const float *face = rf__cubemap_padded_face(resid, 0, f);

		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				if (!near_bright(face, n, i, j))
					continue;
				for (sj = 0; sj < sub; sj++)
					for (si = 0; si < sub; si++) {
						size_t pi = i * sub + si, pj = j * sub + sj;
						float d[3], rgb[3];
						double omega;

						rf_cube_direction((enum rf_face)f, ((float)pi + 0.5f) / (float)m,
						                  ((float)pj + 0.5f) / (float)m, d);
						normalize3(d);
						rf_cubemap_sample_level(resid, 0, d, rgb);
						if (rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f)
							continue;
						if (b->count == cap && grow(b, &cap) < 0)
							return RF_ENOMEM;
						omega = rf_cube_texel_solid_angle(m, pi, pj);
						b->p[b->count] = d[0];
						b->p[cap + b->count] = d[1];
						b->p[2 * cap + b->count] = d[2];
						b->p[3 * cap + b->count] = (float)(omega * rgb[0]);
						b->p[4 * cap + b->count] = (float)(omega * rgb[1]);
						b->p[5 * cap + b->count] = (float)(omega * rgb[2]);
						b->count++;
					}
			}
	}
	b->stride = cap;
	/* the last block of four: points of nothing, at +Z */
	for (i = b->count; i < (b->count + 3) / 4 * 4; i++) {
		int col;

		for (col = 0; col < 6; col++)
			b->p[col * cap + i] = col == 2 ? 1.0f : 0.0f;
	}
	return 0;
}

void
rf__bright_destroy(struct rf__bright *b)
{
	free(b->p);
	memset(b, 0, sizeof(*b));
}

/*
 * The integral of D(h) (n.l) over the sphere of l, h the half vector of
 * n and l: with x = (n.h)^2, n.l = 2x - 1 and dl = 4 (n.h) dh, it is
 * 4 pi times the integral of D(x) (2x - 1) over x in [1/2, 1], which
 * with b = 1 - a^2 comes to (4 / b^2) (1 - a^2 - 2 a^2 ln((1 + a^2) /
 * (2 a^2))).  Near a = 1 the bracket cancels to b^2 / 4 + b^3 / 6 and
 * that series stands for it (the integral is 1 at a = 1: D is 1 / pi).
 */
double
rf__ggx_lobe_integral(double a)
{
	double a2 = a * a, b = 1.0 - a2;

	if (a2 < 1e-12)
		return 4.0; /* a mirror: n.l = 1 over the lobe, dl = 4 dh */
	if (b < 1e-3)
		return 1.0 + 2.0 * b / 3.0; /* the bracket is b^2 / 4 + b^3 / 6 + ... */
	return 4.0 / (b * b) * (1.0 - a2 - 2.0 * a2 * log((1.0 + a2) / (2.0 * a2)));
}

/* The sum in double, one point at a time: for sums past the float
 * range (radiance near RF__TEXEL_MAX over large texels). */
static void
bright_add_wide(const struct rf__bright *b, const float n[3], double alpha, double norm,
                float rgb[3])
{
	const float *x = b->p, *y = x + b->stride, *z = y + b->stride;
	const float *er = z + b->stride, *eg = er + b->stride, *eb = eg + b->stride;
	const double a2 = alpha * alpha;
	double r = 0.0, g = 0.0, bl = 0.0;
	size_t i;

	for (i = 0; i < b->count; i++) {
		double dx = (double)n[0] - x[i], dy = (double)n[1] - y[i], dz = (double)n[2] - z[i];
		double q = 0.25 * (dx * dx + dy * dy + dz * dz), nol = 1.0 - 2.0 * q;
		double s = a2 / (a2 + (1.0 - a2) * q), w = nol > 0.0 ? nol * s * s : 0.0;

		r += w * er[i];
		g += w * eg[i];
		bl += w * eb[i];
	}
	norm = 1.0 / (M_PI * a2 * norm);
	rgb[0] += (float)(r * norm);
	rgb[1] += (float)(g * norm);
	rgb[2] += (float)(bl * norm);
}

/*
 * D(h) (n.l) at each point, four at a time.  With q = |n - l|^2 / 4 =
 * (1 - n.l) / 2, GGX's denominator is a^2 + (1 - a^2) q: no cancellation
 * near the lobe's peak, where 1 + (n.h)^2 (a^2 - 1) loses the digits a
 * lobe of a = 0.01 lives in.  D is a^2 / (pi t^2) = (a^2 / t)^2 / (pi
 * a^2), and (a^2 / t)^2 is at most 1: the constant is applied once.
 * Lanes add in a fixed order: the same bytes on any thread.
 */
void
rf__bright_add(const struct rf__bright *b, const float n[3], double alpha, double norm,
               float rgb[3])
{
	const rf__v4 *x = (const rf__v4 *)b->p, *y = x + b->stride / 4, *z = y + b->stride / 4;
	const rf__v4 *er = z + b->stride / 4, *eg = er + b->stride / 4, *eb = eg + b->stride / 4;
	const float a2 = (float)(alpha * alpha), c = 1.0f - a2;
	const rf__v4 zero = { 0, 0, 0, 0 };
	rf__v4 r = zero, g = zero, bl = zero;
	double k;
	size_t i;

	for (i = 0; i < (b->count + 3) / 4; i++) {
		rf__v4 dx = n[0] - x[i], dy = n[1] - y[i], dz = n[2] - z[i];
		rf__v4 q = 0.25f * (dx * dx + dy * dy + dz * dz), nol = 1.0f - 2.0f * q;
		rf__v4 s = a2 / (a2 + c * q), w = nol * s * s;

		w = (rf__v4)((rf__v4i)w & (nol > zero)); /* the lower hemisphere adds 0 */
		r += w * er[i];
		g += w * eg[i];
		bl += w * eb[i];
	}
	k = 1.0 / (M_PI * (double)a2 * norm);
	r = (r[0] + r[1]) + (r[2] + r[3]) + zero;
	g = (g[0] + g[1]) + (g[2] + g[3]) + zero;
	bl = (bl[0] + bl[1]) + (bl[2] + bl[3]) + zero;
	if (!(isfinite(r[0]) && isfinite(g[0]) && isfinite(bl[0]))) {
		bright_add_wide(b, n, alpha, norm, rgb);
		return;
	}
	rgb[0] += (float)((double)r[0] * k);
	rgb[1] += (float)((double)g[0] * k);
	rgb[2] += (float)((double)bl[0] * k);
}
