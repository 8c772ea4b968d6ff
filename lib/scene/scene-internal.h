/* Internal to the scene part of libreflect: the model behind rf_scene. */
#ifndef REFLECT_SCENE_INTERNAL_H
#define REFLECT_SCENE_INTERNAL_H

#include <math.h>
#include <stdint.h>

#include "scene/vector.h"
#include "util/util.h"
#include "reflect/scene.h"

enum nm_kind { NM_NONE = 0, NM_TILES, NM_BUMPS, NM_NOISE, NM_IMAGE };

struct normalmap {
	enum nm_kind kind;
	double strength;  /* multiplies the tangent-space slope (Unity's _BumpScale) */
	double inv_scale; /* repeats per metre */
	double tiling[2], offset[2];
	/* NM_IMAGE: the scene's copy, channels 0 and 1 are read */
	const float *pixels;
	size_t width, height, nchannels;
};

struct material {
	float roughness, metallic, albedo[3], mask;
	struct normalmap nm;
};

enum obj_kind { OBJ_SPHERE, OBJ_BOX, OBJ_RECT };

/* Values an object keeps per ray origin, so that rays from one camera
 * repeat no work: sphere (O - C, |O - C|^2 - r^2); box (min - O,
 * max - O); rect dot(C - O, n). */
#define RF__ORIGIN_STRIDE 6

struct object {
	enum obj_kind kind;
	size_t line;
	struct material mat;
	double center[3];        /* sphere, rect */
	double radius, radius2, inv_radius;
	double min[3], max[3];   /* box; bounds of the others too */
	/* rect: unit tangent, bitangent = cross(normal, tangent), normal;
	 * half sizes along tangent and bitangent; axis of an axis-aligned
	 * one (hits are put exactly on its plane), else -1 */
	double t[3], b[3], n[3], half[2];
	int axis;
};

struct rf_scene {
	char *name;
	struct rf_camera camera;
	struct rf_scene_probe *probes;
	size_t nprobes;
	int room; /* draw probe 0's box */
	struct material room_mat;
	struct object *objects;
	size_t nobjects;
	/* Normal map images, loaded once per path. */
	rf_image **images;
	char **image_paths;
	size_t nimages;
};

/* scene.c */
rf_scene *rf__scene_create(void);
/* A material with the defaults of an object (or of the room). */
void rf__material_default(struct material *m, int room);
/* An image loaded once for the whole scene; err says why it cannot be. */
int rf__scene_image(rf_scene *s, const char *path, const rf_image **img, char *err,
                    size_t errlen);
/* Completes an object's derived fields (squares, bounds, frames). */
void rf__object_prepare(struct object *o);

/* raycast.c */
/* Fills k[(nobjects + 1) * RF__ORIGIN_STRIDE] for rays from o (the room
 * last). */
void rf__trace_prepare(const rf_scene *s, const double o[3], double *k);
/* Nearest hit of the unit ray; k from rf__trace_prepare for the same o,
 * or NULL to work it out on the way; inv_d the reciprocals of d, or NULL.
 * Only the objects of list (indices) are tried when it is not NULL; the
 * room always is. */
int rf__trace(const rf_scene *s, const double o[3], const double *k,
              const double d[3], const double *inv_d, const uint32_t *list,
              size_t nlist, struct rf_hit *hit);

/* normalmap.c */
/* The shading normal from the geometric frame (t, b, ng) and the surface
 * coordinates uv in metres; ng itself where the map is flat. */
void rf__normalmap_apply(const struct normalmap *nm, const double uv[2],
                         const double t[3], const double b[3], const double ng[3],
                         double out[3]);

/* A camera ready for rays: the ray through image point (x, y) in [-1, 1]
 * (y up) is normalize(f + (x tx) r + (y ty) u).  rf_camera_ray and the
 * G-buffer share it, so that they agree to the bit. */
struct camera_basis {
	double f[3], r[3], u[3];
	double tx, ty;
};

void rf__camera_basis(const struct rf_camera *c, size_t width, size_t height,
                      struct camera_basis *cb);

static inline void
rf__camera_dir(const struct camera_basis *cb, double x, double y, double d[3])
{
	double sx = x * cb->tx, sy = y * cb->ty;
	double dx = cb->f[0] + sx * cb->r[0] + sy * cb->u[0];
	double dy = cb->f[1] + sx * cb->r[1] + sy * cb->u[1];
	double dz = cb->f[2] + sx * cb->r[2] + sy * cb->u[2];
	/* In registers, stored once: this runs for every pixel, and reading
	 * back a vector just stored stalls.  One division, not three. */
	double inv_len = 1.0 / sqrt(dx * dx + dy * dy + dz * dz);

	d[0] = dx * inv_len;
	d[1] = dy * inv_len;
	d[2] = dz * inv_len;
}

#endif
