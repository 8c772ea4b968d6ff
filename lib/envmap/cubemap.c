/* Cubemaps: face geometry, storage with seamless borders, sampling. */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/cubeface.h"
#include "envmap/envmap-internal.h"
#include "reflect/envmap.h"

struct rf_cubemap {
	size_t size, nlevels;
	size_t offset[32]; /* first float of each level */
	float *data;
};

/* Floats in one face of a level of n texels, border included. */
static size_t
face_floats(size_t n)
{
	return (n + 2) * (n + 2) * 3;
}

enum rf_face
rf_cube_face(const float d[3], float *u, float *v)
{
	return (enum rf_face)rf__cube_face(d, u, v);
}

void
rf_cube_direction(enum rf_face face, float u, float v, float d[3])
{
	float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;

	switch (face) {
	case RF_FACE_POS_X: d[0] = 1.0f; d[1] = -b; d[2] = a; break;
	case RF_FACE_NEG_X: d[0] = -1.0f; d[1] = -b; d[2] = -a; break;
	case RF_FACE_POS_Y: d[0] = a; d[1] = 1.0f; d[2] = -b; break;
	case RF_FACE_NEG_Y: d[0] = a; d[1] = -1.0f; d[2] = b; break;
	case RF_FACE_POS_Z: d[0] = -a; d[1] = -b; d[2] = 1.0f; break;
	case RF_FACE_NEG_Z: default: d[0] = a; d[1] = -b; d[2] = -1.0f; break;
	}
}

/* Solid angle of the face region from the face centre to (x, y). */
static double
area_element(double x, double y)
{
	return atan2(x * y, sqrt(x * x + y * y + 1.0));
}

double
rf_cube_texel_solid_angle(size_t n, size_t i, size_t j)
{
	double x0 = 2.0 * (double)i / (double)n - 1.0, x1 = 2.0 * (double)(i + 1) / (double)n - 1.0;
	double y0 = 2.0 * (double)j / (double)n - 1.0, y1 = 2.0 * (double)(j + 1) / (double)n - 1.0;

	return area_element(x0, y0) - area_element(x0, y1) - area_element(x1, y0) +
	       area_element(x1, y1);
}

void
rf_latlong_direction(float u, float v, float d[3])
{
	double phi = -2.0 * M_PI * ((double)u - 0.5);
	double theta = -M_PI * ((double)v - 0.5);

	d[0] = (float)(sin(phi) * cos(theta));
	d[1] = (float)sin(theta);
	d[2] = (float)(cos(phi) * cos(theta));
}

void
rf_latlong_position(const float d[3], float *u, float *v)
{
	double r = sqrt((double)d[0] * d[0] + (double)d[2] * d[2]);
	double len = sqrt(r * r + (double)d[1] * d[1]);
	double theta = len > 0.0 ? atan2((double)d[1], r) : 0.0;
	double phi = r > 0.0 ? atan2((double)d[0], (double)d[2]) : 0.0;

	*u = (float)(phi / (-2.0 * M_PI) + 0.5);
	*v = (float)(theta / -M_PI + 0.5);
}

/* Face widths past this could overflow the index arithmetic. */
#define CUBE_SIZE_MAX ((size_t)1 << 15)

/* Halve while even: 256 -> 9 levels, 96 -> 6. */
static size_t
max_levels(size_t size)
{
	size_t n = 1;

	while (!((size >> (n - 1)) & 1))
		n++;
	return n;
}

size_t
rf_cubemap_bytes(size_t size, size_t nlevels)
{
	size_t k, total = 0;

	if (size == 0 || size > CUBE_SIZE_MAX)
		return SIZE_MAX;
	if (nlevels == 0 || nlevels > max_levels(size))
		nlevels = max_levels(size);
	for (k = 0; k < nlevels; k++)
		total += 6 * face_floats(size >> k);
	return total * sizeof(float);
}

static size_t
max_bytes(void)
{
	const char *env = getenv("REFLECT_MAX_CUBE_MB");
	char *end;
	unsigned long long mb;

	if (env && *env) {
		errno = 0;
		mb = strtoull(env, &end, 10);
		if (!errno && !*end && mb > 0 && mb < ((unsigned long long)SIZE_MAX >> 20))
			return (size_t)mb << 20;
	}
	return (size_t)1024 << 20;
}

