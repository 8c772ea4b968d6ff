/*
 * libreflect: environments, cubemaps, the roughness-to-lod mapping and
 * GGX prefiltering.
 *
 * Conventions (OpenEXR's, see reflect-prefilter(1)): world Y up, right
 * handed; faces +X -X +Y -Y +Z -Z; texel i of a face of N has its centre
 * at ((i + 1/2) / N) * 2 - 1.  Level k of a chain is N >> k texels wide.
 */
#ifndef REFLECT_ENVMAP_H
#define REFLECT_ENVMAP_H

#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- roughness <-> lod ------------------------------------------------- */

enum rf_mapping {
	RF_MAPPING_UNITY = 0,  /* lod = r (1.7 - 0.7 r) steps (default) */
	RF_MAPPING_LINEAR = 1, /* lod = r steps */
	RF_MAPPING_EXACT = 2   /* the spec-power remap Unity's fit approximates */
};

#define RF_MAPPING_DEFAULT RF_MAPPING_UNITY
#define RF_STEPS_DEFAULT 6

/* Parses "unity", "linear" or "exact"; RF_EINVAL otherwise. */
RF_EXTERN int rf_mapping_parse(const char *name, enum rf_mapping *out);
RF_EXTERN const char *rf_mapping_name(enum rf_mapping m);
/* Perceptual roughness in [0, 1] (clamped) to a lod in [0, steps]. */
RF_EXTERN float rf_roughness_to_lod(enum rf_mapping m, float steps, float roughness);
/* A lod in [0, steps] (clamped) to perceptual roughness. */
RF_EXTERN float rf_lod_to_roughness(enum rf_mapping m, float steps, float lod);

/* ---- cube faces and directions ---------------------------------------- */

enum rf_face {
	RF_FACE_POS_X = 0, RF_FACE_NEG_X, RF_FACE_POS_Y,
	RF_FACE_NEG_Y, RF_FACE_POS_Z, RF_FACE_NEG_Z
};

/* The face a direction (need not be unit) lands on and its position in
 * the face: u across (columns), v down (rows), both in [0, 1]. */
RF_EXTERN enum rf_face rf_cube_face(const float dir[3], float *u, float *v);
/* The (unnormalised) direction through face position (u, v). */
RF_EXTERN void rf_cube_direction(enum rf_face face, float u, float v, float dir[3]);
/* Solid angle of texel (i, j) of a face of n texels. */
RF_EXTERN double rf_cube_texel_solid_angle(size_t n, size_t i, size_t j);

/* Lat-long (equirectangular) mapping: the image centre looks along +Z,
 * right turns toward -X, the top row looks up.  u, v in [0, 1]. */
RF_EXTERN void rf_latlong_direction(float u, float v, float dir[3]);
RF_EXTERN void rf_latlong_position(const float dir[3], float *u, float *v);

/* ---- cubemaps --------------------------------------------------------- */

/* A cube of RGB floats with a chain of levels; each face is stored with a
 * one-texel border copied from its neighbours, so bilinear filtering is
 * seamless across edges at every level. */
typedef struct rf_cubemap rf_cubemap;

/* size: level 0 face width; nlevels: 0 means down to 1x1.  RF_ETOOBIG
 * past the memory limit (rf_cubemap_check_size). */
RF_EXTERN int rf_cubemap_create(rf_cubemap **c, size_t size, size_t nlevels);
/* The bytes a cube of these levels takes (its texels, borders
 * included), and whether that fits: RF_ETOOBIG with a message when it
 * is over the limit, REFLECT_MAX_CUBE_MB megabytes (default 1024: faces
 * of 2048 texels with every level take 0.4 GB; the shading pass holds a
 * second copy a third larger).  A reader checks before it allocates, so
 * that a forged or sparse file cannot make it take gigabytes. */
