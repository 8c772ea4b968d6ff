/*
 * The scene text format (reflect-scene(5)): one statement a line, a
 * keyword then attributes as `name value...`, '#' comments, '\' at the
 * end of a line to continue it, "double quotes" around words with spaces.
 * Every error names file:line:column and what was expected there.
 */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/parser.h"

#define SCENE_BYTES_MAX ((size_t)64 << 20)
/* Reads the next statement's tokens: 1, or 0 at the end of the text. */
static int
next_statement(struct parser *p)
{
	p->pos = 0;
	p->nattrs = 0;
	return rf__lexer_next(&p->lx);
}

/* ---- values -------------------------------------------------------------- */

static int
tok_is(const struct rf__token *t, const char *word)
{
	return !t->owned && t->len == strlen(word) && !memcmp(t->text, word, t->len);
}

static const struct rf__token *
take(struct parser *p)
{
	return p->pos < p->lx.ntok ? &p->lx.tok[p->pos++] : NULL;
}


static int
number(struct parser *p, const char *what, double *v)
{
	const struct rf__token *t = take(p);
	char buf[64];
	char *end;
	size_t i;

	if (!t)
		return FAIL_END(p, "expected a number for '%s', found the end of the "
		                "line", what);
	for (i = 0; i < t->len; i++)
		if (!strchr("0123456789+-.eE", t->text[i]))
			break;
	if (t->owned || i < t->len || t->len >= sizeof(buf))
		return FAIL_TOK(p, t, "expected a number for '%s', found " TOKFMT, what,
		                TOKARG(t));
	memcpy(buf, t->text, t->len);
	buf[t->len] = '\0';
	errno = 0;
	*v = strtod(buf, &end);
	if (end == buf || *end || errno == ERANGE || !isfinite(*v))
		return FAIL_TOK(p, t, "expected a number for '%s', found " TOKFMT, what,
		                TOKARG(t));
	return 0;
}

static int
numbers(struct parser *p, const char *what, double *v, int n)
{
	int i, rc;

	for (i = 0; i < n; i++)
		if ((rc = number(p, what, &v[i])) < 0)
			return rc;
	return 0;
}

/* A number in [lo, hi]. */
static int
number_in(struct parser *p, const char *what, double lo, double hi, double *v)
{
	int rc = number(p, what, v);

	if (rc < 0)
		return rc;
	if (*v < lo || *v > hi)
		return FAIL_TOK(p, &p->lx.tok[p->pos - 1], "expected '%s' in [%g, %g], "
		                "found %g", what, lo, hi, *v);
	return 0;
}

static int
positive(struct parser *p, const char *what, double *v)
{
	int rc = number(p, what, v);

	if (rc < 0)
		return rc;
	if (!(*v > 0))
		return FAIL_TOK(p, &p->lx.tok[p->pos - 1], "expected a positive %s, found %g",
		                what, *v);
	return 0;
}

static int
word(struct parser *p, const char *what, const struct rf__token **t)
{
	if (!(*t = take(p)))
		return FAIL_END(p, "expected %s, found the end of the line", what);
	return 0;
}

static int
on_off(struct parser *p, const char *what, int *v)
{
	const struct rf__token *t;
	int rc;

	if ((rc = word(p, "on or off", &t)) < 0)
		return rc;
	if (tok_is(t, "on") || tok_is(t, "1") || tok_is(t, "yes"))
		*v = 1;
	else if (tok_is(t, "off") || tok_is(t, "0") || tok_is(t, "no"))
		*v = 0;
	else
		return FAIL_TOK(p, t, "expected on or off for '%s', found " TOKFMT, what,
		                TOKARG(t));
	return 0;
}

/* R G B of a radiance: finite, at least 0. */
static int
radiance(struct parser *p, const char *what, float rgb[3])
{
	double v;
	int rc, i;

	for (i = 0; i < 3; i++) {
		if ((rc = number_in(p, what, 0, 1e30, &v)) < 0)
			return rc;
		rgb[i] = (float)v;
	}
	return 0;
}

/* A copy of a path, relative ones taken from the scene file's directory. */
static int
resolve_path(struct parser *p, const struct rf__token *t, char **out)
{
	size_t dlen = p->dir && t->text[0] != '/' ? strlen(p->dir) : 0;
	char *s;

	if (!t->len)
		return FAIL_TOK(p, t, "expected a file name, found an empty word");
	if (memchr(t->text, '\0', t->len))
		return FAIL_TOK(p, t, "expected a file name without NUL bytes");
	if (!(s = malloc(dlen + 1 + t->len + 1)))
		return RF_ENOMEM;
	if (dlen) {
		memcpy(s, p->dir, dlen);
		s[dlen] = '/';
		memcpy(s + dlen + 1, t->text, t->len);
		s[dlen + 1 + t->len] = '\0';
	} else {
		memcpy(s, t->text, t->len);
		s[t->len] = '\0';
	}
	*out = s;
	return 0;
}

/* The next attribute name, refusing one given twice.  NULL at the end. */
static int
attribute(struct parser *p, const struct rf__token **key)
{
	size_t i;

	*key = take(p);
	if (!*key)
		return 0;
	for (i = 0; i < p->nattrs; i++)
		if (p->attrs[i]->len == (*key)->len &&
		    !memcmp(p->attrs[i]->text, (*key)->text, (*key)->len))
			return FAIL_TOK(p, *key, "expected each attribute once, " TOKFMT
			                " was given at column %zu already", TOKARG(*key),
			                p->attrs[i]->col);
	if (p->nattrs < ATTRS_MAX)
		p->attrs[p->nattrs++] = *key;
	return 1;
}

static const struct rf__token *
seen(const struct parser *p, const char *name)
{
	size_t i;

	for (i = 0; i < p->nattrs; i++)
		if (tok_is(p->attrs[i], name))
			return p->attrs[i];
	return NULL;
}

/* ---- materials ------------------------------------------------------------ */

#define MATERIAL_WORDS "roughness, smoothness, metallic, albedo, reflective, " \
	"emission, pattern, normalmap, strength, scale, tiling, offset"

