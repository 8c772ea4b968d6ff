/* Geometry shared by the projection modes (header-only: each plugin is
 * one self-contained shared object). */
#ifndef REFLECT_PLUGINS_REFLECTION_H
#define REFLECT_PLUGINS_REFLECTION_H

#include <math.h>
#include <stdio.h>

#include "reflect/plugin.h"

/* Components smaller than this have no exit on their axis (no 0 * inf). */
#define AXIS_EPSILON 1e-8f

/* R = 2 (N.V) N - V, normalised. */
static inline void
reflection_vector(const float n[3], const float v[3], float r[3])
{
	float d = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
	float len;

	r[0] = 2.0f * d * n[0] - v[0];
	r[1] = 2.0f * d * n[1] - v[1];
	r[2] = 2.0f * d * n[2] - v[2];
	len = sqrtf(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
	if (len > 0.0f) {
		float inv = 1.0f / len;

		r[0] *= inv;
		r[1] *= inv;
		r[2] *= inv;
	}
}

/* Points this far outside the box (relative to its size) still count as
 * on its faces: walls of the room lie on the box, and their positions
 * come rounded from a renderer. */
#define BOX_TOLERANCE 1e-4f

/* Distance from p along unit dir to where it leaves the box; -1 when p
 * is outside the box (no exit to speak of). */
static inline int
box_exit(const struct rf_probe *probe, const float p[3], const float dir[3],
         float *dist)
{
	float t = INFINITY;
	int i;

	for (i = 0; i < 3; i++) {
		float lo = probe->box_min[i], hi = probe->box_max[i];
		float slack = BOX_TOLERANCE * (hi - lo), ti;

		if (p[i] < lo - slack || p[i] > hi + slack)
			return -1;
		if (dir[i] > AXIS_EPSILON)
			ti = (hi - p[i]) / dir[i];
		else if (dir[i] < -AXIS_EPSILON)
			ti = (lo - p[i]) / dir[i];
		else
			continue;
		if (ti < t)
			t = ti;
	}
	if (t < 0.0f)
		t = 0.0f; /* on a face (within the slack), leaving it */
	if (!(t < INFINITY))
		return -1; /* zero direction */
	*dist = t;
	return 0;
}

/* From the hit at p + dir * dist: the unit lookup direction from the
 * capture point and the distance from the capture point to the hit. */
static inline void
lookup_from_hit(const struct rf_probe *probe, const float p[3],
                const float dir[3], float dist, float lookup[3], float *probe_dist)
{
	float d[3], len;
	int i;

	for (i = 0; i < 3; i++)
		d[i] = p[i] + dir[i] * dist - probe->center[i];
	len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
	*probe_dist = len;
	if (len > 0.0f) {
		float inv = 1.0f / len;

		for (i = 0; i < 3; i++)
			lookup[i] = d[i] * inv;
	} else {
		for (i = 0; i < 3; i++)
			lookup[i] = dir[i];
	}
}

/* The state of a mode that only needs the probe: a copy of it. */
static inline int
reflection_create(const struct rf_host *host, void **state, char *err,
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
