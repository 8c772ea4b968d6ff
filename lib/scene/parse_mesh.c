/*
 * The mesh statement of reflect-scene(5): its file, transform and
 * material overrides, read into a request that mesh.c loads.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parser.h"

#define MESH_WORDS "translate, rotate, scale, matrix, roughness, smoothness, " \
	"metallic, albedo, emission, reflective or material NAME"

/* rotate DEG AX AY AZ: counter-clockwise about the axis seen from its
 * tip (right-handed), by Rodrigues' formula. */
static int
mesh_rotate(struct parser *p, const struct rf__token *key, double r[16])
{
	double v[4], c, s, t, x, y, z, len;
	int rc;

	if ((rc = rf__parse_numbers(p, "rotate", v, 4)) < 0)
		return rc;
	len = sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
	if (!(len > 0))
		return FAIL_TOK(p, key, "expected a non-zero axis after the angle of "
		                "'rotate'");
	x = v[1] / len, y = v[2] / len, z = v[3] / len;
	c = cos(v[0] * 3.14159265358979323846 / 180.0);
	s = sin(v[0] * 3.14159265358979323846 / 180.0);
	t = 1 - c;
	memset(r, 0, 16 * sizeof(*r));
	r[0] = t * x * x + c, r[1] = t * x * y - s * z, r[2] = t * x * z + s * y;
	r[4] = t * x * y + s * z, r[5] = t * y * y + c, r[6] = t * y * z - s * x;
	r[8] = t * x * z - s * y, r[9] = t * y * z + s * x, r[10] = t * z * z + c;
	r[15] = 1;
	return 0;
}

/* scale S, or SX SY SZ: non-zero (a negative one mirrors). */
static int
mesh_scale(struct parser *p, const struct rf__token *key, double sc[3])
{
	int rc, i;

	if ((rc = rf__parse_number(p, "scale", &sc[0])) < 0)
		return rc;
	sc[1] = sc[2] = sc[0];
	if (p->pos < p->lx.ntok && !p->lx.tok[p->pos].owned &&
	    strchr("0123456789.+-", p->lx.tok[p->pos].text[0]))
		if ((rc = rf__parse_number(p, "scale", &sc[1])) < 0 ||
		    (rc = rf__parse_number(p, "scale", &sc[2])) < 0)
			return rc;
	for (i = 0; i < 3; i++)
		if (!(sc[i] != 0))
			return FAIL_TOK(p, key, "expected non-zero scales, found %g %g %g", sc[0],
			                sc[1], sc[2]);
	return 0;
}

/* A material attribute of a mesh statement into its override. */
static int
mesh_material_attribute(struct parser *p, const struct rf__token *key,
                        struct rf__mesh_override *o)
{
	static const char *const words[] = { "roughness", "smoothness", "metallic", "albedo",
		                             "emission", "reflective", NULL };
	static const unsigned bits[] = { RF__OVR_ROUGHNESS, RF__OVR_ROUGHNESS, RF__OVR_METALLIC,
		                         RF__OVR_ALBEDO, RF__OVR_EMISSION, RF__OVR_MASK };
	struct material m;
	int i, rc;

	for (i = 0; words[i]; i++)
		if (rf__tok_is(key, words[i]))
			break;
	if (!words[i])
		return 0;
	rf__material_default(&m, 0);
	if ((rc = rf__parse_material_attribute(p, key, &m)) < 0)
		return rc;
	o->set |= bits[i];
	if (bits[i] == RF__OVR_ROUGHNESS)
		o->roughness = m.roughness;
	if (bits[i] == RF__OVR_METALLIC)
		o->metallic = m.metallic;
	if (bits[i] == RF__OVR_ALBEDO)
		memcpy(o->albedo, m.albedo, sizeof(o->albedo));
	if (bits[i] == RF__OVR_EMISSION)
		memcpy(o->emission, m.em.rgb, sizeof(o->emission));
	if (bits[i] == RF__OVR_MASK)
		o->mask = m.mask;
	return 1;
}

static void
overrides_free(struct rf__mesh_override *o, size_t n)
{
	size_t i;

	for (i = 0; i < n; i++)
		free(o[i].material);
	free(o);
}