int
rf_cubemap_check_size(size_t size, size_t nlevels, char *err, size_t errlen)
{
	size_t bytes = rf_cubemap_bytes(size, nlevels), limit = max_bytes();

	if (bytes <= limit)
		return 0;
	if (bytes == SIZE_MAX)
		rf__format(err, errlen, "a cube of %zu-texel faces is over the largest, %zu",
		           size, CUBE_SIZE_MAX);
	else
		rf__format(err, errlen, "a cube of %zu-texel faces takes %.1f MB, over the "
		           "limit of %zu MB (REFLECT_MAX_CUBE_MB raises it)", size,
		           (double)bytes / (1 << 20), limit >> 20);
	return RF_ETOOBIG;
}

int
rf_cubemap_create(rf_cubemap **cp, size_t size, size_t nlevels)
{
	rf_cubemap *c;
	size_t k, total = 0, maxlevels = 1;

	*cp = NULL;
	if (size == 0 || size > CUBE_SIZE_MAX)
		return RF_ETOOBIG;
	maxlevels = max_levels(size);
	if (nlevels == 0)
		nlevels = maxlevels;
	if (nlevels > maxlevels)
		return RF_EINVAL;
	if (rf_cubemap_check_size(size, nlevels, NULL, 0) < 0)
		return RF_ETOOBIG;
	if (!(c = calloc(1, sizeof(*c))))
		return RF_ENOMEM;
	c->size = size;
	c->nlevels = nlevels;
	for (k = 0; k < nlevels; k++) {
		c->offset[k] = total;
		total += 6 * face_floats(size >> k);
	}
	if (!(c->data = rf__alloc_big(total * sizeof(float), 1))) {
		free(c);
		return RF_ENOMEM;
	}
	*cp = c;
	return 0;
}

void
rf_cubemap_destroy(rf_cubemap *c)
{
	if (!c)
		return;
	free(c->data);
	free(c);
}

size_t
rf_cubemap_size(const rf_cubemap *c)
{
	return c->size;
}

size_t
rf_cubemap_levels(const rf_cubemap *c)
{
	return c->nlevels;
}

size_t
rf_cubemap_level_size(const rf_cubemap *c, size_t level)
{
	return level < c->nlevels ? c->size >> level : 0;
}

/* Texel (i, j) with i, j in [-1, n]: the border included. */
static float *
padded(const rf_cubemap *c, size_t level, int face, long i, long j)
{
	size_t n = c->size >> level;

	return c->data + c->offset[level] + (size_t)face * face_floats(n) +
	       ((size_t)(j + 1) * (n + 2) + (size_t)(i + 1)) * 3;
}

float *
rf_cubemap_texel(rf_cubemap *c, size_t level, enum rf_face f, size_t i, size_t j)
{
	return padded(c, level, f, (long)i, (long)j);
}

const float *
rf_cubemap_texel_const(const rf_cubemap *c, size_t level, enum rf_face f, size_t i,
                       size_t j)
{
	return padded(c, level, f, (long)i, (long)j);
}

static long
texel_index(float u, size_t n)
{
	long i = (long)floorf(u * (float)n);

	return i < 0 ? 0 : i >= (long)n ? (long)n - 1 : i;
}

/* The texel a border texel (i or j at -1 or n, not both) copies. */
static enum rf_face
border_source(enum rf_face f, size_t n, long i, long j, long *si, long *sj)
{
	float d[3], u, v;
	enum rf_face g;

	rf_cube_direction(f, ((float)i + 0.5f) / (float)n, ((float)j + 0.5f) / (float)n, d);
	g = rf_cube_face(d, &u, &v);
	*si = texel_index(u, n);
	*sj = texel_index(v, n);
	return g;
}

void
rf_cubemap_seal_level(rf_cubemap *c, size_t level)
{
	size_t n = c->size >> level;
	long k, i, j;
	int f;

	/* Each border texel copies the texel its centre's direction lands in
	 * on the neighbouring face; for the 4 corners see below. */
	for (f = 0; f < 6; f++)
		for (k = 0; k < (long)n; k++) {
			long pos[4][2] = { { -1, k }, { (long)n, k }, { k, -1 }, { k, (long)n } };
			int e;

			for (e = 0; e < 4; e++) {
				long si, sj;
				enum rf_face g = border_source((enum rf_face)f, n, pos[e][0],
				                               pos[e][1], &si, &sj);

				memcpy(padded(c, level, f, pos[e][0], pos[e][1]),
				       padded(c, level, g, si, sj), 3 * sizeof(float));
			}
		}
	/* Three faces meet at a corner; giving each face's corner border the
	 * mean of the three corner texels makes bilinear filtering agree
	 * at the corner point from all three faces. */
	for (f = 0; f < 6; f++)
		for (j = -1; j <= (long)n; j += (long)n + 1)
			for (i = -1; i <= (long)n; i += (long)n + 1) {
				long ii = i < 0 ? 0 : (long)n - 1, jj = j < 0 ? 0 : (long)n - 1;
				const float *a = padded(c, level, f, ii, jj);
				const float *b = padded(c, level, f, i, jj);
				const float *d = padded(c, level, f, ii, j);
				float *out = padded(c, level, f, i, j);
				int ch;

				for (ch = 0; ch < 3; ch++)
					out[ch] = (a[ch] + b[ch] + d[ch]) * (1.0f / 3.0f);
			}
}

