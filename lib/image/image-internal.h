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

#endif
