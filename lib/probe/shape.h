/*
 * The shape a probe's lookups are projected onto, its proxy: an
 * axis-aligned box, an oriented box, a sphere, or nothing (infinite).
 * Header-only, like projection.h: the projection plugins and the host's
 * project_rays (lib/plugin/host.c) include it, so that reflect-project's
 * D and a traced ray agree to the bit.
 *
 * Only the exit distance depends on the shape: rotations keep lengths,
 * so the lookup from the capture point and the Jacobian are worked out
 * in world space from the exit, as for the axis-aligned box.  An
 * oriented box takes the ray into its own frame (about its centre) and
 * leaves by the axis-aligned test there; an axis-aligned box takes
 * rf__box_exit itself, so a probe without a rotation gives the bytes it
 * gave before shapes existed.
 */
#ifndef REFLECT_PROBE_SHAPE_H
#define REFLECT_PROBE_SHAPE_H

#include <math.h>

#include "probe/projection.h"

/* A rotation about a centre: world = c + m (local - c), m row-major. */
struct rf__frame {
	float c[3];
	float m[9];
};

static inline void
rf__frame_of(struct rf__frame *f, const float lo[3], const float hi[3], const float m[9])
{
	int i;

	for (i = 0; i < 3; i++)
		f->c[i] = 0.5f * lo[i] + 0.5f * hi[i];
	for (i = 0; i < 9; i++)
		f->m[i] = m[i];
}

/* m^T v: a world vector into the frame. */
static inline void
rf__frame_vector_in(const struct rf__frame *f, const float v[3], float out[3])
{
	const float *m = f->m;

	out[0] = m[0] * v[0] + m[3] * v[1] + m[6] * v[2];
	out[1] = m[1] * v[0] + m[4] * v[1] + m[7] * v[2];
	out[2] = m[2] * v[0] + m[5] * v[1] + m[8] * v[2];
}

/* m v: a frame's vector into the world. */
static inline void
rf__frame_vector_out(const struct rf__frame *f, const float v[3], float out[3])
{
	const float *m = f->m;

	out[0] = m[0] * v[0] + m[1] * v[1] + m[2] * v[2];
	out[1] = m[3] * v[0] + m[4] * v[1] + m[5] * v[2];
	out[2] = m[6] * v[0] + m[7] * v[1] + m[8] * v[2];
}

static inline void
rf__frame_point_in(const struct rf__frame *f, const float p[3], float out[3])
{
	float d[3] = { p[0] - f->c[0], p[1] - f->c[1], p[2] - f->c[2] };

	rf__frame_vector_in(f, d, out);
	out[0] += f->c[0];
	out[1] += f->c[1];
	out[2] += f->c[2];
}

struct rf__proxy {
	uint32_t kind;  /* RF_SHAPE_BOX, RF_SHAPE_SPHERE or RF_SHAPE_INFINITE */
	int rotated;
	struct rf__frame frame; /* the box's, when rotated */
	/* the box (in its own frame); its center is the capture point, in
	 * the world, for rf__lookup_from_hit */
	struct rf__box box;
	float sc[3];    /* the sphere's centre */
	float r2;       /* its radius squared */
	float outer2;   /* that grown by the tolerance */
};

/* The probe with its proxy's bounds for a box (its capture point kept),
 * what the code that knows axis-aligned boxes (the box exit, bevel.h)
 * works on inside the proxy's frame; *frame and *rotated that frame;
 * returns the proxy's kind. */
static inline uint32_t
rf__probe_proxy_aligned(const struct rf_probe *probe, struct rf_probe *aligned,
                        struct rf__frame *frame, int *rotated)
{
	uint32_t kind = probe->proxy_shape;
	const float *lo = probe->proxy_min, *hi = probe->proxy_max, *m = probe->proxy_rotation;
	int i;

	*rotated = probe->proxy_rotated != 0;
	if (kind == RF_SHAPE_SAME) {
		kind = probe->shape == RF_SHAPE_SPHERE ? RF_SHAPE_SPHERE : RF_SHAPE_BOX;
		lo = probe->box_min;
		hi = probe->box_max;
		m = probe->rotation;
		*rotated = probe->rotated != 0;
	}
	*aligned = *probe;
	for (i = 0; i < 3; i++) {
		aligned->box_min[i] = lo[i];
		aligned->box_max[i] = hi[i];
	}
	rf__frame_of(frame, lo, hi, m);
	if (kind != RF_SHAPE_BOX)
		*rotated = 0;
	return kind;
}

