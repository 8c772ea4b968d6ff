/*
 * A mesh file's materials onto glTF's metallic-roughness model (struct
 * rf__mesh_material), their textures through the image layer, and the
 * mesh statement's overrides.  reflect-scene(5) documents the mapping;
 * the comments here say why it is what it is.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>

#include "image/image-internal.h"
#include "scene/mesh-load.h"

static float
srgb_decode(float c)
{
	return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

static int
hexval(char c)
{
	return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
	       : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* A texture's file beside the mesh file: glTF's URIs are %XX-encoded,
 * OBJ's names are as written (with DOS separators made Unix ones). */
static char *
texture_path(const struct rf__loader *ld, const char *name)
{
	size_t dlen = name[0] == '/' ? 0 : strlen(ld->dir), n = strlen(name), i, k;
	char *out = malloc(dlen + n + 1);

	if (!out)
		return NULL;
	memcpy(out, ld->dir, dlen);
	for (i = 0, k = dlen; i < n; i++) {
		if (ld->gltf && name[i] == '%' && i + 2 < n && hexval(name[i + 1]) >= 0 &&
		    hexval(name[i + 2]) >= 0) {
			out[k++] = (char)(hexval(name[i + 1]) * 16 + hexval(name[i + 2]));
			i += 2;
		} else
			out[k++] = !ld->gltf && name[i] == '\\' ? '/' : name[i];
	}
	out[k] = '\0';
	return out;
}

/* The image a material names: a file, or one embedded in the mesh file
 * ("*N", as assimp names a .glb's images and data URIs). */
static int
texture_image(struct rf__loader *ld, const char *name, const char *what, const char *mat,
              const rf_image **img)
{
	char msg[512], *path;
	int rc;

	if (name[0] == '*') {
		const struct aiTexture *t;
		char *end, key[4200];
		unsigned long k = strtoul(name + 1, &end, 10);
		rf_image *im;

		snprintf(key, sizeof(key), "%s#%s", ld->rq->path, name);
		if ((*img = rf__scene_image_find(ld->s, key)))
			return 0;
		if (*end || !name[1] || k >= ld->sc->mNumTextures)
			return rf__format(ld->err, ld->errlen, "'%s': material '%s' names "
			                  "embedded image %s, of %u", ld->rq->path, mat, name,
			                  ld->sc->mNumTextures), RF_EFORMAT;
		t = ld->sc->mTextures[k];
		if (t->mHeight)
			return rf__format(ld->err, ld->errlen, "'%s': embedded image %lu is "
			                  "raw texels, not an image file", ld->rq->path, k),
			       RF_EFORMAT;
		snprintf(key, sizeof(key), "'%s' embedded image %lu", ld->rq->path, k);
		rc = rf__image_read_memory(&im, t->pcData, t->mWidth, t->achFormatHint, key,
		                           msg, sizeof(msg));
		if (rc < 0) {
			if (rc != RF_ENOMEM)
				rf__format(ld->err, ld->errlen, "%s (%s of material '%s')", msg,
				           what, mat);
			return rc;
		}
		snprintf(key, sizeof(key), "%s#%s", ld->rq->path, name);
		if ((rc = rf__scene_image_add(ld->s, key, im)) < 0)
			return rc;
		*img = im;
		return 0;
	}
	if (!(path = texture_path(ld, name)))
		return RF_ENOMEM;
	rc = rf__scene_image(ld->s, path, 1, what, img, msg, sizeof(msg));
	free(path);
	if (rc < 0 && rc != RF_ENOMEM)
		rf__format(ld->err, ld->errlen, "'%s': material '%s': %s", ld->rq->path, mat,
		           msg);
	return rc;
}

/* The image's colour values decoded from sRGB (alpha left alone), once
 * per image for the file. */
