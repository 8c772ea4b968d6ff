/*
 * Internal to scene: the scene's acceleration structure (accel.c), one
 * Embree 3 BVH over the meshes' triangles and the analytic objects as
 * user geometry, one ray or a packet of eight, and what rf__trace and
 * rf__trace8 share with it.
 */
#ifndef REFLECT_SCENE_ACCEL_H
#define REFLECT_SCENE_ACCEL_H

#include <stdint.h>

#include "scene/scene-internal.h"

/* The nearest analytic hit so far. */
struct rf__candidate {
	double t;
	int index; /* object index, or -1 for the room */
	int axis;  /* box or wall: the face's axis */
	int upper; /* box or wall: the face at max (1) or min (0) */
};

/* The nearest triangle: which, where along the ray, and the barycentric
 * coordinates of its second and third vertices. */
struct rf__mesh_hit {
	int mesh; /* index into s->meshes, -1 for none */
	uint32_t prim;
	double t, b1, b2;
};

/* The scene's structure, built on the first call (any thread; the others
 * wait for it).  NULL when it cannot be built, and then err says why. */
const struct rf__accel *rf__accel_get(const rf_scene *s, char *err, size_t errlen);
void rf__accel_destroy(struct rf__accel *a);

/* The nearest object (into *best, whose t the caller sets to INFINITY)
 * and the nearest triangle (into *mh) of the unit ray from o along d, k
 * and inv as rf__trace has them.  Objects are decided in double by
 * raycast.c's arithmetic, ties to the lower index, so that a scene
 * without meshes gives the hits of a plain loop over its objects. */
void rf__accel_intersect(const struct rf__accel *a, const rf_scene *s, const double o[3],
                         const double *k, const double d[3], const double inv[3],
                         unsigned flags, struct rf__candidate *best,
                         struct rf__mesh_hit *mh);

/* One ray of a packet: its origin, k (or NULL), unit direction, its
 * reciprocals and rf__trace's flags, as rf__accel_intersect takes them. */
struct rf__lane {
	const double *o, *k, *d, *inv;
	unsigned flags;
};

/* rf__accel_intersect for lanes 0 .. n-1 (n <= 8) at once, through
 * Embree's packets of eight: those whose valid is 0 are not searched
 * (best and mh as they were, mh[j].mesh -1).  Each lane's hits are those
 * rf__accel_intersect gives it, to the bit. */
void rf__accel_intersect8(const struct rf__accel *a, const rf_scene *s, int n,
                          const struct rf__lane *l, const int *valid,
                          struct rf__candidate *best, struct rf__mesh_hit *mh);

/* Whether an object or a triangle lies on the unit ray from o along d
 * nearer than tmax (INFINITY: anywhere): Embree's occlusion query, which
 * stops at the first thing found. */
int rf__accel_occluded(const struct rf__accel *a, const rf_scene *s, const double o[3],
                       const double d[3], const double inv[3], double tmax);

/* raycast.c: object ob's nearest crossing past the origin's own surface
 * (k from rf__trace_prepare for o, or NULL), whatever its distance. */
int rf__object_hit(const struct object *ob, const double *k, const double o[3],
                   const double d[3], const double inv[3], struct rf__candidate *c);

/* meshhit.c: the hit of a mesh triangle, as rf__trace fills it. */
void rf__mesh_shade(const rf_scene *s, const struct rf__mesh_hit *mh, const double o[3],
                    const double d[3], struct rf_hit *hit);
/* The hit triangle's texture coordinates, both sets (the second is the
 * first where the mesh has none). */
RF_EXTERN void rf__mesh_uv(const struct rf__mesh *m, uint32_t prim, double b1, double b2,
                           double uv[2][2]);
/* The material of a mesh's triangle. */
const struct rf__mesh_material *rf__mesh_material_of(const struct rf__mesh *m,
                                                     uint32_t prim);

#endif
