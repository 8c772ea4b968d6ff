/* Internal to the scene part of libreflect: the model behind rf_scene. */
#ifndef REFLECT_SCENE_INTERNAL_H
#define REFLECT_SCENE_INTERNAL_H

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>

#include "scene/mesh.h"
#include "scene/vector.h"
#include "util/util.h"
#include "reflect/plugin.h"
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

/* What a surface emits (reflect-scene(5) EMISSION). */
enum emit_kind { EMIT_NONE = 0, EMIT_COLOUR, EMIT_PATTERN, EMIT_IMAGE };

struct emission {
	enum emit_kind kind;
	float rgb[3]; /* the colour; the pattern's face colour C; the image's gain */
	/* EMIT_IMAGE: a wall's image, size[0] x size[1] metres from origin in
	 * the wall's (u, v), repeating; colour values linear */
	const float *pixels;
	size_t width, height, nchannels;
	double size[2], origin[2];
	int srgb;
};

/* The walls' procedural pattern: a checker of cells with grid lines. */
struct pattern {
	double cell, line_width, base, checker, line, line_white;
	double inv_cell; /* 1 / cell, for the tracer's millions of lookups */
};

/* A window: radiance inside min < (u, v) < max of a wall, over whatever
 * the wall emits, with an optional cross of mullions through its middle. */
struct window {
	int face;        /* RF__FACE_* */
	double min[2], max[2];
	float rgb[3];
	double mullion;  /* the cross's full width (0: none) */
	float mullion_rgb[3];
};

/* The room's faces by the box side they lie on, as in the objid channel
 * (-1 - face) and in the scene file (+x -x +y -y +z -z). */
enum { RF__FACE_XMAX, RF__FACE_XMIN, RF__FACE_YMAX, RF__FACE_YMIN, RF__FACE_ZMAX,
       RF__FACE_ZMIN, RF__FACES };

struct material {
	float roughness, metallic, albedo[3], mask;
	struct normalmap nm;
	struct emission em;
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
	/* Probe 0's box turned about its centre (room_turned): the walls'
	 * tests and their (u, v) work in the box's own frame, a point p
	 * there being room_center + room_rotation^T (p - room_center). */
	int room_turned;
	double room_rotation[9], room_center[3];
	/* Each wall's emission when set by a wall line, else the room's. */
	struct emission wall_em[RF__FACES];
	struct pattern pattern;
	/* What the walls' chunk reads (rf__wall_classes): per face, and a
	 * seventh for no exit (black), the pattern's line, even cell and odd
	 * cell colours, and whether the face shows the pattern. */
	float wall_class_rgb[RF__FACES + 1][3][3];
	int wall_pattern[RF__FACES + 1];
	struct window *windows;
	size_t nwindows;
	int has_emission; /* anything emits: the G-buffer writes emission.* */
	struct object *objects;
	size_t nobjects;
	/* mesh statements, in file order, and the lights their files hold */
	struct rf__mesh *meshes;
	size_t nmeshes;
	struct rf__light *lights;
	size_t nlights;
	/* the sky statement's environment (NULL: none), its strength, and
	 * its irradiance (rf__sh9_quadratic, strength included) */
	struct rf_cubemap *sky;
	float sky_strength;
	float sky_q[3][9];
	size_t sky_line;
	/* Normal map images, loaded once per path. */
	rf_image **images;
	char **image_paths;
	size_t nimages;
	/* The ray casting structure (accel.c), built by the first trace
	 * under the lock, then only read. */
	struct rf__accel *_Atomic accel;
	pthread_mutex_t accel_lock;
	/* What the meshes' materials point to (their textures, decoded
	 * pixels), freed with the scene. */
	void **blocks;
	size_t nblocks;
};

/* The room's frame (rf_scene's room_turned), in and out. */
static inline void
rf__room_dir_in(const rf_scene *s, const double d[3], double out[3])
{
	rf__mat3_tmul(s->room_rotation, d, out);
}

static inline void
rf__room_dir_out(const rf_scene *s, const double d[3], double out[3])
{
	rf__mat3_mul(s->room_rotation, d, out);
}

static inline void
rf__room_point_in(const rf_scene *s, const double p[3], double out[3])
{
	const double *c = s->room_center;
	double rel[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };

	rf__room_dir_in(s, rel, out);
	out[0] += c[0];
	out[1] += c[1];
	out[2] += c[2];
}

static inline void
rf__room_point_out(const rf_scene *s, const double p[3], double out[3])
{
	const double *c = s->room_center;
	double rel[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };

	rf__room_dir_out(s, rel, out);
	out[0] += c[0];
	out[1] += c[1];
	out[2] += c[2];
}

