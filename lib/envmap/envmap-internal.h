/* Internal to libreflect: a cube's levels as the other areas fill and
 * read them. */
#ifndef REFLECT_ENVMAP_INTERNAL_H
#define REFLECT_ENVMAP_INTERNAL_H

#include "util/util.h"
#include "reflect/envmap.h"

/* Fills level k of a cube from an N x 6N image of that level's size,
 * texel for texel (first 3 channels; non-finite values become 0 and are
 * counted). */
int rf__cube_level_from_pixels(rf_cubemap *c, size_t level, const float *px,
                               size_t w, size_t h, size_t nch, size_t *nonfinite,
                               char *err, size_t errlen);
/* A face of a cube level with its one-texel border: (n + 2)^2 RGB
 * texels, rows top first, starting at border texel (-1, -1). */
const float *rf__cubemap_padded_face(const rf_cubemap *c, size_t level, int face);
/* Level `from_level` of src into level `to_level` (of the same face size)
 * of dst, texel for texel, and sealed. */
void rf__cubemap_copy_level(rf_cubemap *dst, size_t to_level, const rf_cubemap *src,
                            size_t from_level);

/* Exported for the test suite and the bench only, never installed: the
 * reference the prefilter is measured against.  One texel of one lobe by
 * brute force over the source level 0, and the same for count
 * directions at once (the source tables built once): rgb[3 * count]. */
RF_EXTERN void rf__prefilter_brute_texel(const rf_cubemap *src, const float n[3],
                                         float roughness, float rgb[3]);
RF_EXTERN int rf__prefilter_brute_texels(const rf_cubemap *src, const float *dirs,
                                         size_t count, float roughness, float *rgb);

#endif
