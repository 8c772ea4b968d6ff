/*
 * The horizon occlusion mode's share of the lobe (plugins/occlude/
 * horizon.h), against a brute-force integral of its own: uniform
 * directions over the sphere, each weighted by the GGX BRDF times the
 * cosine (D G2 / (4 N.V), height-correlated Smith), counted above N's
 * horizon and above both; and its limits by hand.
 */
#include <stdint.h>

#include "occlude/horizon.h"
#include "tap.h"

static uint64_t rng = 0x2545F4914F6CDD1Dull;

static double
uniform(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) / 9007199254740992.0;
}

static double
dot3(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* E_Ng / E_N by n uniform directions of the sphere. */
static double
brute_force(const double n[3], const double ng[3], const double v[3], double r, int count)
{
	double a = r * r, a2 = a * a, nv = dot3(n, v), num = 0.0, den = 0.0;
	int i;

	for (i = 0; i < count; i++) {
		double z = 2.0 * uniform() - 1.0, phi = 2.0 * M_PI * uniform(), s = sqrt(1 - z * z);
		double l[3] = { s * cos(phi), s * sin(phi), z }, h[3], nl = dot3(n, l), nh, d, g, f;
		int k;

		if (nl <= 0.0)
			continue;
		for (k = 0; k < 3; k++)
			h[k] = l[k] + v[k];
		f = sqrt(dot3(h, h));
		for (k = 0; k < 3; k++)
			h[k] /= f;
		nh = dot3(n, h);
		d = a2 / (M_PI * pow(nh * nh * (a2 - 1.0) + 1.0, 2.0));
		g = 1.0 / (1.0 + rf__ggx_lambda(a2, nv) + rf__ggx_lambda(a2, nl));
		f = d * g / (4.0 * nv);
		den += f;
		if (dot3(ng, l) > 0.0)
			num += f;
	}
	return num / den;
}

static void
unit(double v[3])
{
	double l = sqrt(dot3(v, v));

	v[0] /= l;
	v[1] /= l;
	v[2] /= l;
}

TEST(share_against_brute_force)
{
	/* N up, Ng tilted by 20 or 40 degrees about z, views from both sides */
	static const double cases[][5] = {
		/* tilt (deg), view angle from N (deg, in the xy plane), roughness */
		{ 20, 60, 0.5 }, { 20, -60, 0.5 }, { 40, 70, 0.4 }, { 40, -30, 0.6 },
		{ 20, 80, 0.3 }, { 40, 50, 0.8 },
	};
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		double t = cases[i][0] * M_PI / 180, w = cases[i][1] * M_PI / 180;
		double n[3] = { 0, 1, 0 }, ng[3] = { sin(t), cos(t), 0 };
		double v[3] = { sin(w), cos(w), 0.1 }, want, got;
		float nf[3], ngf[3], vf[3];
		int k;

		unit(v);
		for (k = 0; k < 3; k++) {
			nf[k] = (float)n[k];
			ngf[k] = (float)ng[k];
			vf[k] = (float)v[k];
		}
		want = brute_force(n, ng, v, cases[i][2], 2000000);
		got = horizon_share(nf, ngf, vf, cases[i][2], 1024);
		if (!(fabs(got - want) <= 0.01))
			printf("# case %zu: %g, brute force %g\n", i, got, want);
		ASSERT(fabs(got - want) <= 0.01);
		/* and 128 points, the mode's default, within 0.03 */
		got = horizon_share(nf, ngf, vf, cases[i][2], 128);
		if (!(fabs(got - want) <= 0.03))
			printf("# case %zu at 128 points: %g, brute force %g\n", i, got, want);
		ASSERT(fabs(got - want) <= 0.03);
	}
}

TEST(share_limits)
{
	const float n[3] = { 0, 1, 0 }, v[3] = { 0.6f, 0.8f, 0 };
	const float ng_up[3] = { 0, 2, 0 }, ng_a[3] = { -0.866025f, 0.5f, 0 };
	const float ng_b[3] = { 0.866025f, 0.5f, 0 };

	/* the same normal (any length): exactly 1 */
	ASSERT(horizon_share(n, ng_up, v, 0.5, 64) == 1.0);
	/* a mirror: R = (-0.6, 0.8, 0) has R.ng_a = 0.92 (above: 1) and
	 * R.ng_b = -0.12 (below: 0) */
	ASSERT_NEAR(horizon_share(n, ng_a, v, 0.0, 64), 1.0, 1e-12);
	ASSERT_NEAR(horizon_share(n, ng_b, v, 0.0, 64), 0.0, 1e-12);
	/* tilting Ng away from the lobe (toward +x, R leans to -x) only
	 * darkens */
	{
		double prev = 1.0;
		int k;

		for (k = 1; k <= 8; k++) {
			double t = k * 10 * M_PI / 180;
			const float ng[3] = { (float)sin(t), (float)cos(t), 0 };
			double s = horizon_share(n, ng, v, 0.5, 256);

			ASSERT(s <= prev + 1e-12 && s >= 0.0);
			prev = s;
		}
	}
	/* seen from behind N: 1, nothing to occlude */
	{
		const float back[3] = { 0, -1, 0 };

		ASSERT(horizon_share(n, ng_a, back, 0.5, 64) == 1.0);
	}
}

int
main(void)
{
	RUN(share_against_brute_force);
	RUN(share_limits);
	TAP_DONE();
}