/* scene.c */
rf_scene *rf__scene_create(void);
/* Sets the room's frame from probe 0, once the scene is read. */
void rf__room_frame(rf_scene *s);
/* The scene's probe as the plugins see it, its shapes included. */
void rf__scene_probe_shape(const struct rf_scene_probe *sp, struct rf_probe *out);
/* A material with the defaults of an object (or of the room). */
void rf__material_default(struct material *m, int room);
/* An image loaded once for the whole scene, with at least min_channels
 * (what names its use in messages); err says why it cannot be. */
int rf__scene_image(rf_scene *s, const char *path, size_t min_channels, const char *what,
                    const rf_image **img, char *err, size_t errlen);
/* Completes an object's derived fields (squares, bounds, frames). */
void rf__object_prepare(struct object *o);
/* Adds a mesh to the scene, before any ray is traced, and takes what it
 * owns in every case (its path, arrays, materials and their names, not
 * the textures: the scene keeps those apart): the scene's on success,
 * freed at once on error, *m zeroed either way.  Refused, with err
 * beginning with the mesh's path (the caller says where the statement
 * is): no triangles, an index or a material number out of range, a
 * position, normal, tangent or texture coordinate that is not finite
 * (NaN, infinity), missing normals or tangents.  It fills bounds; objid is set when the first ray is traced
 * (nobjects + 1 + the mesh's index: after every object, whatever the
 * order of statements). */
RF_EXTERN int rf__scene_add_mesh(rf_scene *s, struct rf__mesh *m, char *err,
                                 size_t errlen);
/* An image read by the caller, kept for the scene's life under key (a
 * path, or a mesh file's "FILE#*N" for its embedded images); on error
 * the image is destroyed. */
int rf__scene_image_add(rf_scene *s, const char *key, rf_image *img);
/* The image kept under key, or NULL. */
const rf_image *rf__scene_image_find(const rf_scene *s, const char *key);
/* A malloc'ed block freed with the scene; freed at once on error. */
int rf__scene_keep(rf_scene *s, void *block);

/* mesh.c: the mesh statement's file (reflect-scene(5)). */
/* A statement's material overrides: for every material of the file, or
 * for the one named. */
enum {
	RF__OVR_ROUGHNESS = 1, RF__OVR_METALLIC = 2, RF__OVR_ALBEDO = 4,
	RF__OVR_EMISSION = 8, RF__OVR_MASK = 16
};

struct rf__mesh_override {
	char *material; /* NULL: every material */
	size_t col;     /* of its 'material' word, for messages */
	unsigned set;   /* RF__OVR_* */
	float roughness, metallic, albedo[3], emission[3], mask;
};

struct rf__mesh_request {
	const char *path; /* as the loader opens it (relative to the scene) */
	size_t line;
	double matrix[16]; /* the statement's transform, row-major, last row 0 0 0 1 */
	const struct rf__mesh_override *overrides;
	size_t noverrides;
};

/* Loads the file into one more s->meshes (and its lights into s->lights);
 * err names the mesh file and says what is wrong with it. */
int rf__mesh_load(rf_scene *s, const struct rf__mesh_request *rq, char *err,
                  size_t errlen);
void rf__mesh_free(struct rf__mesh *m);

/* gltf_check.c */
/* Accessors without a bufferView (all zeros) hold at most this many. */
#define RF__GLTF_COUNT_MAX (1 << 24)
/* What the walk finds that assimp 5.2 leaves out, per material in the
 * file's order: KHR_materials_emissive_strength (1 without), and the
 * texCoord of KHR_texture_transform on its base colour, metallic-
 * roughness, normal and emissive textures (-1 without). */
#define RF__GLTF_TEXTURES 4
struct rf__gltf_material {
	char *name; /* as the JSON writes it, escapes kept; NULL without */
	float emissive_strength;
	int texcoord[RF__GLTF_TEXTURES];
	int mirror; /* extras.reflect.mirror: 1 true, 0 false, -1 not there */
};
struct rf__gltf_info {
	struct rf__gltf_material *materials;
	size_t nmaterials;
};
/* Every size a glTF file (.gltf or .glb) claims held to the bytes behind
 * it, before assimp allocates them: 0, or an error naming the file.
 * info is filled (rf__gltf_info_free) either way. */
int rf__gltf_check(const char *path, struct rf__gltf_info *info, char *err,
                   size_t errlen);
void rf__gltf_info_free(struct rf__gltf_info *info);
/* The entry of the material assimp names name: assimp orders a file's
 * materials its own way (as meshes first use them), so they are matched
 * by name; NULL unless exactly one has it. */
const struct rf__gltf_material *rf__gltf_material_named(const struct rf__gltf_info *info,
                                                        const char *name);

/* light.c */
/* What the surface of a hit sends back along the ray: rf__emission, plus
 * on what does not reflect, Lambert's share of the lights' direct light
 * with shadows (rf__direct_light). */
