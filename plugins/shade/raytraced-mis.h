/*
 * sampler=mis of the raytraced mode (raytraced.c): rays drawn from a
 * mixture of the GGX lobe and a per-pixel table of what the lobe sees
 * through the box.  Header-only, as a plugin links nothing of ours;
 * raytraced.c traces its lobe at the table's nodes (mis_nodes, then
 * mis_table on what came back) and moves each pixel's numbers
 * (mis_warp).
 *
 * The write-up's open item, importance sampling by the reflection's
 * luminance, as a second technique beside the lobe's own, combined with
 * it by the balance heuristic in its one-sample form (a mixture).
 *
 * What is bright is found per pixel, in the lobe's own terms: the
 * integrand of the lobe's technique, y = weight x luminance, is read at
 * the nodes of a grid over the unit square of the lobe's two numbers
 * (its primary sample space): g + 1 rows u0 = i / g (the lobe's centre
 * to its rim) by g columns u1 = j / g (the angle about it, periodic),
 * each through the box and at the level of the solid angle of a cell, so
 * that a window anywhere near a node shows in its value.  The second
 * technique's density is the product of the table's two marginals, each
 * piecewise linear; mixed per axis with the lobe's uniform density,
 *   d(u0, u1) = (s + (1 - s) m0(u0)) (s + (1 - s) m1(u1)),  s = 1 / sqrt 2,
 * half of it is the lobe's technique (s^2), and a ray's weight is
 * divided by d at its numbers, so the estimator stays unbiased.
 *
 * Why a product and not the table itself: rays are drawn from d by
 * inverting each marginal, a monotone move of each number on its own,
 * and such a move maps the pattern's strata (Hammersley's elementary
 * intervals, shifted per pixel by blue noise) onto rectangles: its
 * stratification survives whole.  The table's own 2D inverse moves u1 by
 * an amount that depends on u0 and shears the strata: on room-floor at
 * 256 rays it lowered white noise's error by 2.1x but left blue's where
 * the lobe alone has it (0.0116 against 0.0127, and 0.0116 against
 * 0.0105 on the default scene); the product gives 0.0110 and 0.0103.
 *
 * The mixture is taken where the table, integrated by trapezoids, says
 * it halves the variance; elsewhere (smooth light, a lobe that sees no
 * window) the lobe alone keeps its numbers unmoved: the patterns'
 * stratification already takes most of a smooth integrand's error,
 * which a variance does not count.  The footprint of a ray stays the
 * lobe's (trace_lobe, raytraced.c).
 */
#ifndef REFLECT_RAYTRACED_MIS_H
#define REFLECT_RAYTRACED_MIS_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "maths/lanes.h"

#define MIS_AXIS_SHARE 0.70710678f

/* The table's 1D arrays are padded with +inf to a multiple of four
 * entries, so that a search counts four at a time. */
static inline uint32_t
mis_stride(uint32_t g)
{
	return (g + 4) & ~3u;
}

/* How many of r[i], i < stride, are at most s: as the entries never
 * decrease and r[0] = 0, the index of the last one, plus 1. */
static inline uint32_t
mis_count_at_most(const float *r, uint32_t stride, float s)
{
	uint32_t i = 0, count = 0;

#if defined(__SSE2__)
	const rf__lanes_v4f vs = { s, s, s, s };
	rf__lanes_v4i acc = { 0, 0, 0, 0 };

	for (; i < stride; i += 4) {
		rf__lanes_v4f x;

		memcpy(&x, r + i, sizeof(x));
		acc -= (rf__lanes_v4i)(x <= vs);
	}
	count = (uint32_t)(acc[0] + acc[1] + acc[2] + acc[3]);
#endif
	for (; i < stride; i++)
		count += r[i] <= s;
	return count;
}

/* Where the table lives in its scratch of mis_floats(g) floats: the
 * nodes, then per axis its density at the nodes and its running
 * integral. */
struct mis_layout {
	float *y, *d0, *d1, *c0, *c1;
	uint32_t g, stride;
};

static struct mis_layout
mis_layout(float *table, uint32_t g)
{
	struct mis_layout t;

	t.g = g;
	t.stride = mis_stride(t.g);
	t.y = table;
	t.d0 = t.y + (t.g + 1) * t.g;
	t.d1 = t.d0 + t.stride;
	t.c0 = t.d1 + t.stride;
	t.c1 = t.c0 + t.stride;
	return t;
}

