/*
 * A glTF file's sizes, checked before assimp reads it.  assimp allocates
 * a buffer's byteLength before it reads a byte of it, and an accessor's
 * count times its element before it copies one: a file of a few hundred
 * bytes claiming 10 GB would take 10 GB, or the process.  So the JSON is
 * walked here first (the .gltf text, or a .glb's JSON chunk), and every
 * claim is held to what backs it (reflect-scene(5), LIMITS):
 *
 *   a buffer's byteLength   <= its file's size, its data URI's decoded
 *                              size, or the .glb's BIN chunk;
 *   a bufferView's          <= its buffer's byteLength;
 *   an accessor's count     <= its bufferView's byteLength (an element is
 *                              at least a byte), or RF__GLTF_COUNT_MAX
 *                              without a bufferView (all zeros).
 *
 * The walker reads JSON's grammar and only keeps those few numbers, and
 * what assimp leaves out of the materials; it does not
 * unescape strings (URIs are checked as written, %XX decoded).
 */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "scene/scene-internal.h"

/* The .gltf text (with its embedded base64 buffers) read at most. */
#define GLTF_JSON_MAX ((size_t)512 << 20)
#define DEPTH_MAX 64

struct js {
	const char *s;
	size_t n, pos;
};

struct claim {
	double length; /* byteLength, or count */
	double ref;    /* buffer of a view, view of an accessor; -1: none */
	const char *uri;
	size_t urilen;
};

struct claims {
	struct claim *v;
	size_t n;
};

static void
ws(struct js *j)
{
	while (j->pos < j->n && strchr(" \t\r\n", j->s[j->pos]) && j->s[j->pos])
		j->pos++;
}

static int
lit(struct js *j, char c)
{
	ws(j);
	if (j->pos < j->n && j->s[j->pos] == c) {
		j->pos++;
		return 1;
	}
	return 0;
}

/* A string's raw text, escapes left as they are. */
static int
string(struct js *j, const char **t, size_t *len)
{
	size_t start;

	if (!lit(j, '"'))
		return -1;
	start = j->pos;
	while (j->pos < j->n && j->s[j->pos] != '"') {
		if (j->s[j->pos] == '\\')
			j->pos++;
		j->pos++;
	}
	if (j->pos >= j->n)
		return -1;
	*t = j->s + start;
	*len = j->pos - start;
	j->pos++;
	return 0;
}

static int
number(struct js *j, double *v)
{
	char buf[64];
	size_t k = 0;
	char *end;

	ws(j);
	while (j->pos < j->n && strchr("0123456789+-.eE", j->s[j->pos]) && j->s[j->pos] &&
	       k < sizeof(buf) - 1)
		buf[k++] = j->s[j->pos++];
	buf[k] = '\0';
	if (!k)
		return -1;
	*v = strtod(buf, &end);
	return *end ? -1 : 0;
}

static int skip(struct js *j, int depth);

static int
skip_members(struct js *j, char close, int depth)
{
	const char *t;
	size_t len;

	if (lit(j, close))
		return 0;
	do {
		if (close == '}' && (string(j, &t, &len) < 0 || !lit(j, ':')))
			return -1;
		if (skip(j, depth + 1) < 0)
			return -1;
	} while (lit(j, ','));
	return lit(j, close) ? 0 : -1;
}

static int
skip(struct js *j, int depth)
{
	const char *t;
	size_t len;
	double v;

	if (depth > DEPTH_MAX)
		return -1;
	ws(j);
	if (j->pos >= j->n)
		return -1;
	switch (j->s[j->pos]) {
	case '"':
		return string(j, &t, &len);
	case '{':
		j->pos++;
		return skip_members(j, '}', depth);
	case '[':
		j->pos++;
		return skip_members(j, ']', depth);
	case 't':
	case 'f':
	case 'n':
		while (j->pos < j->n && j->s[j->pos] >= 'a' && j->s[j->pos] <= 'z')
			j->pos++;
		return 0;
	default:
		return number(j, &v);
	}
}