/* 1 when key was a material attribute (and its value is read), 0 when it
 * is not one, < 0 on error. */
static int
material_attribute(struct parser *p, const struct rf__token *key, struct material *m)
{
	double v, vv[3];
	int rc, on, i;

	if (tok_is(key, "roughness") || tok_is(key, "smoothness")) {
		const struct rf__token *other = seen(p, tok_is(key, "roughness") ? "smoothness"
		                                                              : "roughness");

		if (other)
			return FAIL_TOK(p, key, "expected 'roughness' or 'smoothness', not "
			                "both (the other is at column %zu)", other->col);
		if ((rc = number_in(p, tok_is(key, "roughness") ? "roughness" : "smoothness",
		                    0, 1, &v)) < 0)
			return rc;
		m->roughness = (float)(tok_is(key, "roughness") ? v : 1.0 - v);
	} else if (tok_is(key, "metallic")) {
		if ((rc = number_in(p, "metallic", 0, 1, &v)) < 0)
			return rc;
		m->metallic = (float)v;
	} else if (tok_is(key, "albedo")) {
		for (i = 0; i < 3; i++) {
			if ((rc = number_in(p, "albedo", 0, 1, &vv[i])) < 0)
				return rc;
			m->albedo[i] = (float)vv[i];
		}
	} else if (tok_is(key, "emission") || tok_is(key, "pattern")) {
		const struct rf__token *other = seen(p, tok_is(key, "emission") ? "pattern"
		                                                              : "emission");

		if (other)
			return FAIL_TOK(p, key, "expected 'emission' or 'pattern', not both "
			                "(the other is at column %zu)", other->col);
		if ((rc = radiance(p, tok_is(key, "emission") ? "emission" : "pattern",
		                   m->em.rgb)) < 0)
			return rc;
		m->em.kind = tok_is(key, "emission") ? EMIT_COLOUR : EMIT_PATTERN;
		p->s->has_emission = 1;
	} else if (tok_is(key, "reflective")) {
		if ((rc = on_off(p, "reflective", &on)) < 0)
			return rc;
		m->mask = on ? 1.0f : 0.0f;
	} else if (tok_is(key, "normalmap")) {
		const struct rf__token *t;

		if ((rc = word(p, "tiles, bumps, noise, image FILE or none", &t)) < 0)
			return rc;
		if (tok_is(t, "tiles"))
			m->nm.kind = NM_TILES;
		else if (tok_is(t, "bumps"))
			m->nm.kind = NM_BUMPS;
		else if (tok_is(t, "noise"))
			m->nm.kind = NM_NOISE;
		else if (tok_is(t, "none"))
			m->nm.kind = NM_NONE;
		else if (tok_is(t, "image")) {
			const rf_image *img;
			char *path, msg[400];

			if ((rc = word(p, "an image file after 'normalmap image'", &t)) < 0)
				return rc;
			if ((rc = resolve_path(p, t, &path)) < 0)
				return rc;
			rc = rf__scene_image(p->s, path, 2, "normal map", &img, msg, sizeof(msg));
			free(path);
			if (rc == RF_ENOMEM)
				return rc;
			if (rc < 0)
				return FAIL_TOK(p, t, "%s", msg);
			m->nm.kind = NM_IMAGE;
			m->nm.pixels = rf_image_pixels(img);
			m->nm.width = rf_image_width(img);
			m->nm.height = rf_image_height(img);
			m->nm.nchannels = rf_image_nchannels(img);
		} else
			return FAIL_TOK(p, t, "expected tiles, bumps, noise, image FILE or "
			                "none for 'normalmap', found " TOKFMT, TOKARG(t));
	} else if (tok_is(key, "strength")) {
		if ((rc = number_in(p, "strength", 0, 1e6, &v)) < 0)
			return rc;
		m->nm.strength = v;
	} else if (tok_is(key, "scale")) {
		if ((rc = positive(p, "scale", &v)) < 0)
			return rc;
		m->nm.inv_scale = 1.0 / v;
	} else if (tok_is(key, "tiling")) {
		if ((rc = numbers(p, "tiling", vv, 2)) < 0)
			return rc;
		if (vv[0] == 0 || vv[1] == 0)
			return FAIL_TOK(p, &p->lx.tok[p->pos - 1], "expected non-zero tiling, "
			                "found %g %g", vv[0], vv[1]);
		m->nm.tiling[0] = vv[0];
		m->nm.tiling[1] = vv[1];
	} else if (tok_is(key, "offset")) {
		if ((rc = numbers(p, "offset", vv, 2)) < 0)
			return rc;
		m->nm.offset[0] = vv[0];
		m->nm.offset[1] = vv[1];
	} else {
		return 0;
	}
	return 1;
}

/* Normal map settings without a normal map are a slip worth naming. */
static int
material_check(struct parser *p)
{
	static const char *const nm_words[] = { "strength", "scale", "tiling", "offset",
		                                NULL };
	const struct rf__token *t;
	int i;

	if (seen(p, "normalmap"))
		return 0;
	for (i = 0; nm_words[i]; i++)
		if ((t = seen(p, nm_words[i])))
			return FAIL_TOK(p, t, "expected a 'normalmap' for " TOKFMT,
			                TOKARG(t));
	return 0;
}

/* ---- statements ---------------------------------------------------------- */

static int
unknown_attribute(struct parser *p, const struct rf__token *key, const char *what,
                  const char *expected)
{
	return FAIL_TOK(p, key, "unknown %s attribute " TOKFMT " (expected %s)", what,
	                TOKARG(key), expected);
}

/* The helpers above, for the statements parsed in files of their own
 * (parser.h). */
int
rf__tok_is(const struct rf__token *t, const char *w)
{
	return tok_is(t, w);
}

int
rf__parse_number(struct parser *p, const char *what, double *v)
{
	return number(p, what, v);
}

int
rf__parse_numbers(struct parser *p, const char *what, double *v, int n)
{
	return numbers(p, what, v, n);
}

