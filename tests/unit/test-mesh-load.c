/* Unit tests of the mesh statement's loader (lib/scene/mesh.c): files
 * written here, loaded through rf_scene_parse, and the model the ray
 * caster reads (struct rf__mesh, scene-internal.h) checked against values
 * worked out by hand. */
#include <stdint.h>
#include <unistd.h>

#include "reflect/envmap.h"
#include "reflect/image.h"
#include "reflect/scene.h"
#include "scene/scene-internal.h"
#include "tap.h"
#include "gltf-write.h"

/* A texture at uv, the point's two sets alike. */
static void
sample_at(const struct rf__texture *t, const float uv[2], float out[4])
{
	const double st[2][2] = { { uv[0], uv[1] }, { uv[0], uv[1] } };

	rf__texture_sample(t, st, out);
}

/* The error a scene gets. */
static int
load_error(const char *text, char *err, size_t errlen)
{
	char name[512];
	rf_scene *s = NULL;
	int rc;

	snprintf(name, sizeof(name), "%s/test.scene", dir);
	err[0] = '\0';
	rc = rf_scene_parse(&s, text, strlen(text), name, err, errlen);
	rf_scene_destroy(s);
	return rc;
}

/* A 2 x 2 quad in z = 0 facing +z: positions, then 2 floats of uv per
 * vertex, then 6 uint16 indices; with normals (+z) and tangents after
 * when asked.  uv in glTF's convention. */
struct quad {
	unsigned char bytes[256];
	size_t n, npos, nuv, nidx, nnorm, ntan;
};

static const float quad_pos[4][3] = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 } };
/* image up is +y: the top row at y = +1 */
static const float quad_uv[4][2] = { { 0, 1 }, { 1, 1 }, { 1, 0 }, { 0, 0 } };

static void
quad_make(struct quad *q, const float uv[4][2], const float *tangent)
{
	static const uint16_t idx[6] = { 0, 1, 2, 0, 2, 3 };
	float n[4][3] = { { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 }, { 0, 0, 1 } };
	int i;

	q->n = 0;
	memcpy(q->bytes, quad_pos, sizeof(quad_pos));
	q->npos = 0;
	q->nuv = sizeof(quad_pos);
	memcpy(q->bytes + q->nuv, uv, 4 * 2 * sizeof(float));
	q->nidx = q->nuv + 4 * 2 * sizeof(float);
	memcpy(q->bytes + q->nidx, idx, sizeof(idx));
	q->nnorm = q->nidx + sizeof(idx);
	memcpy(q->bytes + q->nnorm, n, sizeof(n));
	q->ntan = q->nnorm + sizeof(n);
	for (i = 0; i < 4; i++)
		memcpy(q->bytes + q->ntan + 16 * i, tangent ? tangent : n[0], 16);
	q->n = q->ntan + 64;
}

/* A .gltf of the quad: node_extra is the node's transform, attrs the
 * primitive's attributes beyond POSITION (NORMAL 3, TANGENT 4,
 * TEXCOORD_0 1), material and extra the rest. */
static void
gltf_quad(const char *name, const float uv[4][2], const float *tangent, const char *node,
          const char *attrs, const char *materials, const char *extra)
{
	struct quad q;
	char *data, *text;
	size_t len;

	quad_make(&q, uv, tangent);
	data = b64(q.bytes, q.n);
	len = strlen(data) + 4096 + strlen(materials) + strlen(extra);
	text = malloc(len);
	snprintf(text, len,
	         "{\"asset\":{\"version\":\"2.0\"},"
	         "\"extensionsUsed\":[\"KHR_texture_transform\",\"KHR_lights_punctual\","
	         "\"KHR_materials_emissive_strength\"],"
	         "\"buffers\":[{\"byteLength\":%zu,\"uri\":"
	         "\"data:application/octet-stream;base64,%s\"}],"
	         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":48},"
	         "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":32},"
	         "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":12},"
	         "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":48},"
	         "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":64}],"
	         "\"accessors\":["
	         "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
	         "\"min\":[-1,-1,0],\"max\":[1,1,0]},"
	         "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
	         "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"},"
	         "{\"bufferView\":3,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
	         "{\"bufferView\":4,\"componentType\":5126,\"count\":4,\"type\":\"VEC4\"}],"
	         "\"materials\":[%s],"
	         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0%s},"
	         "\"indices\":2,\"material\":0}]}],"
	         "\"nodes\":[{\"mesh\":0%s}],"
	         "\"scenes\":[{\"nodes\":[0]}],\"scene\":0%s}",
	         q.n, data, q.npos, q.nuv, q.nidx, q.nnorm, q.ntan, materials, attrs, node,
	         extra);
	put_text(name, text);
	free(text);
	free(data);
}

#define PLAIN_MATERIAL "{\"name\":\"plain\"}"
#define UV_NORMAL ",\"TEXCOORD_0\":1,\"NORMAL\":3"

