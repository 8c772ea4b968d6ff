/* Exact ray casting: spheres, boxes, rectangles and the room seen from
 * inside, nearest hit first; the meshes and the search among objects
 * through the scene's acceleration structure (accel.c). */
#include <math.h>
#include <stdint.h>

#include "scene/accel.h"

/* Hits closer than this are the origin's own surface. */
#define T_MIN 1e-9
/* Direction components below this never cross a slab's planes. */
#define D_MIN 1e-12
/* How far a ray that hits nothing puts P: finite, so that no later
 * difference of infinities makes a NaN, and outside any box. */
#define MISS_DISTANCE 1e30

#define candidate rf__candidate

static void
prepare(const struct object *ob, const double o[3], double *k)
{
	int i;

	switch (ob->kind) {
	case OBJ_SPHERE:
		for (i = 0; i < 3; i++)
			k[i] = o[i] - ob->center[i];
		k[3] = rf__dot(k, k) - ob->radius2;
		break;
	case OBJ_BOX:
		for (i = 0; i < 3; i++) {
			k[i] = ob->min[i] - o[i];
			k[i + 3] = ob->max[i] - o[i];
		}
		break;
	case OBJ_RECT:
		k[0] = (ob->center[0] - o[0]) * ob->n[0] + (ob->center[1] - o[1]) * ob->n[1] +
		       (ob->center[2] - o[2]) * ob->n[2];
		break;
	}
}

/* The room's slabs from o, in the room's own frame when it is turned. */
static void
prepare_room(const rf_scene *s, const double o[3], double *k)
{
	const struct rf_scene_probe *room = &s->probes[0];
	double local[3];
	const double *ol = o;
	int i;

	if (s->room_turned) {
		rf__room_point_in(s, o, local);
		ol = local;
	}
	for (i = 0; i < 3; i++) {
		k[i] = room->box_min[i] - ol[i];
		k[i + 3] = room->box_max[i] - ol[i];
	}
}

/* A ray's direction and its reciprocals as the room's slabs take them. */
static void
room_direction(const rf_scene *s, const double d[3], const double inv[3], double dl[3],
               double invl[3], const double **dr, const double **invr)
{
	int i;

	if (!s->room_turned) {
		*dr = d;
		*invr = inv;
		return;
	}
	rf__room_dir_in(s, d, dl);
	for (i = 0; i < 3; i++)
		invl[i] = 1.0 / dl[i];
	*dr = dl;
	*invr = invl;
}

void
rf__trace_prepare(const rf_scene *s, const double o[3], double *k)
{
	size_t i;

	for (i = 0; i < s->nobjects; i++)
		prepare(&s->objects[i], o, k + i * RF__ORIGIN_STRIDE);
	if (s->nprobes)
		prepare_room(s, o, k + s->nobjects * RF__ORIGIN_STRIDE);
}

/* Robust quadratic (Haines et al., Ray Tracing Gems ch. 7): the
 * discriminant from the closest approach, the near root without
 * cancellation. */
static int
hit_sphere(const struct object *ob, const double *k, const double d[3], double tmax,
           double *t)
{
	double b = -(k[0] * d[0] + k[1] * d[1] + k[2] * d[2]);
	double l0 = k[0] + b * d[0], l1 = k[1] + b * d[1], l2 = k[2] + b * d[2];
	double disc = ob->radius2 - (l0 * l0 + l1 * l1 + l2 * l2);
	double q, t0, t1;

	if (disc < 0)
		return 0;
	q = b + copysign(sqrt(disc), b);
	if (q == 0)
		return 0; /* grazes the sphere exactly at the origin */
	t0 = k[3] / q;
	t1 = q;
	if (t0 > t1) {
		double tmp = t0;

		t0 = t1;
		t1 = tmp;
	}
	if (t0 > T_MIN && t0 < tmax) {
		*t = t0;
		return 1;
	}
	if (t1 > T_MIN && t1 < tmax) {
		*t = t1;
		return 1;
	}
	return 0;
}

/* Slab test.  want_exit: only the far crossing counts (the room seen from
 * inside, or from outside through its near walls). */