int
rf__parse_word(struct parser *p, const char *what, const struct rf__token **t)
{
	return word(p, what, t);
}

int
rf__parse_path(struct parser *p, const struct rf__token *t, char **out)
{
	return resolve_path(p, t, out);
}

int
rf__parse_attribute(struct parser *p, const struct rf__token **key)
{
	return attribute(p, key);
}

int
rf__parse_material_attribute(struct parser *p, const struct rf__token *key,
                             struct material *m)
{
	return material_attribute(p, key, m);
}

int
rf__parse_unknown_attribute(struct parser *p, const struct rf__token *key,
                            const char *what, const char *expected)
{
	return unknown_attribute(p, key, what, expected);
}

static int
missing(struct parser *p, const struct rf__token *kw, const char *what)
{
	return FAIL_TOK(p, kw, "expected %s on this line", what);
}

/* The camera from a 4x4 camera-to-world matrix, rows as written:
 * columns right, up, back (the camera looks along -Z, as in OpenGL and
 * Blender), position. */
static int
camera_from_matrix(struct parser *p, const struct rf__token *at, const double m[16],
                   struct rf_camera *c)
{
	double back[3] = { m[2], m[6], m[10] };
	int i;

	if (fabs(m[12]) > 1e-9 || fabs(m[13]) > 1e-9 || fabs(m[14]) > 1e-9 ||
	    fabs(m[15] - 1) > 1e-9)
		return FAIL_TOK(p, at, "expected the matrix's last row to be 0 0 0 1, "
		                "found %g %g %g %g", m[12], m[13], m[14], m[15]);
	if (!(rf__normalize(back) > 0))
		return FAIL_TOK(p, at, "expected a matrix whose third column (the "
		                "camera's back) is not zero");
	for (i = 0; i < 3; i++) {
		c->position[i] = m[4 * i + 3];
		c->target[i] = c->position[i] - back[i];
		c->up[i] = m[4 * i + 1];
	}
	return 0;
}

static int
parse_camera(struct parser *p, const struct rf__token *kw)
{
	struct rf_camera c = { { 0, 0, 0 }, { 0, 0, -1 }, { 0, 1, 0 }, 60.0 };
	const struct rf__token *key;
	double m[16];
	char msg[256];
	int rc;

	if (p->camera_line)
		return FAIL_TOK(p, kw, "expected one 'camera' line, the first is line %zu",
		                p->camera_line);
	p->camera_line = kw->line;
	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "position"))
			rc = numbers(p, "position", c.position, 3);
		else if (tok_is(key, "target"))
			rc = numbers(p, "target", c.target, 3);
		else if (tok_is(key, "up"))
			rc = numbers(p, "up", c.up, 3);
		else if (tok_is(key, "fov"))
			rc = number(p, "fov", &c.fov);
		else if (tok_is(key, "matrix"))
			rc = numbers(p, "matrix", m, 16);
		else
			return unknown_attribute(p, key, "camera",
			                         "position, target, up, fov or matrix");
		if (rc < 0)
			return rc;
	}
	if (rc < 0)
		return rc;
	if ((key = seen(p, "matrix"))) {
		const struct rf__token *other = seen(p, "position");

		if (!other)
			other = seen(p, "target");
		if (!other)
			other = seen(p, "up");
		if (other)
			return FAIL_TOK(p, other, "expected either 'matrix' or 'position' "
			                "and 'target', not both");
		if ((rc = camera_from_matrix(p, key, m, &c)) < 0)
			return rc;
	} else if (!seen(p, "position") || !seen(p, "target")) {
		return missing(p, kw, "'position X Y Z' and 'target X Y Z', or 'matrix' "
		               "and 16 numbers");
	}
	if (rf_camera_check(&c, msg, sizeof(msg)) < 0)
		return FAIL_TOK(p, kw, "%s", msg);
	p->s->camera = c;
	return 0;
}

static int
box_check(struct parser *p, const struct rf__token *at, const double *mn,
          const double *mx, int dims, const char *axes)
{
	int i;

	for (i = 0; i < dims; i++)
		if (!(mn[i] < mx[i]))
			return FAIL_TOK(p, at, "expected min < max on every axis, the box "
			                "is empty on %c (min %g, max %g)", axes[i], mn[i],
			                mx[i]);
	return 0;
}

/*
 * A value that the stream's header carries (the scene's name, a probe's
 * env): a header line holds RF_HEADER_LINE_MAX bytes with its key, and
 * no control byte.  Refused here, at its line, since the writer that
 * would refuse it later has no line to name.
 */
#define HEADER_VALUE_MAX (RF_HEADER_LINE_MAX + 1 - sizeof("PROBE4294967295_ENV="))

static int
header_value(struct parser *p, size_t line, size_t col, const char *what, const char *v,
             size_t n)
{
	size_t i;

	if (n > HEADER_VALUE_MAX)
		return fail_at(p, line, col, "expected %s of at most %zu bytes, since the "
		               "stream's header carries it; it is %zu", what,
		               (size_t)HEADER_VALUE_MAX, n);
	for (i = 0; i < n; i++)
		if ((unsigned char)v[i] < 0x20 || v[i] == 0x7f)
			return fail_at(p, line, col, "expected %s without control characters "
			               "(byte %zu is 0x%02x), since the stream's header carries it",
			               what, i + 1, (unsigned char)v[i]);
	return 0;
}

/* "env capture": the environment is probe k (from 0) of this scene
 * file, baked by whoever reads it (reflect-shade), as capture:FILE#K. */
static int
capture_env(struct parser *p, size_t k, const char **env)
{
	const char *file = !strcmp(p->name, "<default>") ? "default" : p->name;
	size_t n = strlen(file) + 40;
	char *s = malloc(n);

	if (!s)
		return RF_ENOMEM;
	snprintf(s, n, "capture:%s#%zu", file, k + 1);
	*env = s;
	return 0;
}

