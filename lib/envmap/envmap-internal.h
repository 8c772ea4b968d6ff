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

/* Level 0 of c from a square light-probe image (RGB floats) in the
 * mirror-ball or angular layout (layout_sphere.c). */
int rf__from_sphere(rf_cubemap *c, const float *img, size_t w, size_t h,
                    enum rf_layout layout);

/* The irradiance of 9 coefficients (rf_sh9_irradiance) as a quadratic
 * in the unit normal (x, y, z), per channel: E = q0 + q1 x + q2 y + q3 z
 * + q4 xy + q5 yz + q6 xz + q7 z^2 + q8 (x^2 - y^2), for shading a
 * pixel in a few float multiply-adds. */
void rf__sh9_quadratic(const float sh[27], float q[3][9]);

static inline void
rf__sh9_quadratic_eval(const float q[3][9], const float n[3], float e[3])
{
	const float x = n[0], y = n[1], z = n[2];
	const float xy = x * y, yz = y * z, xz = x * z, zz = z * z, d = x * x - y * y;
	int ch;

	for (ch = 0; ch < 3; ch++) {
		const float *k = q[ch];
		float v = k[0] + k[1] * x + k[2] * y + k[3] * z + k[4] * xy + k[5] * yz +
		          k[6] * xz + k[7] * zz + k[8] * d;

		/* ringing of the truncated series can dip below 0 */
		e[ch] = v > 0.0f ? v : 0.0f;
	}
}

/* Exported for the test suite and the bench only, never installed: the
 * reference the prefilter is measured against.  One texel of one lobe by
 * brute force over the source level 0, and the same for count
 * directions at once (the source tables built once): rgb[3 * count]. */
RF_EXTERN void rf__prefilter_brute_texel(const rf_cubemap *src, const float n[3],
                                         float roughness, float rgb[3]);
RF_EXTERN int rf__prefilter_brute_texels(const rf_cubemap *src, const float *dirs,
                                         size_t count, float roughness, float *rgb);

#endif