static int
key_is(const char *t, size_t len, const char *word)
{
	return len == strlen(word) && !memcmp(t, word, len);
}

/* An array of objects, keeping from each the numbers named len_key and
 * ref_key and the string "uri". */
static int
objects(struct js *j, const char *len_key, const char *ref_key, struct claims *c)
{
	const char *t;
	size_t len;

	if (!lit(j, '['))
		return skip(j, 1);
	if (lit(j, ']'))
		return 0;
	do {
		struct claim cl = { -1, -1, NULL, 0 }, *grown;

		if (!lit(j, '{'))
			return -1;
		if (!lit(j, '}')) {
			do {
				if (string(j, &t, &len) < 0 || !lit(j, ':'))
					return -1;
				if (key_is(t, len, len_key)) {
					if (number(j, &cl.length) < 0)
						return -1;
				} else if (ref_key && key_is(t, len, ref_key)) {
					if (number(j, &cl.ref) < 0)
						return -1;
				} else if (key_is(t, len, "uri")) {
					if (string(j, &cl.uri, &cl.urilen) < 0)
						return -1;
				} else if (skip(j, 2) < 0)
					return -1;
			} while (lit(j, ','));
			if (!lit(j, '}'))
				return -1;
		}
		if (!(grown = realloc(c->v, (c->n + 1) * sizeof(*grown))))
			return RF_ENOMEM;
		c->v = grown;
		c->v[c->n++] = cl;
	} while (lit(j, ','));
	return lit(j, ']') ? 0 : -1;
}

/* A number, or true (1) or false (0). */
static int
scalar(struct js *j, double *v)
{
	ws(j);
	if (j->n - j->pos >= 4 && !memcmp(j->s + j->pos, "true", 4)) {
		j->pos += 4;
		*v = 1;
		return 0;
	}
	if (j->n - j->pos >= 5 && !memcmp(j->s + j->pos, "false", 5)) {
		j->pos += 5;
		*v = 0;
		return 0;
	}
	return number(j, v);
}

/* The value at path (keys of nested objects, NULL-terminated) in the
 * object starting at j's position, read by leaf: 1 when found, 0
 * without one (or one of another type, which leaf skips), -1 when the
 * JSON does not parse. */
typedef int leaf_fn(struct js *j, void *out);

static int
lookup(struct js *j, const char *const *path, leaf_fn *leaf, void *out)
{
	const char *t;
	size_t len;
	int rc = 0;

	if (!lit(j, '{'))
		return skip(j, 1) < 0 ? -1 : 0;
	if (lit(j, '}'))
		return 0;
	do {
		if (string(j, &t, &len) < 0 || !lit(j, ':'))
			return -1;
		if (rc == 0 && key_is(t, len, path[0])) {
			rc = path[1] ? lookup(j, path + 1, leaf, out) : leaf(j, out);
			if (rc < 0)
				return -1;
		} else if (skip(j, 1) < 0)
			return -1;
	} while (lit(j, ','));
	return lit(j, '}') ? rc : -1;
}

/* A number or boolean into the double *out; anything else does not
 * parse as what glTF puts there. */
static int
leaf_scalar(struct js *j, void *out)
{
	return scalar(j, out) < 0 ? -1 : 1;
}

/* A string's raw text; another value is skipped. */
struct text {
	const char *t;
	size_t len;
};

static int
leaf_string(struct js *j, void *out)
{
	struct text *x = out;

	ws(j);
	if (j->pos < j->n && j->s[j->pos] == '"')
		return string(j, &x->t, &x->len) < 0 ? -1 : 1;
	return skip(j, 1) < 0 ? -1 : 0;
}

/*
 * What assimp 5.2 does not read of each material: its
 * KHR_materials_emissive_strength, the texCoord of its textures'
 * KHR_texture_transform (which overrides the texture's own), and
 * reflect's own extras.reflect.mirror.
 */