/* Floats of scratch that the table takes. */
static size_t
mis_floats(uint32_t g)
{
	return g ? (size_t)(g + 1) * g + 4 * (size_t)mis_stride(g) : 0;
}

/* The lobe's numbers at the table's nodes, into u0 and u1 ((g + 1) g
 * floats each): the lobe is to be traced at the 1 + g^2 pairs from
 * u0 + g - 1 and u1 + g - 1.  Row 0 (u0 = 0) is the lobe's centre
 * whatever u1: only its last node is read, and the rays start there. */
static void
mis_nodes(uint32_t g, float *u0, float *u1)
{
	const float h = 1.0f / (float)g;
	uint32_t i, j;

	u0[g - 1] = u1[g - 1] = 0.0f;
	for (i = 1; i <= g; i++)
		for (j = 0; j < g; j++) {
			u0[i * g + j] = (float)i * h;
			u1[i * g + j] = (float)j * h;
		}
}

/* Reads the table from the lobe traced at the nodes (count rays that
 * counted: index[i] of each among the nodes, its weight f N.L / pdf and
 * its radiance, 4 floats a ray in rgba) and sets up the mixture; 0 when
 * the lobe alone is to be used. */
static int
mis_table(const struct mis_layout *t, uint32_t count, const uint32_t *index,
          const float *weight, const float *rgba)
{
	const uint32_t g = t->g, nodes = (g + 1) * g;
	const float h = 1.0f / (float)g;
	float *y = t->y, *d0 = t->d0, *d1 = t->d1, *c0 = t->c0, *c1 = t->c1;
	float i0 = 0.0f, i1 = 0.0f, mean = 0.0f, plain = 0.0f, mixed = 0.0f;
	uint32_t i, j;

	memset(y, 0, nodes * sizeof(*y));
	for (i = 0; i < count; i++) {
		const float *c = rgba + 4 * i;
		float v = weight[i] * (0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]);

		if (v > 0.0f && v < 1e30f) /* NaN and Inf weigh nothing */
			y[g - 1 + index[i]] = v;
	}
	for (j = 0; j + 1 < g; j++)
		y[j] = y[g - 1];
	/* The marginals at the nodes: row means (u0), and column means
	 * integrated over u0 by trapezoids (u1). */
	for (i = 0; i <= g; i++) {
		float m = 0.0f;

		for (j = 0; j < g; j++)
			m += y[i * g + j];
		d0[i] = m * h;
	}
	for (j = 0; j < g; j++) {
		float m = 0.5f * (y[j] + y[g * g + j]);

		for (i = 1; i < g; i++)
			m += y[i * g + j];
		d1[j] = m * h;
	}
	for (i = 0; i < g; i++) {
		i0 += 0.5f * h * (d0[i] + d0[i + 1]);
		i1 += h * d1[i];
	}
	if (!(i0 > 1e-30f && i0 < 1e30f && i1 > 1e-30f && i1 < 1e30f))
		return 0; /* nothing to see: the lobe alone */
	for (i = 0; i <= g; i++)
		d0[i] = MIS_AXIS_SHARE + (1.0f - MIS_AXIS_SHARE) * d0[i] / i0;
	for (j = 0; j < g; j++)
		d1[j] = MIS_AXIS_SHARE + (1.0f - MIS_AXIS_SHARE) * d1[j] / i1;
	d1[g] = d1[0];
	c0[0] = c1[0] = 0.0f;
	for (i = 0; i < g; i++) {
		c0[i + 1] = c0[i] + 0.5f * h * (d0[i] + d0[i + 1]);
		c1[i + 1] = c1[i] + 0.5f * h * (d1[i] + d1[i + 1]);
	}
	for (i = g + 1; i < t->stride; i++)
		c0[i] = c1[i] = INFINITY; /* never below: the searches count past g */
	/* Worth it?  The variance of either technique over the nodes. */
	for (i = 0; i <= g; i++) {
		float wq = (i == 0 || i == g ? 0.5f : 1.0f) * h * h, e = d0[i] / c0[g];

		for (j = 0; j < g; j++) {
			float v = y[i * g + j];

			mean += wq * v;
			plain += wq * v * v;
			mixed += wq * v * v / (e * d1[j] / c1[g]);
		}
	}
	return mixed - mean * mean < 0.5f * (plain - mean * mean);
}