/*
 * A probe that names no env reflects the embedded room, which is the
 * default scene's own; in a scene that emits, that room is not what
 * the probe would see, and its reflections would be of another room
 * without a word.  There the probe is captured from the scene, as
 * "env capture" asks; "env default" still asks for the embedded room.
 */
static int
envless_probes(struct parser *p)
{
	size_t i;
	int rc = 0;

	for (i = 0; i < p->nenvless && p->s->has_emission && rc == 0; i++) {
		const struct envless *e = &p->envless[i];
		const char **env = &p->s->probes[e->probe].env;

		if ((rc = capture_env(p, e->probe, env)) == 0)
			rc = header_value(p, e->line, e->col, "the capture of this scene (the "
			                  "probe names no env, and the scene emits)", *env,
			                  strlen(*env));
	}
	return rc;
}

static int
parse_probe(struct parser *p, const struct rf__token *kw)
{
	struct rf_scene_probe pr, *probes;
	const struct rf__token *key, *t;
	double box[6], radius = 0.0;
	int rc, i;

	memset(&pr, 0, sizeof(pr));
	pr.blend = 1.0;
	pr.box_projection = 1;
	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "center") || tok_is(key, "centre"))
			rc = numbers(p, "center", pr.center, 3);
		else if (tok_is(key, "box"))
			rc = numbers(p, "box", box, 6);
		else if (tok_is(key, "blend")) {
			/* one distance, or six: +x -x +y -y +z -z */
			if ((rc = number_in(p, "blend", 0, 1e9, &pr.blend)) >= 0 &&
			    p->pos < p->lx.ntok && !p->lx.tok[p->pos].owned &&
			    strchr("0123456789.+-", p->lx.tok[p->pos].text[0])) {
				pr.face_blend[0] = pr.blend;
				for (i = 1; i < 6 && rc >= 0; i++)
					rc = number_in(p, "blend (six: +x -x +y -y +z -z)", 0, 1e9,
					               &pr.face_blend[i]);
				pr.per_face = 1;
				for (i = 0; i < 6; i++)
					pr.blend = pr.face_blend[i] > pr.blend ? pr.face_blend[i]
					                                       : pr.blend;
			}
		} else if (tok_is(key, "importance")) {
			rc = number_in(p, "importance", -1e9, 1e9, &pr.importance);
		} else if (tok_is(key, "projection"))
			rc = on_off(p, "projection", &pr.box_projection);
		else if (tok_is(key, "env")) {
			if ((rc = word(p, "an environment file, 'default' or 'capture'", &t)) < 0)
				break;
			free((char *)pr.env);
			pr.env = NULL;
			if (tok_is(t, "capture"))
				rc = capture_env(p, p->s->nprobes, &pr.env);
			else if (!tok_is(t, "default"))
				rc = resolve_path(p, t, (char **)&pr.env);
			if (rc >= 0 && pr.env)
				rc = header_value(p, t->line, t->col, tok_is(t, "capture")
				                  ? "the capture of this scene file" : "an environment path",
				                  pr.env, strlen(pr.env));
		} else if ((rc = rf__parse_probe_shape(p, key, &pr, &radius)) == 0) {
			rc = unknown_attribute(p, key, "probe",
			                       "center, box, sphere, rotate, matrix, proxy, "
			                       "proxy_rotate, proxy_matrix, env, blend, importance "
			                       "or projection");
		}
		if (rc < 0)
			break;
	}
	if (rc >= 0 && pr.shape == RF_SHAPE_SPHERE) {
		/* the sphere is around the capture point: it needs one, and no box */
		if ((key = seen(p, "box")))
			rc = FAIL_TOK(p, key, "a probe is a box or a sphere, not both: remove "
			              "'box' or 'sphere'");
		else if (!seen(p, "center") && !seen(p, "centre"))
			rc = missing(p, kw, "'center X Y Z' (the sphere's centre)");
	} else if (rc >= 0 && !(key = seen(p, "box")))
		rc = missing(p, kw, "'box XMIN YMIN ZMIN XMAX YMAX ZMAX'");
	else if (rc >= 0) {
		for (i = 0; i < 3; i++) {
			pr.box_min[i] = box[i];
			pr.box_max[i] = box[i + 3];
		}
		rc = box_check(p, key, pr.box_min, pr.box_max, 3, "XYZ");
	}
	if (rc >= 0 && !seen(p, "center") && !seen(p, "centre"))
		for (i = 0; i < 3; i++)
			pr.center[i] = 0.5 * (pr.box_min[i] + pr.box_max[i]);
	if (rc >= 0)
		rc = rf__probe_shape_finish(p, kw, &pr, radius, p->s->nprobes);
	for (i = 0; rc >= 0 && !pr.rotated && i < 3; i++)
		if (!(pr.center[i] >= pr.box_min[i] && pr.center[i] <= pr.box_max[i])) {
			t = seen(p, "center") ? seen(p, "center") : seen(p, "centre");
			rc = FAIL_TOK(p, t, "expected the probe's centre inside its box, "
			              "(%g %g %g) is outside on %c [%g, %g]", pr.center[0],
			              pr.center[1], pr.center[2], "XYZ"[i], pr.box_min[i],
			              pr.box_max[i]);
		}
	if (rc >= 0 && !seen(p, "env")) {
		struct envless *e = realloc(p->envless, (p->nenvless + 1) * sizeof(*e));

		if (!e)
			rc = RF_ENOMEM;
		else {
			p->envless = e;
			e[p->nenvless].probe = p->s->nprobes;
			e[p->nenvless].line = kw->line;
			e[p->nenvless++].col = kw->col;
		}
	}
	if (rc >= 0) {
		probes = realloc(p->s->probes, (p->s->nprobes + 1) * sizeof(*probes));
		if (!probes)
			rc = RF_ENOMEM;
		else {
			p->s->probes = probes;
			probes[p->s->nprobes++] = pr;
			return 0;
		}
	}
	free((char *)pr.env);
	return rc;
}