/* A 2 x 2 RGB PNG: red, green on the top row, blue, grey 188 below. */
static void
png_2x2(const char *name)
{
	static const float px[12] = { 1, 0, 0, 0, 1, 0, 0, 0, 1,
		                      188 / 255.0f, 188 / 255.0f, 188 / 255.0f };
	rf_image_writer *w;
	char path[512], err[256];

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	if (rf_image_writer_open(&w, path, 2, 2, 3, NULL, RF_PIXEL_UINT8, err, sizeof(err)) <
	            0 ||
	    rf_image_writer_write_rows(w, 0, 2, px) < 0 ||
	    rf_image_writer_close(w, err, sizeof(err)) < 0)
		printf("# png: %s\n", err);
}

static double
srgb(double c)
{
	return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* The vertex of m at p, or -1. */
static long
vertex_at(const struct rf__mesh *m, double x, double y, double z)
{
	for (size_t v = 0; v < m->nvertices; v++)
		if (fabs(m->positions[3 * v] - x) < 1e-5 && fabs(m->positions[3 * v + 1] - y) < 1e-5 &&
		    fabs(m->positions[3 * v + 2] - z) < 1e-5)
			return (long)v;
	return -1;
}

/* Triangle t's geometric normal, unnormalised. */
static void
tri_normal(const struct rf__mesh *m, size_t t, double n[3])
{
	const float *p0 = &m->positions[3 * m->indices[3 * t]];
	const float *p1 = &m->positions[3 * m->indices[3 * t + 1]];
	const float *p2 = &m->positions[3 * m->indices[3 * t + 2]];
	double e1[3] = { p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2] };
	double e2[3] = { p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2] };

	rf__cross(e1, e2, n);
}

#define ASSERT_VEC(v, x, y, z, tol)                                        \
	do {                                                               \
		ASSERT_NEAR((v)[0], x, tol);                               \
		ASSERT_NEAR((v)[1], y, tol);                               \
		ASSERT_NEAR((v)[2], z, tol);                               \
	} while (0)

TEST(node_and_statement_transforms)
{
	/* node: scale 2 then translate (1, 2, 3); statement: rotate 90
	 * about +Y ((x, y, z) -> (z, y, -x)) then translate (10, 0, 0).
	 * (-1, -1, 0) -> (-1, 0, 3) -> (3, 0, 1) -> (13, 0, 1). */
	static const double want[4][3] = {
		{ 13, 0, 1 }, { 13, 0, -3 }, { 13, 4, -3 }, { 13, 4, 1 }
	};
	rf_scene *s;
	const struct rf__mesh *m;
	long v;
	int i;

	gltf_quad("quad.gltf", quad_uv, NULL, ",\"translation\":[1,2,3],\"scale\":[2,2,2]",
	          UV_NORMAL, PLAIN_MATERIAL, "");
	s = load("probe box -10 -10 -10 10 10 10\n"
	         "sphere center 0 0 0 radius 1\n"
	         "mesh quad.gltf translate 10 0 0 rotate 90 0 1 0\n");
	ASSERT(s);
	ASSERT_EQ(s->nmeshes, 1);
	m = &s->meshes[0];
	ASSERT_EQ(m->nvertices, 4);
	ASSERT_EQ(m->ntriangles, 2);
	ASSERT_EQ(m->line, 3);
	/* after the one analytic object */
	ASSERT_EQ(m->objid, 2);
	ASSERT_STR_EQ(rf_scene_object_kind(s, 2), "mesh");
	ASSERT_EQ(rf_scene_object_line(s, 2), 3);
	ASSERT(!rf_scene_object_kind(s, 3));
	for (i = 0; i < 4; i++) {
		v = vertex_at(m, want[i][0], want[i][1], want[i][2]);
		ASSERT(v >= 0);
		/* +Z turned to +X; the tangent (+X, where u grows) to -Z */
		ASSERT_VEC(&m->normals[3 * v], 1, 0, 0, 1e-6);
		ASSERT_VEC(&m->tangents[4 * v], 0, 0, -1, 1e-6);
		ASSERT(m->tangents[4 * v + 3] == 1.0f);
	}
	for (i = 0; i < 2; i++) {
		double n[3];

		tri_normal(m, (size_t)i, n);
		ASSERT(n[0] > 0);
	}
	ASSERT_VEC(m->bounds, 13, 0, -3, 1e-6);
	ASSERT_VEC(m->bounds + 3, 13, 4, 1, 1e-6);
	ASSERT_STR_EQ(m->materials[m->material[0]].name, "plain");
	rf_scene_destroy(s);
}

TEST(matrix_attribute_and_mirror)
{
	/* matrix: mirror X and lift by 5; the file's tangent (0 1 0, w -1)
	 * keeps its direction and changes side; the winding turns back. */
	static const float tan[4] = { 0, 1, 0, -1 };
	rf_scene *s;
	const struct rf__mesh *m;
	long v;

	gltf_quad("tan.gltf", quad_uv, tan, "", UV_NORMAL ",\"TANGENT\":4", PLAIN_MATERIAL,
	          "");
	s = load("probe box -10 -10 -10 10 10 10\n"
	         "mesh tan.gltf matrix -1 0 0 0  0 1 0 5  0 0 1 0  0 0 0 1\n");
	ASSERT(s);
	m = &s->meshes[0];
	v = vertex_at(m, 1, 4, 0); /* (-1, -1, 0) */
	ASSERT(v >= 0);
	ASSERT_VEC(&m->normals[3 * v], 0, 0, 1, 1e-6);
	ASSERT_VEC(&m->tangents[4 * v], 0, 1, 0, 1e-6);
	ASSERT(m->tangents[4 * v + 3] == 1.0f);
	for (size_t t = 0; t < m->ntriangles; t++) {
		double n[3];

		tri_normal(m, t, n);
		ASSERT(n[2] > 0);
	}
	rf_scene_destroy(s);
	/* without the mirror, the file's values as they are */
	s = load("probe box -10 -10 -10 10 10 10\nmesh tan.gltf\n");
	ASSERT(s);
	m = &s->meshes[0];
	v = vertex_at(m, -1, -1, 0);
	ASSERT(v >= 0);
	ASSERT_VEC(&m->tangents[4 * v], 0, 1, 0, 1e-6);
	ASSERT(m->tangents[4 * v + 3] == -1.0f);
	rf_scene_destroy(s);
}