/* The t in [0, 1) at which the area under the line from a0 to a1 over
 * [0, t] (of width 1 / g) reaches s; a0, a1 > 0.  For n at once, into
 * off + t / g, four at a time in SSE vectors where the compiler has
 * them, by the same operations (the same bits): the square root and the
 * division are the move's latency. */
static inline float
mis_invert_trapezoid(float a0, float a1, float g, float s)
{
	float q = s * g, r = a0 * a0 + 2.0f * (a1 - a0) * q, t;

	r = r > 0.0f ? r : 0.0f; /* NaN too */
	t = 2.0f * q / (a0 + sqrtf(r));

	return t < 0.99999994f ? (t > 0.0f ? t : 0.0f) : 0.99999994f;
}

static void
mis_invert_trapezoids(size_t n, const float *restrict a0, const float *restrict a1,
                      const float *restrict s, const float *restrict off, float g,
                      float *restrict t, float *restrict u)
{
	const float h = 1.0f / g;
	size_t i = 0;

#if defined(__SSE2__)
	const rf__lanes_v4f zero = { 0, 0, 0, 0 }, top = { 0.99999994f, 0.99999994f, 0.99999994f,
	                                         0.99999994f };

	for (; i + 4 <= n; i += 4) {
		rf__lanes_v4f va0, va1, vs, vo, q, r;
		rf__lanes_v4i in;
		int k;

		memcpy(&va0, a0 + i, sizeof(va0));
		memcpy(&va1, a1 + i, sizeof(va1));
		memcpy(&vs, s + i, sizeof(vs));
		memcpy(&vo, off + i, sizeof(vo));
		q = vs * g;
		r = va0 * va0 + 2.0f * (va1 - va0) * q;
		r = (rf__lanes_v4f)((rf__lanes_v4i)r & (r > zero)); /* as the scalar's, NaN too */
		for (k = 0; k < 4; k++)
			r[k] = sqrtf(r[k]);
		r = 2.0f * q / (va0 + r);
		in = r > zero;
		r = (rf__lanes_v4f)((rf__lanes_v4i)r & in); /* below 0 and NaN: 0 */
		in = r < top;
		r = (rf__lanes_v4f)(((rf__lanes_v4i)r & in) | ((rf__lanes_v4i)top & ~in));
		memcpy(t + i, &r, sizeof(r));
		r = vo + r * h;
		memcpy(u + i, &r, sizeof(r));
	}
#endif
	for (; i < n; i++) {
		t[i] = mis_invert_trapezoid(a0[i], a1[i], g, s[i]);
		u[i] = off[i] + t[i] * h;
	}
}


/* Scratch for a warp of n numbers: n floats each. */
struct mis_scratch {
	float *a0, *a1, *rem, *off, *t;
};

/* Moves the n numbers u through the inverse of one axis' marginal d
 * (running integral c; on the periodic axis d[g] is d[0]); dens is
 * multiplied by d at the new place. */
static void
mis_move(const struct mis_layout *tb, uint32_t n, const float *d, const float *c, float *u,
         float *dens, const struct mis_scratch *sc)
{
	const uint32_t g = tb->g, stride = tb->stride;
	const float h = 1.0f / (float)g, total = c[g];
	float *a0 = sc->a0, *a1 = sc->a1, *rem = sc->rem, *off = sc->off, *t = sc->t;
	uint32_t k;

	for (k = 0; k < n; k++) {
		float s = u[k] * total;
		uint32_t lo = mis_count_at_most(c, stride, s) - 1;

		lo = lo < g - 1 ? lo : g - 1;
		a0[k] = d[lo];
		a1[k] = d[lo + 1];
		rem[k] = s - c[lo];
		off[k] = (float)lo * h;
	}
	mis_invert_trapezoids(n, a0, a1, rem, off, (float)g, t, u);
	for (k = 0; k < n; k++)
		dens[k] *= ((1.0f - t[k]) * a0[k] + t[k] * a1[k]) / total;
}

/* Draws n rays' numbers from the mixture of table t: u0 and u1, uniform
 * in the unit square, moved in place, and their density there in dens. */
static void
mis_warp(const struct mis_layout *t, uint32_t n, float *u0, float *u1, float *dens,
         const struct mis_scratch *sc)
{
	uint32_t k;

	for (k = 0; k < n; k++)
		dens[k] = 1.0f;
	mis_move(t, n, t->d0, t->c0, u0, dens, sc);
	mis_move(t, n, t->d1, t->c1, u1, dens, sc);
}

#endif
