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

/* out = a b, row-major 4 x 4 matrices (out may be a or b). */
static inline void
rf__mat4_mul(const double a[16], const double b[16], double out[16])
{
	double r[16];
	int i, j, k;

	for (i = 0; i < 4; i++)
		for (j = 0; j < 4; j++) {
			r[4 * i + j] = 0;
			for (k = 0; k < 4; k++)
				r[4 * i + j] += a[4 * i + k] * b[4 * k + j];
		}
	for (i = 0; i < 16; i++)
		out[i] = r[i];
}

/* out = m d and out = m^T d for a row-major 3 x 3 rotation (out may be
 * d): a turned box's frame out to the world and into it. */
static inline void
rf__mat3_mul(const double m[9], const double d[3], double out[3])
{
	double x = m[0] * d[0] + m[1] * d[1] + m[2] * d[2];
	double y = m[3] * d[0] + m[4] * d[1] + m[5] * d[2];
	double z = m[6] * d[0] + m[7] * d[1] + m[8] * d[2];

	out[0] = x;
	out[1] = y;
	out[2] = z;
}

static inline void
rf__mat3_tmul(const double m[9], const double d[3], double out[3])
{
	double x = m[0] * d[0] + m[3] * d[1] + m[6] * d[2];
	double y = m[1] * d[0] + m[4] * d[1] + m[7] * d[2];
	double z = m[2] * d[0] + m[5] * d[1] + m[8] * d[2];

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
