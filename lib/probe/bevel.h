/*
 * The rounded probe box of the bevel projection: where a ray from inside
 * leaves it, and the shape's normal there.  Header-only, like
 * projection.h: the bevel plugin and the host's project_rays (lib/plugin/
 * host.c) include it, so a traced ray and reflect-project's D agree to
 * the bit.
 *
 * The shape is the Minkowski sum of an inner box and a ball of radius r,
 * centred on the probe box's centre: six flat faces, twelve quarter
 * cylinders along the edges, eight eighths of a sphere at the corners.
 * With its faces on the probe box (the default) the inner box is the
 * probe box shrunk by r; grown (offset=1, the write-up's default) it is
 * the probe box itself and the shape reaches r beyond it.
 *
 * The exit from inside a convex shape is its one boundary point ahead,
 * not the nearest of the pieces' roots (the write-up's intersector took
 * a corner's root whenever the line met its sphere, and an edge's root
 * wherever it fell).  So: the slab exit of the shape's bounding box
 * first; on a flat face (at most one coordinate beyond the inner box)
 * that is the exit.  Otherwise the exit lies in the same octant as the
 * slab exit (between the two the ray runs outside the shape and inside
 * its bounding box, in one pocket around an edge or corner, where the
 * signs of the coordinates beyond the inner box cannot change): folded
 * into the positive octant, each edge cylinder's and the corner sphere's
 * far root is taken only where it lies in that piece's own region.
 * When no candidate qualifies (rounding at a region's border), bisection
 * on the signed distance finds the exit.
 */
#ifndef REFLECT_PROBE_BEVEL_H
#define REFLECT_PROBE_BEVEL_H

#include <math.h>

#include "probe/projection.h"

/* Bisection steps of the fallback: the bracket [0, slab exit] shrinks to
 * 2^-30 of itself, below a float's rounding. */
#define RF__BEVEL_BISECTION_STEPS 30

struct rf__bevel {
	float lo[3], hi[3]; /* the bounding box (the probe box, grown or not) */
	float outer_lo[3], outer_hi[3]; /* that grown by the slack */
	float c[3];     /* the shape's centre: the probe box's */
	float s[3];     /* half extents of the inner box */
	float outer[3]; /* half extents of the bounding box, s + r */
	float slack[3]; /* how far outside a point still counts as on it */
	float r;        /* the rounding radius */
	float tol;      /* region tests' tolerance, relative to the shape */
};

/* The largest radius a probe box takes with its faces on the box (its
 * smallest half extent). */
static inline float
rf__bevel_max_radius(const struct rf_probe *probe)
{
	float m = INFINITY;
	int i;

	for (i = 0; i < 3; i++) {
		float h = 0.5f * (probe->box_max[i] - probe->box_min[i]);

		m = h < m ? h : m;
	}
	return m;
}

/* The shape of probe rounded by radius (0 <= radius, and with the faces
 * on the box radius <= rf__bevel_max_radius), grown beyond the box or not. */
static inline struct rf__bevel
rf__bevel_of_probe(const struct rf_probe *probe, float radius, int grown)
{
	struct rf__bevel b;
	float big = 0.0f;
	int i;

	for (i = 0; i < 3; i++) {
		float half = 0.5f * (probe->box_max[i] - probe->box_min[i]);

		b.c[i] = 0.5f * probe->box_min[i] + 0.5f * probe->box_max[i];
		b.s[i] = grown ? half : half - radius;
		if (b.s[i] < 0.0f)
			b.s[i] = 0.0f;
		b.outer[i] = b.s[i] + radius;
		b.slack[i] = RF__BOX_TOLERANCE * (probe->box_max[i] - probe->box_min[i]);
		/* as rf__box_of_probe has them, so that radius 0 is the box's bits */
		b.lo[i] = grown ? probe->box_min[i] - radius : probe->box_min[i];
		b.hi[i] = grown ? probe->box_max[i] + radius : probe->box_max[i];
		b.outer_lo[i] = b.lo[i] - b.slack[i];
		b.outer_hi[i] = b.hi[i] + b.slack[i];
		big = b.outer[i] > big ? b.outer[i] : big;
	}
	b.r = radius;
	b.tol = 1e-5f * big;
	return b;
}

/* Signed distance from the shape at x (relative to the centre). */
static inline float
rf__bevel_sdf(const struct rf__bevel *b, const float x[3])
{
	float q[3], out = 0.0f, in = -INFINITY;
	int i;

	for (i = 0; i < 3; i++) {
		q[i] = fabsf(x[i]) - b->s[i];
		out += q[i] > 0.0f ? q[i] * q[i] : 0.0f;
		in = q[i] > in ? q[i] : in;
	}
	return sqrtf(out) + (in < 0.0f ? in : 0.0f) - b->r;
}

/* The outward normal at a point x on (or near) the boundary. */
static inline void
rf__bevel_normal(const struct rf__bevel *b, const float x[3], float n[3])
{
	float q[3], len = 0.0f;
	int i, top = 0;

	for (i = 0; i < 3; i++) {
		q[i] = fabsf(x[i]) - b->s[i];
		if (q[i] > q[top])
			top = i;
	}
	for (i = 0; i < 3; i++) {
		n[i] = q[i] > 0.0f ? copysignf(q[i], x[i]) : 0.0f;
		len += n[i] * n[i];
	}
	if (len > 0.0f) {
		len = 1.0f / sqrtf(len);
		for (i = 0; i < 3; i++)
			n[i] *= len;
	} else { /* inside the inner box: the nearest face's */
		n[0] = n[1] = n[2] = 0.0f;
		n[top] = copysignf(1.0f, x[top]);
	}
}

