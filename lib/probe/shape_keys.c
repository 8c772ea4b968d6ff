/*
 * A probe's shapes in the header: PROBE_SHAPE and PROBE_ROTATION for its
 * influence, PROBE_PROXY, PROBE_PROXY_BOX and PROBE_PROXY_ROTATION for
 * the shape its lookups are projected onto (PROBE2_SHAPE ... for the
 * frame's other probes).  Each key is absent for today's probe, an
 * axis-aligned box that is its own proxy, so such a stream reads and
 * writes as it did before shapes existed.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "probe/probe-internal.h"
#include "stream/stream-internal.h"
#include "util/util.h"

/* How far from orthonormal a rotation may be: %.9g of a float matrix
 * reads back within 1e-7, a matrix typed to 4 digits within 1e-4. */
#define ROTATION_TOLERANCE 2e-4

void
rf__rotation_from_euler(const double deg[3], double m[9])
{
	/* Unity's Transform order: z first, then x, then y, about the world
	 * axes, m = Ry Rx Rz */
	const double k = 3.14159265358979323846 / 180.0;
	double cx = cos(deg[0] * k), sx = sin(deg[0] * k);
	double cy = cos(deg[1] * k), sy = sin(deg[1] * k);
	double cz = cos(deg[2] * k), sz = sin(deg[2] * k);

	m[0] = cy * cz + sy * sx * sz;
	m[1] = -cy * sz + sy * sx * cz;
	m[2] = sy * cx;
	m[3] = cx * sz;
	m[4] = cx * cz;
	m[5] = -sx;
	m[6] = -sy * cz + cy * sx * sz;
	m[7] = sy * sz + cy * sx * cz;
	m[8] = cy * cx;
}

int
rf__rotation_check(const double m[9])
{
	double det;
	int i, j, k;

	for (i = 0; i < 9; i++)
		if (!isfinite(m[i]))
			return -1;
	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++) {
			double dot = 0.0;

			for (k = 0; k < 3; k++)
				dot += m[3 * i + k] * m[3 * j + k];
			if (fabs(dot - (i == j)) > ROTATION_TOLERANCE)
				return -1;
		}
	det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
	      m[2] * (m[3] * m[7] - m[4] * m[6]);
	return det > 0.0 ? 0 : -2;
}

int
rf__rotation_parse(const char *v, float m[9], int *rotated)
{
	double d[9];
	int i, rc;

	if (rf__scan_doubles(v, d, 9) < 0) {
		double euler[3];

		if (rf__scan_doubles(v, euler, 3) < 0)
			return -3;
		rf__rotation_from_euler(euler, d);
	}
	if ((rc = rf__rotation_check(d)) < 0)
		return rc;
	*rotated = 0;
	for (i = 0; i < 9; i++) {
		m[i] = (float)d[i];
		if (m[i] != (i % 4 == 0 ? 1.0f : 0.0f))
			*rotated = 1;
	}
	return 0;
}

static const char *
rotation_problem(int rc)
{
	return rc == -3 ? "needs 9 numbers (a row-major matrix) or 3 angles in degrees"
	       : rc == -2 ? "is a reflection, not a rotation (its determinant is negative)"
	                 : "is not a rotation (its rows are not orthonormal)";
}

/* The shape named v: 0 when v names none of the allowed ones. */
static uint32_t
shape_named(const char *v, int infinite_too)
{
	if (!strcmp(v, "box"))
		return RF_SHAPE_BOX;
	if (!strcmp(v, "sphere"))
		return RF_SHAPE_SPHERE;
	if (infinite_too && !strcmp(v, "infinite"))
		return RF_SHAPE_INFINITE;
	return 0;
}

/* A sphere's box is its bounding cube. */
static int
cube(const float lo[3], const float hi[3])
{
	float e = hi[0] - lo[0];

	return fabsf((hi[1] - lo[1]) - e) <= 1e-5f * e && fabsf((hi[2] - lo[2]) - e) <= 1e-5f * e;
}