static int
hit_slabs(const double *k, const double d[3], const double inv[3], double tmax,
          int want_exit, struct candidate *c)
{
	double tn = -INFINITY, tf = INFINITY;
	int an = -1, af = -1, a;

	for (a = 0; a < 3; a++) {
		double t0, t1;

		if (fabs(d[a]) < D_MIN) {
			if (k[a] > 0 || k[a + 3] < 0)
				return 0; /* parallel to the slab and outside it */
			continue;
		}
		t0 = k[a] * inv[a];
		t1 = k[a + 3] * inv[a];
		if (t0 > t1) {
			double tmp = t0;

			t0 = t1;
			t1 = tmp;
		}
		if (t0 > tn) {
			tn = t0;
			an = a;
		}
		if (t1 < tf) {
			tf = t1;
			af = a;
		}
	}
	if (tn > tf || af < 0)
		return 0;
	if (!want_exit && tn > T_MIN) {
		if (tn >= tmax)
			return 0;
		c->t = tn;
		c->axis = an;
		c->upper = d[an] < 0;
		return 1;
	}
	if (tf > T_MIN && tf < tmax) {
		c->t = tf;
		c->axis = af;
		c->upper = d[af] > 0;
		return 1;
	}
	return 0;
}

static int
hit_rect(const struct object *ob, const double *k, const double o[3],
         const double d[3], double tmax, double *t)
{
	double denom = rf__dot(d, ob->n), tt, rel[3];
	int i;

	if (fabs(denom) < D_MIN)
		return 0;
	tt = k[0] / denom;
	if (!(tt > T_MIN && tt < tmax))
		return 0;
	for (i = 0; i < 3; i++)
		rel[i] = o[i] + tt * d[i] - ob->center[i];
	if (fabs(rf__dot(rel, ob->t)) > ob->half[0] || fabs(rf__dot(rel, ob->b)) > ob->half[1])
		return 0;
	*t = tt;
	return 1;
}

/* Tangent frame of an axis-aligned face whose normal is -sign * e_axis,
 * from a table: the rule of rf__plane_tangent without its arithmetic. */
static void
face_frame(int axis, double sign, double ng[3], double t[3], double b[3])
{
	double n[3] = { 0, 0, 0 };

	n[axis] = -sign;
	ng[0] = n[0];
	ng[1] = n[1];
	ng[2] = n[2];
	rf__plane_tangent(n, t);
	rf__cross(n, t, b);
}

static void
set_material(struct rf_hit *hit, const struct material *m)
{
	hit->roughness = m->roughness;
	hit->metallic = m->metallic;
	hit->albedo[0] = m->albedo[0];
	hit->albedo[1] = m->albedo[1];
	hit->albedo[2] = m->albedo[2];
	hit->mask = m->mask;
}

/* hit->T from the texture's tangent t: its part perpendicular to the
 * (perhaps bent) normal, unit; any perpendicular when t is along N. */
void
rf__hit_tangent(struct rf_hit *hit, const double t[3])
{
	double d = rf__dot(t, hit->N), len;
	int i;

	for (i = 0; i < 3; i++)
		hit->T[i] = t[i] - d * hit->N[i];
	len = sqrt(rf__dot(hit->T, hit->T));
	if (!(len > 1e-12)) {
		rf__plane_tangent(hit->N, hit->T);
		return;
	}
	for (i = 0; i < 3; i++)
		hit->T[i] /= len;
}

static void
shade_face(const struct material *m, const double d[3], int axis, double plane,
           struct rf_hit *hit)
{
	double t[3], b[3], uv[2];

	hit->P[axis] = plane; /* exactly on the face */
	set_material(hit, m);
	face_frame(axis, d[axis] > 0 ? 1.0 : -1.0, hit->Ng, t, b);
	if (m->nm.kind == NM_NONE) {
		hit->N[0] = hit->Ng[0];
		hit->N[1] = hit->Ng[1];
		hit->N[2] = hit->Ng[2];
		rf__hit_tangent(hit, t);
		return;
	}
	/* World-anchored coordinates: patterns line up across faces. */
	uv[0] = rf__dot(hit->P, t);
	uv[1] = rf__dot(hit->P, b);
	rf__normalmap_apply(&m->nm, uv, t, b, hit->Ng, hit->N);
	rf__hit_tangent(hit, t);
}

