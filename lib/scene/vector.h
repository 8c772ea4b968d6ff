/* Internal to the scene area: small vector helpers in double precision. */
#ifndef REFLECT_SCENE_VECTOR_H
#define REFLECT_SCENE_VECTOR_H

#include <math.h>

static inline double
rf__dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void
rf__cross(const double a[3], const double b[3], double out[3])
{
	double x = a[1] * b[2] - a[2] * b[1];
	double y = a[2] * b[0] - a[0] * b[2];
	double z = a[0] * b[1] - a[1] * b[0];

	out[0] = x;
	out[1] = y;
	out[2] = z;
}

/* Normalises v in place; returns its former length (0 leaves v alone). */
static inline double
rf__normalize(double v[3])
{
	double len = sqrt(rf__dot(v, v));

	if (len > 0) {
		v[0] /= len;
		v[1] /= len;
		v[2] /= len;
	}
	return len;
}

/* A unit tangent for a plane of normal n: horizontal on walls so that the
 * bitangent (cross(n, t)) points up, +X on floors and ceilings. */
static inline void
rf__plane_tangent(const double n[3], double t[3])
{
	static const double y[3] = { 0, 1, 0 };

	if (fabs(n[1]) < 0.999) {
		rf__cross(y, n, t);
		rf__normalize(t);
	} else {
		/* +X made perpendicular to n */
		t[0] = 1.0 - n[0] * n[0];
		t[1] = -n[0] * n[1];
		t[2] = -n[0] * n[2];
		rf__normalize(t);
	}
}

#endif
