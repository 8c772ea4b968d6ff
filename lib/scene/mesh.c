/*
 * The mesh statement's file (reflect-scene(5)): glTF 2.0 (.gltf, .glb)
 * and Wavefront OBJ with MTL, read through assimp's C interface into one
 * struct rf__mesh in world space, with the lights the file holds.
 *
 * assimp triangulates, sorts points and lines out, and joins identical
 * vertices (a deterministic pass: the same file gives the same indices).
 * Everything else is done here, so that it is the same for every format
 * and documented once: node transforms, normals and tangents where the
 * file has none, the checks on what the file claims.
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "scene/mesh-load.h"

/* The most vertices a mesh statement takes: indices are 32-bit. */
#define VERTICES_MAX ((size_t)UINT32_MAX)

static void
mat_from_ai(const struct aiMatrix4x4 *m, double out[16])
{
	const ai_real *v = &m->a1; /* a1..a4, b1..b4...: row-major */
	int i;

	for (i = 0; i < 16; i++)
		out[i] = v[i];
}

/* A node's transform to the world: the statement's times the chain of
 * node transforms from the root. */
static void
node_world(const struct rf__mesh_request *rq, const struct aiNode *n, double out[16])
{
	double m[16];

	memcpy(out, rq->matrix, sizeof(m));
	if (!n)
		return;
	node_world(rq, n->mParent, out);
	mat_from_ai(&n->mTransformation, m);
	rf__mat4_mul(out, m, out);
}

/* The frame of one instance: positions by the matrix, normals by its
 * inverse transpose, tangents by the matrix; det < 0 mirrors. */
struct frame {
	double m[16];
	double nt[9]; /* inverse transpose of the upper 3 x 3 */
	double det;
};

static int
frame_make(const double m[16], struct frame *f)
{
	const double *a = m;
	double c[9];

	memcpy(f->m, m, sizeof(f->m));
	/* cofactors of the 3 x 3: the inverse transpose is cofactor / det */
	c[0] = a[5] * a[10] - a[6] * a[9];
	c[1] = a[6] * a[8] - a[4] * a[10];
	c[2] = a[4] * a[9] - a[5] * a[8];
	c[3] = a[2] * a[9] - a[1] * a[10];
	c[4] = a[0] * a[10] - a[2] * a[8];
	c[5] = a[1] * a[8] - a[0] * a[9];
	c[6] = a[1] * a[6] - a[2] * a[5];
	c[7] = a[2] * a[4] - a[0] * a[6];
	c[8] = a[0] * a[5] - a[1] * a[4];
	f->det = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
	if (!(fabs(f->det) > 1e-300) || !isfinite(f->det))
		return -1;
	for (int i = 0; i < 9; i++)
		f->nt[i] = c[i] / f->det;
	return 0;
}

static void
xform_point(const struct frame *f, const struct aiVector3D *v, double out[3])
{
	for (int i = 0; i < 3; i++)
		out[i] = f->m[4 * i] * v->x + f->m[4 * i + 1] * v->y + f->m[4 * i + 2] * v->z +
		         f->m[4 * i + 3];
}

static void
xform_dir(const double *m3, int stride, const struct aiVector3D *v, double out[3])
{
	for (int i = 0; i < 3; i++)
		out[i] = m3[stride * i] * v->x + m3[stride * i + 1] * v->y +
		         m3[stride * i + 2] * v->z;
}

/* ---- counting and filling ----------------------------------------------- */

struct fill {
	struct rf__loader *ld;
	struct rf__mesh *m;
	unsigned char *gen_n, *gen_t; /* per vertex: generate its normal, tangent */
	int has_uv1;
	size_t nv, nt; /* filled so far */
};

static int
mesh_flat(const struct rf__loader *ld, const struct aiMesh *am)
{
	/* glTF: "When normals are not specified, client implementations MUST
	 * calculate flat normals": each triangle its own three vertices. */
	return ld->gltf && !am->mNormals;
}