static int
decoded(struct rf__loader *ld, const rf_image *img, const float **out)
{
	const float *src = rf_image_pixels(img);
	size_t nch = rf_image_nchannels(img), n, i;
	struct rf__decoded *grown;
	float *px;
	int rc;

	for (i = 0; i < ld->nloaded; i++)
		if (ld->loaded[i].from == src) {
			*out = ld->loaded[i].to;
			return 0;
		}
	if (rf__mul3(rf_image_width(img), rf_image_height(img), nch, &n) < 0 ||
	    !(px = malloc(n * sizeof(*px))))
		return RF_ENOMEM;
	for (i = 0; i < n; i++)
		px[i] = nch == 2 || nch == 4 ? (i % nch == nch - 1 ? src[i] : srgb_decode(src[i]))
		                             : srgb_decode(src[i]);
	if ((rc = rf__scene_keep(ld->s, px)) < 0)
		return rc;
	if (!(grown = realloc(ld->loaded, (ld->nloaded + 1) * sizeof(*grown))))
		return RF_ENOMEM;
	ld->loaded = grown;
	ld->loaded[ld->nloaded].from = src;
	ld->loaded[ld->nloaded++].to = px;
	*out = px;
	return 0;
}

static enum rf__wrap
wrap_mode(const struct aiMaterial *mat, const char *key, enum aiTextureType type)
{
	int mode = aiTextureMapMode_Wrap;

	aiGetMaterialIntegerArray(mat, key, type, 0, &mode, NULL);
	return mode == aiTextureMapMode_Mirror ? RF__WRAP_MIRROR
	       : mode == aiTextureMapMode_Clamp || mode == aiTextureMapMode_Decal
	               ? RF__WRAP_CLAMP : RF__WRAP_REPEAT;
}

/*
 * KHR_texture_transform as one 2 x 3 matrix in glTF's uv (v down):
 * uv' = T(offset) R(rotation) S(scale) uv, R counter-clockwise in the uv
 * plane drawn v down: u' = cos r u + sin r v, v' = -sin r u + cos r v (as
 * the extension's sample model and viewers have it; the GLSL listing of
 * its specification transposes R, glTF issue 1563).
 * assimp hands it over as an aiUVTransform re-expressed for its own uv
 * (v up, rotation about the centre, the angle negated); its translation
 * is undone here into glTF's offset, by the inverse of the formula of
 * assimp's glTF 2 importer (5.2).
 */
static void
uv_transform(const struct aiMaterial *mat, enum aiTextureType type, float out[6])
{
	struct aiUVTransform t;
	unsigned n = sizeof(t) / sizeof(ai_real);
	double r, c, s, sx, sy, ox, oy;

	out[0] = 1, out[1] = 0, out[2] = 0;
	out[3] = 0, out[4] = 1, out[5] = 0;
	if (aiGetMaterialFloatArray(mat, _AI_MATKEY_UVTRANSFORM_BASE, type, 0, (ai_real *)&t,
	                            &n) != aiReturn_SUCCESS || n != sizeof(t) / sizeof(ai_real))
		return;
	r = -t.mRotation;
	c = cos(r);
	s = sin(r);
	sx = t.mScaling.x;
	sy = t.mScaling.y;
	ox = t.mTranslation.x - 0.5 * sx * (-c + s + 1);
	oy = -(t.mTranslation.y - 0.5 * sy * (s + c - 1) - 1 + sy);
	out[0] = (float)(c * sx);
	out[1] = (float)(s * sy);
	out[2] = (float)ox;
	out[3] = (float)(-s * sx);
	out[4] = (float)(c * sy);
	out[5] = (float)oy;
}

/* A material's texture of that type: NULL without one.  uvset, when not
 * -1, is the set KHR_texture_transform names (assimp 5.2 drops it). */