static void
shade_sphere(const struct object *ob, const double d[3], struct rf_hit *hit)
{
	const struct material *m = &ob->mat;
	double *ng = hit->Ng, t[3], b[3], uv[2], sin_theta;
	int flip, i;

	for (i = 0; i < 3; i++)
		ng[i] = (hit->P[i] - ob->center[i]) * ob->inv_radius;
	flip = rf__dot(ng, d) > 0;
	set_material(hit, m);
	/* Longitude phi about +Y, colatitude theta from the bottom pole:
	 * u runs along the equator, v up the meridians, in metres. */
	sin_theta = sqrt(ng[0] * ng[0] + ng[2] * ng[2]);
	if (sin_theta > 1e-9) {
		t[0] = ng[2] / sin_theta;
		t[1] = 0.0;
		t[2] = -ng[0] / sin_theta;
	} else {
		t[0] = 1.0;
		t[1] = t[2] = 0.0;
	}
	if (m->nm.kind != NM_NONE) {
		uv[0] = ob->radius * (atan2(-ng[2], ng[0]) + 3.14159265358979323846);
		uv[1] = ob->radius * acos(ng[1] < -1 ? 1.0 : ng[1] > 1 ? -1.0 : -ng[1]);
		if (flip)
			for (i = 0; i < 3; i++)
				ng[i] = -ng[i];
		rf__cross(ng, t, b);
		rf__normalmap_apply(&m->nm, uv, t, b, ng, hit->N);
		rf__hit_tangent(hit, t);
		return;
	}
	if (flip)
		for (i = 0; i < 3; i++)
			ng[i] = -ng[i];
	for (i = 0; i < 3; i++)
		hit->N[i] = ng[i];
	rf__hit_tangent(hit, t);
}

static void
shade_rect(const struct object *ob, const double d[3], struct rf_hit *hit)
{
	const struct material *m = &ob->mat;
	double rel[3], b[3], uv[2], s;
	int flip = rf__dot(ob->n, d) > 0, i;

	if (ob->axis >= 0) {
		hit->P[ob->axis] = ob->center[ob->axis];
	} else {
		for (i = 0; i < 3; i++)
			rel[i] = hit->P[i] - ob->center[i];
		s = rf__dot(rel, ob->n);
		for (i = 0; i < 3; i++)
			hit->P[i] -= s * ob->n[i];
	}
	for (i = 0; i < 3; i++)
		hit->Ng[i] = flip ? -ob->n[i] : ob->n[i];
	set_material(hit, m);
	if (m->nm.kind == NM_NONE) {
		for (i = 0; i < 3; i++)
			hit->N[i] = hit->Ng[i];
		rf__hit_tangent(hit, ob->t);
		return;
	}
	/* Coordinates from the corner, so that an image starts there. */
	for (i = 0; i < 3; i++)
		rel[i] = hit->P[i] - ob->center[i];
	uv[0] = rf__dot(rel, ob->t) + ob->half[0];
	uv[1] = rf__dot(rel, ob->b) + ob->half[1];
	for (i = 0; i < 3; i++)
		b[i] = flip ? -ob->b[i] : ob->b[i];
	rf__normalmap_apply(&m->nm, uv, ob->t, b, hit->Ng, hit->N);
	rf__hit_tangent(hit, ob->t);
}

int
rf__object_hit(const struct object *ob, const double *k, const double o[3],
               const double d[3], const double inv[3], struct candidate *c)
{
	double tmp[RF__ORIGIN_STRIDE];

	if (!k) {
		prepare(ob, o, tmp);
		k = tmp;
	}
	c->axis = -1;
	c->upper = 0;
	switch (ob->kind) {
	case OBJ_SPHERE:
		return hit_sphere(ob, k, d, INFINITY, &c->t);
	case OBJ_BOX:
		return hit_slabs(k, d, inv, INFINITY, 0, c);
	case OBJ_RECT:
		return hit_rect(ob, k, o, d, INFINITY, &c->t);
	}
	return 0;
}