RF_EXTERN size_t rf_cubemap_bytes(size_t size, size_t nlevels);
RF_EXTERN int rf_cubemap_check_size(size_t size, size_t nlevels, char *err, size_t errlen);
RF_EXTERN void rf_cubemap_destroy(rf_cubemap *c);
RF_EXTERN size_t rf_cubemap_size(const rf_cubemap *c);
RF_EXTERN size_t rf_cubemap_levels(const rf_cubemap *c);
RF_EXTERN size_t rf_cubemap_level_size(const rf_cubemap *c, size_t level);
/* Texel (i = column, j = row) of a face at a level: 3 floats, RGB. */
RF_EXTERN float *rf_cubemap_texel(rf_cubemap *c, size_t level, enum rf_face f,
                                  size_t i, size_t j);
RF_EXTERN const float *rf_cubemap_texel_const(const rf_cubemap *c, size_t level,
                                              enum rf_face f, size_t i, size_t j);
/* Refreshes the borders of a level after its texels changed. */
RF_EXTERN void rf_cubemap_seal_level(rf_cubemap *c, size_t level);
/* Makes the texels along every edge equal to their neighbours across
 * it (pairs averaged, corners the mean of three), for readers that filter
 * each face on its own; reflect's own sampling needs no such fixup. */
RF_EXTERN void rf_cubemap_average_edges(rf_cubemap *c, size_t level);
/* Fills levels from+1 .. last by 2x2 box filtering (a plain mip chain). */
RF_EXTERN void rf_cubemap_box_chain(rf_cubemap *c, size_t from);

/* Bilinear sample of one level; trilinear across levels, lod clamped to
 * [0, levels - 1] (NaN to 0).  dir need not be unit: any finite one reads
 * inside the cube (a zero direction the centre of -X, a denormal one its
 * face); a NaN or infinite component reads black, as the shading pass
 * does. */
RF_EXTERN void rf_cubemap_sample_level(const rf_cubemap *c, size_t level,
                                       const float dir[3], float rgb[3]);
RF_EXTERN void rf_cubemap_sample(const rf_cubemap *c, const float dir[3], float lod,
                                 float rgb[3]);
/* Solid-angle-weighted mean of a level, per channel. */
RF_EXTERN void rf_cubemap_level_mean(const rf_cubemap *c, size_t level, double rgb[3]);
/* A level's radiance as 9 spherical-harmonic coefficients a channel
 * (sh[3 k + channel], k the basis function of bands 0, 1, 2 in the order
 * 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2), and the irradiance they
 * give at a normal n (need not be unit): the cosine-weighted integral of
 * the radiance over n's hemisphere, so that a Lambert surface of albedo a
 * reflects a E / pi. */
RF_EXTERN void rf_cubemap_sh9(const rf_cubemap *c, size_t level, float sh[27]);
RF_EXTERN void rf_sh9_irradiance(const float sh[27], const float n[3], float rgb[3]);
/* An irradiance cube: level 0 of out (any size) gets, for each texel's
 * direction n, E(n) / pi, the radiance a white Lambert surface facing n
 * reflects: the cosine convolution of src's level, read from a
 * box-filtered copy of at most 32 texels a face (a hemisphere's lobe
 * keeps nothing finer).  RF_ENOMEM. */
RF_EXTERN int rf_cubemap_irradiance(const rf_cubemap *src, size_t level, rf_cubemap *out);

/* ---- environment images ---------------------------------------------- */

enum rf_layout {
	RF_LAYOUT_AUTO = 0,
	RF_LAYOUT_LATLONG,   /* 2:1 equirectangular */
	RF_LAYOUT_CUBE,      /* N x 6N, faces +X -X +Y -Y +Z -Z top to bottom */
	RF_LAYOUT_VCROSS,    /* 3N x 4N vertical cross */
	RF_LAYOUT_HCROSS,    /* 4N x 3N horizontal cross */
	RF_LAYOUT_MIRRORBALL, /* square: a photographed mirror ball (never guessed) */
	RF_LAYOUT_ANGULAR    /* square: Debevec's angular map (never guessed) */
};

RF_EXTERN int rf_layout_parse(const char *name, enum rf_layout *out);
RF_EXTERN const char *rf_layout_name(enum rf_layout layout);
/* The layout of a w x h image: from its OpenEXR envmap attribute
 * ("latlong" or "cube", may be NULL), else from its aspect ratio.
 * RF_EINVAL with a message when neither tells. */
