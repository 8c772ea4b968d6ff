/* Internal to the surface area: the integrals of the DFG table, shared by
 * the library (rf_dfg_integrate) and dfg-gen, which makes the table when
 * reflect is built. */
#ifndef REFLECT_DFG_INTEGRATE_H
#define REFLECT_DFG_INTEGRATE_H

#include <math.h>
#include <stdint.h>

/* the radical inverse and Smith's Lambda, in double */
#include "maths/ggx.h"

/*
 * Samples per entry.  Drawing the GGX distribution of *visible* normals
 * (Heitz 2018) rather than the plain normal distribution makes every
 * sample's weight G2/G1(v), bounded by 1: at grazing angles the plain
 * estimator needs some 50 times as many samples for the same error.
 * With 1024 Hammersley points and 64 x 64 entries, the bilinear lookup
 * is within 1e-3 of the integral for n.v >= 0.05 (tests/unit/test-dfg.c).
 */
#define DFG_SAMPLES 1024

static inline double
pow5(double x)
{
	double x2 = x * x;

	return x2 * x2 * x;
}

/* Hammersley point i of n as (sqrt(u1), cos 2 pi u2, sin 2 pi u2): the
 * polar disc coordinates of the VNDF sampler. */
static inline void
disc_point(unsigned i, unsigned n, double p[3])
{
	double phi = 2.0 * M_PI * rf__ggx_radical_inverse(i);

	p[0] = sqrt(((double)i + 0.5) / (double)n);
	p[1] = cos(phi);
	p[2] = sin(phi);
}

/* The integrals for one (n.v, roughness), from precomputed disc points;
 * the frame has n = +Z and v in the XZ plane. */
static inline void
integrate(double nv, double roughness, const double *disc, unsigned n, double *a,
          double *b)
{
	double alpha = roughness * roughness, a2 = alpha * alpha;
	double vx, vz = nv, hx, hz, len, lv, s, sum_a = 0.0, sum_b = 0.0;
	unsigned i;

	if (nv < 1e-4)
		vz = nv = 1e-4; /* the limit at grazing, without 0 / 0 */
	if (nv > 1.0)
		vz = nv = 1.0;
	if (alpha < 1e-7) {
		/* A mirror: h = n, l = reflect(v), G2 = 1. */
		*b = pow5(1.0 - nv);
		*a = 1.0 - *b;
		return;
	}
	vx = sqrt(1.0 - nv * nv);
	/* The view in the hemisphere configuration (stretched by alpha);
	 * its tangent frame is T1 = +Y, T2 = vh x T1. */
	hx = alpha * vx;
	hz = vz;
	len = sqrt(hx * hx + hz * hz);
	hx /= len;
	hz /= len;
	s = 0.5 * (1.0 + hz);
	lv = rf__ggx_lambda(a2, nv);
	for (i = 0; i < n; i++) {
		const double *p = disc + 3 * i;
		double t1 = p[0] * p[1], t2 = p[0] * p[2], t3, mx, my, mz, vh, lz, w, fc;

		t2 = (1.0 - s) * sqrt(1.0 - t1 * t1) + s * t2;
		t3 = sqrt(fmax(0.0, 1.0 - t1 * t1 - t2 * t2));
		/* nh = t1 T1 + t2 (vh x T1) + t3 vh, with T1 = (0, 1, 0) and
		 * vh x T1 = (-hz, 0, hx); then unstretched. */
		mx = alpha * (-t2 * hz + t3 * hx);
		my = alpha * t1;
		mz = fmax(0.0, t2 * hx + t3 * hz);
		len = sqrt(mx * mx + my * my + mz * mz);
		if (!(len > 0.0))
			continue;
		mx /= len;
		mz /= len;
		vh = vx * mx + vz * mz;
		lz = 2.0 * vh * mz - vz;
		if (lz <= 0.0 || vh <= 0.0)
			continue;
		/* Visible-normal sampling leaves G2 / G1(v) as the weight. */
		w = (1.0 + lv) / (1.0 + lv + rf__ggx_lambda(a2, lz));
		fc = pow5(1.0 - vh);
		sum_a += w * (1.0 - fc);
		sum_b += w * fc;
	}
	*a = sum_a / n;
	*b = sum_b / n;
}

#endif