static inline struct rf__proxy
rf__proxy_of_probe(const struct rf_probe *probe)
{
	struct rf__proxy x;
	struct rf_probe aligned;
	float r, grown;
	int i;

	x.kind = rf__probe_proxy_aligned(probe, &aligned, &x.frame, &x.rotated);
	x.box = rf__box_of_probe(&aligned);
	for (i = 0; i < 3; i++)
		x.sc[i] = x.frame.c[i];
	r = 0.5f * (aligned.box_max[0] - aligned.box_min[0]);
	grown = r * (1.0f + RF__BOX_TOLERANCE);
	x.r2 = r * r;
	x.outer2 = grown * grown;
	return x;
}

/* Where a ray from p inside a sphere leaves it: the far root of
 * |p + t dir - sc|^2 = r^2, written so that it does not cancel. */
static inline int
rf__sphere_exit(const struct rf__proxy *x, const float p[3], const float dir[3], float *dist)
{
	float o[3] = { p[0] - x->sc[0], p[1] - x->sc[1], p[2] - x->sc[2] };
	float b = o[0] * dir[0] + o[1] * dir[1] + o[2] * dir[2];
	float oo = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
	float a = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
	float c = oo - x->r2, disc, q;

	if (!(oo <= x->outer2) || !(a > 0.0f))
		return -1;
	if (c > 0.0f)
		c = 0.0f; /* on the sphere, within the slack */
	disc = sqrtf(b * b - a * c);
	/* with c <= 0 the roots have opposite signs (or one is 0) and the
	 * exit is the one ahead; moving away from the centre (b > 0) it is
	 * c over the other root, which does not cancel as -b + disc would */
	q = -b - disc;
	*dist = b > 0.0f ? (q < 0.0f ? c / q : 0.0f) : (disc - b) / a;
	if (*dist < 0.0f)
		*dist = 0.0f;
	return 0;
}

/* Distance from p along unit dir to where it leaves the proxy; -1 when p
 * is outside it or the proxy is infinite. */
static inline int
rf__proxy_exit(const struct rf__proxy *x, const float p[3], const float dir[3], float *dist)
{
	float q[3], e[3];

	switch (x->kind) {
	case RF_SHAPE_BOX:
		if (!x->rotated)
			return rf__box_exit(&x->box, p, dir, dist);
		rf__frame_point_in(&x->frame, p, q);
		rf__frame_vector_in(&x->frame, dir, e);
		return rf__box_exit(&x->box, q, e, dist);
	case RF_SHAPE_SPHERE:
		return rf__sphere_exit(x, p, dir, dist);
	default:
		return -1;
	}
}

/* The proxy's outward unit normal at its exit point p + dir dist: the
 * wall's axis for a box (the nearest of the three walls to the point),
 * the radius for a sphere. */
static inline void
rf__proxy_normal(const struct rf__proxy *x, const float p[3], const float dir[3], float dist,
                 float n[3])
{
	float h[3] = { p[0] + dir[0] * dist, p[1] + dir[1] * dist, p[2] + dir[2] * dist };

	if (x->kind == RF_SHAPE_SPHERE) {
		float o[3] = { h[0] - x->sc[0], h[1] - x->sc[1], h[2] - x->sc[2] };
		float len = sqrtf(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
		int k;

		for (k = 0; k < 3; k++)
			n[k] = len > 0.0f ? o[k] / len : dir[k];
		return;
	} else {
		float q[3], local[3] = { 0.0f, 0.0f, 0.0f }, best = INFINITY;
		int k, axis = 0;

		if (x->rotated)
			rf__frame_point_in(&x->frame, h, q);
		else
			q[0] = h[0], q[1] = h[1], q[2] = h[2];
		for (k = 0; k < 3; k++) {
			float span = x->box.hi[k] - x->box.lo[k];
			float d = fminf(fabsf(q[k] - x->box.hi[k]), fabsf(q[k] - x->box.lo[k])) / span;

			if (d < best) {
				best = d;
				axis = k;
			}
		}
		local[axis] = 1.0f;
		if (x->rotated)
			rf__frame_vector_out(&x->frame, local, n);
		else
			n[0] = local[0], n[1] = local[1], n[2] = local[2];
	}
}

#endif
