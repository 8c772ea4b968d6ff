/* Internal to libreflect: a cube's levels as the other areas fill and
 * read them. */
#ifndef REFLECT_ENVMAP_INTERNAL_H
#define REFLECT_ENVMAP_INTERNAL_H

#include <float.h>

#include "util/util.h"
#include "reflect/envmap.h"

/* The largest magnitude of a texel: a quarter of the float range, so that
 * the weighted sums of a few texels every sampler and filter makes (with
 * weights that add up to 1, rounded) stay finite.  3e38 is no radiance,
 * and a texel past this is refused as an infinite one is. */
#define RF__TEXEL_MAX (FLT_MAX / 4)

static inline int
rf__texel_ok(float v)
{
	return v >= -RF__TEXEL_MAX && v <= RF__TEXEL_MAX; /* and not NaN */
}

/* The values a reader met that are NaN, infinite or past RF__TEXEL_MAX,
 * each made 0, and the first:
 * a cube's level, face and texel (column x, row y of the face as the file
 * stores it), or for an image (face -1) its pixel. */
struct rf__nonfinite {
	size_t count;
	size_t level, x, y;
	int face, channel; /* channel 0..3: R G B A */
	float value;
};
/* Counts a value (nf may be NULL: nothing kept). */
void rf__nonfinite_note(struct rf__nonfinite *nf, size_t level, int face, size_t x,
                        size_t y, int channel, float value);
/* The first as "level 0, face +X, texel (3, 5): G is nan" (or "pixel
 * (3, 5): ..."). */
void rf__nonfinite_where(const struct rf__nonfinite *nf, char *buf, size_t len);

/* Fills level k of a cube from an N x 6N image of that level's size,
 * texel for texel (first 3 channels; non-finite values become 0 and are
 * noted in nf). */
int rf__cube_level_from_pixels(rf_cubemap *c, size_t level, const float *px,
                               size_t w, size_t h, size_t nch, struct rf__nonfinite *nf,
                               char *err, size_t errlen);
/* The readers of envmap.h with the non-finite values noted in nf (the
 * public ones count them, rf_chain_read_stream refuses them); a stream's
 * first frame may have been read already (first, else NULL). */
int rf__chain_read_stream(rf_cubemap **c, struct rf_chain_info *info, rf_reader *r,
                          const rf_header *first, struct rf__nonfinite *nf, char *err,
                          size_t errlen);
int rf__chain_read_file(rf_cubemap **c, struct rf_chain_info *info, int *is_reflect,
                        struct rf__nonfinite *nf, const char *path, char *err,
                        size_t errlen);
int rf__chain_read_dds(rf_cubemap **c, struct rf_chain_info *info,
                       struct rf__nonfinite *nf, const char *path, char *err,
                       size_t errlen);
int rf__chain_read_ktx(rf_cubemap **c, struct rf_chain_info *info, int *is_reflect,
                       struct rf__nonfinite *nf, const char *path, char *err,
                       size_t errlen);
int rf__envmap_from_pixels(rf_cubemap *c, const float *pixels, size_t w, size_t h,
                           size_t nch, enum rf_layout layout,
                           const struct rf_decode *decode, struct rf__nonfinite *nf,
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

		/* ringing of the truncated series can dip below 0; coefficients
		 * near the float range can add up past it (inf, or inf - inf) */
		e[ch] = v > 0.0f ? (v < FLT_MAX ? v : FLT_MAX) : 0.0f;
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
