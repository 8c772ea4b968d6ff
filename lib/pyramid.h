/* Internal: a cube's levels as RGBA vectors, for the prefilter's hot loop. */
#ifndef REFLECT_PYRAMID_H
#define REFLECT_PYRAMID_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "cubeface.h"
#include "reflect/envmap.h"

typedef float rf__v4 __attribute__((vector_size(16)));

/* The levels of a cube with borders, 4 floats a texel so one texel is one
 * aligned vector load. */
struct rf__pyramid {
	size_t nlevels;
	size_t size[32];       /* face width of each level */
	size_t face_stride[32]; /* vectors from one face to the next */
	rf__v4 *level[32];
	rf__v4 *data;
};

/* Where a sample reads: two levels and their weights. */
struct rf__lod {
	uint32_t l0, l1;
	float w0, w1;
};

int rf__pyramid_from_cube(struct rf__pyramid *p, const rf_cubemap *c);
void rf__pyramid_free(struct rf__pyramid *p);
struct rf__lod rf__pyramid_lod(const struct rf__pyramid *p, float lod);

static inline rf__v4
rf__pyramid_bilinear(const struct rf__pyramid *p, uint32_t l, int face, float u,
                     float v)
{
	size_t n = p->size[l], row = n + 2;
	float s = u * (float)n - 0.5f, t = v * (float)n - 0.5f;
	float fs, ft, a, b;
	const rf__v4 *q;

	/* keep a rounding error from stepping past the border */
	s = s < -0.5f ? -0.5f : s > (float)n - 0.5f ? (float)n - 0.5f : s;
	t = t < -0.5f ? -0.5f : t > (float)n - 0.5f ? (float)n - 0.5f : t;
	fs = floorf(s);
	ft = floorf(t);
	a = s - fs;
	b = t - ft;
	q = p->level[l] + (size_t)face * p->face_stride[l] +
	    ((size_t)(ft + 1.0f) * row + (size_t)(fs + 1.0f));
	return (1.0f - b) * ((1.0f - a) * q[0] + a * q[1]) +
	       b * ((1.0f - a) * q[row] + a * q[row + 1]);
}

/* Trilinear fetch in direction d (need not be unit). */
static inline rf__v4
rf__pyramid_fetch(const struct rf__pyramid *p, const float d[3], const struct rf__lod *lod)
{
	float u, v;
	int face = rf__cube_face(d, &u, &v);
	rf__v4 c = lod->w0 * rf__pyramid_bilinear(p, lod->l0, face, u, v);

	if (lod->w1 > 0.0f)
		c += lod->w1 * rf__pyramid_bilinear(p, lod->l1, face, u, v);
	return c;
}

#endif