static int
parse_room(struct parser *p, const struct rf__token *kw)
{
	const struct rf__token *key;
	int rc;

	if (p->room_line)
		return FAIL_TOK(p, kw, "expected one 'room' line, the first is line %zu",
		                p->room_line);
	p->room_line = kw->line;
	if (p->pos < p->lx.ntok && (tok_is(&p->lx.tok[p->pos], "on") ||
	                         tok_is(&p->lx.tok[p->pos], "off"))) {
		p->s->room = tok_is(&p->lx.tok[p->pos], "on");
		p->pos++;
	}
	while ((rc = attribute(p, &key)) > 0) {
		if ((rc = material_attribute(p, key, &p->s->room_mat)) < 0)
			return rc;
		if (!rc)
			return unknown_attribute(p, key, "room",
			                         "on, off or a material attribute ("
			                         MATERIAL_WORDS ")");
	}
	return rc < 0 ? rc : material_check(p);
}

static int
parse_name(struct parser *p, const struct rf__token *kw)
{
	const struct rf__token *t;
	char *name;
	int rc;

	if (p->name_line)
		return FAIL_TOK(p, kw, "expected one 'name' line, the first is line %zu",
		                p->name_line);
	p->name_line = kw->line;
	if ((rc = word(p, "a scene name", &t)) < 0 ||
	    (rc = header_value(p, t->line, t->col, "a name", t->text, t->len)) < 0)
		return rc;
	if (p->pos < p->lx.ntok)
		return FAIL_TOK(p, &p->lx.tok[p->pos], "expected the end of the line after "
		                "the name (quote a name with spaces)");
	if (!(name = malloc(t->len + 1)))
		return RF_ENOMEM;
	memcpy(name, t->text, t->len);
	name[t->len] = '\0';
	free(p->s->name);
	p->s->name = name;
	return 0;
}

static int
add_object(struct parser *p, const struct object *o)
{
	struct object *objs = realloc(p->s->objects, (p->s->nobjects + 1) * sizeof(*objs));

	if (!objs)
		return RF_ENOMEM;
	p->s->objects = objs;
	objs[p->s->nobjects] = *o;
	rf__object_prepare(&objs[p->s->nobjects]);
	p->s->nobjects++;
	return 0;
}

static int
parse_sphere(struct parser *p, const struct rf__token *kw, struct object *o)
{
	const struct rf__token *key;
	int rc;

	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "center") || tok_is(key, "centre"))
			rc = numbers(p, "center", o->center, 3);
		else if (tok_is(key, "radius"))
			rc = positive(p, "radius", &o->radius);
		else if (!(rc = material_attribute(p, key, &o->mat)))
			return unknown_attribute(p, key, "sphere", "center, radius or a "
			                         "material attribute (" MATERIAL_WORDS ")");
		if (rc < 0)
			return rc;
	}
	if (rc < 0)
		return rc;
	if (!seen(p, "center") && !seen(p, "centre"))
		return missing(p, kw, "'center X Y Z'");
	if (!seen(p, "radius"))
		return missing(p, kw, "'radius R'");
	return material_check(p);
}

static int
parse_box(struct parser *p, const struct rf__token *kw, struct object *o)
{
	const struct rf__token *key;
	int rc;

	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "min"))
			rc = numbers(p, "min", o->min, 3);
		else if (tok_is(key, "max"))
			rc = numbers(p, "max", o->max, 3);
		else if (!(rc = material_attribute(p, key, &o->mat)))
			return unknown_attribute(p, key, "box", "min, max or a material "
			                         "attribute (" MATERIAL_WORDS ")");
		if (rc < 0)
			return rc;
	}
	if (rc < 0)
		return rc;
	if (!seen(p, "min") || !seen(p, "max"))
		return missing(p, kw, "'min X Y Z' and 'max X Y Z'");
	if ((rc = box_check(p, seen(p, "min"), o->min, o->max, 3, "XYZ")) < 0)
		return rc;
	return material_check(p);
}

/* rect plane x|y|z VALUE min A B max A B: A B are the other two axes in
 * x, y, z order; the normal is +axis, the tangent the first other axis. */
static int
rect_from_plane(struct parser *p, const struct rf__token *at, int axis, double value,
                const double mn[2], const double mx[2], struct object *o)
{
	int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2, rc;
	const char axes[3] = { "XYZ"[a], "XYZ"[b], 0 };

	if ((rc = box_check(p, at, mn, mx, 2, axes)) < 0)
		return rc;
	o->axis = axis;
	memset(o->n, 0, sizeof(o->n));
	memset(o->t, 0, sizeof(o->t));
	o->n[axis] = 1.0;
	/* The frame must be right-handed (t x b = n): for the Y plane the
	 * plane-tangent rule gives t = +X; for X and Z, t lies along Z or X
	 * so that b is up. */
	rf__plane_tangent(o->n, o->t);
	o->center[axis] = value;
	o->center[a] = 0.5 * (mn[0] + mx[0]);
	o->center[b] = 0.5 * (mn[1] + mx[1]);
	{
		double b3[3];
		double ea[3] = { 0, 0, 0 };

		ea[a] = 1.0;
		rf__cross(o->n, o->t, b3);
		/* half sizes along t and b, whichever of a, b they are */
		o->half[0] = fabs(rf__dot(o->t, ea)) > 0.5 ? 0.5 * (mx[0] - mn[0])
		                                          : 0.5 * (mx[1] - mn[1]);
		o->half[1] = fabs(rf__dot(b3, ea)) > 0.5 ? 0.5 * (mx[0] - mn[0])
		                                        : 0.5 * (mx[1] - mn[1]);
	}
	return 0;
}