void
rf_cubemap_average_edges(rf_cubemap *c, size_t level)
{
	size_t n = c->size >> level;
	long k;
	int f, e, ch;

	if (n == 1) {
		/* Six single texels all touch each other: one value for all. */
		float mean[3] = { 0, 0, 0 };

		for (f = 0; f < 6; f++)
			for (ch = 0; ch < 3; ch++)
				mean[ch] += padded(c, level, f, 0, 0)[ch] / 6.0f;
		for (f = 0; f < 6; f++)
			memcpy(padded(c, level, f, 0, 0), mean, sizeof(mean));
		rf_cubemap_seal_level(c, level);
		return;
	}
	/* Each edge texel and the texel its border copies are the same pair
	 * seen from both faces: average them once from each side, which
	 * leaves both equal (the second visit averages equal values). */
	for (f = 0; f < 6; f++)
		for (k = 0; k < (long)n; k++) {
			long pos[4][2] = { { -1, k }, { (long)n, k }, { k, -1 }, { k, (long)n } };

			for (e = 0; e < 4; e++) {
				long i = pos[e][0] < 0 ? 0 : pos[e][0] >= (long)n ? (long)n - 1 : pos[e][0];
				long j = pos[e][1] < 0 ? 0 : pos[e][1] >= (long)n ? (long)n - 1 : pos[e][1];
				long si, sj;
				enum rf_face g = border_source((enum rf_face)f, n, pos[e][0], pos[e][1],
				                               &si, &sj);
				float *a = padded(c, level, f, i, j), *b = padded(c, level, g, si, sj);
				int corner = (i == 0 || i == (long)n - 1) && (j == 0 || j == (long)n - 1);

				if (corner)
					continue; /* corners below */
				for (ch = 0; ch < 3; ch++)
					a[ch] = b[ch] = 0.5f * (a[ch] + b[ch]);
			}
		}
	/* A corner texel meets two other faces' corner texels. */
	rf_cubemap_seal_level(c, level);
	for (f = 0; f < 6; f++)
			for (k = 0; k < 4; k++) {
				long i = k & 1 ? (long)n - 1 : 0, j = k & 2 ? (long)n - 1 : 0;
				long bi = i ? (long)n : -1, bj = j ? (long)n : -1;
				float *t = padded(c, level, f, i, j);
				const float *m = padded(c, level, f, bi, bj);

				/* The sealed corner border already holds the mean of the
				 * three corner texels. */
				for (ch = 0; ch < 3; ch++)
					t[ch] = m[ch];
			}
	rf_cubemap_seal_level(c, level);
}

/*
 * Each texel of the next level is the solid-angle-weighted mean of its
 * four children: an unweighted mean would let the small texels near cube
 * corners count as much as the large ones near face centres, and a bright
 * source near a corner would gain energy level by level.
 */
void
rf_cubemap_box_chain(rf_cubemap *c, size_t from)
{
	size_t k, i, j;
	int f, ch, q;
	/* The children's solid angles: the same on every face, and atan2
	 * four times a texel six times over was most of the chain's time. */
	double *omega = malloc(c->size * c->size * sizeof(double));

	for (k = from + 1; k < c->nlevels; k++) {
		size_t n = c->size >> k, m = 2 * n;

		if (omega)
			for (j = 0; j < m; j++)
				for (i = 0; i < m; i++)
					omega[j * m + i] = rf_cube_texel_solid_angle(m, i, j);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++) {
					float *out = padded(c, k, f, (long)i, (long)j);
					double acc[3] = { 0, 0, 0 }, wsum = 0.0;

					for (q = 0; q < 4; q++) {
						size_t ci = 2 * i + (size_t)(q & 1), cj = 2 * j + (size_t)(q >> 1);
						const float *p = padded(c, k - 1, f, (long)ci, (long)cj);
						double w = omega ? omega[cj * m + ci]
						                 : rf_cube_texel_solid_angle(m, ci, cj);

						for (ch = 0; ch < 3; ch++)
							acc[ch] += w * p[ch];
						wsum += w;
					}
					for (ch = 0; ch < 3; ch++)
						out[ch] = (float)(acc[ch] / wsum);
				}
		rf_cubemap_seal_level(c, k);
	}
	free(omega);
}