/* The objects one after the other: in a scene without meshes, whose few
 * objects a loop decides faster than the BVH's user geometry, and where
 * the scene's structure cannot be built (its error was told to whoever
 * built it first). */
static void
trace_objects(const rf_scene *s, const double o[3], const double *k, const double d[3],
              const double inv[3], unsigned flags, struct candidate *best)
{
	size_t i;

	for (i = 0; i < s->nobjects; i++) {
		struct candidate c;

		if ((flags & RF__TRACE_SKIP_REFLECTIVE) && s->objects[i].mat.mask > 0.0f)
			continue;
		if (rf__object_hit(&s->objects[i], k ? k + i * RF__ORIGIN_STRIDE : NULL, o, d,
		                   inv, &c) && c.t < best->t) {
			*best = c;
			best->index = (int)i;
		}
	}
}

int
rf__occluded(const rf_scene *s, const double o[3], const double d[3], double tmax)
{
	double inv[3], k[RF__ORIGIN_STRIDE];
	struct candidate best = { INFINITY, -1, -1, 0 }, c;
	const struct rf__accel *acc;
	int j;

	for (j = 0; j < 3; j++)
		inv[j] = 1.0 / d[j];
	if (s->nmeshes && (acc = rf__accel_get(s, NULL, 0))) {
		if (rf__accel_occluded(acc, s, o, d, inv, tmax))
			return 1;
	} else if (s->nobjects || s->nmeshes) {
		trace_objects(s, o, NULL, d, inv, 0, &best);
		if (best.t < tmax)
			return 1;
	}
	if (s->nprobes && s->room) {
		double dl[3], invl[3];
		const double *dr, *invr;

		prepare_room(s, o, k);
		room_direction(s, d, inv, dl, invl, &dr, &invr);
		return hit_slabs(k, dr, invr, tmax, 1, &c);
	}
	return 0;
}

/* The point t along a ray from o, in the turned room's frame: where
 * its wall is shaded, so that the wall's (u, v) and tangents are the
 * room's own. */
static void
room_point(const rf_scene *s, const double o[3], const double dl[3], double t,
           double p[3])
{
	int i;

	rf__room_point_in(s, o, p);
	for (i = 0; i < 3; i++)
		p[i] += t * dl[i];
}

/* A wall's hit shaded in the turned room's frame, taken out to the world. */
static void
turn_out(const rf_scene *s, struct rf_hit *hit)
{
	rf__room_point_out(s, hit->P, hit->P);
	rf__room_dir_out(s, hit->Ng, hit->Ng);
	rf__room_dir_out(s, hit->N, hit->N);
	rf__room_dir_out(s, hit->T, hit->T);
}

/* A ray's hit once the objects and the triangles are searched: the room
 * if it is nearer, then the shading of what was met. */
static int
finish(const rf_scene *s, const double o[3], const double *k, const double d[3],
       const double inv[3], struct candidate best, struct rf__mesh_hit mh,
       struct rf_hit *hit)
{
	double tmp[RF__ORIGIN_STRIDE], dl[3], invl[3];
	const double *dr = d, *invr = inv;
	struct candidate c;
	const struct rf_scene_probe *room = s->nprobes && s->room ? &s->probes[0] : NULL;
	int j;