int
rf__parse_mesh(struct parser *p, const struct rf__token *kw)
{
	struct rf__mesh_override *ovr, *grown;
	struct rf__mesh_request rq;
	const struct rf__token *file, *key, *t, *matrix = NULL, *trs = NULL;
	double T[16] = { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }, R[16], S[16], v[3];
	size_t novr = 1;
	char *path = NULL, msg[1024];
	int rc;

	memcpy(R, T, sizeof(R));
	memcpy(S, T, sizeof(S));
	memset(&rq, 0, sizeof(rq));
	if ((rc = rf__parse_word(p, "a mesh file (.gltf, .glb or .obj) after 'mesh'",
	                         &file)) < 0)
		return rc;
	if (!(ovr = calloc(1, sizeof(*ovr))))
		return RF_ENOMEM;
	while ((rc = rf__parse_attribute(p, &key)) > 0) {
		if (rf__tok_is(key, "material")) {
			if ((rc = rf__parse_word(p, "a material name after 'material'", &t)) < 0)
				break;
			if (!(grown = realloc(ovr, (novr + 1) * sizeof(*ovr)))) {
				rc = RF_ENOMEM;
				break;
			}
			ovr = grown;
			memset(&ovr[novr], 0, sizeof(*ovr));
			ovr[novr].col = t->col;
			if (!(ovr[novr++].material = strndup(t->text, t->len))) {
				rc = RF_ENOMEM;
				break;
			}
			/* each material's attributes are its own: they may repeat
			 * those of the file's or of another material */
			p->nattrs = 0;
			continue;
		}
		if (rf__tok_is(key, "translate") || rf__tok_is(key, "rotate") ||
		    rf__tok_is(key, "scale") || rf__tok_is(key, "matrix")) {
			if (novr > 1) {
				rc = FAIL_TOK(p, key, "expected " TOKFMT " before the first "
				              "'material'", TOKARG(key));
				break;
			}
			if (rf__tok_is(key, "matrix") ? trs != NULL : matrix != NULL) {
				rc = FAIL_TOK(p, key, "expected either 'matrix' or 'translate', "
				              "'rotate' and 'scale', not both");
				break;
			}
			if (rf__tok_is(key, "translate")) {
				trs = key;
				if ((rc = rf__parse_numbers(p, "translate", v, 3)) >= 0)
					T[3] = v[0], T[7] = v[1], T[11] = v[2];
			} else if (rf__tok_is(key, "rotate")) {
				trs = key;
				rc = mesh_rotate(p, key, R);
			} else if (rf__tok_is(key, "scale")) {
				trs = key;
				if ((rc = mesh_scale(p, key, v)) >= 0)
					S[0] = v[0], S[5] = v[1], S[10] = v[2];
			} else {
				matrix = key;
				rc = rf__parse_numbers(p, "matrix", rq.matrix, 16);
			}
		} else if ((rc = mesh_material_attribute(p, key, &ovr[novr - 1])) == 0)
			rc = rf__parse_unknown_attribute(p, key, "mesh", MESH_WORDS);
		if (rc < 0)
			break;
	}
	if (rc >= 0 && matrix) {
		const double *m = rq.matrix;
		double det = m[0] * (m[5] * m[10] - m[6] * m[9]) -
		             m[1] * (m[4] * m[10] - m[6] * m[8]) +
		             m[2] * (m[4] * m[9] - m[5] * m[8]);

		if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1)
			rc = FAIL_TOK(p, matrix, "expected the matrix's last row to be 0 0 0 1, "
			              "found %g %g %g %g", m[12], m[13], m[14], m[15]);
		else if (!(fabs(det) > 1e-12))
			rc = FAIL_TOK(p, matrix, "expected a matrix that does not flatten the "
			              "mesh (its determinant is %g)", det);
	} else if (rc >= 0) {
		/* scale, then rotate, then translate */
		rf__mat4_mul(R, S, rq.matrix);
		rf__mat4_mul(T, rq.matrix, rq.matrix);
	}
	if (rc >= 0)
		rc = rf__parse_path(p, file, &path);
	if (rc >= 0) {
		rq.path = path;
		rq.line = kw->line;
		/* the file's overrides apply first, the named ones after */
		rq.overrides = ovr[0].set ? ovr : ovr + 1;
		rq.noverrides = ovr[0].set ? novr : novr - 1;
		rc = rf__mesh_load(p->s, &rq, msg, sizeof(msg));
		if (rc < 0 && rc != RF_ENOMEM)
			rc = FAIL_TOK(p, file, "%s", msg);
	}
	free(path);
	overrides_free(ovr, novr);
	return rc < 0 ? rc : 0;
}