/* Far root of |u + t d|^2 = r^2 over the axes of mask (2 or 3 of them),
 * or NaN when the line misses. */
static inline float
rf__bevel_far_root(const float u[3], const float d[3], const int use[3], float r)
{
	float a = 0.0f, bb = 0.0f, c = -r * r, disc;
	int i;

	for (i = 0; i < 3; i++)
		if (use[i]) {
			a += d[i] * d[i];
			bb += u[i] * d[i];
			c += u[i] * u[i];
		}
	disc = bb * bb - a * c;
	if (!(a > 1e-12f) || disc < 0.0f)
		return NAN;
	return (-bb + sqrtf(disc)) / a;
}

/* Distance from p along unit dir to where it leaves the shape, and the
 * shape's outward normal there (normal may be NULL); -1 when p lies
 * outside the shape's bounding box or dir is zero.  A p outside the
 * shape but inside its bounding box (near a rounded edge of a shape with
 * its faces on the box) leaves where the ray last crosses the boundary,
 * or at once (0) when it does not cross it ahead. */
static inline int
rf__bevel_exit(const struct rf__bevel *b, const float p[3], const float dir[3], float *dist,
           float normal[3])
{
	float o[3], h[3], sg[3], oo[3], dd[3], best = INFINITY, tf = INFINITY, x[3];
	int i, k, beyond = 0, axis = 0, found = 0;

	/* the slab exit of the bounding box, by rf__box_exit's operations */
	for (i = 0; i < 3; i++) {
		float to_hi, to_lo, ti;

		if (p[i] < b->outer_lo[i] || p[i] > b->outer_hi[i])
			return -1;
		o[i] = p[i] - b->c[i];
		if (!(fabsf(dir[i]) > RF__AXIS_EPSILON))
			continue;
		to_hi = (b->hi[i] - p[i]) / dir[i];
		to_lo = (b->lo[i] - p[i]) / dir[i];
		ti = to_hi > to_lo ? to_hi : to_lo;
		if (ti < tf) {
			tf = ti;
			axis = i;
		}
	}
	if (tf < 0.0f)
		tf = 0.0f;
	if (!(tf < INFINITY))
		return -1;
	for (i = 0; i < 3; i++) {
		h[i] = o[i] + dir[i] * tf;
		sg[i] = h[i] < 0.0f || (h[i] == 0.0f && dir[i] < 0.0f) ? -1.0f : 1.0f;
		oo[i] = o[i] * sg[i];
		dd[i] = dir[i] * sg[i];
		beyond += h[i] * sg[i] > b->s[i];
	}
	if (beyond <= 1 || b->r <= 0.0f) { /* a flat face */
		*dist = tf;
		if (normal) {
			normal[0] = normal[1] = normal[2] = 0.0f;
			normal[axis] = sg[axis];
		}
		return 0;
	}
	/* The three edges (k: the free axis) and the corner (k = 3), the
	 * likeliest first: the edge along the one axis within the inner box
	 * at the slab exit, or the corner when none is.  The exit is unique,
	 * so the first candidate in its own region is it. */
	{
		int first = 3, order[4], n = 1;

		for (i = 0; i < 3; i++)
			if (!(h[i] * sg[i] > b->s[i]))
				first = i;
		order[0] = first;
		for (k = 0; k < 4; k++)
			if (k != first)
				order[n++] = k;
		for (n = 0; n < 4 && !found; n++) {
			int use[3], ok = 1;
			float u[3], t;

			k = order[n];
			for (i = 0; i < 3; i++) {
				use[i] = k != i;
				u[i] = oo[i] - b->s[i];
			}
			t = rf__bevel_far_root(u, dd, use, b->r);
			if (!(t >= -b->tol))
				continue;
			for (i = 0; i < 3; i++) {
				float xi = oo[i] + dd[i] * t;

				ok &= use[i] ? xi >= b->s[i] - b->tol : fabsf(xi) <= b->s[i] + b->tol;
			}
			if (ok) {
				best = t;
				found = 1;
			}
		}
	}
	if (found) {
		*dist = best > 0.0f ? best : 0.0f;
	} else {
		for (i = 0; i < 3; i++)
			x[i] = o[i];
		if (rf__bevel_sdf(b, x) >= 0.0f) {
			*dist = 0.0f; /* outside, not crossing ahead: leaving */
		} else {
			float lo = 0.0f, hi = tf;

			for (k = 0; k < RF__BEVEL_BISECTION_STEPS; k++) {
				float mid = 0.5f * (lo + hi);

				for (i = 0; i < 3; i++)
					x[i] = o[i] + dir[i] * mid;
				if (rf__bevel_sdf(b, x) < 0.0f)
					lo = mid;
				else
					hi = mid;
			}
			*dist = hi;
		}
	}
	if (normal) {
		for (i = 0; i < 3; i++)
			x[i] = o[i] + dir[i] * *dist;
		rf__bevel_normal(b, x, normal);
	}
	return 0;
}

#endif
