/* Normal maps: procedural tiles, bumps and noise, and tangent-space
 * images unpacked as Unity's UnpackNormalWithScale (reflect-scene(5)),
 * applied in each primitive's tangent frame. */
#include <math.h>
#include <stdint.h>

#include "scene/scene-internal.h"

/* Fraction of a tile, on each side, taken by its bevelled edge. */
#define TILE_BEVEL 0.05
/* Radius of a bump, as a fraction of its cell. */
#define BUMP_RADIUS 0.4
#define NOISE_OCTAVES 3
/* Brings the summed slopes of the octaves to about 0.4 on average. */
#define NOISE_GAIN 0.25

static const double pi = 3.14159265358979323846;

/* Slope of one axis of a tile: smoothstep up from the grout over the
 * bevel, flat on top, normalised so that the steepest point is 1.  h is
 * the height (1 on top), for choosing the lower of the two axes. */
static double
tile_axis(double f, double *h)
{
	double t, sign;

	if (f < TILE_BEVEL) {
		t = f / TILE_BEVEL;
		sign = 1.0;
	} else if (f > 1.0 - TILE_BEVEL) {
		t = (1.0 - f) / TILE_BEVEL;
		sign = -1.0;
	} else {
		*h = 1.0;
		return 0.0;
	}
	*h = t * t * (3.0 - 2.0 * t);
	return sign * 4.0 * t * (1.0 - t);
}

static void
tiles(double u, double v, double g[2])
{
	double hu, hv, su = tile_axis(u - floor(u), &hu), sv = tile_axis(v - floor(v), &hv);

	/* The height is the lower of the two profiles: its slope wins. */
	g[0] = hu <= hv ? su : 0.0;
	g[1] = hu <= hv ? 0.0 : sv;
}

/* A raised cosine dome per cell, its slope normalised to 1 at the steepest. */
static void
bumps(double u, double v, double g[2])
{
	double du = u - floor(u) - 0.5, dv = v - floor(v) - 0.5;
	double r = sqrt(du * du + dv * dv), s;

	if (r >= BUMP_RADIUS || r == 0.0) {
		g[0] = g[1] = 0.0;
		return;
	}
	s = -sin(pi * r / BUMP_RADIUS) / r;
	g[0] = s * du;
	g[1] = s * dv;
}

/* A lattice value in [-1, 1]: integer hashing, so the same on every
 * machine and thread. */
static double
lattice(int64_t x, int64_t y, uint32_t seed)
{
	uint32_t h = (uint32_t)x * 0x8da6b343u ^ (uint32_t)y * 0xd8163841u ^ seed;

	h ^= h >> 16;
	h *= 0x7feb352du;
	h ^= h >> 15;
	h *= 0x846ca68bu;
	h ^= h >> 16;
	return (double)h / 2147483647.5 - 1.0;
}

/* Gradient of value noise with a quintic fade, derived analytically. */
static void
value_noise_gradient(double u, double v, uint32_t seed, double g[2])
{
	double fu = floor(u), fv = floor(v), su = u - fu, sv = v - fv;
	int64_t ix = (int64_t)fu, iy = (int64_t)fv;
	double wu = su * su * su * (su * (su * 6.0 - 15.0) + 10.0);
	double wv = sv * sv * sv * (sv * (sv * 6.0 - 15.0) + 10.0);
	double dwu = 30.0 * su * su * (su * (su - 2.0) + 1.0);
	double dwv = 30.0 * sv * sv * (sv * (sv - 2.0) + 1.0);
	double a = lattice(ix, iy, seed), b = lattice(ix + 1, iy, seed);
	double c = lattice(ix, iy + 1, seed), d = lattice(ix + 1, iy + 1, seed);
	double k = a - b - c + d;

	g[0] = dwu * ((b - a) + k * wv);
	g[1] = dwv * ((c - a) + k * wu);
}

