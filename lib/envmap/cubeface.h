/* Internal: the face and face position of a direction, inline for the
 * samplers' inner loops (OpenEXR's face orientations). */
#ifndef REFLECT_CUBEFACE_H
#define REFLECT_CUBEFACE_H

#include <math.h>

/* A face coordinate kept in [0, 1], NaN to 0: whatever the direction,
 * a sampler's texel index stays inside the face and its border. */
static inline float
rf__face_clamp(float u)
{
	u = u > 0.0f ? u : 0.0f;
	return u < 1.0f ? u : 1.0f;
}

/*
 * Returns the face index (+X -X +Y -Y +Z -Z = 0..5); u across, v down,
 * both in [0, 1] for any float direction.  A major axis below FLT_MIN
 * (a denormal direction) is scaled up by 2^24 first, so that 0.5 / major
 * cannot overflow; the zero vector (and NaN) reads the -X face's centre
 * (NaN components clamp to its edge), and the vector kernels do the same.
 */
static inline int
rf__cube_face(const float d[3], float *u, float *v)
{
	float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]);
	/* Selects instead of branches: a lobe's samples cross faces at
	 * random, and mispredicted branches cost more than the arithmetic. */
	int on_x = ax >= ay && ax >= az, on_y = !on_x && ay >= az;
	int pos = on_x ? d[0] > 0.0f : on_y ? d[1] > 0.0f : d[2] > 0.0f;
	float major = on_x ? ax : on_y ? ay : az;
	float across = on_x ? (pos ? d[2] : -d[2]) : on_y ? d[0] : (pos ? -d[0] : d[0]);
	float down = on_y ? (pos ? -d[2] : d[2]) : -d[1];
	float scale = major < 0x1p-126f ? 0x1p24f : 1.0f;
	float inv = major > 0.0f ? 0.5f / (major * scale) : 0.0f;

	*u = rf__face_clamp(0.5f + across * scale * inv);
	*v = rf__face_clamp(0.5f + down * scale * inv);
	return 2 * (on_x ? 0 : on_y ? 1 : 2) + !pos;
}

#endif
