/*
 * The share of a GGX lobe that the geometric horizon leaves, for the
 * horizon occlusion mode (horizon.c) and its test.  Header-only: the
 * plugin is one self-contained object.
 *
 * The split-sum's DFG term is the lobe's directional albedo with the
 * shading normal N alone: it counts every direction above N's horizon.
 * A surface whose N is bent away from its geometric normal Ng (a normal
 * map, a bump) reflects nothing from below Ng's horizon, since light
 * there would come through the surface (a path tracer discards those
 * directions).  The share of the albedo that is left,
 *   E_Ng / E_N = E[w [N.L > 0] [Ng.L > 0]] / E[w [N.L > 0]],
 * is exact for an environment of one radiance, and the factor to put on
 * a prefiltered lookup.  Estimated as the DFG table is, by sampling the
 * visible normals (Heitz 2018) at K Hammersley points, each weighted
 * G2/G1(V) (height-correlated Smith), the same points for every pixel:
 * a smooth function of the pixel's vectors, the same bytes at any thread
 * count.
 */
#ifndef REFLECT_PLUGINS_HORIZON_H
#define REFLECT_PLUGINS_HORIZON_H

#include <math.h>
#include <stdint.h>

#include "maths/ggx.h"

/* N and Ng closer than this (the sine of their angle) are one normal. */
#define HORIZON_SAME_NORMAL 1e-4

/* E_Ng / E_N for unit-free vectors n, ng, v (the view, from the surface
 * toward the eye), perceptual roughness r, k points. */
static inline double
horizon_share(const float nf[3], const float ngf[3], const float vf[3], double r, int k)
{
	double n[3] = { nf[0], nf[1], nf[2] }, ng[3] = { ngf[0], ngf[1], ngf[2] };
	double v[3] = { vf[0], vf[1], vf[2] }, t[3], b[3], c[3], vl[3];
	double alpha = r * r, a2, lv, num = 0.0, den = 0.0, sign, aa, bb;
	struct rf__ggx_vndf g;
	int i;

	rf__ggx_normalise(n);
	rf__ggx_normalise(ng);
	rf__ggx_normalise(v);
	c[0] = n[1] * ng[2] - n[2] * ng[1];
	c[1] = n[2] * ng[0] - n[0] * ng[2];
	c[2] = n[0] * ng[1] - n[1] * ng[0];
	if (sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) < HORIZON_SAME_NORMAL &&
	    n[0] * ng[0] + n[1] * ng[1] + n[2] * ng[2] > 0.0)
		return 1.0;
	/* a frame about n (Duff et al. 2017) */
	sign = copysign(1.0, n[2]);
	aa = -1.0 / (sign + n[2]);
	bb = n[0] * n[1] * aa;
	t[0] = 1.0 + sign * n[0] * n[0] * aa;
	t[1] = sign * bb;
	t[2] = -sign * n[0];
	b[0] = bb;
	b[1] = sign + n[1] * n[1] * aa;
	b[2] = -n[1];
	vl[0] = v[0] * t[0] + v[1] * t[1] + v[2] * t[2];
	vl[1] = v[0] * b[0] + v[1] * b[1] + v[2] * b[2];
	vl[2] = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
	if (!(vl[2] > 0.0))
		return 1.0; /* seen from behind: nothing reflected to occlude */
	if (alpha < 1e-4)
		alpha = 1e-4;
	a2 = alpha * alpha;
	lv = rf__ggx_lambda(a2, vl[2]);
	rf__ggx_vndf_init(&g, vl, alpha);
	for (i = 0; i < k; i++) {
		double h[3], l[3], vdh, w, lw;
		int j;

		rf__ggx_vndf_normal(&g, (i + 0.5) / k, rf__ggx_radical_inverse((uint32_t)i), h);
		vdh = vl[0] * h[0] + vl[1] * h[1] + vl[2] * h[2];
		for (j = 0; j < 3; j++)
			l[j] = 2.0 * vdh * h[j] - vl[j];
		if (!(l[2] > 0.0))
			continue;
		w = (1.0 + lv) / (1.0 + lv + rf__ggx_lambda(a2, l[2]));
		den += w;
		/* l in the world, against Ng */
		lw = 0.0;
		for (j = 0; j < 3; j++)
			lw += (l[0] * t[j] + l[1] * b[j] + l[2] * n[j]) * ng[j];
		if (lw > 0.0)
			num += w;
	}
	return den > 0.0 ? num / den : 1.0;
}

#endif