static void
bilinear(const rf_cubemap *c, size_t level, enum rf_face f, float u, float v,
         float w, float rgb[3])
{
	size_t n = c->size >> level, stride = (n + 2) * 3;
	float s = u * (float)n - 0.5f, t = v * (float)n - 0.5f;
	float fs = floorf(s), ft = floorf(t);
	long i = (long)fs, j = (long)ft;
	const float *p;
	float a, b;

	/* Guard against u, v a hair outside [0, 1] from rounding. */
	if (i < -1)
		i = -1, fs = -1.0f, s = -1.0f;
	if (i > (long)n - 1)
		i = (long)n - 1, fs = s = (float)n - 1.0f;
	if (j < -1)
		j = -1, ft = -1.0f, t = -1.0f;
	if (j > (long)n - 1)
		j = (long)n - 1, ft = t = (float)n - 1.0f;
	a = s - fs;
	b = t - ft;
	p = padded(c, level, f, i, j);
	rgb[0] += w * ((1 - b) * ((1 - a) * p[0] + a * p[3]) +
	               b * ((1 - a) * p[stride] + a * p[stride + 3]));
	rgb[1] += w * ((1 - b) * ((1 - a) * p[1] + a * p[4]) +
	               b * ((1 - a) * p[stride + 1] + a * p[stride + 4]));
	rgb[2] += w * ((1 - b) * ((1 - a) * p[2] + a * p[5]) +
	               b * ((1 - a) * p[stride + 2] + a * p[stride + 5]));
}

static int
finite_direction(const float d[3])
{
	return isfinite(d[0]) && isfinite(d[1]) && isfinite(d[2]);
}

void
rf_cubemap_sample_level(const rf_cubemap *c, size_t level, const float dir[3],
                        float rgb[3])
{
	float u, v;
	enum rf_face f = rf_cube_face(dir, &u, &v);

	rgb[0] = rgb[1] = rgb[2] = 0.0f;
	if (!finite_direction(dir))
		return;
	if (level >= c->nlevels)
		level = c->nlevels - 1;
	bilinear(c, level, f, u, v, 1.0f, rgb);
}

void
rf_cubemap_sample(const rf_cubemap *c, const float dir[3], float lod, float rgb[3])
{
	float u, v, top = (float)(c->nlevels - 1), frac;
	enum rf_face f = rf_cube_face(dir, &u, &v);
	size_t l;

	rgb[0] = rgb[1] = rgb[2] = 0.0f;
	if (!finite_direction(dir))
		return;
	if (!(lod > 0.0f))
		lod = 0.0f; /* NaN too */
	if (lod > top)
		lod = top;
	l = (size_t)lod;
	frac = lod - (float)l;
	if (frac > 0.0f && l + 1 < c->nlevels) {
		bilinear(c, l, f, u, v, 1.0f - frac, rgb);
		bilinear(c, l + 1, f, u, v, frac, rgb);
	} else {
		bilinear(c, l, f, u, v, 1.0f, rgb);
	}
}

void
rf_cubemap_level_mean(const rf_cubemap *c, size_t level, double rgb[3])
{
	size_t n = rf_cubemap_level_size(c, level), i, j;
	double sum[3] = { 0, 0, 0 }, wsum = 0.0;
	int f, ch;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				double w = rf_cube_texel_solid_angle(n, i, j);
				const float *p = padded(c, level, f, (long)i, (long)j);

				for (ch = 0; ch < 3; ch++)
					sum[ch] += w * p[ch];
				wsum += w;
			}
	for (ch = 0; ch < 3; ch++)
		rgb[ch] = wsum > 0.0 ? sum[ch] / wsum : 0.0;
}

const float *
rf__cubemap_padded_face(const rf_cubemap *c, size_t level, int face)
{
	return padded(c, level, face, -1, -1);
}

void
rf__cubemap_copy_level(rf_cubemap *dst, size_t to_level, const rf_cubemap *src,
                       size_t from_level)
{
	size_t n = rf_cubemap_level_size(dst, to_level), f, i, j;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++)
				memcpy(rf_cubemap_texel(dst, to_level, (enum rf_face)f, i, j),
				       rf_cubemap_texel_const(src, from_level, (enum rf_face)f, i, j),
				       3 * sizeof(float));
	rf_cubemap_seal_level(dst, to_level);
}