int
rf__probe_shape_read(const rf_header *h, size_t index, struct rf_probe *probe, char *err,
                     size_t errlen)
{
	char key[64];
	const char *v;
	float box[6];
	int i, rc;

	probe->shape = RF_SHAPE_BOX;
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_SHAPE);
	if ((v = rf_header_get(h, key)) && !(probe->shape = shape_named(v, 0))) {
		rf__format(err, errlen, "header key %s: '%.40s' is not a shape: box or sphere",
		           key, v);
		return RF_EINVAL;
	}
	if (probe->shape == RF_SHAPE_SPHERE && !cube(probe->box_min, probe->box_max)) {
		rf__format(err, errlen, "header key %s: a sphere's box (%s) is its bounding "
		           "cube, and this one's sides differ", key,
		           index ? "PROBEn_BOX" : RF_KEY_PROBE_BOX);
		return RF_EINVAL;
	}
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_ROTATION);
	if ((v = rf_header_get(h, key))) {
		int rotated;

		if (probe->shape == RF_SHAPE_SPHERE) {
			rf__format(err, errlen, "header key %s: a sphere has no rotation; "
			           "remove the key", key);
			return RF_EINVAL;
		}
		if ((rc = rf__rotation_parse(v, probe->rotation, &rotated)) < 0) {
			rf__format(err, errlen, "header key %s: '%.60s' %s", key, v,
			           rotation_problem(rc));
			return RF_EINVAL;
		}
		probe->rotated = (uint32_t)rotated;
	}
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_PROXY);
	v = rf_header_get(h, key);
	probe->proxy_shape = RF_SHAPE_SAME;
	if (v && !(probe->proxy_shape = shape_named(v, 1))) {
		rf__format(err, errlen, "header key %s: '%.40s' is not a proxy: box, sphere "
		           "or infinite", key, v);
		return RF_EINVAL;
	}
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_PROXY_BOX);
	if (probe->proxy_shape == RF_SHAPE_BOX || probe->proxy_shape == RF_SHAPE_SPHERE) {
		if (!(v = rf_header_get(h, key))) {
			rf__format(err, errlen, "the probe's proxy is a %s and %s is missing: "
			           "give its box, 6 numbers", probe->proxy_shape == RF_SHAPE_BOX
			                                          ? "box" : "sphere", key);
			return RF_EINVAL;
		}
		if (rf__scan_floats(v, box, 6) < 0) {
			rf__format(err, errlen, "header key %s: '%.60s' needs 6 numbers", key, v);
			return RF_EINVAL;
		}
		for (i = 0; i < 3; i++) {
			probe->proxy_min[i] = box[i];
			probe->proxy_max[i] = box[i + 3];
			if (!(box[i] < box[i + 3])) {
				rf__format(err, errlen, "header key %s: the box is empty on axis %c "
				           "(min %g, max %g)", key, "XYZ"[i], (double)box[i],
				           (double)box[i + 3]);
				return RF_EINVAL;
			}
		}
		if (probe->proxy_shape == RF_SHAPE_SPHERE &&
		    !cube(probe->proxy_min, probe->proxy_max)) {
			rf__format(err, errlen, "header key %s: a sphere's box is its bounding "
			           "cube, and this one's sides differ", key);
			return RF_EINVAL;
		}
	} else if (rf_header_get(h, key)) {
		rf__format(err, errlen, "header key %s is given but the probe has no proxy of "
		           "its own: give PROBE_PROXY box or sphere, or remove it", key);
		return RF_EINVAL;
	}
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_PROXY_ROTATION);
	if ((v = rf_header_get(h, key))) {
		int rotated;

		if (probe->proxy_shape != RF_SHAPE_BOX) {
			rf__format(err, errlen, "header key %s: only a proxy box turns; remove "
			           "the key", key);
			return RF_EINVAL;
		}
		if ((rc = rf__rotation_parse(v, probe->proxy_rotation, &rotated)) < 0) {
			rf__format(err, errlen, "header key %s: '%.60s' %s", key, v,
			           rotation_problem(rc));
			return RF_EINVAL;
		}
		probe->proxy_rotated = (uint32_t)rotated;
	}
	if (probe->bevel > 0.0f && (probe->proxy_shape == RF_SHAPE_INFINITE ||
	                            (probe->proxy_shape == RF_SHAPE_SAME
	                                 ? probe->shape : probe->proxy_shape) == RF_SHAPE_SPHERE)) {
		rf__format(err, errlen, "the probe has a bevel (%s) but its proxy is no box",
		           RF_KEY_PROBE_BEVEL);
		return RF_EINVAL;
	}
	return 0;
}

static int
set_rotation(rf_header *h, const char *key, int rotated, const float m[9])
{
	double d[9];
	int i;

	if (!rotated)
		return rf_header_unset(h, key);
	for (i = 0; i < 9; i++)
		d[i] = m[i] + 0.0; /* -0 is written as 0 */
	return rf__header_set_numbers(h, key, d, 9);
}

int
rf__probe_shape_write(rf_header *h, size_t index, const struct rf_probe *probe)
{
	static const char *const names[] = { "", "box", "sphere", "infinite" };
	char key[64];
	int rc;

	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_SHAPE);
	rc = probe->shape == RF_SHAPE_SPHERE ? rf_header_set(h, key, "sphere")
	                                     : rf_header_unset(h, key);
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_ROTATION);
	if (rc < 0 || (rc = set_rotation(h, key, probe->shape != RF_SHAPE_SPHERE &&
	                                             probe->rotated, probe->rotation)) < 0)
		return rc;
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_PROXY);
	rc = probe->proxy_shape > RF_SHAPE_SAME && probe->proxy_shape <= RF_SHAPE_INFINITE
	         ? rf_header_set(h, key, names[probe->proxy_shape])
	         : rf_header_unset(h, key);
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_PROXY_BOX);
	if (rc >= 0 && (probe->proxy_shape == RF_SHAPE_BOX ||
	                probe->proxy_shape == RF_SHAPE_SPHERE)) {
		double box[6];
		int i;

		for (i = 0; i < 3; i++) {
			box[i] = probe->proxy_min[i];
			box[i + 3] = probe->proxy_max[i];
		}
		rc = rf__header_set_numbers(h, key, box, 6);
	} else if (rc >= 0)
		rc = rf_header_unset(h, key);
	rf__header_probe_key(key, sizeof(key), index, RF_KEY_PROBE_PROXY_ROTATION);
	if (rc < 0)
		return rc;
	return set_rotation(h, key, probe->proxy_shape == RF_SHAPE_BOX && probe->proxy_rotated,
	                    probe->proxy_rotation);
}
