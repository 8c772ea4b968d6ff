/*
 * Internal to scene: triangle meshes, their materials and the lights
 * that come with them (reflect-scene(5)'s `mesh FILE` statement).
 *
 * The loader (mesh.c, through assimp) fills these; the ray caster
 * (accel.c, through Embree) reads them.  Everything is in world space,
 * with the statement's transform and the file's node transforms already
 * applied, so that a hit needs no matrix.  Single precision, as the
 * files and Embree have it; the analytic objects stay in double.
 */
#ifndef REFLECT_SCENE_MESH_H
#define REFLECT_SCENE_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "reflect/reflect.h"

/* A texture, linear values (sRGB ones decoded when loaded), read with
 * wrapping (glTF's REPEAT, MIRRORED_REPEAT, CLAMP_TO_EDGE per axis) and
 * bilinear filtering.  uv' = transform * (u, v, 1): KHR_texture_transform
 * folded into one 2 x 3 matrix, the identity without one. */
enum rf__wrap { RF__WRAP_REPEAT = 0, RF__WRAP_MIRROR, RF__WRAP_CLAMP };

struct rf__texture {
	const float *pixels; /* the scene owns them, shared between uses */
	size_t width, height, nchannels;
	enum rf__wrap wrap[2];
	float transform[6]; /* row-major: u' = t0 u + t1 v + t2; v' = t3 u + t4 v + t5 */
	int texcoord;       /* which uv set (0 or 1) */
};

/* The texture at a point whose texture coordinates are uv[0] and uv[1]
 * (glTF's convention, as struct rf__mesh holds them: u right, v down from
 * the image's first row): the texture's own set, through its transform
 * and wrap modes, bilinear between texel centres.  R G B A: grey images
 * give R = G = B, a missing alpha is 1 (meshhit.c). */
RF_EXTERN void rf__texture_sample(const struct rf__texture *t, const double uv[2][2],
                                  float out[4]);

/* glTF 2.0's metallic-roughness material; OBJ/MTL is mapped onto it as
 * reflect-scene(5) documents.  A texture pointer is NULL where there is
 * none.  Factors multiply the texture's values, as glTF says. */
struct rf__mesh_material {
	char *name;
	float base_colour[4];
	const struct rf__texture *base_colour_tex;
	float metallic, roughness;
	const struct rf__texture *metallic_roughness_tex; /* B metallic, G roughness */
	const struct rf__texture *normal_tex;
	float normal_scale;
	float emission[3]; /* emissiveFactor times KHR_materials_emissive_strength */
	const struct rf__texture *emission_tex;
	/* The G-buffer's mask: 1 where the surface shows the probe's
	 * reflection (reflect-scene(5) says how a file's material decides). */
	float mask;
};

/* One mesh statement: its triangles, with what each vertex carries.
 * normals and tangents are always present (generated where the file has
 * none: normals by angle-weighted averaging, flat for glTF as its
 * specification asks, tangents MikkTSpace-compatible); uv[1] may be
 * NULL, uv[0] is zeros where the file has none.  uv in glTF's convention
 * (v down from the image's first row, for OBJ too); the bitangent
 * cross(normal, tangent) * w points up the image (toward -v), as a normal
 * map's green does.  Triangles wind counter-clockwise around the normal
 * seen from its side, mirroring transforms included. */
struct rf__mesh {
	size_t line;      /* of the statement, for messages */
	char *path;
	size_t nvertices, ntriangles;
	float *positions; /* 3 per vertex */
	float *normals;   /* 3 per vertex, unit */
	float *tangents;  /* 4 per vertex: unit xyz, then the bitangent's sign */
	float *uv[2];     /* 2 per vertex */
	uint32_t *indices;   /* 3 per triangle */
	uint32_t *material;  /* per triangle, into materials */
	struct rf__mesh_material *materials;
	size_t nmaterials;
	int objid; /* the G-buffer's objid of every triangle */
	float bounds[6]; /* min xyz, max xyz */
};

/* KHR_lights_punctual, in the scene's units: intensity in candela
 * (point, spot) or lux (directional), converted to radiometric values as
 * reflect-scene(5) documents; position and direction in world space
 * (direction: where the light points). */
enum rf__light_kind { RF__LIGHT_POINT, RF__LIGHT_SPOT, RF__LIGHT_DIRECTIONAL };

struct rf__light {
	enum rf__light_kind kind;
	size_t line;
	double position[3], direction[3];
	float colour[3]; /* linear, times intensity */
	double range;    /* 0: unlimited */
	double inner_cone, outer_cone; /* spot, radians */
};

#endif