RF_EXTERN int rf_layout_detect(size_t w, size_t h, const char *envmap_attribute,
                               enum rf_layout *out, char *err, size_t errlen);
/* Checks that a w x h image can hold the layout; the face size in *face
 * (for lat-long, the face size a cube of it gets by default: a quarter
 * of the width, rounded down to a power of two). */
RF_EXTERN int rf_layout_check(enum rf_layout layout, size_t w, size_t h,
                              size_t *face, char *err, size_t errlen);

/* How the pixels' channels become radiance. */
struct rf_decode {
	int srgb;          /* 1: the colour channels are sRGB-encoded */
	int rgbm;          /* 1: RGBM: rgb * multiplier * a^exponent */
	float multiplier;  /* RGBM range (Unity's DecodeHDR x) */
	float exponent;    /* RGBM alpha exponent (Unity's DecodeHDR y) */
	float intensity;   /* a scale applied last (1) */
};

/* Fills level 0 of c (whose face size decides the resolution) from an
 * image in a layout: cube layouts are copied texel for texel (resampled
 * when the sizes differ); lat-long is area-filtered, with more taps
 * where the image's pixels crowd (toward the poles).  Non-finite values
 * become 0 and are counted in *nonfinite.  nch is 1 (grey), 3 or 4. */
RF_EXTERN int rf_envmap_from_pixels(rf_cubemap *c, const float *pixels, size_t w,
                                    size_t h, size_t nch, enum rf_layout layout,
                                    const struct rf_decode *decode,
                                    size_t *nonfinite, char *err, size_t errlen);
/* Writes level `level` of c into an image of a layout (w x h computed
 * from the level's face size, or given for lat-long): RGB, nch = 3. */
RF_EXTERN int rf_envmap_to_pixels(const rf_cubemap *c, size_t level,
                                  enum rf_layout layout, float *pixels, size_t w,
                                  size_t h);
/* The image size a level takes in a layout (lat-long: 4N x 2N). */
RF_EXTERN void rf_layout_size(enum rf_layout layout, size_t face, size_t *w,
                              size_t *h);

/* ---- prefiltering ----------------------------------------------------- */

enum rf_prefilter_method {
	RF_PREFILTER_FILTERED = 0, /* GGX importance sampling reading source mips */
	RF_PREFILTER_BRUTE = 1     /* every source texel, for reference */
};

struct rf_prefilter_options {
	enum rf_mapping mapping;
	float steps;            /* lod of the roughest level; 0: levels - 1 */
	unsigned samples;       /* GGX samples per texel (filtered method) */
	enum rf_prefilter_method method;
	float lod_bias;         /* added to each sample's source lod */
	int nthreads;
	/* Called from the calling thread now and then with done/total work;
	 * may be NULL. */
	void (*progress)(void *arg, double done, double total);
	void *progress_arg;
};

RF_EXTERN void rf_prefilter_defaults(struct rf_prefilter_options *o);
/* Convolves every level k >= 1 of `out` from level 0 of `src` with the
 * GGX lobe of the roughness the mapping gives level k (V = N, N.L
 * weighted, normalised); level 0 of out is a copy of src's level 0 when
 * the sizes match, else a box-filtered copy.  The filtered method samples
 * the source clamped at 16 times its mean and integrates the texels above
 * (a sun) exactly, within a bound on their number.  RF_EINVAL for a NaN or
 * infinite texel in src's level 0, which would spread over the levels,
 * or one past a quarter of the float range. */
RF_EXTERN int rf_prefilter(const rf_cubemap *src, rf_cubemap *out,
                           const struct rf_prefilter_options *o, char *err,
                           size_t errlen);
/* GGX samples a texel of level k >= 1 takes when level 1 takes `base`. */
RF_EXTERN size_t rf_prefilter_level_samples(unsigned base, size_t level);

/* ---- chains as streams and files -------------------------------------- */