TEST(gltf_without_normals_is_flat)
{
	/* glTF asks for flat normals: each triangle its own vertices */
	rf_scene *s;
	const struct rf__mesh *m;

	gltf_quad("flat.gltf", quad_uv, NULL, ",\"rotation\":[0.7071067811865476,0,0,"
	          "0.7071067811865476]", ",\"TEXCOORD_0\":1", PLAIN_MATERIAL, "");
	s = load("probe box -10 -10 -10 10 10 10\nmesh flat.gltf\n");
	ASSERT(s);
	m = &s->meshes[0];
	ASSERT_EQ(m->nvertices, 6);
	/* +Z turned 90 degrees about +X: -Y */
	for (size_t v = 0; v < 6; v++)
		ASSERT_VEC(&m->normals[3 * v], 0, -1, 0, 1e-6);
	rf_scene_destroy(s);
}

TEST(obj_normals_weighted_by_angle)
{
	/* Triangles A (0,0,0) (1,0,0) (0,1,0), normal +Z, and B (1,0,0)
	 * (0,0,0) (1,0,-1), normal -Y.  At (0,0,0) A's angle is 90 degrees
	 * and B's 45: n = normalize(pi/2 (0,0,1) + pi/4 (0,-1,0)) =
	 * (0, -1, 2) / sqrt 5; at (1,0,0) the other way: (0, -2, 1) / sqrt 5;
	 * (0,1,0) and (1,0,-1) keep their triangle's. */
	rf_scene *s;
	const struct rf__mesh *m;
	long v;

	put_text("roof.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 -1\nf 1 2 3\nf 2 1 4\n");
	s = load("probe box -10 -10 -10 10 10 10\nmesh roof.obj\n");
	ASSERT(s);
	m = &s->meshes[0];
	ASSERT_EQ(m->ntriangles, 2);
	ASSERT_EQ(m->nvertices, 4);
	ASSERT((v = vertex_at(m, 0, 0, 0)) >= 0);
	ASSERT_VEC(&m->normals[3 * v], 0, -1 / sqrt(5), 2 / sqrt(5), 1e-6);
	ASSERT((v = vertex_at(m, 1, 0, 0)) >= 0);
	ASSERT_VEC(&m->normals[3 * v], 0, -2 / sqrt(5), 1 / sqrt(5), 1e-6);
	ASSERT((v = vertex_at(m, 0, 1, 0)) >= 0);
	ASSERT_VEC(&m->normals[3 * v], 0, 0, 1, 1e-6);
	ASSERT((v = vertex_at(m, 1, 0, -1)) >= 0);
	ASSERT_VEC(&m->normals[3 * v], 0, -1, 0, 1e-6);
	rf_scene_destroy(s);
}

TEST(tangents_from_uv_layouts)
{
	/* u along +Y, v (glTF's, down the image) along +X: the image's up
	 * is -X, T = +Y, cross(N, T) = cross(+Z, +Y) = -X: w = +1. */
	static const float turned[4][2] = { { 0, 0 }, { 0, 1 }, { 1, 1 }, { 1, 0 } };
	/* u along -X, v down along -Y (the image mirrored): T = -X,
	 * cross(+Z, -X) = -Y but the image's up is +Y: w = -1. */
	static const float mirrored[4][2] = { { 1, 1 }, { 0, 1 }, { 0, 0 }, { 1, 0 } };
	rf_scene *s;
	const struct rf__mesh *m;
	size_t v;

	gltf_quad("turned.gltf", turned, NULL, "", UV_NORMAL, PLAIN_MATERIAL, "");
	gltf_quad("mirrored.gltf", mirrored, NULL, "", UV_NORMAL, PLAIN_MATERIAL, "");
	s = load("probe box -10 -10 -10 10 10 10\nmesh turned.gltf\nmesh mirrored.gltf\n");
	ASSERT(s);
	ASSERT_EQ(s->nmeshes, 2);
	m = &s->meshes[0];
	for (v = 0; v < m->nvertices; v++) {
		ASSERT_VEC(&m->tangents[4 * v], 0, 1, 0, 1e-6);
		ASSERT(m->tangents[4 * v + 3] == 1.0f);
	}
	m = &s->meshes[1];
	ASSERT_EQ(m->objid, 2);
	for (v = 0; v < m->nvertices; v++) {
		ASSERT_VEC(&m->tangents[4 * v], -1, 0, 0, 1e-6);
		ASSERT(m->tangents[4 * v + 3] == -1.0f);
	}
	rf_scene_destroy(s);
}