RF_EXTERN void rf__radiance(const rf_scene *s, const struct rf_hit *hit, float rgb[3]);
/* (1 - mask) (1 - metallic) albedo / pi times the sum of the lights'
 * irradiance at the hit, each 0 where a shadow ray is blocked. */
void rf__direct_light(const rf_scene *s, const struct rf_hit *hit, float rgb[3]);

/* sky.c */
/* What a ray leaving the scene along unit d sees of the sky (0 without). */
void rf__sky_radiance(const rf_scene *s, const double d[3], float rgb[3]);
/* Lambert's share of the sky's irradiance at a hit, times 1 - mask. */
void rf__sky_diffuse(const rf_scene *s, const struct rf_hit *hit, float rgb[3]);

/* emission.c */
/* The pattern's defaults: those of the path-traced references. */
void rf__pattern_default(struct pattern *pt);
/* What the surface of a hit (as rf__trace returns it) emits toward the
 * ray; 0 for nothing (objid 0). */
void rf__emission(const rf_scene *s, const struct rf_hit *hit, float rgb[3]);
/* A wall's emission at in-plane (u, v) (rf__wall_uv). */
void rf__wall_emission(const rf_scene *s, int face, const double uv[2], float rgb[3]);
/* The in-plane coordinates of a point on a wall: (z, y) on the x walls,
 * (x, z) on the floor and ceiling, (x, y) on the z walls. */
void rf__wall_uv(int face, const double p[3], double uv[2]);
/* The wall a ray from o (inside the room) along d leaves the room by,
 * and where in its (u, v); -1 without a room or an exit. */
int rf__room_exit(const rf_scene *s, const double o[3], const double d[3], double uv[2]);
/* Fills the scene's wall_class_rgb and wall_pattern from its walls'
 * emission and pattern, by pattern_at's own arithmetic: once the scene
 * is read. */
void rf__wall_classes(rf_scene *s);
/* Rays a call of rf__room_emission_chunk takes at most. */
#define RF__EMIT_CHUNK 64
/* rf__room_exit then rf__wall_emission (black without an exit) for the
 * rays d[j] from o, j < n; a ray without use[j] gets a finite colour
 * that stands for nothing.  The arrays hold RF__EMIT_CHUNK entries,
 * every one readable. */
void rf__room_emission_chunk(const rf_scene *s, const double o[3], const float *dx,
                             const float *dy, const float *dz, const int *use, size_t n,
                             float rgb[][3]);
/* rf__wall_emission for the n points (us[j], vs[j]) of one wall, as
 * rf__room_emission_chunk reads them. */
void rf__wall_emission_chunk(const rf_scene *s, int wall, const float *us, const float *vs,
                             size_t n, float rgb[][3]);
/* The face of a wall's objid (RF_WALL_*), or -1. */
int rf__wall_face(int objid);
/* The wall's emission: its own or the room's. */
const struct emission *rf__wall_emission_of(const rf_scene *s, int face);

/* raycast.c */
/* Fills k[(nobjects + 1) * RF__ORIGIN_STRIDE] for rays from o (the room
 * last). */
RF_EXTERN void rf__trace_prepare(const rf_scene *s, const double o[3], double *k);
/* rf__trace's flags: objects and mesh triangles whose mask is above 0
 * (what reflects the probe) are passed through. */
#define RF__TRACE_SKIP_REFLECTIVE 1u
/* The caller knows that the ray meets no object and no mesh: the room
 * alone is tried, without a search. */
#define RF__TRACE_ROOM_ONLY 2u
/* Nearest hit of the unit ray; k from rf__trace_prepare for the same o,
 * or NULL to work it out on the way; inv_d the reciprocals of d, or NULL.
 * The room is always tried. */
RF_EXTERN int rf__trace(const rf_scene *s, const double o[3], const double *k,
                        const double d[3], const double *inv_d, unsigned flags,
                        struct rf_hit *hit);
/* rf__trace for n <= 8 rays from o at once (inv_d[j] the reciprocals of
 * d[j], or inv_d NULL), each into hit[j] as rf__trace would fill it, to
 * the bit: a scene with meshes searches them as one packet. */
RF_EXTERN void rf__trace8(const rf_scene *s, const double o[3], const double *k, int n,
                          const double *const d[], const double *const inv_d[],
                          const unsigned flags[], struct rf_hit hit[]);
/* Whether the room, an object or a triangle lies on the unit ray from o
 * along d nearer than tmax (INFINITY: anywhere): a shadow ray. */
int rf__occluded(const rf_scene *s, const double o[3], const double d[3], double tmax);
/* hit->T from the surface's tangent t: its part perpendicular to N. */
void rf__hit_tangent(struct rf_hit *hit, const double t[3]);

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
