/* Mapping another renderer's passes onto reflect's G-buffer channels. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/util.h"
#include "reflect/import.h"

enum source_kind { FROM_IMAGE, FROM_CONSTANT, FROM_VIEW };

struct source {
	enum source_kind kind;
	const float *pixels; /* FROM_IMAGE: first pixel of the image */
	size_t channel, stride;
	float value;         /* FROM_CONSTANT */
	int component;       /* FROM_VIEW: 0 1 2 */
};

struct rf_import {
	rf_header *h;
	size_t width, height, nout;
	struct source *src;
	/* Output indices of vector layers turned from Z up to Y up, and of P
	 * (for V from the camera). */
	int turn[16][3];
	size_t nturn;
	int p[3];
	float camera[3];
};

/* Blender's passes, matched by the end of the name (any view layer). */
static const struct {
	const char *out;
	const char *suffix[3];
} blender[] = {
	{ "P.X", { ".Position.X", NULL } }, { "P.Y", { ".Position.Y", NULL } },
	{ "P.Z", { ".Position.Z", NULL } }, { "N.X", { ".Normal.X", NULL } },
	{ "N.Y", { ".Normal.Y", NULL } }, { "N.Z", { ".Normal.Z", NULL } },
	{ "depth", { ".Depth.Z", ".Depth.V", NULL } },
	{ "albedo.R", { ".DiffCol.R", NULL } }, { "albedo.G", { ".DiffCol.G", NULL } },
	{ "albedo.B", { ".DiffCol.B", NULL } },
	{ "objid", { ".IndexOB.X", ".IndexOB.V", NULL } },
	{ "roughness", { ".Roughness.V", ".roughness.V", ".Roughness.X" } },
	/* no standard pass: an AOV named Tangent (or tangent), a vector */
	{ "T.X", { ".Tangent.X", ".tangent.X", NULL } },
	{ "T.Y", { ".Tangent.Y", ".tangent.Y", NULL } },
	{ "T.Z", { ".Tangent.Z", ".tangent.Z", NULL } },
};

struct input {
	size_t file, channel;
	const char *name;
	int used;
};

static const char *
base_name(const char *path)
{
	const char *s = strrchr(path, '/');

	return s ? s + 1 : path;
}

/* Finds input `spec` (NAME or FILE:NAME); -1 with a message if absent or
 * ambiguous. */
static long
find_input(struct input *in, size_t nin, const char *const *paths, size_t nfiles,
           const char *spec, char *err, size_t errlen)
{
	const char *colon = strrchr(spec, ':'), *name = spec;
	long file = -1, found = -1;
	size_t i, hits = 0;

	if (colon && colon != spec) {
		size_t len = (size_t)(colon - spec);
		char *end;
		unsigned long idx = strtoul(spec, &end, 10);

		for (i = 0; i < nfiles && file < 0; i++)
			if ((strlen(paths[i]) == len && !strncmp(paths[i], spec, len)) ||
			    (strlen(base_name(paths[i])) == len &&
			     !strncmp(base_name(paths[i]), spec, len)))
				file = (long)i;
		if (file < 0 && end == colon && idx < nfiles)
			file = (long)idx;
		if (file < 0) {
			rf__format(err, errlen, "'%s': no input file '%.*s'", spec, (int)len, spec);
			return -1;
		}
		name = colon + 1;
	}
	for (i = 0; i < nin; i++)
		if (!strcmp(in[i].name, name) && (file < 0 || (long)in[i].file == file)) {
			if (found < 0)
				found = (long)i;
			hits++;
		}
	if (hits > 1) {
		rf__format(err, errlen, "channel '%s' is in several inputs ('%s' and '%s'); "
		           "write FILE:%s", name, paths[in[found].file],
		           paths[in[found + 1 < (long)nin ? found + 1 : found].file], name);
		return -1;
	}
	if (found < 0) {
		char list[512] = "";
		size_t k = 0;

		for (i = 0; i < nin && k + 2 < sizeof(list); i++)
			if (file < 0 || (long)in[i].file == file)
				k += (size_t)snprintf(list + k, sizeof(list) - k, "%s%s", k ? " " : "",
				                      in[i].name);
		rf__format(err, errlen, "no input channel '%s' (the input has: %s)", name, list);
		return -1;
	}
	return found;
}

static int
add_output(rf_import *im, const char *name, struct source s, char *err,
           size_t errlen)
{
	struct source *grown;
	int rc;

	if (rf_header_find_channel(im->h, name) >= 0) {
		rf__format(err, errlen, "output channel '%s' is given twice", name);
		return RF_EINVAL;
	}
	if ((rc = rf_header_add_channel(im->h, name)) < 0) {
		rf__format(err, errlen, "cannot make output channel '%s'", name);
		return rc;
	}
	if (!(grown = realloc(im->src, (im->nout + 1) * sizeof(*grown))))
		return RF_ENOMEM;
	im->src = grown;
	im->src[im->nout++] = s;
	return 0;
}

