/* The prefilter's bright part (prefilter_bright.c): texels far above
 * the mean, integrated exactly against each lobe. */
#ifndef REFLECT_PREFILTER_BRIGHT_H
#define REFLECT_PREFILTER_BRIGHT_H

#include <stddef.h>

#include "reflect/envmap.h"

/* The brute-force integration points of the bright part that hold some
 * of it: columns of `stride` floats (a multiple of 4, the last block
 * padded with points of nothing), x y z (unit directions) and the
 * solid angle times the reconstructed radiance r g b. */
struct rf__bright {
	float *p;
	size_t count, stride;
	size_t sub; /* points per texel side they were made with */
};

/* Clamps level 0 of c (sealed again) at a multiple of its mean, raised
 * until the points at sub x sub a texel are few enough, and puts what is
 * above into *resid, a new one-level cube of the same size; no texel is
 * that bright: *resid NULL, c untouched.  *count: the bright texels. */
int rf__bright_split(rf_cubemap *c, size_t sub, rf_cubemap **resid, size_t *count);
/* The points of level 0 of resid at sub x sub per texel, those whose
 * bilinear reconstruction is not zero (b zeroed first, or reused). */
int rf__bright_points(struct rf__bright *b, const rf_cubemap *resid, size_t sub);
void rf__bright_destroy(struct rf__bright *b);
/* The integral of GGX D(h) (n.l) over the sphere for V = N. */
double rf__ggx_lobe_integral(double alpha);
/* Adds the bright part's lobe integral about unit n (norm: the lobe's
 * integral, rf__ggx_lobe_integral of alpha) to rgb. */
void rf__bright_add(const struct rf__bright *b, const float n[3], double alpha,
                    double norm, float rgb[3]);

#endif