/* What a chain is: read from and written to its metadata. */
struct rf_chain_info {
	int prefiltered;          /* 1: levels are GGX-convolved (else plain) */
	enum rf_mapping mapping;  /* the roughness-to-lod mapping it was made with */
	float steps;              /* the lod of its roughest level */
	unsigned samples;         /* GGX samples at level 1 (0: brute force) */
	int base_copied;          /* 1: level 0 is the source as it was */
	/* Level 0's irradiance coefficients (rf_cubemap_sh9), kept with a
	 * chain stream as IRRADIANCE_SH9 (written always, read when there). */
	int has_sh9;
	float sh9[27];
};

/* How an environment is read: the options of reflect-prefilter(1) and
 * reflect-shade(1) (--layout, --prefiltered, --srgb, --rgbm,
 * --intensity, --size). */
struct rf_envmap_options {
	enum rf_layout layout;  /* RF_LAYOUT_AUTO: from the file */
	int prefiltered;        /* take the file's levels as convolved */
	int srgb;               /* 1, 0, or -1: from the file's colour space */
	struct rf_decode decode; /* its srgb is set from the field above */
	int strict;             /* refuse NaN and Inf texels (1, the default
	                           of rf_envmap_options_init), or 0: replace
	                           them with 0, counted */
	size_t size;            /* face size of level 0 (0: the file's) */
	int nthreads;           /* for rendering the embedded room */
	int from_header;        /* the path came from a stream (PROBE_ENV): a
	                           regular file, never standard input or a pipe */
};
RF_EXTERN void rf_envmap_options_init(struct rf_envmap_options *o);
/* Loads the environment at path: NULL or "default" is the embedded room,
 * "-" a stream on standard input, a name with %d or %s six face images
 * (or with --prefiltered one file per level), else a stream, DDS,
 * MIP-mapped OpenEXR chain or image in any layout.  A raw environment
 * is level 0 of a one-level cube (info->prefiltered 0), a chain all its
 * levels; a cube of one level is always raw (a DDS or KTX cube without
 * mips, a one-level stream whatever its PREFILTER key), unless
 * o->prefiltered takes it as a chain of one level.  A NaN or infinite
 * value, or one past a quarter of the float range, is refused (RF_EINVAL, the message naming the file and the first:
 * level, face and texel, or an image's pixel) unless o->strict is 0;
 * then *nonfinite (may be NULL) counts the values replaced by 0.
 * RF_ENOTFOUND when the file cannot be opened. */
RF_EXTERN int rf_envmap_load(rf_cubemap **c, struct rf_chain_info *info, const char *path,
                             const struct rf_envmap_options *o, size_t *nonfinite,
                             char *err, size_t errlen);
/* Levels of a prefiltered chain of a cube of `size` texels: `want` when
 * not 0 (RF_EINVAL when the size cannot halve that often), else at most
 * RF_STEPS_DEFAULT + 1 (Unity's 7), never below min_size texels, never
 * halving an odd size. */
RF_EXTERN int rf_chain_levels(size_t size, size_t want, size_t min_size, size_t *levels,
                              char *err, size_t errlen);

/* Writes every level as one frame of a stream: NCOLS=N NROWS=6N,
 * channels R G B, keys ENVMAP=CUBE LEVEL LEVELS and the chain's info. */
RF_EXTERN int rf_chain_write_stream(const rf_cubemap *c, const struct rf_chain_info *info,
                                    rf_writer *w, const rf_header *base, char *err,
                                    size_t errlen);
/* Reads a chain from a stream: frames with ENVMAP=CUBE, one per level
 * (LEVEL 0, 1, ...), or one frame of a raw environment.  A NaN or
 * infinite texel, or one past a quarter of the float range, is refused
 * (RF_EINVAL, the message naming its level, face, texel and channel). */
RF_EXTERN int rf_chain_read_stream(rf_cubemap **c, struct rf_chain_info *info,
                                   rf_reader *r, char *err, size_t errlen);

/* Writes a chain as a MIP-mapped OpenEXR cube (N x 6N, envmap=cube):
 * the chain's levels first, then box-filtered levels down to 1x1 that
 * OpenEXR requires and readers ignore; the chain's info goes into
 * reflect:* attributes. */
RF_EXTERN int rf_chain_write_file(const rf_cubemap *c, const struct rf_chain_info *info,
                                  const char *path, char *err, size_t errlen);