static struct source
image_source(const rf_image *const *images, const struct input *in)
{
	struct source s;

	memset(&s, 0, sizeof(s));
	s.kind = FROM_IMAGE;
	s.pixels = rf_image_pixels(images[in->file]);
	s.channel = in->channel;
	s.stride = rf_image_nchannels(images[in->file]);
	return s;
}

static int
ends_with(const char *s, const char *suffix)
{
	size_t n = strlen(s), m = strlen(suffix);

	return n >= m && !strcmp(s + n - m, suffix);
}

/* Output `out` from input `spec` (NAME or FILE:NAME), marked as used. */
static int
map_input(rf_import *im, const rf_image *const *images, struct input *in, size_t nin,
          const char *const *paths, size_t n, const char *spec, const char *out, char *err,
          size_t errlen)
{
	long k = find_input(in, nin, paths, n, spec, err, errlen);

	if (k < 0)
		return RF_EINVAL;
	in[k].used = 1;
	return add_output(im, out, image_source(images, &in[k]), err, errlen);
}

int
rf_import_create(rf_import **imp, const rf_image *const *images,
              const char *const *paths, size_t n, const struct rf_import_options *o,
              char *err, size_t errlen)
{
	rf_import *im;
	struct input *in = NULL;
	size_t nin = 0, i, j, f, c;
	int rc = RF_EINVAL;

	*imp = NULL;
	if (!n) {
		rf__format(err, errlen, "no input image");
		return RF_EINVAL;
	}
	for (f = 1; f < n; f++)
		if (rf_image_width(images[f]) != rf_image_width(images[0]) ||
		    rf_image_height(images[f]) != rf_image_height(images[0])) {
			rf__format(err, errlen, "'%s' is %zux%zu but '%s' is %zux%zu; the passes "
			           "must have one size", paths[f], rf_image_width(images[f]),
			           rf_image_height(images[f]), paths[0], rf_image_width(images[0]),
			           rf_image_height(images[0]));
			return RF_EINVAL;
		}
	if (!(im = calloc(1, sizeof(*im))) || rf_header_create(&im->h) < 0) {
		free(im);
		return RF_ENOMEM;
	}
	im->width = rf_image_width(images[0]);
	im->height = rf_image_height(images[0]);
	rf_header_set_size(im->h, im->width, im->height);
	for (f = 0; f < n; f++)
		nin += rf_image_nchannels(images[f]);
	if (!(in = calloc(nin, sizeof(*in)))) {
		rc = RF_ENOMEM;
		goto fail;
	}
	for (f = 0, nin = 0; f < n; f++)
		for (c = 0; c < rf_image_nchannels(images[f]); c++, nin++) {
			in[nin].file = f;
			in[nin].channel = c;
			in[nin].name = rf_image_channel(images[f], c);
		}
	/* 1. explicit mappings */
	for (i = 0; i < o->nmaps; i++)
		if ((rc = map_input(im, images, in, nin, paths, n, o->maps[i].in,
		                    o->maps[i].out, err, errlen)) < 0)
			goto fail;
	/* 2. the preset's passes that are present */
	if (o->preset == RF_IMPORT_BLENDER)
		for (i = 0; i < sizeof(blender) / sizeof(blender[0]); i++) {
			if (rf_header_find_channel(im->h, blender[i].out) >= 0 ||
			    (!strcmp(blender[i].out, "roughness") && o->roughness))
				continue;
			for (j = 0; j < 3 && blender[i].suffix[j]; j++) {
				size_t k;

				for (k = 0; k < nin && !ends_with(in[k].name, blender[i].suffix[j]); k++)
					;
				if (k < nin) {
					in[k].used = 1;
					if ((rc = add_output(im, blender[i].out, image_source(images, &in[k]),
					                     err, errlen)) < 0)
						goto fail;
					break;
				}
			}
		}
	/* 3. roughness from a channel or a constant */
	if (o->roughness) {
		char *end;
		double v;

		errno = 0;
		v = strtod(o->roughness, &end);
		if (end != o->roughness && !*end && !errno) {
			struct source s;

			if (!(v >= 0.0 && v <= 1.0)) {
				rf__format(err, errlen, "roughness %s is outside [0, 1]", o->roughness);
				rc = RF_EINVAL;
				goto fail;
			}
			memset(&s, 0, sizeof(s));
			s.kind = FROM_CONSTANT;
			s.value = (float)v;
			if ((rc = add_output(im, "roughness", s, err, errlen)) < 0)
				goto fail;
		} else if ((rc = map_input(im, images, in, nin, paths, n, o->roughness,
		                           "roughness", err, errlen)) < 0) {
			goto fail;
		}
	}
	/* 4. every other input under its own name, when that name is unique */
	for (i = 0; i < nin; i++) {
		size_t k, dup = 0;

		if (in[i].used || !rf_channel_name_valid(in[i].name) ||
		    rf_header_find_channel(im->h, in[i].name) >= 0)
			continue;
		for (k = 0; k < nin; k++)
			dup += k != i && !strcmp(in[k].name, in[i].name);
		if (dup)
			continue;
		if ((rc = add_output(im, in[i].name, image_source(images, &in[i]), err,
		                     errlen)) < 0)
			goto fail;
	}
	/* 5. V from the camera */
	for (i = 0; i < 3; i++) {
		static const char *const pn[3] = { "P.X", "P.Y", "P.Z" };

		im->p[i] = rf_header_find_channel(im->h, pn[i]);
	}
	if (o->camera) {
		static const char *const vn[3] = { "V.X", "V.Y", "V.Z" };

		if (rf_header_find_channel(im->h, "V.X") >= 0) {
			rf__format(err, errlen, "--camera derives V, but the input has V already");
			rc = RF_EINVAL;
			goto fail;
		}
		if (im->p[0] < 0 || im->p[1] < 0 || im->p[2] < 0) {
			rf__format(err, errlen, "V from the camera needs P.X P.Y P.Z");
			rc = RF_ECHANNEL;
			goto fail;
		}
		memcpy(im->camera, o->camera, sizeof(im->camera));
		if (o->z_up) {
			float y = im->camera[1];

			im->camera[1] = im->camera[2];
			im->camera[2] = -y;
		}
		for (i = 0; i < 3; i++) {
			struct source s;

			memset(&s, 0, sizeof(s));
			s.kind = FROM_VIEW;
			s.component = (int)i;
			if ((rc = add_output(im, vn[i], s, err, errlen)) < 0)
				goto fail;
		}
	}
	/* Vector layers to turn from Z up: every L.X L.Y L.Z triple. */
	if (o->z_up)
		for (i = 0; i < rf_header_nchannels(im->h) && im->nturn < 16; i++) {
			const char *name = rf_header_channel(im->h, i);
			size_t len = strlen(name);
			char other[RF_CHANNEL_NAME_MAX + 1];
			int y, z;

			if (len < 3 || strcmp(name + len - 2, ".X") || im->src[i].kind == FROM_VIEW)
				continue;
			memcpy(other, name, len + 1);
			other[len - 1] = 'Y';
			y = rf_header_find_channel(im->h, other);
			other[len - 1] = 'Z';
			z = rf_header_find_channel(im->h, other);
			if (y < 0 || z < 0)
				continue;
			im->turn[im->nturn][0] = (int)i;
			im->turn[im->nturn][1] = y;
			im->turn[im->nturn][2] = z;
			im->nturn++;
		}
	if (!rf_header_nchannels(im->h)) {
		rf__format(err, errlen, "no channel to write");
		rc = RF_EINVAL;
		goto fail;
	}
	free(in);
	*imp = im;
	return 0;
fail:
	free(in);
	rf_import_destroy(im);
	return rc;
}

