/* Internal to the mesh loader (mesh.c, mesh_material.c): what one load
 * through assimp shares between its geometry and its materials. */
#ifndef REFLECT_SCENE_MESH_LOAD_H
#define REFLECT_SCENE_MESH_LOAD_H

#include <assimp/scene.h>

#include "scene/scene-internal.h"

struct rf__loader {
	rf_scene *s;
	const struct rf__mesh_request *rq;
	const struct aiScene *sc;
	int gltf;  /* else OBJ */
	char *dir; /* the mesh file's directory with its '/', or "" */
	struct rf__gltf_info gltf_info;
	char *err;
	size_t errlen;
	/* pixels decoded from sRGB for this file, once per image */
	struct rf__decoded {
		const float *from, *to;
	} *loaded;
	size_t nloaded;
};

/* Fills m->materials from the file's, with the statement's overrides;
 * an error's message (naming the mesh file) in ld->err. */
int rf__mesh_materials(struct rf__loader *ld, struct rf__mesh *m);

/* mesh_normals.c: the normals, then the tangents (from the normals and
 * uv set 0), of the vertices v with gen[v], the others left alone. */
int rf__mesh_normals(struct rf__mesh *m, const unsigned char *gen);
int rf__mesh_tangents(struct rf__mesh *m, const unsigned char *gen);

#endif
