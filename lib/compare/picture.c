/*
 * A picture to compare (reflect/compare.h): a stream's first frame or an
 * image file, whichever the file is, as one array of floats with its
 * channel names.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "stream/stream-internal.h"
#include "util/util.h"
#include "reflect/image.h"
#include "reflect/reflect.h"

struct rf_picture {
	size_t width, height, nch;
	int srgb;
	char **names;
	float *px;
};

void
rf_picture_destroy(rf_picture *p)
{
	size_t i;

	if (!p)
		return;
	for (i = 0; p->names && i < p->nch; i++)
		free(p->names[i]);
	free(p->names);
	free(p->px);
	free(p);
}

/* Room for the pixels and names of a width x height x nch picture. */
static int
make(rf_picture **pp, size_t width, size_t height, size_t nch)
{
	rf_picture *p;

	if (!(*pp = p = calloc(1, sizeof(*p))))
		return RF_ENOMEM;
	p->width = width;
	p->height = height;
	p->nch = nch;
	if (!(p->names = calloc(nch ? nch : 1, sizeof(*p->names))) ||
	    (width && height && nch &&
	     (width > (size_t)-1 / height / nch / sizeof(float) ||
	      !(p->px = malloc(width * height * nch * sizeof(float)))))) {
		rf_picture_destroy(p);
		*pp = NULL;
		return RF_ENOMEM;
	}
	return 0;
}

static int
name(rf_picture *p, size_t i, const char *s)
{
	return (p->names[i] = strdup(s)) ? 0 : RF_ENOMEM;
}

/*
 * A supersampled frame (SUPERSAMPLE, from reflect-gbuffer --supersample)
 * is the picture at factor times its size: resolved as reflect-export
 * resolves it by default (a box over each pixel's samples, objid taken
 * at the centre), so that a picture compares and draws at its own size.
 */
static int
resolve(rf_picture *p, size_t factor, const char *path, char *err, size_t errlen)
{
	unsigned char nearest[RF_CHANNELS_MAX] = { 0 };
	rf_downsampler *d;
	size_t i, n;
	float *out;
	int rc;

	for (i = 0; i < p->nch && i < RF_CHANNELS_MAX; i++)
		nearest[i] = !strcmp(p->names[i], "objid");
	if ((rc = rf_downsampler_create(&d, p->width, p->height, p->nch, factor, RF_RESOLVE_BOX,
	                                RF_RESOLVE_SIGMA_DEFAULT, nearest)) < 0) {
		rf__format(err, errlen, "'%s': cannot resolve its %zu x %zu samples a pixel: %s",
		           path, factor, factor, rf_strerror(rc));
		return rc;
	}
	if (!(out = malloc(rf_downsampler_width(d) * rf_downsampler_height(d) * p->nch *
	                   sizeof(float) + 1))) {
		rf_downsampler_destroy(d);
		rf__format(err, errlen, "'%s': out of memory", path);
		return RF_ENOMEM;
	}
	rc = rf_downsampler_push(d, p->px, p->height, out, &n);
	if (rc == 0) {
		free(p->px);
		p->px = out;
		p->width = rf_downsampler_width(d);
		p->height = rf_downsampler_height(d);
	} else {
		free(out);
		rf__format(err, errlen, "'%s': %s", path, rf_strerror(rc));
	}
	rf_downsampler_destroy(d);
	return rc;
}

