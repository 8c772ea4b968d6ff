/* Internal: the image files libreflect reads itself, without loading the
 * image module (exr_read.c). */
#ifndef REFLECT_IMAGE_READERS_H
#define REFLECT_IMAGE_READERS_H

#include <stddef.h>
#include <stdint.h>

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

/* The bounds every reader applies before it allocates (bounds.c): at
 * most 2^28 values, and no more than the file can hold (format: the
 * module's name of the format, "hdr", "openexr", "png"..., or NULL).
 * 0, or RF_ETOOBIG with "'path': a WxH image of N channels is out of
 * range". */
int rf__image_bounds(const char *path, const char *format, size_t w, size_t h,
                     size_t nch, char *err, size_t errlen);

/* A Radiance HDR header as the bounds see it: scanlines of length pixels,
 * the data from byte data on. */
struct rf__hdr_shape {
	size_t scanlines, length, data;
};
/* 0 and s filled when buf (the file's first len bytes) holds a header
 * and its resolution line; -1 otherwise. */
int rf__hdr_shape(const unsigned char *buf, size_t len, struct rf__hdr_shape *s);
/* The fewest bytes a file with that header can have (UINTMAX_MAX when
 * past counting). */
uintmax_t rf__hdr_bytes(const struct rf__hdr_shape *s);

#endif