void
rf_import_destroy(rf_import *im)
{
	if (!im)
		return;
	rf_header_destroy(im->h);
	free(im->src);
	free(im);
}

const rf_header *
rf_import_header(const rf_import *im)
{
	return im->h;
}

void
rf_import_rows(const rf_import *im, size_t y, size_t n, float *out)
{
	size_t npix = n * im->width, first = y * im->width, k, c, t;

	for (k = 0; k < npix; k++) {
		float *px = out + k * im->nout;

		for (c = 0; c < im->nout; c++) {
			const struct source *s = &im->src[c];

			px[c] = s->kind == FROM_IMAGE ? s->pixels[(first + k) * s->stride + s->channel]
			      : s->kind == FROM_CONSTANT ? s->value : 0.0f;
		}
		/* Z up to Y up: (x, y, z) -> (x, z, -y), a rotation. */
		for (t = 0; t < im->nturn; t++) {
			float yv = px[im->turn[t][1]];

			px[im->turn[t][1]] = px[im->turn[t][2]];
			px[im->turn[t][2]] = -yv;
		}
		if (im->nout && im->src[im->nout - 1].kind == FROM_VIEW) {
			float v[3], len;
			int i;

			for (i = 0; i < 3; i++)
				v[i] = im->camera[i] - px[im->p[i]];
			len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
			for (i = 0; i < 3; i++)
				px[im->nout - 3 + (size_t)i] = len > 0.0f ? v[i] / len : 0.0f;
		}
	}
}
