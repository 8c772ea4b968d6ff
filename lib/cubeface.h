/* Internal: the face and face position of a direction, inline for the
 * samplers' inner loops (OpenEXR's face orientations). */
#ifndef REFLECT_CUBEFACE_H
#define REFLECT_CUBEFACE_H

#include <math.h>

/* Returns the face index (+X -X +Y -Y +Z -Z = 0..5); u across, v down. */
static inline int
rf__cube_face(const float d[3], float *u, float *v)
{
	float ax = fabsf(d[0]), ay = fabsf(d[1]), az = fabsf(d[2]), inv;

	if (ax >= ay && ax >= az) {
		if (ax == 0.0f) {
			*u = *v = 0.5f;
			return 0;
		}
		inv = 0.5f / ax;
		*v = 0.5f - d[1] * inv;
		if (d[0] > 0.0f) {
			*u = 0.5f + d[2] * inv;
			return 0;
		}
		*u = 0.5f - d[2] * inv;
		return 1;
	}
	if (ay >= az) {
		inv = 0.5f / ay;
		*u = 0.5f + d[0] * inv;
		if (d[1] > 0.0f) {
			*v = 0.5f - d[2] * inv;
			return 2;
		}
		*v = 0.5f + d[2] * inv;
		return 3;
	}
	inv = 0.5f / az;
	*v = 0.5f - d[1] * inv;
	if (d[2] > 0.0f) {
		*u = 0.5f - d[0] * inv;
		return 4;
	}
	*u = 0.5f + d[0] * inv;
	return 5;
}

#endif