static int
materials(struct js *j, struct rf__gltf_info *info)
{
	static const char *const strength[] = { "extensions",
		                                "KHR_materials_emissive_strength",
		                                "emissiveStrength", NULL };
	static const char *const tex[RF__GLTF_TEXTURES][6] = {
		{ "pbrMetallicRoughness", "baseColorTexture", "extensions",
		  "KHR_texture_transform", "texCoord", NULL },
		{ "pbrMetallicRoughness", "metallicRoughnessTexture", "extensions",
		  "KHR_texture_transform", "texCoord", NULL },
		{ "normalTexture", "extensions", "KHR_texture_transform", "texCoord", NULL },
		{ "emissiveTexture", "extensions", "KHR_texture_transform", "texCoord", NULL },
	};
	static const char *const mirror[] = { "extras", "reflect", "mirror", NULL };
	static const char *const name[] = { "name", NULL };

	if (!lit(j, '['))
		return skip(j, 1);
	if (lit(j, ']'))
		return 0;
	do {
		struct rf__gltf_material m, *grown;
		struct text t;
		size_t start;
		double v;
		int k, rc;

		ws(j);
		start = j->pos;
		m.emissive_strength = 1.0f;
		if ((rc = lookup(j, strength, leaf_scalar, &v)) < 0)
			return -1;
		if (rc)
			m.emissive_strength = (float)v;
		for (k = 0; k < RF__GLTF_TEXTURES; k++) {
			j->pos = start;
			if ((rc = lookup(j, tex[k], leaf_scalar, &v)) < 0)
				return -1;
			m.texcoord[k] = rc && v >= 0 && v < 1e9 ? (int)v : -1;
		}
		j->pos = start;
		if ((rc = lookup(j, mirror, leaf_scalar, &v)) < 0)
			return -1;
		m.mirror = rc ? v != 0 : -1;
		j->pos = start;
		m.name = NULL;
		if ((rc = lookup(j, name, leaf_string, &t)) < 0)
			return -1;
		if (rc && !(m.name = strndup(t.t, t.len)))
			return RF_ENOMEM;
		if (!(grown = realloc(info->materials, (info->nmaterials + 1) * sizeof(*grown)))) {
			free(m.name);
			return RF_ENOMEM;
		}
		info->materials = grown;
		info->materials[info->nmaterials++] = m;
	} while (lit(j, ','));
	return lit(j, ']') ? 0 : -1;
}