TEST(base_colour_texture_and_transform)
{
	rf_scene *s;
	const struct rf__mesh_material *mm;
	const struct rf__texture *t;
	float out[4], uv[2];
	double c = cos(0.3), sn = sin(0.3);

	png_2x2("tex.png");
	gltf_quad("tex.gltf", quad_uv, NULL, "", UV_NORMAL,
	          "{\"name\":\"painted\",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
	          "[0.5,1,1,1],\"baseColorTexture\":{\"index\":0},"
	          "\"metallicFactor\":0.25,\"roughnessFactor\":0.75},"
	          "\"emissiveFactor\":[1,0.5,0.25],\"emissiveTexture\":{\"index\":0,"
	          "\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.25,0.5],"
	          "\"scale\":[2,3],\"rotation\":0.3}}},"
	          "\"extensions\":{\"KHR_materials_emissive_strength\":"
	          "{\"emissiveStrength\":4}}}",
	          ",\"images\":[{\"uri\":\"tex.png\"}],\"samplers\":[{\"wrapS\":33071,"
	          "\"wrapT\":33648}],\"textures\":[{\"source\":0,\"sampler\":0}]");
	s = load("probe box -10 -10 -10 10 10 10\nmesh tex.gltf\n");
	ASSERT(s);
	ASSERT(s->has_emission);
	mm = &s->meshes[0].materials[s->meshes[0].material[0]];
	ASSERT_STR_EQ(mm->name, "painted");
	ASSERT_NEAR(mm->base_colour[0], 0.5, 1e-7);
	ASSERT_NEAR(mm->metallic, 0.25, 1e-7);
	ASSERT_NEAR(mm->roughness, 0.75, 1e-7);
	ASSERT_VEC(mm->emission, 4, 2, 1, 1e-6);
	ASSERT(mm->mask == 0.0f);
	t = mm->base_colour_tex;
	ASSERT(t && t->width == 2 && t->height == 2 && t->nchannels == 3);
	/* decoded from sRGB: the grey texel, bottom right */
	ASSERT_NEAR(t->pixels[9], srgb(188 / 255.0), 1e-6);
	ASSERT(t->pixels[0] == 1.0f && t->pixels[1] == 0.0f);
	ASSERT(t->wrap[0] == RF__WRAP_CLAMP && t->wrap[1] == RF__WRAP_MIRROR);
	/* no transform: the identity; (0.25, 0.25) is the top left texel's
	 * centre (red), (0.75, 0.75) the bottom right's */
	ASSERT(t->transform[0] == 1 && t->transform[1] == 0 && t->transform[2] == 0 &&
	       t->transform[3] == 0 && t->transform[4] == 1 && t->transform[5] == 0);
	uv[0] = 0.25f, uv[1] = 0.25f;
	sample_at(t, uv, out);
	ASSERT_VEC(out, 1, 0, 0, 1e-6);
	ASSERT(out[3] == 1.0f);
	uv[0] = 0.75f, uv[1] = 0.75f;
	sample_at(t, uv, out);
	ASSERT_NEAR(out[1], srgb(188 / 255.0), 1e-6);
	/* halfway between red and green */
	uv[0] = 0.5f, uv[1] = 0.25f;
	sample_at(t, uv, out);
	ASSERT_VEC(out, 0.5, 0.5, 0, 1e-6);
	/* KHR_texture_transform: T(0.25, 0.5) R(0.3) S(2, 3) */
	t = mm->emission_tex;
	ASSERT(t);
	ASSERT_NEAR(t->transform[0], 2 * c, 1e-6);
	ASSERT_NEAR(t->transform[1], 3 * sn, 1e-6);
	ASSERT_NEAR(t->transform[2], 0.25, 1e-6);
	ASSERT_NEAR(t->transform[3], -2 * sn, 1e-6);
	ASSERT_NEAR(t->transform[4], 3 * c, 1e-6);
	ASSERT_NEAR(t->transform[5], 0.5, 1e-6);
	/* the same pixels, decoded once */
	ASSERT(t->pixels == mm->base_colour_tex->pixels);
	rf_scene_destroy(s);
}

TEST(linear_textures_and_second_uv_set)
{
	/* The metallic-roughness and normal textures are data, read as
	 * stored; KHR_texture_transform's texCoord picks the uv set. */
	rf_scene *s;
	const struct rf__mesh *m;
	const struct rf__mesh_material *mm;

	png_2x2("data.png");
	gltf_quad("data.gltf", quad_uv, NULL, "",
	          UV_NORMAL ",\"TEXCOORD_1\":1",
	          "{\"name\":\"data\",\"pbrMetallicRoughness\":{\"metallicRoughnessTexture\":"
	          "{\"index\":0,\"texCoord\":1}},"
	          "\"normalTexture\":{\"index\":0,\"scale\":0.5,\"extensions\":"
	          "{\"KHR_texture_transform\":{\"texCoord\":1}}}}",
	          ",\"images\":[{\"uri\":\"data.png\"}],\"textures\":[{\"source\":0}]");
	s = load("probe box -10 -10 -10 10 10 10\nmesh data.gltf\n");
	ASSERT(s);
	m = &s->meshes[0];
	ASSERT(m->uv[1]);
	mm = &m->materials[m->material[0]];
	ASSERT(mm->metallic == 1.0f && mm->roughness == 1.0f);
	ASSERT(mm->metallic_roughness_tex && mm->normal_tex);
	ASSERT_NEAR(mm->normal_tex->pixels[9], 188 / 255.0, 1e-6);
	ASSERT_NEAR(mm->metallic_roughness_tex->pixels[9], 188 / 255.0, 1e-6);
	ASSERT_NEAR(mm->normal_scale, 0.5, 1e-7);
	ASSERT_EQ(mm->metallic_roughness_tex->texcoord, 1);
	ASSERT_EQ(mm->normal_tex->texcoord, 1);
	ASSERT(mm->normal_tex->wrap[0] == RF__WRAP_REPEAT);
	rf_scene_destroy(s);
}