static int
parse_rect(struct parser *p, const struct rf__token *kw, struct object *o)
{
	const struct rf__token *key, *t, *plane = NULL;
	double mn[2], mx[2], size[2], value = 0, tangent[3];
	int rc, axis = -1;

	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "plane")) {
			plane = key;
			if ((rc = word(p, "x, y or z after 'plane'", &t)) < 0)
				return rc;
			if (tok_is(t, "x") || tok_is(t, "y") || tok_is(t, "z"))
				axis = t->text[0] - 'x';
			else
				return FAIL_TOK(p, t, "expected x, y or z after 'plane', found "
				                TOKFMT, TOKARG(t));
			rc = number(p, "plane", &value);
		} else if (tok_is(key, "min"))
			rc = numbers(p, "min", mn, 2);
		else if (tok_is(key, "max"))
			rc = numbers(p, "max", mx, 2);
		else if (tok_is(key, "center") || tok_is(key, "centre"))
			rc = numbers(p, "center", o->center, 3);
		else if (tok_is(key, "normal"))
			rc = numbers(p, "normal", o->n, 3);
		else if (tok_is(key, "size")) {
			if ((rc = numbers(p, "size", size, 2)) >= 0 &&
			    !(size[0] > 0 && size[1] > 0))
				rc = FAIL_TOK(p, key, "expected two positive sizes, found %g %g",
				              size[0], size[1]);
		} else if (tok_is(key, "tangent"))
			rc = numbers(p, "tangent", tangent, 3);
		else if (!(rc = material_attribute(p, key, &o->mat)))
			return unknown_attribute(p, key, "rect", "plane, min, max, or center, "
			                         "normal, size, tangent, or a material "
			                         "attribute (" MATERIAL_WORDS ")");
		if (rc < 0)
			return rc;
	}
	if (rc < 0)
		return rc;
	if (plane) {
		static const char *const general[] = { "center", "centre", "normal", "size",
			                               "tangent", NULL };
		int i;

		for (i = 0; general[i]; i++)
			if ((t = seen(p, general[i])))
				return FAIL_TOK(p, t, "expected either 'plane' with 'min' and "
				                "'max', or 'center', 'normal' and 'size', not both");
		if (!seen(p, "min") || !seen(p, "max"))
			return missing(p, kw, "'min A B' and 'max A B' with 'plane'");
		rc = rect_from_plane(p, seen(p, "min"), axis, value, mn, mx, o);
	} else if (seen(p, "min") || seen(p, "max")) {
		t = seen(p, "min") ? seen(p, "min") : seen(p, "max");
		return FAIL_TOK(p, t, "expected 'plane x|y|z VALUE' before 'min' and 'max'");
	} else {
		if ((!seen(p, "center") && !seen(p, "centre")) || !seen(p, "normal") ||
		    !seen(p, "size"))
			return missing(p, kw, "'plane x|y|z VALUE min A B max A B', or "
			               "'center X Y Z normal X Y Z size W H'");
		if (!(rf__normalize(o->n) > 0))
			return FAIL_TOK(p, seen(p, "normal"), "expected a non-zero normal");
		if ((t = seen(p, "tangent"))) {
			double d = rf__dot(tangent, o->n);
			int i;

			for (i = 0; i < 3; i++)
				tangent[i] -= d * o->n[i];
			if (!(rf__normalize(tangent) > 1e-9))
				return FAIL_TOK(p, t, "expected a tangent not parallel to the "
				                "normal");
			memcpy(o->t, tangent, sizeof(tangent));
		} else {
			rf__plane_tangent(o->n, o->t);
		}
		o->half[0] = 0.5 * size[0];
		o->half[1] = 0.5 * size[1];
		o->axis = -1;
	}
	if (rc < 0)
		return rc;
	return material_check(p);
}

static int
parse_object(struct parser *p, const struct rf__token *kw)
{
	struct object o;
	int rc;

	memset(&o, 0, sizeof(o));
	o.line = kw->line;
	o.axis = -1;
	rf__material_default(&o.mat, 0);
	if (tok_is(kw, "sphere")) {
		o.kind = OBJ_SPHERE;
		rc = parse_sphere(p, kw, &o);
	} else if (tok_is(kw, "box")) {
		o.kind = OBJ_BOX;
		rc = parse_box(p, kw, &o);
	} else {
		o.kind = OBJ_RECT;
		rc = parse_rect(p, kw, &o);
	}
	return rc < 0 ? rc : add_object(p, &o);
}

/* ---- emission: the walls' pattern, each wall, windows --------------------- */

#define FACE_WORDS "+x, -x, +y, -y, +z or -z"

/* A face of the room by the box side it lies on. */
static int
face_word(struct parser *p, int *face)
{
	static const char *const names[RF__FACES] = { "+x", "-x", "+y", "-y", "+z", "-z" };
	const struct rf__token *t;
	int rc, f;

	if ((rc = word(p, "a wall (" FACE_WORDS ")", &t)) < 0)
		return rc;
	for (f = 0; f < RF__FACES; f++)
		if (tok_is(t, names[f])) {
			*face = f;
			return 0;
		}
	return FAIL_TOK(p, t, "expected a wall (" FACE_WORDS ", the box side it lies on), "
	                "found " TOKFMT, TOKARG(t));
}

static int
parse_pattern(struct parser *p, const struct rf__token *kw)
{
	struct pattern *pt = &p->s->pattern;
	const struct rf__token *key;
	int rc;

	if (p->pattern_line)
		return FAIL_TOK(p, kw, "expected one 'pattern' line, the first is line %zu",
		                p->pattern_line);
	p->pattern_line = kw->line;
	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "cell"))
			rc = positive(p, "cell", &pt->cell);
		else if (tok_is(key, "line-width"))
			rc = number_in(p, "line-width", 0, 1e9, &pt->line_width);
		else if (tok_is(key, "base"))
			rc = number_in(p, "base", 0, 1e30, &pt->base);
		else if (tok_is(key, "checker"))
			rc = number_in(p, "checker", -1e30, 1e30, &pt->checker);
		else if (tok_is(key, "line"))
			rc = number_in(p, "line", 0, 1e30, &pt->line);
		else if (tok_is(key, "line-white"))
			rc = number_in(p, "line-white", 0, 1, &pt->line_white);
		else
			rc = unknown_attribute(p, key, "pattern", "cell, line-width, base, "
			                       "checker, line or line-white");
		if (rc < 0)
			return rc;
	}
	if (rc < 0)
		return rc;
	pt->inv_cell = 1.0 / pt->cell;
	if (pt->base + (pt->checker < 0 ? pt->checker : 0) < 0)
		return FAIL_TOK(p, kw, "expected base + checker >= 0 (no negative radiance), "
		                "found %g + %g", pt->base, pt->checker);
	return 0;
}

