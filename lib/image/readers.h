/* Internal: the image files libreflect reads itself, without loading the
 * image module (exr_read.c). */
#ifndef REFLECT_IMAGE_READERS_H
#define REFLECT_IMAGE_READERS_H

#include <stddef.h>

/* An image read by libreflect: floats, channels interleaved, rows top
 * first; names and string attributes (key, value pairs) its own. */
struct rf__image_data {
	size_t width, height, nchannels;
	char **names;
	float *pixels;
	char **attr;
	size_t nattr;
};

void rf__image_data_free(struct rf__image_data *img);

/* 1 when the file starts with OpenEXR's magic number. */
int rf__is_exr(const char *path);
/* RF_ENOTFOUND for a file the module should read instead (deep data,
 * subsampled channels, RIP maps); other errors are the file's. */
int rf__exr_read_level(struct rf__image_data *img, const char *path, size_t level,
                       char *err, size_t errlen);
int rf__exr_count_levels(const char *path, size_t *nlevels, char *err, size_t errlen);

/* 1 when the file starts with PNG's signature; the one image of it. */
int rf__is_png(const char *path);
int rf__png_read(struct rf__image_data *img, const char *path, char *err, size_t errlen);

#endif