TEST(obj_mtl_mapping)
{
	rf_scene *s;
	const struct rf__mesh *m;
	const struct rf__mesh_material *a, *b;

	png_2x2("kd.png");
	put_text("two.mtl", "newmtl mirror_steel\nKd 0.5 0.25 0.125\nKs 0.52 0.1 0.1\n"
	                    "Ns 98\nKe 1 2 3\nmap_Kd kd.png\n"
	                    "newmtl plaster\nKd 0.8 0.8 0.8\nKs 0 0 0\nNs 0\n");
	put_text("two.obj", "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
	                    "vt 0 0\nvt 1 0\nvt 0 1\n"
	                    "usemtl mirror_steel\nf 1/1 2/2 3/3\n"
	                    "usemtl plaster\nf 2/2 4/1 3/3\n");
	s = load("probe box -10 -10 -10 10 10 10\nmesh two.obj\n");
	ASSERT(s);
	m = &s->meshes[0];
	ASSERT_EQ(m->ntriangles, 2);
	a = b = NULL;
	for (size_t i = 0; i < m->nmaterials; i++) {
		if (!strcmp(m->materials[i].name, "mirror_steel"))
			a = &m->materials[i];
		if (!strcmp(m->materials[i].name, "plaster"))
			b = &m->materials[i];
	}
	ASSERT(a && b);
	ASSERT_VEC(a->base_colour, 0.5, 0.25, 0.125, 1e-7);
	/* (0.52 - 0.04) / 0.96 */
	ASSERT_NEAR(a->metallic, 0.5, 1e-6);
	/* (2 / (98 + 2))^(1/4) */
	ASSERT_NEAR(a->roughness, pow(0.02, 0.25), 1e-6);
	ASSERT_VEC(a->emission, 1, 2, 3, 1e-7);
	ASSERT(a->mask == 1.0f && b->mask == 0.0f);
	ASSERT(a->base_colour_tex && a->base_colour_tex->width == 2);
	ASSERT_NEAR(a->base_colour_tex->pixels[9], srgb(188 / 255.0), 1e-6);
	ASSERT(b->metallic == 0.0f && b->roughness == 1.0f && !b->base_colour_tex);
	/* OBJ's vt has v up: vertex 3 (0 1 0) at vt (0, 1), glTF's (0, 0) */
	{
		long v = vertex_at(m, 0, 1, 0);

		ASSERT(v >= 0);
		ASSERT(m->uv[0][2 * v] == 0.0f && m->uv[0][2 * v + 1] == 0.0f);
	}
	rf_scene_destroy(s);
	/* overrides: every material, then one by name */
	s = load("probe box -10 -10 -10 10 10 10\n"
	         "mesh two.obj roughness 0.5 reflective off material plaster metallic 1 "
	         "albedo 0.1 0.2 0.3 reflective on emission 0 0 0\n");
	ASSERT(s);
	m = &s->meshes[0];
	for (size_t i = 0; i < m->nmaterials; i++) {
		const struct rf__mesh_material *mm = &m->materials[i];

		ASSERT_NEAR(mm->roughness, 0.5, 1e-7);
		if (!strcmp(mm->name, "plaster")) {
			ASSERT(mm->metallic == 1.0f && mm->mask == 1.0f);
			ASSERT_VEC(mm->base_colour, 0.1, 0.2, 0.3, 1e-7);
		} else if (!strcmp(mm->name, "mirror_steel")) {
			ASSERT(mm->mask == 0.0f && mm->base_colour_tex);
			ASSERT_NEAR(mm->metallic, 0.5, 1e-6);
		}
	}
	rf_scene_destroy(s);
}