static int
hexval(char c)
{
	return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
	       : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

/* The file a relative URI names, beside the glTF file, %XX decoded. */
static char *
uri_path(const char *gltf, const char *uri, size_t len)
{
	const char *slash = strrchr(gltf, '/');
	size_t dlen = slash ? (size_t)(slash - gltf) + 1 : 0, i, k;
	char *out = malloc(dlen + len + 1);

	if (!out)
		return NULL;
	memcpy(out, gltf, dlen);
	for (i = 0, k = dlen; i < len; i++) {
		if (uri[i] == '%' && i + 2 < len && hexval(uri[i + 1]) >= 0 &&
		    hexval(uri[i + 2]) >= 0) {
			out[k++] = (char)(hexval(uri[i + 1]) * 16 + hexval(uri[i + 2]));
			i += 2;
		} else
			out[k++] = uri[i];
	}
	out[k] = '\0';
	return out;
}

static int
check_buffers(const char *path, const struct claims *b, int glb, double bin,
              char *err, size_t errlen)
{
	size_t i;

	for (i = 0; i < b->n; i++) {
		const struct claim *c = &b->v[i];
		double have;
		const char *what;

		/* Below 2^64 first: converting a larger double is undefined. */
		if (!(c->length >= 0 && c->length < 0x1p64 &&
		      c->length == (double)(uint64_t)c->length))
			return rf__format(err, errlen, "'%s': buffer %zu has no valid "
			                  "byteLength", path, i), RF_EFORMAT;
		if (!c->uri) {
			if (!glb || i)
				return rf__format(err, errlen, "'%s': buffer %zu has no uri "
				                  "(only a .glb's first buffer may)", path, i),
				       RF_EFORMAT;
			have = bin;
			what = "the .glb's BIN chunk holds";
		} else if (c->urilen >= 5 && !memcmp(c->uri, "data:", 5)) {
			const char *comma = memchr(c->uri, ',', c->urilen);

			have = comma ? (double)(c->urilen - (size_t)(comma + 1 - c->uri)) * 0.75
			             : 0;
			what = "its data URI holds";
		} else {
			char *file = uri_path(path, c->uri, c->urilen);
			struct stat st;

			if (!file)
				return RF_ENOMEM;
			if (stat(file, &st) < 0) {
				rf__format(err, errlen, "'%s': cannot open buffer %zu's file "
				           "'%s': %s", path, i, file, strerror(errno));
				free(file);
				return RF_EIO;
			}
			free(file);
			have = (double)st.st_size;
			what = "its file holds";
		}
		if (c->length > have)
			return rf__format(err, errlen, "'%s': buffer %zu claims %.0f bytes, "
			                  "but %s %.0f", path, i, c->length, what, have),
			       RF_ETOOBIG;
	}
	return 0;
}

static int
check_refs(const char *path, const struct claims *inner, const struct claims *outer,
           const char *iname, const char *oname, const char *what, char *err,
           size_t errlen)
{
	size_t i;

	for (i = 0; i < inner->n; i++) {
		const struct claim *c = &inner->v[i];
		double cap = RF__GLTF_COUNT_MAX;

		if (!(c->length >= 0))
			return rf__format(err, errlen, "'%s': %s %zu has no valid %s", path,
			                  iname, i, what), RF_EFORMAT;
		if (c->ref >= 0) {
			if (c->ref >= (double)outer->n || c->ref != (double)(size_t)c->ref)
				return rf__format(err, errlen, "'%s': %s %zu names %s %.0f, of "
				                  "%zu", path, iname, i, oname, c->ref, outer->n),
				       RF_EFORMAT;
			cap = outer->v[(size_t)c->ref].length;
		}
		if (c->length > cap)
			return rf__format(err, errlen, "'%s': %s %zu claims %s %.0f, more than "
			                  "%s%s (%.0f)", path, iname, i, what, c->length,
			                  c->ref >= 0 ? "the byteLength of its " :
			                  "reflect reads without a bufferView",
			                  c->ref >= 0 ? oname : "", cap),
			       RF_ETOOBIG;
	}
	return 0;
}

static uint32_t
le32(const unsigned char *b)
{
	return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
	       (uint32_t)b[3] << 24;
}

int
rf__gltf_check(const char *path, struct rf__gltf_info *info, char *err, size_t errlen)
{
	struct claims bufs = { NULL, 0 }, views = { NULL, 0 }, accs = { NULL, 0 };
	unsigned char head[20];
	struct stat st;
	struct js j;
	char *text = NULL;
	size_t n, off = 0;
	double bin = 0;
	int glb, rc = 0;
	FILE *fp;

	info->materials = NULL;
	info->nmaterials = 0;
	if (!(fp = fopen(path, "rb")) || fstat(fileno(fp), &st) < 0) {
		rf__format(err, errlen, "cannot open '%s': %s", path, strerror(errno));
		if (fp)
			fclose(fp);
		return RF_EIO;
	}
	n = fread(head, 1, sizeof(head), fp);
	glb = n == sizeof(head) && !memcmp(head, "glTF", 4);
	if (glb) {
		/* 12 bytes of header, then the JSON chunk's length and type */
		n = le32(head + 12);
		if (le32(head + 16) != 0x4E4F534Au || (uintmax_t)n + 20 > (uintmax_t)st.st_size) {
			fclose(fp);
			rf__format(err, errlen, "'%s': a .glb whose first chunk is no JSON "
			           "within the file", path);
			return RF_EFORMAT;
		}
		off = 20;
	} else {
		n = st.st_size > 0 ? (size_t)st.st_size : 0;
		if ((uintmax_t)st.st_size > GLTF_JSON_MAX) {
			fclose(fp);
			rf__format(err, errlen, "'%s': a .gltf of %jd bytes, more than the "
			           "%zu reflect reads (pack its buffers in a .glb)", path,
			           (intmax_t)st.st_size, GLTF_JSON_MAX);
			return RF_ETOOBIG;
		}
	}
	if (!(text = malloc(n + 1)) || fseek(fp, (long)off, SEEK_SET) < 0 ||
	    fread(text, 1, n, fp) != n) {
		rc = text ? RF_EIO : RF_ENOMEM;
		if (text)
			rf__format(err, errlen, "cannot read '%s': %s", path,
			           ferror(fp) ? strerror(errno) : "the file is shorter than it says");
		free(text);
		fclose(fp);
		return rc;
	}
	if (glb) {
		unsigned char bh[8];
		size_t at = 20 + ((n + 3) & ~(size_t)3);

		if (fseek(fp, (long)at, SEEK_SET) == 0 && fread(bh, 1, 8, fp) == 8 &&
		    le32(bh + 4) == 0x004E4942u)
			bin = (double)le32(bh) > (double)st.st_size - (double)at - 8
			      ? (double)st.st_size - (double)at - 8 : (double)le32(bh);
	}
	fclose(fp);
	j.s = text;
	j.n = n;
	j.pos = 0;
	if (!lit(&j, '{'))
		rc = -1;
	else if (!lit(&j, '}')) {
		do {
			const char *t;
			size_t len;

			if (string(&j, &t, &len) < 0 || !lit(&j, ':'))
				rc = -1;
			else if (key_is(t, len, "buffers"))
				rc = objects(&j, "byteLength", NULL, &bufs);
			else if (key_is(t, len, "bufferViews"))
				rc = objects(&j, "byteLength", "buffer", &views);
			else if (key_is(t, len, "accessors"))
				rc = objects(&j, "count", "bufferView", &accs);
			else if (key_is(t, len, "materials"))
				rc = materials(&j, info);
			else
				rc = skip(&j, 1);
		} while (rc == 0 && lit(&j, ','));
		if (rc == 0 && !lit(&j, '}'))
			rc = -1;
	}
	if (rc == -1) {
		rf__format(err, errlen, "'%s': not a glTF 2.0 file (its JSON does not parse "
		           "near byte %zu)", path, j.pos + off);
		rc = RF_EFORMAT;
	}
	if (rc == 0)
		rc = check_buffers(path, &bufs, glb, bin, err, errlen);
	if (rc == 0)
		rc = check_refs(path, &views, &bufs, "bufferView", "buffer", "byteLength", err,
		                errlen);
	if (rc == 0)
		rc = check_refs(path, &accs, &views, "accessor", "bufferView", "count", err,
		                errlen);
	free(bufs.v);
	free(views.v);
	free(accs.v);
	free(text);
	return rc;
}

void
rf__gltf_info_free(struct rf__gltf_info *info)
{
	size_t i;

	for (i = 0; i < info->nmaterials; i++)
		free(info->materials[i].name);
	free(info->materials);
	info->materials = NULL;
	info->nmaterials = 0;
}

const struct rf__gltf_material *
rf__gltf_material_named(const struct rf__gltf_info *info, const char *name)
{
	const struct rf__gltf_material *found = NULL;
	size_t i;

	for (i = 0; i < info->nmaterials; i++)
		if (info->materials[i].name && !strcmp(info->materials[i].name, name)) {
			if (found)
				return NULL;
			found = &info->materials[i];
		}
	return found;
}
