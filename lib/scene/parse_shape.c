/*
 * A probe's shapes in the scene format (reflect-scene(5)): its influence
 * turned (rotate AX AY AZ, or matrix and nine numbers) or a sphere
 * (sphere R, around the capture point), and a proxy of its own
 * (proxy box X0 Y0 Z0 X1 Y1 Z1, proxy sphere R, proxy infinite; a proxy
 * box turned by proxy_rotate or proxy_matrix).  The header keys they
 * become are lib/probe's.
 */
#include <math.h>
#include <string.h>

#include "probe/probe-internal.h"
#include "scene/parser.h"

/* Three angles or nine numbers into m; fails at the keyword for a matrix
 * that is no rotation. */
static int
rotation(struct parser *p, const struct rf__token *key, int matrix, double m[9], int *rotated)
{
	double v[9];
	int rc, i;

	if ((rc = rf__parse_numbers(p, matrix ? "matrix (nine numbers, row-major)"
	                                      : "rotate (three angles in degrees)",
	                            v, matrix ? 9 : 3)) < 0)
		return rc;
	if (matrix)
		memcpy(m, v, sizeof(v));
	else
		rf__rotation_from_euler(v, m);
	if ((rc = rf__rotation_check(m)) < 0)
		return FAIL_TOK(p, key, "expected a rotation, and this matrix %s",
		                rc == -2 ? "is a reflection (its determinant is negative)"
		                         : "is not orthonormal");
	*rotated = 0;
	for (i = 0; i < 9; i++)
		if ((float)m[i] != (i % 4 == 0 ? 1.0f : 0.0f))
			*rotated = 1;
	return 0;
}

static int
radius_of(struct parser *p, const char *what, double *r)
{
	int rc = rf__parse_number(p, what, r);

	if (rc < 0)
		return rc;
	if (!(*r > 0.0) || !(*r < 1e9))
		return FAIL_TOK(p, &p->lx.tok[p->pos - 1], "expected a radius greater than 0 "
		                "for '%s', found %g", what, *r);
	return 0;
}

int
rf__parse_probe_shape(struct parser *p, const struct rf__token *key, struct rf_scene_probe *pr,
                      double *radius)
{
	const struct rf__token *t;
	double box[6];
	int rc, i;

	if (rf__tok_is(key, "rotate") || rf__tok_is(key, "matrix"))
		return rotation(p, key, rf__tok_is(key, "matrix"), pr->rotation, &pr->rotated) < 0
		           ? RF_EFORMAT : 1;
	if (rf__tok_is(key, "proxy_rotate") || rf__tok_is(key, "proxy_matrix"))
		return rotation(p, key, rf__tok_is(key, "proxy_matrix"), pr->proxy_rotation,
		                &pr->proxy_rotated) < 0 ? RF_EFORMAT : 1;
	if (rf__tok_is(key, "sphere")) {
		pr->shape = RF_SHAPE_SPHERE;
		return radius_of(p, "sphere", radius) < 0 ? RF_EFORMAT : 1;
	}
	if (!rf__tok_is(key, "proxy"))
		return 0;
	if ((rc = rf__parse_word(p, "a proxy: box, sphere or infinite", &t)) < 0)
		return rc;
	if (rf__tok_is(t, "infinite")) {
		pr->proxy_shape = RF_SHAPE_INFINITE;
		return 1;
	}
	if (rf__tok_is(t, "sphere")) {
		pr->proxy_shape = RF_SHAPE_SPHERE;
		/* around the capture point, placed in rf__probe_shape_finish */
		if ((rc = radius_of(p, "proxy sphere", &box[0])) < 0)
			return rc;
		for (i = 0; i < 3; i++) {
			pr->proxy_min[i] = -box[0];
			pr->proxy_max[i] = box[0];
		}
		return 1;
	}
	if (!rf__tok_is(t, "box"))
		return FAIL_TOK(p, t, "expected a proxy: box, sphere or infinite, found " TOKFMT,
		                TOKARG(t));
	pr->proxy_shape = RF_SHAPE_BOX;
	if ((rc = rf__parse_numbers(p, "proxy box", box, 6)) < 0)
		return rc;
	for (i = 0; i < 3; i++) {
		pr->proxy_min[i] = box[i];
		pr->proxy_max[i] = box[i + 3];
		if (!(box[i] < box[i + 3]))
			return FAIL_TOK(p, t, "expected the proxy box's min below its max, and on "
			                "%c it is [%g, %g]", "XYZ"[i], box[i], box[i + 3]);
	}
	return 1;
}

/* The attribute named name of the statement, for a message's place. */
static const struct rf__token *
attribute_token(const struct parser *p, const char *name, const struct rf__token *kw)
{
	size_t i;

	for (i = 0; i < p->nattrs; i++)
		if (rf__tok_is(p->attrs[i], name))
			return p->attrs[i];
	return kw;
}

int
rf__probe_shape_finish(struct parser *p, const struct rf__token *kw, struct rf_scene_probe *pr,
                       double radius, size_t index)
{
	int i;

	if (pr->shape == RF_SHAPE_SPHERE) {
		if (pr->rotated)
			return FAIL_TOK(p, attribute_token(p, "rotate", kw), "a sphere has no "
			                "rotation: remove 'rotate' or 'matrix'");
		for (i = 0; i < 3; i++) {
			pr->box_min[i] = pr->center[i] - radius;
			pr->box_max[i] = pr->center[i] + radius;
		}
	} else
		pr->shape = RF_SHAPE_BOX;
	if (pr->proxy_shape == RF_SHAPE_SPHERE)
		for (i = 0; i < 3; i++) {
			pr->proxy_min[i] += pr->center[i];
			pr->proxy_max[i] += pr->center[i];
		}
	if (pr->proxy_rotated && pr->proxy_shape != RF_SHAPE_BOX)
		return FAIL_TOK(p, attribute_token(p, "proxy_rotate", kw), "only a proxy box "
		                "turns: give 'proxy box X0 Y0 Z0 X1 Y1 Z1' or remove the rotation");
	if (pr->rotated) {
		/* the capture point in the box's frame, about its centre */
		double c[3], d[3], q[3];

		for (i = 0; i < 3; i++) {
			c[i] = 0.5 * (pr->box_min[i] + pr->box_max[i]);
			d[i] = pr->center[i] - c[i];
		}
		rf__mat3_tmul(pr->rotation, d, q);
		for (i = 0; i < 3; i++) {
			q[i] += c[i];
			if (!(q[i] >= pr->box_min[i] - 1e-9 && q[i] <= pr->box_max[i] + 1e-9))
				return FAIL_TOK(p, attribute_token(p, "center", kw), "expected the "
				                "probe's centre inside its turned box, and (%g %g %g) "
				                "is outside it on the box's own %c axis",
				                pr->center[0], pr->center[1], pr->center[2], "XYZ"[i]);
		}
	}
	if (index == 0 && pr->shape == RF_SHAPE_SPHERE) {
		const struct rf__token *t = attribute_token(p, "sphere", kw);

		p->room_sphere_line = t->line;
		p->room_sphere_col = t->col;
	}
	return 0;
}