TEST(lights_in_scene_units)
{
	rf_scene *s;
	const struct rf__light *l;
	int seen = 0;

	/* the lights on nodes of their own, children of the mesh's */
	gltf_quad("lights.gltf", quad_uv, NULL,
	          ",\"children\":[1,2,3]},"
	          "{\"translation\":[1,2,3],\"extensions\":{\"KHR_lights_punctual\":"
	          "{\"light\":0}}},"
	          "{\"name\":\"spot\",\"rotation\":[0.7071067811865476,0,0,"
	          "0.7071067811865476],\"extensions\":{\"KHR_lights_punctual\":"
	          "{\"light\":1}}},"
	          "{\"name\":\"sun\",\"extensions\":{\"KHR_lights_punctual\":"
	          "{\"light\":2}}",
	          UV_NORMAL, PLAIN_MATERIAL,
	          ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":["
	          "{\"type\":\"point\",\"color\":[1,0.5,0.25],\"intensity\":683,"
	          "\"range\":5},"
	          "{\"type\":\"spot\",\"intensity\":1366,\"spot\":{\"innerConeAngle\":0.2,"
	          "\"outerConeAngle\":0.5}},"
	          "{\"type\":\"directional\",\"intensity\":6.83}]}}");
	s = load("probe box -10 -10 -10 10 10 10\nmesh lights.gltf translate 0 10 0\n");
	ASSERT(s);
	ASSERT_EQ(s->nlights, 3);
	for (size_t i = 0; i < s->nlights; i++) {
		l = &s->lights[i];
		ASSERT_EQ(l->line, 2);
		switch (l->kind) {
		case RF__LIGHT_POINT:
			/* 683 cd of (1, 0.5, 0.25): 1 W/sr of it */
			ASSERT_VEC(l->colour, 1, 0.5, 0.25, 1e-6);
			ASSERT_VEC(l->position, 1, 12, 3, 1e-6);
			ASSERT_NEAR(l->range, 5, 1e-6);
			seen |= 1;
			break;
		case RF__LIGHT_SPOT:
			/* -Z turned 90 degrees about +X: +Y */
			ASSERT_VEC(l->colour, 2, 2, 2, 1e-6);
			ASSERT_VEC(l->direction, 0, 1, 0, 1e-6);
			ASSERT_VEC(l->position, 0, 10, 0, 1e-6);
			ASSERT_NEAR(l->inner_cone, 0.2, 1e-6);
			ASSERT_NEAR(l->outer_cone, 0.5, 1e-6);
			ASSERT(l->range == 0);
			seen |= 2;
			break;
		case RF__LIGHT_DIRECTIONAL:
			ASSERT_VEC(l->colour, 0.01, 0.01, 0.01, 1e-7);
			ASSERT_VEC(l->direction, 0, 0, -1, 1e-6);
			seen |= 4;
			break;
		}
	}
	ASSERT_EQ(seen, 7);
	rf_scene_destroy(s);
}

static void
le32(unsigned char *b, uint32_t v)
{
	b[0] = (unsigned char)v, b[1] = (unsigned char)(v >> 8);
	b[2] = (unsigned char)(v >> 16), b[3] = (unsigned char)(v >> 24);
}

/* glTF extras decide which materials reflect, over their names; the
 * statement's reflective attribute over both. */
TEST(reflective_from_extras)
{
	static const struct {
		const char *material;
		float mask;
	} cases[] = {
		{ "{\"name\":\"plain\",\"extras\":{\"reflect\":{\"mirror\":true}}}", 1 },
		{ "{\"name\":\"mirror-glass\",\"extras\":{\"reflect\":{\"mirror\":false}}}", 0 },
		{ "{\"name\":\"mirror-floor\",\"extras\":{\"author\":\"x\"}}", 1 },
		{ "{\"name\":\"stone\",\"extras\":{\"reflect\":{\"mirror\":0}}}", 0 },
		{ "{\"name\":\"stone\",\"extras\":{\"reflect\":{\"mirror\":1}}}", 1 },
	};
	rf_scene *s;
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		gltf_quad("extras.gltf", quad_uv, NULL, "", UV_NORMAL, cases[i].material, "");
		s = load("probe box -10 -10 -10 10 10 10\nmesh extras.gltf\n");
		ASSERT(s);
		ASSERT(s->meshes[0].nmaterials >= 1);
		ASSERT_EQ(s->meshes[0].materials[0].mask, cases[i].mask);
		rf_scene_destroy(s);
	}
	/* the statement's attribute decides over the extras */
	gltf_quad("extras.gltf", quad_uv, NULL, "", UV_NORMAL, cases[0].material, "");
	s = load("probe box -10 -10 -10 10 10 10\nmesh extras.gltf reflective off\n");
	ASSERT(s);
	ASSERT(s->meshes[0].materials[0].mask == 0.0f);
	rf_scene_destroy(s);
}

/* assimp orders a file's materials as meshes first use them, not as the
 * file lists them: what it leaves out (emission strength, extras) is
 * matched by name.  The quad uses the second of three materials. */
TEST(materials_matched_by_name)
{
	char path[512], *text, *at;
	rf_scene *s;
	const struct rf__mesh_material *mm;
	FILE *fp;
	long n;

	gltf_quad("order.gltf", quad_uv, NULL, "", UV_NORMAL,
	          "{\"name\":\"first\",\"emissiveFactor\":[1,1,1],\"extensions\":"
	          "{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":3}}},"
	          "{\"name\":\"glow\",\"emissiveFactor\":[1,0.5,0.25],\"extensions\":"
	          "{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":8}},"
	          "\"extras\":{\"reflect\":{\"mirror\":true}}},"
	          "{\"name\":\"last\"}", "");
	/* the primitive's material: the second */
	snprintf(path, sizeof(path), "%s/order.gltf", dir);
	fp = fopen(path, "rb");
	ASSERT(fp);
	fseek(fp, 0, SEEK_END);
	n = ftell(fp);
	rewind(fp);
	text = calloc(1, (size_t)n + 1);
	ASSERT(text && fread(text, 1, (size_t)n, fp) == (size_t)n);
	fclose(fp);
	at = strstr(text, "\"material\":0");
	ASSERT(at);
	at[strlen("\"material\":")] = '1';
	put_text("order.gltf", text);
	free(text);
	s = load("probe box -10 -10 -10 10 10 10\nmesh order.gltf\n");
	ASSERT(s);
	mm = &s->meshes[0].materials[s->meshes[0].material[0]];
	ASSERT_STR_EQ(mm->name, "glow");
	ASSERT_VEC(mm->emission, 8, 4, 2, 1e-6);
	ASSERT(mm->mask == 1.0f);
	rf_scene_destroy(s);
}

