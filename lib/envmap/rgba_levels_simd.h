/* Internal: the RGBA levels' vector kernels, eight samples at a time (the
 * prefilter's lobe sum and the shading pass's reads). */
#ifndef REFLECT_RGBA_LEVELS_SIMD_H
#define REFLECT_RGBA_LEVELS_SIMD_H

#include <stddef.h>
#include <stdint.h>

#include "envmap/rgba_levels.h"

/*
 * A level's samples as columns (one array per field), so eight samples
 * load as one vector each.  The offsets are in texels from the start of
 * the levels' data, hence the int32 limit checked by
 * rf__rgba_levels_simd_usable.
 */
struct rf__lobe_table {
	size_t n;
	float *lx, *ly, *lz;         /* L in the frame of N */
	float *scale0, *scale1;      /* face widths of the two levels read */
	float *w0, *w1;              /* their weights */
	int32_t *base0, *base1;      /* face 0 of each level */
	int32_t *face0, *face1;      /* texels from one face to the next */
	int32_t *row0, *row1;        /* texels from one row to the next */
	void *block;
};

/* Whether this CPU has the vector unit the kernel needs and the levels
 * are small enough for 32-bit offsets.  REFLECT_SIMD=off in the
 * environment turns the kernel off (to compare it with the scalar path). */
int rf__rgba_levels_simd_usable(const struct rf__rgba_levels *p);

int rf__lobe_table_alloc(struct rf__lobe_table *t, size_t n);
void rf__lobe_table_destroy(struct rf__lobe_table *t);
void rf__lobe_table_set(struct rf__lobe_table *t, size_t i, const float l[3],
                        const struct rf__lod *lod, const struct rf__rgba_levels *p);

/* The sum of the first `count` samples (a multiple of 8) around the unit
 * normal n with tangent frame tg, bt: what the scalar loop adds up. */
rf__v4 rf__lobe_sum8(const struct rf__lobe_table *t, size_t count,
                     const struct rf__rgba_levels *p, const float n[3],
                     const float tg[3], const float bt[3]);

/* Trilinear reads in count directions (x, y, z, need not be unit) at
 * their lods, as rf__rgba_levels_lod and rf__rgba_levels_fetch make them; eight
 * at a time when `vector` (rf__rgba_levels_simd_usable said yes). */
void rf__rgba_levels_fetch_many(const struct rf__rgba_levels *p, int vector, size_t count,
                            const float *x, const float *y, const float *z, const float *lod,
                            rf__v4 *rgb);

#endif