	if (mh.mesh >= 0)
		best.t = mh.t;
	if (room) {
		const double *ko = k ? k + s->nobjects * RF__ORIGIN_STRIDE : tmp;

		if (!k)
			prepare_room(s, o, tmp);
		room_direction(s, d, inv, dl, invl, &dr, &invr);
		if (hit_slabs(ko, dr, invr, best.t, 1, &c)) {
			best = c;
			best.index = -1;
			mh.mesh = -1;
		}
	}
	hit->prim = 0;
	hit->bary[0] = hit->bary[1] = 0.0;
	if (mh.mesh >= 0) {
		rf__mesh_shade(s, &mh, o, d, hit);
		return hit->objid;
	}
	if (best.t == INFINITY) {
		hit->t = INFINITY;
		for (j = 0; j < 3; j++) {
			hit->P[j] = o[j] + MISS_DISTANCE * d[j];
			hit->N[j] = hit->Ng[j] = -d[j];
			hit->albedo[j] = 0.0f;
		}
		rf__plane_tangent(hit->N, hit->T);
		hit->roughness = 1.0f;
		hit->metallic = 0.0f;
		hit->mask = 0.0f;
		hit->objid = RF_OBJID_NONE;
		return hit->objid;
	}
	hit->t = best.t;
	for (j = 0; j < 3; j++)
		hit->P[j] = o[j] + best.t * d[j];
	if (best.index < 0) {
		int a = best.axis;

		if (s->room_turned)
			room_point(s, o, dr, best.t, hit->P);
		shade_face(&s->room_mat, dr, a, best.upper ? room->box_max[a] : room->box_min[a],
		           hit);
		if (s->room_turned)
			turn_out(s, hit);
		hit->objid = -(2 * a + (best.upper ? 1 : 2));
		return hit->objid;
	}
	hit->objid = best.index + 1;
	{
		const struct object *ob = &s->objects[best.index];

		switch (ob->kind) {
		case OBJ_SPHERE:
			shade_sphere(ob, d, hit);
			break;
		case OBJ_BOX:
			shade_face(&ob->mat, d, best.axis,
			           best.upper ? ob->max[best.axis] : ob->min[best.axis], hit);
			break;
		case OBJ_RECT:
			shade_rect(ob, d, hit);
			break;
		}
	}
	return hit->objid;
}

int
rf__trace(const rf_scene *s, const double o[3], const double *k, const double d[3],
          const double *inv_d, unsigned flags, struct rf_hit *hit)
{
	double own_inv[3];
	const double *inv = inv_d ? inv_d : own_inv;
	struct candidate best = { INFINITY, -1, -1, 0 };
	struct rf__mesh_hit mh = { -1, 0, 0.0, 0.0, 0.0 };
	const struct rf__accel *acc;
	int j;

	if (!inv_d)
		for (j = 0; j < 3; j++)
			own_inv[j] = 1.0 / d[j];
	if ((s->nobjects || s->nmeshes) && !(flags & RF__TRACE_ROOM_ONLY)) {
		if (s->nmeshes && (acc = rf__accel_get(s, NULL, 0)))
			rf__accel_intersect(acc, s, o, k, d, inv, flags, &best, &mh);
		else
			trace_objects(s, o, k, d, inv, flags, &best);
	}
	return finish(s, o, k, d, inv, best, mh, hit);
}

void
rf__trace8(const rf_scene *s, const double o[3], const double *k, int n,
           const double *const d[], const double *const inv_d[], const unsigned flags[],
           struct rf_hit hit[])
{
	struct rf__lane l[8];
	struct candidate best[8];
	struct rf__mesh_hit mh[8];
	double own_inv[8][3];
	int valid[8], j, c;
	const struct rf__accel *acc;

	if (!s->nmeshes || !(acc = rf__accel_get(s, NULL, 0))) {
		/* the objects' own loop, as before: no packets to gain */
		for (j = 0; j < n; j++)
			rf__trace(s, o, k, d[j], inv_d ? inv_d[j] : NULL, flags[j], &hit[j]);
		return;
	}
	for (j = 0; j < n; j++) {
		if (!inv_d)
			for (c = 0; c < 3; c++)
				own_inv[j][c] = 1.0 / d[j][c];
		l[j].o = o;
		l[j].k = k;
		l[j].d = d[j];
		l[j].inv = inv_d ? inv_d[j] : own_inv[j];
		l[j].flags = flags[j];
		valid[j] = !(flags[j] & RF__TRACE_ROOM_ONLY);
		best[j].t = INFINITY;
		best[j].index = -1;
		best[j].axis = -1;
		best[j].upper = 0;
		mh[j].mesh = -1;
		mh[j].prim = 0;
		mh[j].t = mh[j].b1 = mh[j].b2 = 0.0;
	}
	rf__accel_intersect8(acc, s, n, l, valid, best, mh);
	for (j = 0; j < n; j++)
		finish(s, o, k, d[j], l[j].inv, best[j], mh[j], &hit[j]);
}
