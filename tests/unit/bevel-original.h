/*
 * The write-up's flipped rounded-box intersector, as its spec section 8.3
 * restates it: kept in the tests only, to measure it (test-bevel.c) and
 * to picture its artefacts (the bevel_original test plugin, for
 * doc/pictures).  Not reflect's: plugins/project/bevel.h is.
 */
#ifndef REFLECT_TESTS_BEVEL_ORIGINAL_H
#define REFLECT_TESTS_BEVEL_ORIGINAL_H

#include <math.h>

static inline float
sgn(float x)
{
	return x < 0.0f ? -1.0f : 1.0f;
}

/* The write-up's flipped intersector (its §8.3 as the spec restates it):
 * the slab exit of the grown box, folded into the first octant; a face
 * when at most one coordinate is beyond the inner box; else the edges'
 * far roots, the smallest within its edge's extent, then the corner
 * sphere's far root over it whenever the line meets the sphere.  -1 when
 * nothing is found. */
static inline float
original_exit(const float size[3], float rad, const float ro[3], const float rd[3])
{
	float o[3], d[3], tn = -INFINITY, tf = INFINITY, t, q[3], best = 1e20f;
	float oc[3], b, c, h;
	int i, k;

	for (i = 0; i < 3; i++) {
		float m = 1.0f / rd[i], n = m * ro[i], kk = fabsf(m) * (size[i] + rad);
		float t1 = -n - kk, t2 = -n + kk;

		tn = t1 > tn ? t1 : tn;
		tf = t2 < tf ? t2 : tf;
	}
	if (tn > tf || tf < 0.0f)
		return -1.0f;
	t = tf;
	for (i = 0; i < 3; i++) {
		float s = sgn(ro[i] + t * rd[i]);

		o[i] = ro[i] * s;
		d[i] = rd[i] * s;
		q[i] = o[i] + t * d[i] - size[i];
	}
	{
		float a = q[0] > q[1] ? q[0] : q[1], bb = q[1] > q[2] ? q[1] : q[2];
		float cc = q[2] > q[0] ? q[2] : q[0], m = a < bb ? a : bb;

		if ((m < cc ? m : cc) < 0.0f)
			return t;
	}
	for (i = 0; i < 3; i++)
		oc[i] = o[i] - size[i];
	for (k = 0; k < 3; k++) { /* the edge along axis k */
		int u = (k + 1) % 3, v = (k + 2) % 3;
		float a = d[u] * d[u] + d[v] * d[v];

		b = oc[u] * d[u] + oc[v] * d[v];
		c = oc[u] * oc[u] + oc[v] * oc[v] - rad * rad;
		h = b * b - a * c;
		if (h > 0.0f) {
			h = (-b + sqrtf(h)) / a;
			if (h > 0.0f && h < best && fabsf(o[k] + d[k] * h) < size[k])
				best = h;
		}
	}
	b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
	c = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - rad * rad;
	h = b * b - c;
	if (h > 0.0f)
		best = -b + sqrtf(h);
	return best > 1e19f ? -1.0f : best;
}

/* Relative error, or absolute over 1 cm for exits nearer than that: the
 * float positions of a 6 m room are good to some 1e-7 m, so that a ray
 * starting 1e-4 from a wall cannot be told to 1e-3 relative. */
#endif