static size_t
mesh_triangles(const struct aiMesh *am)
{
	size_t n = 0;

	for (unsigned f = 0; f < am->mNumFaces; f++)
		n += am->mFaces[f].mNumIndices == 3;
	return n;
}

static int
count(struct rf__loader *ld, const struct aiNode *n, size_t *nv, size_t *nt, int *uv1)
{
	for (unsigned i = 0; i < n->mNumMeshes; i++) {
		const struct aiMesh *am = ld->sc->mMeshes[n->mMeshes[i]];
		size_t t = mesh_triangles(am);

		*nv += mesh_flat(ld, am) ? 3 * t : am->mNumVertices;
		*nt += t;
		*uv1 |= am->mTextureCoords[1] != NULL;
		if (*nv > VERTICES_MAX || *nt > VERTICES_MAX)
			return -1;
	}
	for (unsigned i = 0; i < n->mNumChildren; i++)
		if (count(ld, n->mChildren[i], nv, nt, uv1) < 0)
			return -1;
	return 0;
}

static int
finite3(const double v[3])
{
	return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* Vertex k of am into output vertex o. */
static int
put_vertex(struct fill *fl, const struct aiMesh *am, const struct frame *fr, unsigned k,
           size_t o, const char *name)
{
	struct rf__mesh *m = fl->m;
	double p[3], n[3], t[3];
	int i;

	xform_point(fr, &am->mVertices[k], p);
	if (!finite3(p))
		return rf__format(fl->ld->err, fl->ld->errlen, "'%s': vertex %u of mesh '%s' "
		                  "is not a finite point (%g %g %g)", fl->ld->rq->path, k, name,
		                  am->mVertices[k].x, am->mVertices[k].y, am->mVertices[k].z),
		       RF_EFORMAT;
	for (i = 0; i < 3; i++)
		m->positions[3 * o + i] = (float)p[i];
	fl->gen_n[o] = !am->mNormals;
	if (am->mNormals) {
		xform_dir(fr->nt, 3, &am->mNormals[k], n);
		if (!(rf__normalize(n) > 0) || !finite3(n))
			fl->gen_n[o] = 1;
		for (i = 0; i < 3; i++)
			m->normals[3 * o + i] = (float)n[i];
	}
	fl->gen_t[o] = !am->mTangents || !am->mBitangents || !am->mNormals;
	if (!fl->gen_t[o]) {
		const struct aiVector3D *a = &am->mNormals[k], *tt = &am->mTangents[k],
		                        *b = &am->mBitangents[k];
		/* the file's w: the side of cross(N, T) its bitangent is on */
		double cx = a->y * tt->z - a->z * tt->y, cy = a->z * tt->x - a->x * tt->z,
		       cz = a->x * tt->y - a->y * tt->x;
		double w = cx * b->x + cy * b->y + cz * b->z < 0 ? -1.0 : 1.0;

		xform_dir(fr->m, 4, tt, t);
		if (!(rf__normalize(t) > 0) || !finite3(t))
			fl->gen_t[o] = 1;
		for (i = 0; i < 3; i++)
			m->tangents[4 * o + i] = (float)t[i];
		m->tangents[4 * o + 3] = (float)(fr->det < 0 ? -w : w);
	}
	for (i = 0; i < 2; i++) {
		const struct aiVector3D *uv = am->mTextureCoords[i] ? &am->mTextureCoords[i][k]
		                                                   : NULL;
		float *dst = m->uv[i] ? &m->uv[i][2 * o] : NULL;

		if (!dst)
			continue;
		if (uv && !(isfinite(uv->x) && isfinite(uv->y)))
			return rf__format(fl->ld->err, fl->ld->errlen, "'%s': vertex %u of mesh "
			                  "'%s' has texture coordinates that are not finite",
			                  fl->ld->rq->path, k, name), RF_EFORMAT;
		/* assimp gives v up (OpenGL's, OBJ's; it flips glTF's); the mesh
		 * keeps glTF's, v down from the image's first row */
		dst[0] = uv ? uv->x : 0.0f;
		dst[1] = uv ? 1.0f - uv->y : 0.0f;
	}
	return 0;
}

static int
fill_node(struct fill *fl, const struct aiNode *node)
{
	struct rf__loader *ld = fl->ld;
	struct rf__mesh *m = fl->m;
	struct frame fr;
	double w[16];
	int rc;

	node_world(ld->rq, node, w);
	if (node->mNumMeshes && frame_make(w, &fr) < 0)
		return rf__format(ld->err, ld->errlen, "'%s': node '%s' has a transform that "
		                  "flattens it (determinant 0 with the statement's)",
		                  ld->rq->path, node->mName.data), RF_EFORMAT;
	for (unsigned i = 0; i < node->mNumMeshes; i++) {
		const struct aiMesh *am = ld->sc->mMeshes[node->mMeshes[i]];
		const char *name = am->mName.length ? am->mName.data : node->mName.data;
		int flat = mesh_flat(ld, am);
		size_t base = fl->nv;

		if (!flat) {
			for (unsigned k = 0; k < am->mNumVertices; k++)
				if ((rc = put_vertex(fl, am, &fr, k, base + k, name)) < 0)
					return rc;
			fl->nv += am->mNumVertices;
		}
		for (unsigned f = 0; f < am->mNumFaces; f++) {
			const struct aiFace *face = &am->mFaces[f];
			uint32_t *tri = &m->indices[3 * fl->nt];

			if (face->mNumIndices != 3)
				continue;
			for (int c = 0; c < 3; c++) {
				if (face->mIndices[c] >= am->mNumVertices)
					return rf__format(ld->err, ld->errlen, "'%s': mesh '%s' has a "
					                  "triangle with vertex %u of %u", ld->rq->path,
					                  name, face->mIndices[c], am->mNumVertices),
					       RF_EFORMAT;
				if (flat) {
					if ((rc = put_vertex(fl, am, &fr, face->mIndices[c], fl->nv,
					                     name)) < 0)
						return rc;
					tri[c] = (uint32_t)fl->nv++;
				} else
					tri[c] = (uint32_t)(base + face->mIndices[c]);
			}
			/* A mirroring transform turns counter-clockwise into clockwise:
			 * swapped back, the winding keeps agreeing with the normals. */
			if (fr.det < 0) {
				uint32_t x = tri[1];

				tri[1] = tri[2];
				tri[2] = x;
			}
			m->material[fl->nt++] = am->mMaterialIndex;
		}
	}
	for (unsigned i = 0; i < node->mNumChildren; i++)
		if ((rc = fill_node(fl, node->mChildren[i])) < 0)
			return rc;
	return 0;
}

/* ---- lights -------------------------------------------------------------- */

static const struct aiNode *
find_node(const struct aiNode *n, const struct aiString *name)
{
	if (n->mName.length == name->length && !memcmp(n->mName.data, name->data, name->length))
		return n;
	for (unsigned i = 0; i < n->mNumChildren; i++) {
		const struct aiNode *f = find_node(n->mChildren[i], name);

		if (f)
			return f;
	}
	return NULL;
}

static double
light_range(const struct aiNode *n)
{
	const struct aiMetadata *md = n->mMetaData;

	for (unsigned i = 0; md && i < md->mNumProperties; i++)
		if (!strcmp(md->mKeys[i].data, "PBR_LightRange")) {
			if (md->mValues[i].mType == AI_FLOAT)
				return *(const float *)md->mValues[i].mData;
			if (md->mValues[i].mType == AI_DOUBLE)
				return *(const double *)md->mValues[i].mData;
		}
	return 0;
}

/*
 * KHR_lights_punctual: intensity in candela (point, spot) or lux
 * (directional), which assimp multiplies into the colour.  Converted to
 * the scene's radiometric units at 683 lm/W (the photopic peak): a light
 * of I cd gives I / 683 W/sr, in the units of the scene's radiances, so
 * that 683 cd at 1 m give an irradiance of 1.
 */
static int
load_lights(struct rf__loader *ld)
{
	const struct aiScene *sc = ld->sc;
	rf_scene *s = ld->s;
	struct rf__light *lights;

	if (!sc->mNumLights)
		return 0;
	lights = realloc(s->lights, (s->nlights + sc->mNumLights) * sizeof(*lights));
	if (!lights)
		return RF_ENOMEM;
	s->lights = lights;
	for (unsigned i = 0; i < sc->mNumLights; i++) {
		const struct aiLight *al = sc->mLights[i];
		const struct aiNode *node = find_node(sc->mRootNode, &al->mName);
		struct rf__light *l = &s->lights[s->nlights];
		struct aiVector3D o = al->mPosition;
		double w[16];

		if (al->mType != aiLightSource_POINT && al->mType != aiLightSource_SPOT &&
		    al->mType != aiLightSource_DIRECTIONAL)
			continue;
		memset(l, 0, sizeof(*l));
		l->kind = al->mType == aiLightSource_POINT ? RF__LIGHT_POINT
		          : al->mType == aiLightSource_SPOT ? RF__LIGHT_SPOT
		                                             : RF__LIGHT_DIRECTIONAL;
		l->line = ld->rq->line;
		node_world(ld->rq, node, w);
		for (int k = 0; k < 3; k++)
			l->position[k] = w[4 * k] * o.x + w[4 * k + 1] * o.y + w[4 * k + 2] * o.z +
			                 w[4 * k + 3];
		xform_dir(w, 4, &al->mDirection, l->direction);
		if (l->kind != RF__LIGHT_POINT && !(rf__normalize(l->direction) > 0))
			return rf__format(ld->err, ld->errlen, "'%s': light '%s' points nowhere",
			                  ld->rq->path, al->mName.data), RF_EFORMAT;
		l->colour[0] = al->mColorDiffuse.r / 683.0f;
		l->colour[1] = al->mColorDiffuse.g / 683.0f;
		l->colour[2] = al->mColorDiffuse.b / 683.0f;
		l->range = node ? light_range(node) : 0;
		l->inner_cone = al->mAngleInnerCone;
		l->outer_cone = al->mAngleOuterCone;
		if (!finite3(l->position) || !isfinite(l->colour[0] + l->colour[1] + l->colour[2]) ||
		    l->colour[0] < 0 || l->colour[1] < 0 || l->colour[2] < 0 ||
		    !(l->range >= 0) || (l->kind == RF__LIGHT_SPOT &&
		                         !(l->inner_cone >= 0 && l->inner_cone < l->outer_cone &&
		                           l->outer_cone <= 1.5707964)))
			return rf__format(ld->err, ld->errlen, "'%s': light '%s' is not one glTF "
			                  "allows (colour, intensity, range or cone angles)",
			                  ld->rq->path, al->mName.data), RF_EFORMAT;
		s->nlights++;
	}
	return 0;
}

/* ---- the whole ----------------------------------------------------------- */

void
rf__mesh_free(struct rf__mesh *m)
{
	size_t i;

	for (i = 0; i < m->nmaterials; i++)
		free(m->materials[i].name);
	free(m->materials);
	free(m->path);
	free(m->positions);
	free(m->normals);
	free(m->tangents);
	free(m->uv[0]);
	free(m->uv[1]);
	free(m->indices);
	free(m->material);
	memset(m, 0, sizeof(*m));
}

static int
ext_is(const char *path, const char *ext)
{
	size_t n = strlen(path), e = strlen(ext);

	return n > e && !strcasecmp(path + n - e, ext);
}

/*
 * An OBJ's material libraries must be there: assimp reads on without a
 * missing one, with default materials, and the surfaces would be wrong
 * without a word.  assimp takes the rest of the mtllib line as one file
 * name, and so does this.
 */
static int
obj_mtllibs(const char *path, const char *dir, char *err, size_t errlen)
{
	char line[4096], *name, *end, *file;
	FILE *fp = fopen(path, "r");
	size_t len;
	int rc = 0, whole = 1;

	if (!fp) {
		rf__format(err, errlen, "cannot open '%s': %s", path, strerror(errno));
		return RF_EIO;
	}
	while (rc == 0 && fgets(line, sizeof(line), fp)) {
		/* only the start of a line can be a statement */
		int start = whole;

		len = strlen(line);
		whole = len && line[len - 1] == '\n';
		if (!start)
			continue;
		for (name = line; *name == ' ' || *name == '\t'; name++)
			;
		if (strncmp(name, "mtllib", 6) || (name[6] != ' ' && name[6] != '\t'))
			continue;
		for (name += 6; *name == ' ' || *name == '\t'; name++)
			;
		for (end = name + strlen(name); end > name && strchr(" \t\r\n", end[-1]); end--)
			;
		*end = '\0';
		if (!*name)
			continue;
		if (!(file = malloc(strlen(dir) + strlen(name) + 1))) {
			rc = RF_ENOMEM;
			break;
		}
		sprintf(file, "%s%s", name[0] == '/' ? "" : dir, name);
		if (access(file, R_OK) < 0) {
			rf__format(err, errlen, "'%s': cannot open its material library '%s': %s",
			           path, file, strerror(errno));
			rc = RF_EIO;
		}
		free(file);
	}
	fclose(fp);
	return rc;
}

static int
build(struct rf__loader *ld, struct rf__mesh *m)
{
	struct fill fl;
	size_t nv = 0, nt = 0, i;
	int uv1 = 0, rc;

	if (count(ld, ld->sc->mRootNode, &nv, &nt, &uv1) < 0)
		return rf__format(ld->err, ld->errlen, "'%s': more than %zu vertices or "
		                  "triangles", ld->rq->path, VERTICES_MAX), RF_ETOOBIG;
	if (!nt)
		return rf__format(ld->err, ld->errlen, "'%s': no triangles (a mesh statement "
		                  "needs surfaces; points and lines are not drawn)",
		                  ld->rq->path), RF_EFORMAT;
	memset(&fl, 0, sizeof(fl));
	fl.ld = ld;
	fl.m = m;
	m->nvertices = nv;
	m->ntriangles = nt;
	m->positions = malloc(3 * nv * sizeof(float));
	m->normals = malloc(3 * nv * sizeof(float));
	m->tangents = malloc(4 * nv * sizeof(float));
	m->uv[0] = malloc(2 * nv * sizeof(float));
	m->uv[1] = uv1 ? malloc(2 * nv * sizeof(float)) : NULL;
	m->indices = malloc(3 * nt * sizeof(uint32_t));
	m->material = malloc(nt * sizeof(uint32_t));
	fl.gen_n = malloc(nv);
	fl.gen_t = malloc(nv);
	if (!m->positions || !m->normals || !m->tangents || !m->uv[0] || (uv1 && !m->uv[1]) ||
	    !m->indices || !m->material || !fl.gen_n || !fl.gen_t)
		rc = RF_ENOMEM;
	else
		rc = fill_node(&fl, ld->sc->mRootNode);
	if (rc == 0)
		rc = rf__mesh_normals(m, fl.gen_n);
	if (rc == 0)
		rc = rf__mesh_tangents(m, fl.gen_t);
	free(fl.gen_n);
	free(fl.gen_t);
	if (rc < 0)
		return rc;
	for (i = 0; i < 3; i++) {
		m->bounds[i] = INFINITY;
		m->bounds[3 + i] = -INFINITY;
	}
	for (size_t v = 0; v < nv; v++)
		for (i = 0; i < 3; i++) {
			float x = m->positions[3 * v + i];

			m->bounds[i] = x < m->bounds[i] ? x : m->bounds[i];
			m->bounds[3 + i] = x > m->bounds[3 + i] ? x : m->bounds[3 + i];
		}
	return 0;
}

int
rf__mesh_load(rf_scene *s, const struct rf__mesh_request *rq, char *err, size_t errlen)
{
	struct rf__loader ld;
	struct rf__mesh m;
	struct aiPropertyStore *props;
	const char *slash;
	size_t nlights = s->nlights;
	int rc;

	memset(&ld, 0, sizeof(ld));
	memset(&m, 0, sizeof(m));
	ld.s = s;
	ld.rq = rq;
	ld.err = err;
	ld.errlen = errlen;
	if (ext_is(rq->path, ".gltf") || ext_is(rq->path, ".glb"))
		ld.gltf = 1;
	else if (!ext_is(rq->path, ".obj")) {
		rf__format(err, errlen, "'%s': expected a glTF 2.0 (.gltf, .glb) or Wavefront "
		           "OBJ (.obj) file", rq->path);
		return RF_EFORMAT;
	}
	if ((rc = rf__regular_file(rq->path, err, errlen)) < 0)
		return rc;
	if (access(rq->path, R_OK) < 0) {
		rf__format(err, errlen, "cannot open '%s': %s", rq->path, strerror(errno));
		return RF_EIO;
	}
	if (ld.gltf && (rc = rf__gltf_check(rq->path, &ld.gltf_info, err, errlen)) < 0) {
		rf__gltf_info_free(&ld.gltf_info);
		return rc;
	}
	slash = strrchr(rq->path, '/');
	if (!(ld.dir = strndup(rq->path, slash ? (size_t)(slash - rq->path) + 1 : 0)) ||
	    !(props = aiCreatePropertyStore())) {
		free(ld.dir);
		rf__gltf_info_free(&ld.gltf_info);
		return RF_ENOMEM;
	}
	if (!ld.gltf && (rc = obj_mtllibs(rq->path, ld.dir, err, errlen)) < 0) {
		free(ld.dir);
		aiReleasePropertyStore(props);
		return rc;
	}
	/* Points and lines stay, in meshes of their own that give no
	 * triangle: removed, a file of lines alone would be an error of
	 * assimp's own wording instead of "no triangles". */
	ld.sc = aiImportFileExWithProperties(rq->path, aiProcess_Triangulate |
	                                     aiProcess_JoinIdenticalVertices |
	                                     aiProcess_SortByPType, NULL, props);
	aiReleasePropertyStore(props);
	if (!ld.sc) {
		const char *why = aiGetErrorString();

		rf__format(err, errlen, "'%s': not a mesh reflect can read (%s)", rq->path,
		           why && *why ? why : "assimp gives no reason");
		free(ld.dir);
		rf__gltf_info_free(&ld.gltf_info);
		return RF_EFORMAT;
	}
	if (!ld.sc->mRootNode || !ld.sc->mNumMeshes) {
		rf__format(err, errlen, "'%s': no triangles (a mesh statement needs "
		           "surfaces; points and lines are not drawn)", rq->path);
		rc = RF_EFORMAT;
	}
	if (rc == 0)
		rc = build(&ld, &m);
	if (rc == 0)
		rc = rf__mesh_materials(&ld, &m);
	if (rc == 0)
		rc = load_lights(&ld);
	if (rc == 0 && !(m.path = strdup(rq->path)))
		rc = RF_ENOMEM;
	aiReleaseImport(ld.sc);
	free(ld.dir);
	free(ld.loaded);
	rf__gltf_info_free(&ld.gltf_info);
	m.line = rq->line;
	if (rc == 0)
		rc = rf__scene_add_mesh(s, &m, err, errlen);
	if (rc < 0) {
		rf__mesh_free(&m);
		s->nlights = nlights;
		if (rc == RF_ENOMEM)
			rf__format(err, errlen, "'%s': %s", rq->path, rf_strerror(rc));
		return rc;
	}
	/* lit surfaces send light out as emitting ones do */
	if (s->nlights)
		s->has_emission = 1;
	return 0;
}