/* Reads a MIP-mapped OpenEXR cube: its cube levels (N x 6N) as a chain,
 * the non-cube tail ignored.  *is_reflect is 1 for files this library
 * wrote (then info is filled from their attributes).  NaN and infinite
 * texels become 0 (rf_envmap_load refuses them). */
RF_EXTERN int rf_chain_read_file(rf_cubemap **c, struct rf_chain_info *info,
                                 int *is_reflect, const char *path, char *err,
                                 size_t errlen);
/* Reads a DDS cube map (all six faces) with its mip levels as a
 * prefiltered chain (mapping unity, steps = levels - 1): the levels while
 * the size halves evenly, as rf_cubemap_create counts them; a cube of one
 * level is a raw environment (info->prefiltered 0).  Float, half,
 * R11G11B10, RGB9E5 and 8-bit RGBA/BGRA (sRGB decoded) texels; alpha is
 * ignored, block-compressed formats are refused.  Faces are mirrored
 * from Direct3D's orientation to OpenEXR's, so a direction reads what
 * Direct3D reads for it.  Non-finite values become 0, counted in *nonfinite (may
 * be NULL). */
RF_EXTERN int rf_chain_read_dds(rf_cubemap **c, struct rf_chain_info *info,
                                size_t *nonfinite, const char *path, char *err,
                                size_t errlen);
/* Reads a KTX 1 or KTX 2 cube map (told apart by the file's identifier)
 * with its mip levels, kept as rf_chain_read_dds keeps them: float,
 * half, R11G11B10, RGB9E5 and 8-bit RGB(A)/BGRA texels (sRGB decoded),
 * KTX 2 levels plain or Zstandard-supercompressed (with libzstd).  Both
 * store faces in OpenGL's orientation, that of DDS, and are mirrored to
 * OpenEXR's the same way.  Block-compressed and Basis Universal formats,
 * arrays, 3D textures and non-square faces are refused by name.  Info
 * is that of a DDS chain, or what reflect wrote into the file's
 * reflect:* keys, *is_reflect (may be NULL) then 1. */
RF_EXTERN int rf_chain_read_ktx(rf_cubemap **c, struct rf_chain_info *info,
                                int *is_reflect, size_t *nonfinite, const char *path,
                                char *err, size_t errlen);

/* How a chain is written as KTX: version 1 or 2, RGBA half floats or
 * floats (alpha 1), KTX 2 levels Zstandard-supercompressed at zstd
 * (1 to 22; 0: none). */
enum rf_ktx_texel {
	RF_KTX_RGBA16F = 0,
	RF_KTX_RGBA32F = 1
};
struct rf_ktx_options {
	int version;
	enum rf_ktx_texel texel;
	int zstd;
};
/* Writes every level of the chain, and nothing past them, as a KTX cube
 * map in OpenGL's orientation (KTXorientation rd) with the chain's info
 * in reflect:* keys; through a file beside path renamed over it, so a
 * failure leaves path as it was.  RF_EINVAL for options it cannot do
 * (zstd in KTX 1, or without libzstd). */
RF_EXTERN int rf_chain_write_ktx(const rf_cubemap *c, const struct rf_chain_info *info,
                                 const char *path, const struct rf_ktx_options *o,
                                 char *err, size_t errlen);

/* ---- the embedded environment ----------------------------------------- */

/* Radiance of the default room as seen from its probe centre: the room
 * box (-3,0,-2)..(3,3,2), centre (0,1.5,0); a hue per wall, a bright
 * grid, two HDR windows. */
RF_EXTERN void rf_default_environment(const float dir[3], float rgb[3]);
/* The same room as radiance leaving a point of its walls (world units). */
RF_EXTERN void rf_default_room_radiance(const float point[3], float rgb[3]);
/* Renders it into level 0 of a cube (supersampled) and seals it. */
RF_EXTERN void rf_default_environment_cube(rf_cubemap *c);
/* The same on nthreads threads (the same bytes at any count). */
RF_EXTERN void rf_default_environment_cube_threads(rf_cubemap *c, int nthreads);

#ifdef __cplusplus
}
#endif

#endif
