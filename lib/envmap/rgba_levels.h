/* Internal: a cube's levels as RGBA vectors, for the prefilter's hot loop. */
#ifndef REFLECT_RGBA_LEVELS_H
#define REFLECT_RGBA_LEVELS_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "envmap/cubeface.h"
#include "reflect/envmap.h"

typedef float rf__v4 __attribute__((vector_size(16)));

/* The levels of a cube with borders, 4 floats a texel so one texel is one
 * aligned vector load. */
struct rf__rgba_levels {
	size_t nlevels;
	size_t size[32];       /* face width of each level */
	size_t face_stride[32]; /* vectors from one face to the next */
	rf__v4 *level[32];
	rf__v4 *data;
	/* The same per level as the vector kernels gather them: face
	 * width, and in texels from data: face 0, face to face, row to row. */
	float lvl_scale[32];
	int32_t lvl_base[32], lvl_face[32], lvl_row[32];
	/* The cube's frame when it is not the world's (a turned probe's
	 * capture): rf__rgba_levels_fetch_many reads direction d at
	 * turn^T d, turn being row-major, world = turn local. */
	int turned;
	float turn[9];
};

typedef int rf__v4i __attribute__((vector_size(16)));

/* Where a sample reads: two levels, their weights, and what the inner
 * loop needs of each level, looked up once per sample instead of once
 * per texel. */
struct rf__lod {
	rf__v4 scale;             /* face widths n0 n0 n1 n1 */
	const rf__v4 *base[2];    /* face 0 of each level */
	size_t face_stride[2];    /* vectors from one face to the next */
	size_t row[2];            /* vectors from one row to the next */
	float w0, w1;
};

int rf__rgba_levels_from_cube(struct rf__rgba_levels *p, const rf_cubemap *c);
void rf__rgba_levels_destroy(struct rf__rgba_levels *p);
/* Sets the cube's frame (NULL: the world's); from_cube resets it. */
void rf__rgba_levels_turn(struct rf__rgba_levels *p, const float rotation[9]);
/* d turned into the frame of rotation (row-major, world = rotation
 * local): rotation^T d. */
static inline void
rf__turn_in(const float m[9], float x, float y, float z, float out[3])
{
	out[0] = m[0] * x + m[3] * y + m[6] * z;
	out[1] = m[1] * x + m[4] * y + m[7] * z;
	out[2] = m[2] * x + m[5] * y + m[8] * z;
}

/* Where a read at this lod goes (clamped to the levels); inline, as the
 * shading pass asks once a pixel. */
static inline struct rf__lod
rf__rgba_levels_lod(const struct rf__rgba_levels *p, float lod)
{
	struct rf__lod r;
	float top = (float)(p->nlevels - 1);
	size_t l0, l1;

	if (!(lod > 0.0f))
		lod = 0.0f;
	if (lod > top)
		lod = top;
	l0 = (size_t)lod;
	r.w1 = lod - (float)l0;
	l1 = l0 + 1 < p->nlevels ? l0 + 1 : l0;
	if (l1 == l0)
		r.w1 = 0.0f;
	r.w0 = 1.0f - r.w1;
	r.scale[0] = r.scale[1] = (float)p->size[l0];
	r.scale[2] = r.scale[3] = (float)p->size[l1];
	r.base[0] = p->level[l0];
	r.base[1] = p->level[l1];
	r.face_stride[0] = p->face_stride[l0];
	r.face_stride[1] = p->face_stride[l1];
	r.row[0] = p->size[l0] + 2;
	r.row[1] = p->size[l1] + 2;
	return r;
}

static inline rf__v4
rf__rgba_levels_bilinear(const rf__v4 *q, size_t row, float a, float b)
{
	return (1.0f - b) * ((1.0f - a) * q[0] + a * q[1]) +
	       b * ((1.0f - a) * q[row] + a * q[row + 1]);
}

/*
 * Trilinear fetch in direction d (need not be unit).  Both levels'
 * texel coordinates are found at once in one vector: (s0, t0, s1, t1).
 * u and v lie in [0, 1] (to an ulp), so s >= -0.5 and the truncation of
 * s + 1 is floor(s) + 1, the index in the bordered face.
 */
static inline rf__v4
rf__rgba_levels_fetch(const float d[3], const struct rf__lod *lod)
{
	float u, v;
	int face = rf__cube_face(d, &u, &v);
	rf__v4 uv = { u, v, u, v };
	rf__v4 st = uv * lod->scale + 0.5f; /* coordinates + 1, in the border frame */
	rf__v4i it = __builtin_convertvector(st, rf__v4i);
	rf__v4 fr = st - __builtin_convertvector(it, rf__v4);
	const rf__v4 *q0 = lod->base[0] + (size_t)face * lod->face_stride[0] +
	                   (size_t)it[1] * lod->row[0] + (size_t)it[0];
	rf__v4 c = lod->w0 * rf__rgba_levels_bilinear(q0, lod->row[0], fr[0], fr[1]);

	if (lod->w1 > 0.0f) {
		const rf__v4 *q1 = lod->base[1] + (size_t)face * lod->face_stride[1] +
		                   (size_t)it[3] * lod->row[1] + (size_t)it[2];

		c += lod->w1 * rf__rgba_levels_bilinear(q1, lod->row[1], fr[2], fr[3]);
	}
	return c;
}

#endif