static int
texture(struct rf__loader *ld, const struct aiMaterial *mat, enum aiTextureType type,
        int srgb, const char *what, const char *mname, int uvset,
        const struct rf__texture **out)
{
	struct aiString name;
	struct rf__texture *t;
	const rf_image *img;
	const char *cs;
	int rc;

	*out = NULL;
	if (!aiGetMaterialTextureCount(mat, type) ||
	    aiGetMaterialTexture(mat, type, 0, &name, NULL, NULL, NULL, NULL, NULL, NULL) !=
	            aiReturn_SUCCESS || !name.length)
		return 0;
	if (uvset < 0) {
		uvset = 0;
		aiGetMaterialIntegerArray(mat, _AI_MATKEY_UVWSRC_BASE, type, 0, &uvset, NULL);
	}
	if (uvset < 0 || uvset > 1)
		return rf__format(ld->err, ld->errlen, "'%s': material '%s' reads its %s with "
		                  "uv set %d; reflect reads sets 0 and 1", ld->rq->path, mname,
		                  what, uvset), RF_EFORMAT;
	if ((rc = texture_image(ld, name.data, what, mname, &img)) < 0)
		return rc;
	if (!(t = calloc(1, sizeof(*t))) || (rc = rf__scene_keep(ld->s, t)) < 0)
		return RF_ENOMEM;
	t->width = rf_image_width(img);
	t->height = rf_image_height(img);
	t->nchannels = rf_image_nchannels(img);
	t->pixels = rf_image_pixels(img);
	/* 8- and 16-bit files hold sRGB-encoded colour; float files linear */
	cs = rf_image_attribute(img, "oiio:ColorSpace");
	if (srgb && cs && (!strcasecmp(cs, "sRGB") || !strcmp(cs, "srgb_rec709_scene")) &&
	    (rc = decoded(ld, img, &t->pixels)) < 0)
		return rc;
	t->wrap[0] = wrap_mode(mat, _AI_MATKEY_MAPPINGMODE_U_BASE, type);
	t->wrap[1] = wrap_mode(mat, _AI_MATKEY_MAPPINGMODE_V_BASE, type);
	uv_transform(mat, type, t->transform);
	t->texcoord = uvset;
	*out = t;
	return 0;
}

static float
get_float(const struct aiMaterial *mat, const char *key, unsigned type, unsigned idx,
          float dflt)
{
	ai_real v;
	unsigned n = 1;

	return aiGetMaterialFloatArray(mat, key, type, idx, &v, &n) == aiReturn_SUCCESS &&
	               n == 1 && isfinite(v) ? (float)v : dflt;
}

static int
get_colour(const struct aiMaterial *mat, const char *key, unsigned type, unsigned idx,
           float rgba[4])
{
	struct aiColor4D c;

	if (aiGetMaterialColor(mat, key, type, idx, &c) != aiReturn_SUCCESS)
		return 0;
	rgba[0] = c.r, rgba[1] = c.g, rgba[2] = c.b, rgba[3] = c.a;
	return 1;
}

/*
 * Which surfaces show the probe's reflection (the G-buffer's mask):
 * those whose material's name starts with "mirror" or "reflective" (any
 * case), a name being what every exporter keeps, unless a glTF
 * material's extras say "reflect": { "mirror": true or false }; the
 * statement's `reflective on|off` overrides both.
 */
static float
mask_of(const char *name)
{
	return !strncasecmp(name, "mirror", 6) || !strncasecmp(name, "reflective", 10)
	       ? 1.0f : 0.0f;
}

static float
clamp01(float x)
{
	return x < 0 ? 0 : x > 1 ? 1 : x;
}

static int
gltf_material(struct rf__loader *ld, const struct aiMaterial *am,
              struct rf__mesh_material *mm)
{
	const struct rf__gltf_material *gm = rf__gltf_material_named(&ld->gltf_info, mm->name);
	float e[4] = { 0, 0, 0, 1 };
	int rc, k, set[RF__GLTF_TEXTURES];

	if (!get_colour(am, AI_MATKEY_BASE_COLOR, mm->base_colour))
		get_colour(am, AI_MATKEY_COLOR_DIFFUSE, mm->base_colour);
	mm->metallic = get_float(am, AI_MATKEY_METALLIC_FACTOR, 1.0f);
	mm->roughness = get_float(am, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f);
	mm->normal_scale = get_float(am, AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0),
	                             1.0f);
	get_colour(am, AI_MATKEY_COLOR_EMISSIVE, e);
	/* KHR_materials_emissive_strength: assimp 5.2 does not read it, the
	 * walk of gltf_check.c does (assimp keeps the file's material order,
	 * and adds a default material after them) */
	e[3] = gm ? gm->emissive_strength : 1.0f;
	for (int i = 0; i < 3; i++)
		mm->emission[i] = e[i] * e[3];
	for (k = 0; k < RF__GLTF_TEXTURES; k++)
		set[k] = gm ? gm->texcoord[k] : -1;
	if ((rc = texture(ld, am, aiTextureType_BASE_COLOR, 1, "base colour texture",
	                  mm->name, set[0], &mm->base_colour_tex)) < 0 ||
	    (!mm->base_colour_tex &&
	     (rc = texture(ld, am, aiTextureType_DIFFUSE, 1, "base colour texture", mm->name,
	                   set[0], &mm->base_colour_tex)) < 0) ||
	    (rc = texture(ld, am, AI_MATKEY_GLTF_PBRMETALLICROUGHNESS_METALLICROUGHNESS_TEXTURE,
	                  "metallic-roughness texture", mm->name, set[1],
	                  &mm->metallic_roughness_tex)) < 0 ||
	    (rc = texture(ld, am, aiTextureType_NORMALS, 0, "normal texture", mm->name,
	                  set[2], &mm->normal_tex)) < 0 ||
	    (rc = texture(ld, am, aiTextureType_EMISSIVE, 1, "emissive texture", mm->name,
	                  set[3], &mm->emission_tex)) < 0)
		return rc;
	return 0;
}