static int
read_stream(rf_picture **pp, FILE *fp, const char *path, char *err, size_t errlen)
{
	const rf_header *h;
	rf_reader *r;
	size_t i, factor = 1;
	int rc;

	if ((rc = rf_reader_open(&r, fp, path, NULL)) < 0) {
		rf__format(err, errlen, "'%s': %s", path, rf_strerror(rc));
		return rc;
	}
	if ((rc = rf_reader_next_frame(r, &h)) != 1) {
		if (rc == 0)
			rf__format(err, errlen, "'%s': no frame in the stream", path);
		else
			rf__format(err, errlen, "%s", rf_reader_error(r));
		rf_reader_close(r);
		return rc == 0 ? RF_EFORMAT : rc;
	}
	if ((rc = make(pp, rf_header_ncols(h), rf_header_nrows(h), rf_header_nchannels(h))) < 0) {
		rf__format(err, errlen, "'%s': out of memory for %zux%zu pixels", path,
		           rf_header_ncols(h), rf_header_nrows(h));
		rf_reader_close(r);
		return rc;
	}
	for (i = 0; i < (*pp)->nch && rc == 0; i++)
		rc = name(*pp, i, rf_header_channel(h, i));
	if (rc == 0 && (*pp)->height && (rc = rf_reader_read_rows(r, (*pp)->px, (*pp)->height)) < 0)
		rf__format(err, errlen, "%s", rf_reader_error(r));
	if (rc == 0 && (rc = rf_header_supersample(h, &factor)) < 0)
		rf__format(err, errlen, "'%s': header key %s='%s' is not a whole number in [1, %d] "
		           "that divides the %zux%zu frame's sides", path, RF_KEY_SUPERSAMPLE,
		           rf_header_get(h, RF_KEY_SUPERSAMPLE), RF_SUPERSAMPLE_MAX,
		           rf_header_ncols(h), rf_header_nrows(h));
	if (rc == 0 && factor > 1)
		rc = resolve(*pp, factor, path, err, errlen);
	/* A failed stream's trailer after the frame: the frame is not to be
	 * trusted (a later frame, or anything else after it, is no concern
	 * of a picture). */
	if (rc == 0 && rf_reader_next_frame(r, &h) == RF_EFAILED) {
		rc = RF_EFAILED;
		rf__format(err, errlen, "%s", rf_reader_error(r));
	}
	rf_reader_close(r);
	if (rc < 0) {
		rf_picture_destroy(*pp);
		*pp = NULL;
	}
	return rc < 0 ? rc : 0;
}

static int
read_image(rf_picture **pp, const char *path, char *err, size_t errlen)
{
	rf_image *img;
	const char *cs;
	size_t i, n;
	int rc;

	if ((rc = rf_image_read(&img, path, err, errlen)) < 0)
		return rc;
	if ((rc = make(pp, rf_image_width(img), rf_image_height(img), rf_image_nchannels(img))) < 0) {
		rf__format(err, errlen, "'%s': out of memory", path);
		rf_image_destroy(img);
		return rc;
	}
	cs = rf_image_attribute(img, "oiio:ColorSpace");
	(*pp)->srgb = cs && !strcasecmp(cs, "sRGB");
	n = (*pp)->width * (*pp)->height * (*pp)->nch;
	if (n)
		memcpy((*pp)->px, rf_image_pixels(img), n * sizeof(float));
	for (i = 0; i < (*pp)->nch && rc == 0; i++)
		rc = name(*pp, i, rf_image_channel(img, i));
	rf_image_destroy(img);
	if (rc < 0) {
		rf_picture_destroy(*pp);
		*pp = NULL;
		rf__format(err, errlen, "'%s': out of memory", path);
	}
	return rc;
}

int
rf_picture_read(rf_picture **pp, const char *path, char *err, size_t errlen)
{
	char magic[sizeof(RF__STREAM_MAGIC) - 1];
	FILE *fp;
	int rc;

	*pp = NULL;
	if (!strcmp(path, "-"))
		return read_stream(pp, stdin, "<stdin>", err, errlen);
	if ((rc = rf__regular_file(path, err, errlen)) < 0)
		return rc;
	if (!(fp = fopen(path, "rb"))) {
		rf__format(err, errlen, "cannot open '%s': %s", path, strerror(errno));
		return RF_EIO;
	}
	if (fread(magic, 1, sizeof(magic), fp) == sizeof(magic) &&
	    !memcmp(magic, RF__STREAM_MAGIC, sizeof(magic))) {
		rewind(fp);
		rc = read_stream(pp, fp, path, err, errlen);
		fclose(fp);
		return rc;
	}
	fclose(fp);
	return read_image(pp, path, err, errlen);
}

size_t rf_picture_width(const rf_picture *p) { return p->width; }
size_t rf_picture_height(const rf_picture *p) { return p->height; }
size_t rf_picture_nchannels(const rf_picture *p) { return p->nch; }
const char *rf_picture_channel(const rf_picture *p, size_t i) { return i < p->nch ? p->names[i] : NULL; }
const float *rf_picture_pixels(const rf_picture *p) { return p->px; }
int rf_picture_srgb(const rf_picture *p) { return p->srgb; }

int
rf_picture_find_channel(const rf_picture *p, const char *s)
{
	size_t i;

	for (i = 0; i < p->nch; i++)
		if (!strcmp(p->names[i], s))
			return (int)i;
	return RF_ECHANNEL;
}