TEST(glb_with_embedded_png)
{
	struct quad q;
	char path[512], json[4096];
	unsigned char *png, *glb;
	size_t npng, njson, nbin, n;
	FILE *fp;
	long len;
	rf_scene *s;
	const struct rf__texture *t;

	png_2x2("embed.png");
	snprintf(path, sizeof(path), "%s/embed.png", dir);
	fp = fopen(path, "rb");
	ASSERT(fp);
	fseek(fp, 0, SEEK_END);
	len = ftell(fp);
	rewind(fp);
	npng = (size_t)len;
	png = malloc(npng);
	ASSERT(fread(png, 1, npng, fp) == npng);
	fclose(fp);
	unlink(path);
	quad_make(&q, quad_uv, NULL);
	snprintf(json, sizeof(json),
	         "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":%zu}],"
	         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":48},"
	         "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":32},"
	         "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":12},"
	         "{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}],"
	         "\"accessors\":["
	         "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
	         "\"min\":[-1,-1,0],\"max\":[1,1,0]},"
	         "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
	         "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
	         "\"images\":[{\"bufferView\":3,\"mimeType\":\"image/png\"}],"
	         "\"textures\":[{\"source\":0}],"
	         "\"materials\":[{\"name\":\"m\",\"pbrMetallicRoughness\":"
	         "{\"baseColorTexture\":{\"index\":0}}}],"
	         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,"
	         "\"TEXCOORD_0\":1},\"indices\":2,\"material\":0}]}],"
	         "\"nodes\":[{\"mesh\":0}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}",
	         q.n + npng, q.npos, q.nuv, q.nidx, q.n, npng);
	njson = (strlen(json) + 3) & ~(size_t)3;
	nbin = (q.n + npng + 3) & ~(size_t)3;
	n = 12 + 8 + njson + 8 + nbin;
	glb = calloc(1, n);
	memcpy(glb, "glTF", 4);
	le32(glb + 4, 2);
	le32(glb + 8, (uint32_t)n);
	le32(glb + 12, (uint32_t)njson);
	memcpy(glb + 16, "JSON", 4);
	memset(glb + 20, ' ', njson);
	memcpy(glb + 20, json, strlen(json));
	le32(glb + 20 + njson, (uint32_t)nbin);
	memcpy(glb + 24 + njson, "BIN", 4);
	memcpy(glb + 28 + njson, q.bytes, q.n);
	memcpy(glb + 28 + njson + q.n, png, npng);
	put("embed.glb", glb, n);
	free(glb);
	free(png);
	s = load("probe box -10 -10 -10 10 10 10\nmesh embed.glb\n");
	ASSERT(s);
	t = s->meshes[0].materials[s->meshes[0].material[0]].base_colour_tex;
	ASSERT(t && t->width == 2 && t->height == 2);
	ASSERT(t->pixels[0] == 1.0f && t->pixels[4] == 1.0f && t->pixels[8] == 1.0f);
	ASSERT_NEAR(t->pixels[11], srgb(188 / 255.0), 1e-6);
	rf_scene_destroy(s);
}

/* An 8 x 8 float texture of four 4 x 4 quadrants, each one colour. */
static const float quadrant_rgb[4][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 1 } };

static void
exr_quadrants(const char *name)
{
	float px[8 * 8 * 3];
	rf_image_writer *w;
	char path[512], err[256];
	int x, y, c;

	for (y = 0; y < 8; y++)
		for (x = 0; x < 8; x++)
			for (c = 0; c < 3; c++)
				px[3 * (8 * y + x) + c] = quadrant_rgb[2 * (y / 4) + x / 4][c];
	snprintf(path, sizeof(path), "%s/%s", dir, name);
	if (rf_image_writer_open(&w, path, 8, 8, 3, NULL, RF_PIXEL_FLOAT, err, sizeof(err)) <
	            0 ||
	    rf_image_writer_write_rows(w, 0, 8, px) < 0 ||
	    rf_image_writer_close(w, err, sizeof(err)) < 0)
		printf("# exr: %s\n", err);
}

/* A probe 1 m in front of a textured emissive quad (2 x 2 m, z = 0)
 * sees it fill its -Z face: each texel well inside a quadrant of the
 * texture (half a texture texel from every edge of it, where bilinear
 * filtering is constant) is the quadrant's colour times the emission
 * strength, exactly. */