/*
 * OBJ/MTL onto metallic-roughness (reflect-scene(5) says the same):
 *   Kd, map_Kd       base colour and its texture;
 *   Ke, map_Ke       emission and its texture;
 *   Ns               roughness: alpha = sqrt(2 / (Ns + 2)), the Beckmann
 *                    slope that matches a Blinn-Phong exponent (Walter et
 *                    al. 2007), and reflect's roughness is perceptual,
 *                    alpha = roughness^2, so roughness = (2 / (Ns + 2))^(1/4);
 *   Ks               metallic = (max(Ks) - 0.04) / 0.96 clamped to [0, 1]:
 *                    a dielectric's 4 % reflectance is metallic 0, a
 *                    white specular colour 1;
 *   norm, map_Bump, bump   the normal texture (a tangent-space normal map,
 *                    as exporters write there, not a height map).
 */
static int
obj_material(struct rf__loader *ld, const struct aiMaterial *am,
             struct rf__mesh_material *mm)
{
	float ks[4] = { 0, 0, 0, 1 }, e[4] = { 0, 0, 0, 1 }, ns, kmax;
	int rc;

	get_colour(am, AI_MATKEY_COLOR_DIFFUSE, mm->base_colour);
	mm->base_colour[3] = 1.0f;
	get_colour(am, AI_MATKEY_COLOR_SPECULAR, ks);
	kmax = ks[0] > ks[1] ? ks[0] : ks[1];
	kmax = kmax > ks[2] ? kmax : ks[2];
	mm->metallic = clamp01((kmax - 0.04f) / 0.96f);
	ns = get_float(am, AI_MATKEY_SHININESS, 0.0f);
	ns = ns < 0 ? 0 : ns;
	mm->roughness = clamp01((float)pow(2.0 / (ns + 2.0), 0.25));
	get_colour(am, AI_MATKEY_COLOR_EMISSIVE, e);
	for (int i = 0; i < 3; i++)
		mm->emission[i] = e[i];
	mm->normal_scale = 1.0f;
	if ((rc = texture(ld, am, aiTextureType_DIFFUSE, 1, "map_Kd", mm->name, -1,
	                  &mm->base_colour_tex)) < 0 ||
	    (rc = texture(ld, am, aiTextureType_EMISSIVE, 1, "map_Ke", mm->name, -1,
	                  &mm->emission_tex)) < 0 ||
	    (rc = texture(ld, am, aiTextureType_NORMALS, 0, "norm", mm->name, -1,
	                  &mm->normal_tex)) < 0 ||
	    (!mm->normal_tex && (rc = texture(ld, am, aiTextureType_HEIGHT, 0, "map_Bump",
	                                      mm->name, -1, &mm->normal_tex)) < 0))
		return rc;
	return 0;
}

static int
material_valid(const struct rf__loader *ld, const struct rf__mesh_material *mm)
{
	const float *v[] = { mm->base_colour, mm->emission };
	int i;

	for (i = 0; i < 4; i++)
		if (!(mm->base_colour[i] >= 0))
			break;
	if (i < 4 || !(mm->emission[0] >= 0 && mm->emission[1] >= 0 && mm->emission[2] >= 0) ||
	    !isfinite(mm->emission[0] + mm->emission[1] + mm->emission[2]) ||
	    !isfinite(v[0][0] + v[0][1] + v[0][2] + v[0][3]))
		return rf__format(ld->err, ld->errlen, "'%s': material '%s' has a colour or "
		                  "emission that is negative or not finite", ld->rq->path,
		                  mm->name), RF_EFORMAT;
	return 0;
}

