/*
 * Internal to envmap: the uncompressed texels GPU texture files store
 * (DDS, KTX 1, KTX 2), and their cube faces, which all three address
 * with OpenGL's face selection table, the first row of a face at t = 0.
 */
#ifndef REFLECT_ENVMAP_TEXEL_H
#define REFLECT_ENVMAP_TEXEL_H

#include <stddef.h>

#include "reflect/envmap.h"

enum rf__texel_kind {
	RF__TEXEL_F32,       /* nch 32-bit floats: 1 (grey), 3 or 4 */
	RF__TEXEL_F16,       /* 3 or 4 half floats */
	RF__TEXEL_R11G11B10, /* packed in a little-endian 32-bit word */
	RF__TEXEL_RGB9E5,    /* likewise */
	RF__TEXEL_RGBA8,     /* bytes R G B (A) */
	RF__TEXEL_BGRA8      /* bytes B G R (A or X) */
};

struct rf__texel_format {
	enum rf__texel_kind kind;
	unsigned nch;   /* RF__TEXEL_F32 only */
	unsigned bytes; /* per texel */
	int srgb;       /* 8-bit kinds: decode sRGB to linear */
};

/* One texel's RGB (alpha ignored). */
void rf__texel_decode(const struct rf__texel_format *fmt, const unsigned char *p,
                      float rgb[3]);
/* The half float nearest v (ties to even; past 65504 infinite). */
unsigned rf__float_to_half(float v);

/*
 * Where texel (i, j) of face f of a GL cube (i across, j down from the
 * first row) lies in reflect's cube: the faces select alike, but within
 * a face OpenEXR's orientations mirror the X and Z faces left to right
 * and the Y faces top to bottom (chain_dds.c has the table).  The map
 * is its own inverse.
 */
static inline void
rf__gl_texel(int f, size_t n, size_t i, size_t j, size_t *ri, size_t *rj)
{
	int y = f == RF_FACE_POS_Y || f == RF_FACE_NEG_Y;

	*ri = y ? i : n - 1 - i;
	*rj = y ? n - 1 - j : j;
}

struct rf__nonfinite;

/* Decodes row j of GL face f at a level (n texels of fmt) into reflect's
 * cube; NaN and Inf become 0, noted in nf (may be NULL) at their place in
 * the file. */
void rf__texel_store_gl_row(rf_cubemap *c, size_t level, int f, size_t j,
                            const unsigned char *row, const struct rf__texel_format *fmt,
                            struct rf__nonfinite *nf);

#endif