/* An emission image: its file, the metres it spans, where its lower
 * left corner lies, its gain. */
static int
wall_image(struct parser *p, struct emission *e)
{
	const struct rf__token *t;
	const rf_image *img;
	const char *cs;
	char *path, msg[400];
	int rc;

	if ((rc = word(p, "an image file after 'image'", &t)) < 0)
		return rc;
	if ((rc = resolve_path(p, t, &path)) < 0)
		return rc;
	rc = rf__scene_image(p->s, path, 1, "emission image", &img, msg, sizeof(msg));
	free(path);
	if (rc == RF_ENOMEM)
		return rc;
	if (rc < 0)
		return FAIL_TOK(p, t, "%s", msg);
	e->kind = EMIT_IMAGE;
	e->pixels = rf_image_pixels(img);
	e->width = rf_image_width(img);
	e->height = rf_image_height(img);
	e->nchannels = rf_image_nchannels(img);
	/* 8- and 16-bit pictures are stored sRGB-encoded; float files are
	 * linear.  OpenImageIO names the file's colour space. */
	cs = rf_image_attribute(img, "oiio:ColorSpace");
	e->srgb = cs && (!strcmp(cs, "sRGB") || !strcmp(cs, "srgb_rec709_scene"));
	return 0;
}

static int
parse_wall(struct parser *p, const struct rf__token *kw)
{
	struct emission e;
	const struct rf__token *key, *kind = NULL;
	int face, rc, i, srgb = -1;

	memset(&e, 0, sizeof(e));
	e.size[0] = e.size[1] = 1.0;
	e.rgb[0] = e.rgb[1] = e.rgb[2] = 1.0f;
	if ((rc = face_word(p, &face)) < 0)
		return rc;
	if (p->wall_line[face])
		return FAIL_TOK(p, kw, "expected one 'wall' line for each wall, the first "
		                "for this one is line %zu", p->wall_line[face]);
	p->wall_line[face] = kw->line;
	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "emission") || tok_is(key, "pattern") || tok_is(key, "image")) {
			if (kind)
				return FAIL_TOK(p, key, "expected one of emission, pattern or "
				                "image, " TOKFMT " is at column %zu already",
				                TOKARG(kind), kind->col);
			kind = key;
			if (tok_is(key, "image")) {
				rc = wall_image(p, &e);
			} else {
				rc = radiance(p, tok_is(key, "emission") ? "emission" : "pattern",
				              e.rgb);
				e.kind = tok_is(key, "emission") ? EMIT_COLOUR : EMIT_PATTERN;
			}
		} else if (tok_is(key, "size")) {
			if ((rc = positive(p, "size", &e.size[0])) >= 0)
				rc = positive(p, "size", &e.size[1]);
		} else if (tok_is(key, "origin")) {
			rc = numbers(p, "origin", e.origin, 2);
		} else if (tok_is(key, "gain")) {
			double g;

			if ((rc = number_in(p, "gain", 0, 1e30, &g)) >= 0)
				for (i = 0; i < 3; i++)
					e.rgb[i] = (float)g;
		} else if (tok_is(key, "srgb")) {
			rc = on_off(p, "srgb", &srgb);
		} else {
			rc = unknown_attribute(p, key, "wall", "emission R G B, pattern R G B, "
			                       "image FILE, size, origin, gain or srgb");
		}
		if (rc < 0)
			return rc;
	}
	if (rc < 0)
		return rc;
	if (!kind)
		return missing(p, kw, "emission R G B, pattern R G B or image FILE");
	for (i = 0; i < 4; i++) {
		static const char *const image_words[] = { "size", "origin", "gain", "srgb" };

		if (e.kind != EMIT_IMAGE && (key = seen(p, image_words[i])))
			return FAIL_TOK(p, key, "expected " TOKFMT " with an 'image' only",
			                TOKARG(key));
	}
	if (srgb >= 0)
		e.srgb = srgb;
	p->s->wall_em[face] = e;
	p->s->has_emission = 1;
	return 0;
}

static int
parse_window(struct parser *p, const struct rf__token *kw)
{
	struct window w, *ws;
	const struct rf__token *key;
	int rc;

	memset(&w, 0, sizeof(w));
	if ((rc = face_word(p, &w.face)) < 0)
		return rc;
	while ((rc = attribute(p, &key)) > 0) {
		if (tok_is(key, "min"))
			rc = numbers(p, "min", w.min, 2);
		else if (tok_is(key, "max"))
			rc = numbers(p, "max", w.max, 2);
		else if (tok_is(key, "radiance"))
			rc = radiance(p, "radiance", w.rgb);
		else if (tok_is(key, "mullions")) {
			if ((rc = positive(p, "mullions", &w.mullion)) >= 0)
				rc = radiance(p, "mullions", w.mullion_rgb);
		} else
			rc = unknown_attribute(p, key, "window", "min U V, max U V, radiance "
			                       "R G B or mullions WIDTH R G B");
		if (rc < 0)
			return rc;
	}
	if (rc < 0)
		return rc;
	if (!seen(p, "min") || !seen(p, "max") || !seen(p, "radiance"))
		return missing(p, kw, "min U V, max U V and radiance R G B");
	if ((rc = box_check(p, seen(p, "min"), w.min, w.max, 2, "UV")) < 0)
		return rc;
	if (!(ws = realloc(p->s->windows, (p->s->nwindows + 1) * sizeof(*ws))))
		return RF_ENOMEM;
	p->s->windows = ws;
	ws[p->s->nwindows++] = w;
	p->s->has_emission = 1;
	return 0;
}