static void
apply(const struct rf__mesh_override *o, struct rf__mesh_material *mm)
{
	/* An override says what the surface is: it replaces the factor and
	 * the texture that would modulate it. */
	if (o->set & RF__OVR_ROUGHNESS)
		mm->roughness = o->roughness;
	if (o->set & RF__OVR_METALLIC)
		mm->metallic = o->metallic;
	/* one texture holds both: with one overridden, the other keeps its
	 * factor alone */
	if (o->set & (RF__OVR_ROUGHNESS | RF__OVR_METALLIC))
		mm->metallic_roughness_tex = NULL;
	if (o->set & RF__OVR_ALBEDO) {
		memcpy(mm->base_colour, o->albedo, sizeof(o->albedo));
		mm->base_colour[3] = 1.0f;
		mm->base_colour_tex = NULL;
	}
	if (o->set & RF__OVR_EMISSION) {
		memcpy(mm->emission, o->emission, sizeof(o->emission));
		mm->emission_tex = NULL;
	}
	if (o->set & RF__OVR_MASK)
		mm->mask = o->mask;
}

int
rf__mesh_materials(struct rf__loader *ld, struct rf__mesh *m)
{
	const struct aiScene *sc = ld->sc;
	size_t i, k;
	int rc;

	if (!sc->mNumMaterials)
		return rf__format(ld->err, ld->errlen, "'%s': no materials", ld->rq->path),
		       RF_EFORMAT;
	if (!(m->materials = calloc(sc->mNumMaterials, sizeof(*m->materials))))
		return RF_ENOMEM;
	m->nmaterials = sc->mNumMaterials;
	for (i = 0; i < m->nmaterials; i++) {
		const struct aiMaterial *am = sc->mMaterials[i];
		struct rf__mesh_material *mm = &m->materials[i];
		struct aiString name;

		if (aiGetMaterialString(am, AI_MATKEY_NAME, &name) != aiReturn_SUCCESS)
			name.length = 0, name.data[0] = '\0';
		if (!(mm->name = strdup(name.data)))
			return RF_ENOMEM;
		mm->base_colour[0] = mm->base_colour[1] = mm->base_colour[2] = 1.0f;
		mm->base_colour[3] = 1.0f;
		rc = ld->gltf ? gltf_material(ld, am, mm) : obj_material(ld, am, mm);
		if (rc == 0)
			rc = material_valid(ld, mm);
		if (rc < 0)
			return rc;
		mm->mask = mask_of(mm->name);
		if (ld->gltf) {
			const struct rf__gltf_material *gm =
				rf__gltf_material_named(&ld->gltf_info, mm->name);

			if (gm && gm->mirror >= 0)
				mm->mask = (float)gm->mirror;
		}
	}
	for (k = 0; k < m->ntriangles; k++)
		if (m->material[k] >= m->nmaterials)
			return rf__format(ld->err, ld->errlen, "'%s': a triangle names material "
			                  "%u, of %zu", ld->rq->path, m->material[k],
			                  m->nmaterials), RF_EFORMAT;
	/* the statement's overrides, in its order: every material first, then
	 * the named ones */
	for (k = 0; k < ld->rq->noverrides; k++) {
		const struct rf__mesh_override *o = &ld->rq->overrides[k];
		int found = 0;

		for (i = 0; i < m->nmaterials; i++)
			if (!o->material || !strcmp(o->material, m->materials[i].name)) {
				apply(o, &m->materials[i]);
				found = 1;
			}
		if (!found) {
			char names[256] = "";
			size_t len = 0;

			/* (assimp's default material, without a name, left out) */
			for (i = 0; i < m->nmaterials && len < sizeof(names) - 1; i++)
				if (m->materials[i].name[0])
					len += (size_t)snprintf(names + len, sizeof(names) - len,
					                        "%s'%s'", len ? ", " : "",
					                        m->materials[i].name);
			return rf__format(ld->err, ld->errlen, "'%s' has no material '%s' (it has "
			                  "%s)", ld->rq->path, o->material, names), RF_EFORMAT;
		}
	}
	return 0;
}
