/*
 * GGX in double precision for the library, the plugins and their
 * build-time tables (the path tracer, the DFG table, the horizon
 * occlusion mode, footprint-gen): Hammersley's second coordinate,
 * Smith's Lambda, and Heitz's sampler of the visible normals (JCGT 2018;
 * spec 7.3).  Header-only: each plugin stays one self-contained object.
 */
#ifndef REFLECT_MATHS_GGX_H
#define REFLECT_MATHS_GGX_H

#include <math.h>
#include <stdint.h>

/* The radical inverse of i in base 2: its bits reversed, over 2^32. */
static inline double
rf__ggx_radical_inverse(uint32_t i)
{
	i = (i << 16) | (i >> 16);
	i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
	i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
	i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
	i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
	return (double)i * 2.3283064365386963e-10;
}

/* Smith's Lambda for alpha^2 = a2, a direction at cosine c from N. */
static inline double
rf__ggx_lambda(double a2, double c)
{
	double c2 = c * c;

	return 0.5 * (sqrt(1.0 + a2 * (1.0 - c2) / c2) - 1.0);
}

/* v / |v|, left as it is when it has no length. */
static inline void
rf__ggx_normalise(double v[3])
{
	double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);

	if (l > 0.0) {
		v[0] /= l;
		v[1] /= l;
		v[2] /= l;
	}
}

/* What the sampler works out once for a view vl (local frame, N = z)
 * and an alpha: the stretched view and its frame. */
struct rf__ggx_vndf {
	double alpha, vh[3], t1[3], t2[3], s;
};

static inline void
rf__ggx_vndf_init(struct rf__ggx_vndf *g, const double vl[3], double alpha)
{
	double *vh = g->vh, *t1 = g->t1, *t2 = g->t2, lensq;

	g->alpha = alpha;
	vh[0] = alpha * vl[0];
	vh[1] = alpha * vl[1];
	vh[2] = vl[2];
	rf__ggx_normalise(vh);
	lensq = vh[0] * vh[0] + vh[1] * vh[1];
	if (lensq > 0.0) {
		t1[0] = -vh[1] / sqrt(lensq);
		t1[1] = vh[0] / sqrt(lensq);
	} else {
		t1[0] = 1.0;
		t1[1] = 0.0;
	}
	t1[2] = 0.0;
	t2[0] = vh[1] * t1[2] - vh[2] * t1[1];
	t2[1] = vh[2] * t1[0] - vh[0] * t1[2];
	t2[2] = vh[0] * t1[1] - vh[1] * t1[0];
	g->s = 0.5 * (1.0 + vh[2]);
}

/* The visible microfacet normal h (unit, local frame; 0 when it has no
 * length) of the numbers u1, u2 in [0, 1). */
static inline void
rf__ggx_vndf_normal(const struct rf__ggx_vndf *g, double u1, double u2, double h[3])
{
	double rr = sqrt(u1), phi = 2.0 * M_PI * u2, p1 = rr * cos(phi), p2 = rr * sin(phi);
	double nh[3];
	int j;

	p2 = (1.0 - g->s) * sqrt(1.0 - p1 * p1) + g->s * p2;
	for (j = 0; j < 3; j++)
		nh[j] = p1 * g->t1[j] + p2 * g->t2[j] +
		        sqrt(fmax(0.0, 1.0 - p1 * p1 - p2 * p2)) * g->vh[j];
	h[0] = g->alpha * nh[0];
	h[1] = g->alpha * nh[1];
	h[2] = fmax(0.0, nh[2]);
	rf__ggx_normalise(h);
}

#endif
