/* The geometry of the projection modes: the reflection vector, and the
 * exit of a ray from the probe box (box projection).  Header-only: each
 * plugin is one self-contained shared object. */
#ifndef REFLECT_PROBE_PROJECTION_H
#define REFLECT_PROBE_PROJECTION_H

#include <math.h>
#include <stdio.h>

#include "reflect/plugin.h"

/* Components smaller than this have no exit on their axis (no 0 * inf). */
#define RF__AXIS_EPSILON 1e-8f

/* R = 2 (N.V) N - V, normalised. */
static inline void
rf__reflection_vector(const float n[3], const float v[3], float r[3])
{
	float nx = n[0], ny = n[1], nz = n[2], vx = v[0], vy = v[1], vz = v[2];
	float d2 = 2.0f * (nx * vx + ny * vy + nz * vz);
	float rx = d2 * nx - vx, ry = d2 * ny - vy, rz = d2 * nz - vz;
	float len = sqrtf(rx * rx + ry * ry + rz * rz);

	if (len > 0.0f) {
		float inv = 1.0f / len;

		rx *= inv;
		ry *= inv;
		rz *= inv;
	}
	r[0] = rx;
	r[1] = ry;
	r[2] = rz;
}

/* Points this far outside the box (relative to its size) still count as
 * on its faces: walls of the room lie on the box, and their positions
 * come rounded from a renderer. */
#define RF__BOX_TOLERANCE 1e-4f

typedef float rf__box_v4 __attribute__((vector_size(16)));
typedef int rf__box_v4i __attribute__((vector_size(16)));

/* A probe as the projection uses it, worked out once per span and held in
 * locals (stores to the output, floats too, would otherwise make the
 * compiler reload the probe for every pixel).  The three axes are lanes
 * of one vector; the fourth lane is an axis with no walls. */
struct rf__box {
	rf__box_v4 lo, hi;             /* the box */
	rf__box_v4 outer_lo, outer_hi; /* the box grown by the tolerance */
	float center[3];
};

static inline struct rf__box
rf__box_of_probe(const struct rf_probe *probe)
{
	struct rf__box b;
	int i;

	for (i = 0; i < 3; i++) {
		float slack = RF__BOX_TOLERANCE * (probe->box_max[i] - probe->box_min[i]);

		b.lo[i] = probe->box_min[i];
		b.hi[i] = probe->box_max[i];
		b.outer_lo[i] = b.lo[i] - slack;
		b.outer_hi[i] = b.hi[i] + slack;
		b.center[i] = probe->center[i];
	}
	b.lo[3] = b.hi[3] = b.outer_hi[3] = INFINITY;
	b.outer_lo[3] = -INFINITY;
	return b;
}

/* Lane by lane: a where mask is set (all ones), else b. */
static inline rf__box_v4
rf__box_select(rf__box_v4i mask, rf__box_v4 a, rf__box_v4 b)
{
	return (rf__box_v4)(((rf__box_v4i)a & mask) | ((rf__box_v4i)b & ~mask));
}

/* Distance from p along unit dir to where it leaves the box; -1 when p
 * is outside the box (no exit to speak of). */
static inline int
rf__box_exit(const struct rf__box *b, const float p[3], const float dir[3], float *dist)
{
	const rf__box_v4 inf = { INFINITY, INFINITY, INFINITY, INFINITY };
	rf__box_v4 pv = { p[0], p[1], p[2], 0.0f }, dv = { dir[0], dir[1], dir[2], 1.0f };
	rf__box_v4 ad = { fabsf(dir[0]), fabsf(dir[1]), fabsf(dir[2]), 1.0f };
	/* Per axis the wall ahead is the farther of the two planes along the
	 * ray, whatever its sign: the same quotient as choosing the wall by
	 * the sign, without a branch that mispredicts from pixel to pixel.
	 * An axis the ray hardly moves along has no exit (its x/0 is
	 * computed and thrown away). */
	rf__box_v4 to_hi = (b->hi - pv) / dv, to_lo = (b->lo - pv) / dv;
	rf__box_v4 t = rf__box_select(to_hi > to_lo, to_hi, to_lo);
	rf__box_v4i outside = (pv < b->outer_lo) | (pv > b->outer_hi);
	float tmin;

	t = rf__box_select(ad > RF__AXIS_EPSILON, t, inf);
	if (outside[0] | outside[1] | outside[2])
		return -1;
	tmin = t[0] < t[1] ? t[0] : t[1];
	tmin = t[2] < tmin ? t[2] : tmin;
	if (tmin < 0.0f)
		tmin = 0.0f; /* on a face (within the slack), leaving it */
	if (!(tmin < INFINITY))
		return -1; /* zero direction */
	*dist = tmin;
	return 0;
}

/* From the hit at p + dir * dist: the unit lookup direction from the
 * capture point and the distance from the capture point to the hit.
 * Written out by component: a loop over an array kept it in memory. */
static inline void
rf__lookup_from_hit(const struct rf__box *b, const float p[3], const float dir[3], float dist,
                float lookup[3], float *probe_dist)
{
	float dx = p[0] + dir[0] * dist - b->center[0];
	float dy = p[1] + dir[1] * dist - b->center[1];
	float dz = p[2] + dir[2] * dist - b->center[2];
	float len = sqrtf(dx * dx + dy * dy + dz * dz);

	*probe_dist = len;
	if (len > 0.0f) {
		float inv = 1.0f / len;

		lookup[0] = dx * inv;
		lookup[1] = dy * inv;
		lookup[2] = dz * inv;
	} else {
		lookup[0] = dir[0];
		lookup[1] = dir[1];
		lookup[2] = dir[2];
	}
}

/* A projection's eight outputs for one pixel: R, D, hit.dist and
 * probe.dist; with ok < 0 (no exit) D = R and both distances +inf.
 * Stored once each, from locals: the output could alias the input as far
 * as the compiler knows, and stores between reads would make it read
 * the inputs again. */
static inline void
rf__projection_out(float *out, int ok, const float r[3], const float d[3], float hit,
               float reach)
{
	out[0] = r[0];
	out[1] = r[1];
	out[2] = r[2];
	if (ok == 0) {
		out[3] = d[0];
		out[4] = d[1];
		out[5] = d[2];
		out[6] = hit;
		out[7] = reach;
	} else {
		out[3] = r[0];
		out[4] = r[1];
		out[5] = r[2];
		out[6] = out[7] = INFINITY;
	}
}

/* The state of a mode that only needs the probe: a copy of it. */
static inline int
rf__reflection_create(const struct rf_host *host, void **state, char *err,
                  size_t errlen)
{
	if (!host->probe) {
		snprintf(err, errlen, "no probe box: give --box and --center or a "
		         "stream with PROBE_BOX and PROBE_CENTER");
		return -1;
	}
	*state = (void *)host->probe;
	return 0;
}

#endif