static int
statement(struct parser *p)
{
	const struct rf__token *kw = take(p);

	if (tok_is(kw, "camera"))
		return parse_camera(p, kw);
	if (tok_is(kw, "probe"))
		return parse_probe(p, kw);
	if (tok_is(kw, "room"))
		return parse_room(p, kw);
	if (tok_is(kw, "name"))
		return parse_name(p, kw);
	if (tok_is(kw, "sphere") || tok_is(kw, "box") || tok_is(kw, "rect"))
		return parse_object(p, kw);
	if (tok_is(kw, "pattern"))
		return parse_pattern(p, kw);
	if (tok_is(kw, "wall"))
		return parse_wall(p, kw);
	if (tok_is(kw, "window"))
		return parse_window(p, kw);
	if (tok_is(kw, "mesh"))
		return rf__parse_mesh(p, kw);
	if (tok_is(kw, "sky"))
		return rf__parse_sky(p, kw);
	return FAIL_TOK(p, kw, "unknown keyword " TOKFMT " (expected name, camera, "
	                "probe, room, sphere, box, rect, mesh, sky, pattern, wall or "
	                "window)",
	                TOKARG(kw));
}

/* The scene's name from its file name: the base name without extension. */
static int
name_from_file(rf_scene *s, const char *file)
{
	const char *base = strrchr(file, '/') ? strrchr(file, '/') + 1 : file;
	size_t n = strcspn(base, "."), i;

	if (!n || !strcmp(file, "-") || base[0] == '<') {
		base = "scene";
		n = strlen(base);
	}
	if (!(s->name = malloc(n + 1)))
		return RF_ENOMEM;
	/* into the header, which takes no control byte */
	for (i = 0; i < n; i++)
		s->name[i] = (unsigned char)base[i] < 0x20 || base[i] == 0x7f ? '?' : base[i];
	s->name[n] = '\0';
	return 0;
}

int
rf_scene_parse(rf_scene **sp, const char *text, size_t len, const char *name,
               char *err, size_t errlen)
{
	struct parser p;
	const char *slash;
	size_t i;
	int rc;

	*sp = NULL;
	memset(&p, 0, sizeof(p));
	p.name = name ? name : "<scene>";
	rf__lexer_init(&p.lx, text, len, p.name, err, errlen);
	if (!(p.s = rf__scene_create()))
		return RF_ENOMEM;
	if (name && (slash = strrchr(name, '/'))) {
		size_t n = (size_t)(slash - name);

		if (!(p.dir = malloc(n + 2))) {
			rf_scene_destroy(p.s);
			return RF_ENOMEM;
		}
		/* "/x.scene" lives in "/": its files are "//file", still right. */
		memcpy(p.dir, name, n);
		p.dir[n] = '\0';
	}
	while ((rc = next_statement(&p)) > 0)
		if ((rc = statement(&p)) < 0)
			break;
	if (rc == 0)
		rc = envless_probes(&p);
	if (rc == 0 && p.room_sphere_line && p.s->room)
		rc = fail_at(&p, p.room_sphere_line, p.room_sphere_col,
		             "the first probe's box is the scene's room, whose walls cannot be "
		             "a sphere: give the first probe a box (turned if need be) and a "
		             "sphere proxy ('proxy sphere R'), make the sphere a second probe, "
		             "or draw no room ('room off')");
	free(p.envless);
	rf__lexer_destroy(&p.lx);
	free(p.dir);
	if (rc == 0 && !p.s->nprobes)
		rc = fail_at(&p, p.lx.line, 1, "expected a 'probe' line (the room's box and "
		             "the capture point) before the end of the file");
	if (rc == 0 && !p.camera_line) {
		/* From the capture point, looking along -Z. */
		for (i = 0; i < 3; i++) {
			p.s->camera.position[i] = p.s->probes[0].center[i];
			p.s->camera.target[i] = p.s->probes[0].center[i];
			p.s->camera.up[i] = i == 1;
		}
		p.s->camera.target[2] -= 1.0;
		p.s->camera.fov = 60.0;
	}
	if (rc == 0 && !p.s->name)
		rc = name_from_file(p.s, p.name);
	/* a mesh statement's triangles share one objid, after the objects' */
	for (i = 0; rc == 0 && i < p.s->nmeshes; i++)
		p.s->meshes[i].objid = (int)(p.s->nobjects + 1 + i);
	if (rc == RF_ENOMEM)
		rf__format(err, errlen, "%s: %s", p.name, rf_strerror(rc));
	if (rc < 0 && err) {
		/* Messages quote the scene's words: none of its control bytes
		 * may reach a terminal. */
		char *c;

		for (c = err; *c; c++)
			if ((unsigned char)*c < 0x20 || *c == 0x7f)
				*c = '?';
	}
	if (rc < 0) {
		rf_scene_destroy(p.s);
		return rc;
	}
	rf__room_frame(p.s);
	rf__wall_classes(p.s);
	*sp = p.s;
	return 0;
}

int
rf_scene_read(rf_scene **sp, FILE *fp, const char *name, char *err, size_t errlen)
{
	size_t len = 0, cap = 0, n;
	char *buf = NULL, *grown;
	int rc;

	*sp = NULL;
	for (;;) {
		if (len == cap) {
			cap = cap ? 2 * cap : 8192;
			if (cap > SCENE_BYTES_MAX + 1)
				cap = SCENE_BYTES_MAX + 1;
			if (len == cap) {
				free(buf);
				rf__format(err, errlen, "%s: expected a scene file of at most "
				           "%zu bytes", name ? name : "<scene>", SCENE_BYTES_MAX);
				return RF_ETOOBIG;
			}
			if (!(grown = realloc(buf, cap))) {
				free(buf);
				return RF_ENOMEM;
			}
			buf = grown;
		}
		n = fread(buf + len, 1, cap - len, fp);
		len += n;
		if (n == 0)
			break;
	}
	if (ferror(fp)) {
		rf__format(err, errlen, "cannot read '%s': %s", name ? name : "<scene>",
		           strerror(errno));
		free(buf);
		return RF_EIO;
	}
	rc = rf_scene_parse(sp, buf ? buf : "", len, name, err, errlen);
	free(buf);
	return rc;
}