static void
noise(double u, double v, double g[2])
{
	double f = 1.0, amp = 1.0, o[2];
	int i;

	g[0] = g[1] = 0.0;
	/* Each octave has half the height and twice the frequency: the same
	 * slope, finer. */
	for (i = 0; i < NOISE_OCTAVES; i++) {
		value_noise_gradient(u * f + 17.31 * i, v * f - 7.77 * i, (uint32_t)i, o);
		g[0] += amp * f * o[0];
		g[1] += amp * f * o[1];
		f *= 2.0;
		amp *= 0.5;
	}
	g[0] *= NOISE_GAIN;
	g[1] *= NOISE_GAIN;
}

static size_t
wrap(int64_t i, size_t n)
{
	int64_t m = i % (int64_t)n;

	return (size_t)(m < 0 ? m + (int64_t)n : m);
}

/* Exact for a constant map: a + (b - a) f returns a when b == a. */
static double
lerp(double a, double b, double f)
{
	return a + (b - a) * f;
}

/* Bilinear, repeating; v runs up the image (row 0 is the top), as in
 * the OpenGL convention of Unity's maps. */
static void
image_sample(const struct normalmap *nm, double u, double v, double rg[2])
{
	size_t w = nm->width, h = nm->height, nc = nm->nchannels, x0, x1, y0, y1;
	double s = (u - floor(u)) * (double)w - 0.5;
	double r = (1.0 - (v - floor(v))) * (double)h - 0.5;
	double fs = floor(s), fr = floor(r), fx = s - fs, fy = r - fr;
	const float *p = nm->pixels;
	int c;

	x0 = wrap((int64_t)fs, w);
	x1 = wrap((int64_t)fs + 1, w);
	y0 = wrap((int64_t)fr, h);
	y1 = wrap((int64_t)fr + 1, h);
	for (c = 0; c < 2; c++) {
		double top = lerp(p[(y0 * w + x0) * nc + c], p[(y0 * w + x1) * nc + c], fx);
		double bottom = lerp(p[(y1 * w + x0) * nc + c], p[(y1 * w + x1) * nc + c], fx);

		rg[c] = lerp(top, bottom, fy);
	}
}

void
rf__normalmap_apply(const struct normalmap *nm, const double uv[2], const double t[3],
                    const double b[3], const double ng[3], double out[3])
{
	double u = uv[0] * nm->inv_scale * nm->tiling[0] + nm->offset[0];
	double v = uv[1] * nm->inv_scale * nm->tiling[1] + nm->offset[1];
	double g[2], rg[2], x, y, z, len;
	int i;

	switch (nm->kind) {
	case NM_TILES:
	case NM_BUMPS:
	case NM_NOISE:
		if (nm->kind == NM_TILES)
			tiles(u, v, g);
		else if (nm->kind == NM_BUMPS)
			bumps(u, v, g);
		else
			noise(u, v, g);
		/* The normal of a height field leans against its gradient. */
		x = -nm->strength * g[0];
		y = -nm->strength * g[1];
		z = 1.0;
		break;
	case NM_IMAGE:
		image_sample(nm, u, v, rg);
		x = (2.0 * rg[0] - 1.0) * nm->strength;
		y = (2.0 * rg[1] - 1.0) * nm->strength;
		z = 1.0 - (x * x + y * y);
		z = z > 0.0 ? sqrt(z) : 0.0;
		break;
	default:
		x = y = 0.0;
		z = 1.0;
		break;
	}
	if (x == 0.0 && y == 0.0) {
		/* A flat map leaves the normal as it is, to the bit. */
		for (i = 0; i < 3; i++)
			out[i] = ng[i];
		return;
	}
	for (i = 0; i < 3; i++)
		out[i] = x * t[i] + y * b[i] + z * ng[i];
	len = sqrt(rf__dot(out, out));
	if (!(len > 1e-300)) {
		for (i = 0; i < 3; i++)
			out[i] = ng[i];
		return;
	}
	for (i = 0; i < 3; i++)
		out[i] /= len;
}