TEST(captured_texels_are_the_texture)
{
	struct rf_capture_options co;
	rf_cubemap *cube = NULL;
	rf_scene *s;
	char err[256];
	size_t i, j, n = 16, checked = 0;

	exr_quadrants("quadrants.exr");
	gltf_quad("wall.gltf", quad_uv, NULL, "", UV_NORMAL,
	          "{\"name\":\"wall\",\"emissiveFactor\":[1,1,1],"
	          "\"emissiveTexture\":{\"index\":0},\"extensions\":"
	          "{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}}",
	          ",\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"quadrants.exr\"}]");
	s = load("probe box -10 -10 -10 10 10 10 center 0 0 1\nroom off\nmesh wall.gltf\n");
	ASSERT(s);
	rf_capture_options_init(&co);
	co.size = n;
	co.bounces = 0;
	ASSERT(rf_scene_capture(s, 0, &co, &cube, err, sizeof(err)) == 0);
	for (j = 0; j < n; j++)
		for (i = 0; i < n; i++) {
			const float *tx = rf_cubemap_texel(cube, 0, RF_FACE_NEG_Z, i, j);
			float d[3];
			double x, y, ax, ay;
			int q;

			rf_cube_direction(RF_FACE_NEG_Z, ((float)i + 0.5f) / (float)n,
			                  ((float)j + 0.5f) / (float)n, d);
			/* where the texel's centre ray meets the quad, 1 m away */
			x = d[0] / -d[2];
			y = d[1] / -d[2];
			ax = fabs(x);
			ay = fabs(y);
			/* the footprint is 1/8 m wide, a texture texel 1/4 m: of the 16
			 * texels a row, 6 on each side of the middle */
			if (ax - 0.0625 < 0.125 || 1.0 - ax - 0.0625 < 0.125 ||
			    ay - 0.0625 < 0.125 || 1.0 - ay - 0.0625 < 0.125)
				continue;
			/* the image's top row at y = +1, its left column at x = -1 */
			q = 2 * (y < 0) + (x > 0);
			ASSERT_VEC(tx, 4 * quadrant_rgb[q][0], 4 * quadrant_rgb[q][1],
			           4 * quadrant_rgb[q][2], 1e-6);
			checked++;
		}
	ASSERT_EQ(checked, 144);
	rf_cubemap_destroy(cube);
	rf_scene_destroy(s);
}

TEST(errors_name_the_files)
{
	char err[1024];

	put_text("empty.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
	ASSERT(load_error("probe box -1 -1 -1 1 1 1\nmesh empty.obj\n", err, sizeof(err)) < 0);
	printf("# %s\n", err);
	ASSERT(strstr(err, "test.scene:2:6: '") && strstr(err, "empty.obj': no triangles"));
	ASSERT(load_error("probe box -1 -1 -1 1 1 1\nmesh quad.gltf spin 3\n", err,
	                  sizeof(err)) < 0);
	ASSERT(strstr(err, "test.scene:2:16: unknown mesh attribute 'spin'"));
	ASSERT(load_error("probe box -1 -1 -1 1 1 1\nmesh quad.gltf material nosuch "
	                  "roughness 1\n", err, sizeof(err)) < 0);
	printf("# %s\n", err);
	ASSERT(strstr(err, "has no material 'nosuch' (it has 'plain'"));
	ASSERT(load_error("probe box -1 -1 -1 1 1 1\nmesh quad.gltf scale 1 0 1\n", err,
	                  sizeof(err)) < 0);
	ASSERT(strstr(err, "expected non-zero scales"));
	ASSERT(load_error("probe box -1 -1 -1 1 1 1\nmesh quad.gltf matrix 1 0 0 0 0 1 0 0 "
	                  "0 0 1 0 0 0 0 1 translate 1 1 1\n", err, sizeof(err)) < 0);
	ASSERT(strstr(err, "either 'matrix' or"));
	ASSERT(load_error("probe box -1 -1 -1 1 1 1\nmesh quad.gltf normalmap tiles\n", err,
	                  sizeof(err)) < 0);
	ASSERT(strstr(err, "unknown mesh attribute 'normalmap'"));
	ASSERT(load_error("probe box -1 -1 -1 1 1 1\nmesh quad.stl\n", err, sizeof(err)) < 0);
	ASSERT(strstr(err, "expected a glTF 2.0 (.gltf, .glb) or Wavefront OBJ"));
}

int
main(void)
{
	const char *tmp = getenv("TMPDIR");

	snprintf(dir, sizeof(dir), "%s/test-mesh-XXXXXX", tmp && *tmp ? tmp : "/tmp");
	if (!mkdtemp(dir)) {
		printf("Bail out! cannot make a directory\n");
		return 1;
	}
	RUN(node_and_statement_transforms);
	RUN(matrix_attribute_and_mirror);
	RUN(gltf_without_normals_is_flat);
	RUN(obj_normals_weighted_by_angle);
	RUN(tangents_from_uv_layouts);
	RUN(base_colour_texture_and_transform);
	RUN(linear_textures_and_second_uv_set);
	RUN(obj_mtl_mapping);
	RUN(lights_in_scene_units);
	RUN(reflective_from_extras);
	RUN(materials_matched_by_name);
	RUN(glb_with_embedded_png);
	RUN(captured_texels_are_the_texture);
	RUN(errors_name_the_files);
	{
		char cmd[512];

		snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
		if (!tap_failed && system(cmd) != 0)
			printf("# cannot remove %s\n", dir);
	}
	TAP_DONE();
}
