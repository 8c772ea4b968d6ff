/* Internal to libreflect: the image layer's entry points for other areas
 * that are not public. */
#ifndef REFLECT_IMAGE_INTERNAL_H
#define REFLECT_IMAGE_INTERNAL_H

#include <stddef.h>

#include "reflect/image.h"

/* An image file held in memory (a mesh file's embedded PNG or JPEG),
 * read as rf_image_read reads a file; name stands for it in messages,
 * ext ("png", "jpg"...) says its type where its bytes do not. */
int rf__image_read_memory(rf_image **img, const void *data, size_t size, const char *ext,
                          const char *name, char *err, size_t errlen);

/* An 8-bit PNG of width x height pixels of nchannels (1 to 4: grey, grey
 * and alpha, RGB, RGBA) made in memory, as PNG files are written: values
 * clamped to [0, 1], rounded, tagged sRGB.  *data (malloc'd, the
 * caller's to free) and *len; RF_EINVAL for a bad size, RF_ENOMEM. */
int rf__png_encode(unsigned char **data, size_t *len, const float *pixels, size_t width,
                   size_t height, size_t nchannels);

#endif
