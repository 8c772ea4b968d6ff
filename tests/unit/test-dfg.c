/* The DFG table against the integral computed here another way: a plain
 * quadrature over the hemisphere of l, no importance sampling. */
#include <math.h>

#include "reflect/surface.h"
#include "tap.h"

/* Smith's Lambda for GGX. */
static double
lambda(double a2, double c)
{
	return 0.5 * (sqrt(1.0 + a2 * (1.0 - c * c) / (c * c)) - 1.0);
}

/*
 * A and B by the midpoint rule in (theta_l, phi_l), v in the XZ plane:
 *   f n.l = D(h) G2(v, l) F / (4 n.v),  dl = sin(theta) dtheta dphi,
 * with GGX D, height-correlated G2 = 1 / (1 + L(v) + L(l)) and
 * F = F0 + (1 - F0) (1 - v.h)^5 split into its F0 and 1 parts.  The
 * integrand is even in phi: integrate [0, pi] and double.  theta is
 * sampled in u = 1 - cos(theta)^(1/4)-like steps near the pole where
 * the lobe is (a tan substitution: theta = atan(alpha s)).
 */
static void
quadrature(double nv, double r, int n, double *a, double *b)
{
	double alpha = r * r, a2 = alpha * alpha;
	double vx = sqrt(1.0 - nv * nv), vz = nv, lv = lambda(a2, nv);
	double sa = 0.0, sb = 0.0, dphi = M_PI / n;
	int i, j;

	for (i = 0; i < n; i++) {
		/* theta in [0, pi/2) through s in [0, 1): theta = atan(k s / (1 - s)),
		 * k ~ alpha, dense where D is large. */
		double s = (i + 0.5) / n, k = alpha < 0.05 ? 0.05 : alpha;
		double q = k * s / (1.0 - s), th = atan(q);
		double dth = (k / ((1.0 - s) * (1.0 - s))) / (1.0 + q * q) / n;
		double lz = cos(th), st = sin(th);

		for (j = 0; j < n; j++) {
			double ph = (j + 0.5) * dphi;
			double lx = st * cos(ph), ly = st * sin(ph);
			double hx = vx + lx, hy = ly, hz = vz + lz;
			double len = sqrt(hx * hx + hy * hy + hz * hz), nh, vh, t, d, g, w, fc;

			hx /= len;
			hz /= len;
			hy /= len;
			nh = hz;
			vh = vx * hx + vz * hz;
			t = nh * nh * (a2 - 1.0) + 1.0;
			d = a2 / (M_PI * t * t);
			g = 1.0 / (1.0 + lv + lambda(a2, lz));
			w = d * g / (4.0 * nv) * st * dth * dphi * 2.0;
			fc = pow(1.0 - vh, 5.0);
			sa += w * (1.0 - fc);
			sb += w * fc;
		}
	}
	*a = sa;
	*b = sb;
}

static const double points[][2] = {
	{ 0.9, 0.3 }, { 0.5, 0.5 }, { 0.25, 0.75 }, { 0.1, 1.0 }, { 0.7, 0.9 },
	{ 0.15, 0.4 }, { 0.33, 0.62 }, { 0.05, 0.55 }, { 0.62, 0.27 }, { 1.0, 0.8 },
};

TEST(quadrature_is_converged)
{
	double a1, b1, a2, b2;

	/* The reference itself: two resolutions agree far below 1e-3. */
	quadrature(0.25, 0.5, 500, &a1, &b1);
	quadrature(0.25, 0.5, 1000, &a2, &b2);
	ASSERT_NEAR(a1, a2, 1e-5);
	ASSERT_NEAR(b1, b2, 1e-5);
}

TEST(lookup_matches_quadrature)
{
	size_t k;

	for (k = 0; k < sizeof(points) / sizeof(points[0]); k++) {
		double qa, qb;
		float a, b;

		quadrature(points[k][0], points[k][1], 800, &qa, &qb);
		rf_dfg_lookup((float)points[k][0], (float)points[k][1], &a, &b);
		printf("# n.v %.2f r %.2f: A %.5f (%.5f) B %.5f (%.5f)\n", points[k][0],
		       points[k][1], a, qa, b, qb);
		ASSERT_NEAR(a, qa, 1e-3);
		ASSERT_NEAR(b, qb, 1e-3);
	}
}

TEST(integrator_matches_quadrature)
{
	size_t k;

	for (k = 0; k < sizeof(points) / sizeof(points[0]); k++) {
		double qa, qb, a, b;

		quadrature(points[k][0], points[k][1], 800, &qa, &qb);
		rf_dfg_integrate(points[k][0], points[k][1], 4096, &a, &b);
		ASSERT_NEAR(a, qa, 5e-4);
		ASSERT_NEAR(b, qb, 5e-4);
	}
}

TEST(mirror_is_schlick)
{
	double nv;

	/* alpha = 0: A = 1 - (1 - n.v)^5, B = (1 - n.v)^5 exactly. */
	for (nv = 0.05; nv <= 1.0; nv += 0.05) {
		float a, b;
		double fc = pow(1.0 - nv, 5.0);

		rf_dfg_lookup((float)nv, 0.0f, &a, &b);
		ASSERT_NEAR(a, 1.0 - fc, 2e-3);
		ASSERT_NEAR(b, fc, 2e-3);
	}
}

TEST(table_nodes_and_bounds)
{
	size_t n, i, j;
	const float *t = rf_dfg_table(&n);

	ASSERT_EQ(n, RF_DFG_SIZE);
	for (j = 0; j < n; j++)
		for (i = 0; i < n; i++) {
			double x = (double)i / (n - 1);
			float a, b;
			const float *e = t + 2 * (j * n + i);

			/* Albedo of a white surface: in [0, 1]. */
			ASSERT(e[0] >= 0.0f && e[1] >= 0.0f && e[0] + e[1] <= 1.0f + 1e-4f);
			rf_dfg_lookup((float)(x * x), (float)j / (float)(n - 1), &a, &b);
			ASSERT_NEAR(a, e[0], 1e-5);
			ASSERT_NEAR(b, e[1], 1e-5);
		}
}

TEST(no_nan)
{
	float a, b;

	rf_dfg_lookup(NAN, NAN, &a, &b);
	ASSERT(isfinite(a) && isfinite(b));
	rf_dfg_lookup(-3.0f, 7.0f, &a, &b);
	ASSERT(isfinite(a) && isfinite(b));
	rf_dfg_lookup(INFINITY, -INFINITY, &a, &b);
	ASSERT(isfinite(a) && isfinite(b));
}

int
main(void)
{
	RUN(quadrature_is_converged);
	RUN(lookup_matches_quadrature);
	RUN(integrator_matches_quadrature);
	RUN(mirror_is_schlick);
	RUN(table_nodes_and_bounds);
	RUN(no_nan);
	TAP_DONE();
}
