/* Unit tests of cube geometry, sampling and the roughness mapping. */
#include "reflect/envmap.h"
#include "tap.h"

/*
 * Where OpenEXR puts direction d in an N x 6N cube, restated from its
 * ImfEnvmap rules so the test does not share code with the library:
 * the face by the largest component, then a position in the face whose
 * axes depend on the face.  Returns the continuous column and row in
 * [0, 1], texel centres at (i + 1/2) / N.
 */
static int
openexr_position(const double d[3], double *col, double *row)
{
	double ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]);
	double px, py; /* OpenEXR's positionInFace, scaled to [0, 1] */

	if (ax >= ay && ax >= az) {
		px = (d[1] / ax + 1) / 2;
		py = (d[2] / ax + 1) / 2;
		if (d[0] > 0) {
			*col = py;
			*row = 1 - px;
			return RF_FACE_POS_X;
		}
		*col = 1 - py;
		*row = 1 - px;
		return RF_FACE_NEG_X;
	}
	if (ay >= az) {
		px = (d[0] / ay + 1) / 2;
		py = (d[2] / ay + 1) / 2;
		if (d[1] > 0) {
			*col = px;
			*row = 1 - py;
			return RF_FACE_POS_Y;
		}
		*col = px;
		*row = py;
		return RF_FACE_NEG_Y;
	}
	px = (d[0] / az + 1) / 2;
	py = (d[1] / az + 1) / 2;
	if (d[2] > 0) {
		*col = 1 - px;
		*row = 1 - py;
		return RF_FACE_POS_Z;
	}
	*col = px;
	*row = 1 - py;
	return RF_FACE_NEG_Z;
}

/* A labelled cube: texel (i, j) of face f holds (f, i, j). */
static rf_cubemap *
labelled(size_t n)
{
	rf_cubemap *c;
	size_t i, j;
	int f;

	if (rf_cubemap_create(&c, n, 1) < 0)
		return NULL;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);

				t[0] = (float)f;
				t[1] = (float)i;
				t[2] = (float)j;
			}
	rf_cubemap_seal_level(c, 0);
	return c;
}

/* Each face centre and each face's +u and +v edge read the texel OpenEXR
 * puts there. */
TEST(orientation_matches_openexr)
{
	static const double centres[6][3] = {
		{ 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 },
	};
	const size_t n = 8;
	rf_cubemap *c = labelled(n);
	int f, k;

	ASSERT(c);
	for (f = 0; f < 6; f++) {
		/* Centre, then points 80% of the way to the face's +u and +v
		 * edges, found by stepping the direction along each axis. */
		for (k = 0; k < 7; k++) {
			double d[3] = { centres[f][0], centres[f][1], centres[f][2] };
			double col, row;
			float fd[3], rgb[3], u, v;
			int face;

			if (k > 0) {
				int axis = (k - 1) / 2;

				if (d[axis] != 0)
					continue;
				d[axis] = (k % 2 ? 0.8 : -0.8);
			}
			face = openexr_position(d, &col, &row);
			ASSERT_EQ(face, f);
			fd[0] = (float)d[0];
			fd[1] = (float)d[1];
			fd[2] = (float)d[2];
			ASSERT_EQ(rf_cube_face(fd, &u, &v), f);
			ASSERT_NEAR(u, col, 1e-6);
			ASSERT_NEAR(v, row, 1e-6);
			/* The texel under that position, read back nearest. */
			rf_cubemap_sample_level(c, 0, fd, rgb);
			ASSERT_NEAR(rgb[0], f, 1e-6);
			if (k == 0) {
				/* the centre of an even face lies between 4 texels */
				ASSERT_NEAR(rgb[1], (n - 1) / 2.0, 1e-5);
				ASSERT_NEAR(rgb[2], (n - 1) / 2.0, 1e-5);
			} else {
				ASSERT_NEAR(rgb[1], col * n - 0.5, 1e-4);
				ASSERT_NEAR(rgb[2], row * n - 0.5, 1e-4);
			}
		}
	}
	rf_cubemap_destroy(c);
}

/* The lat-long axes: image centre +Z, right turns to -X, top looks up. */
TEST(latlong_axes)
{
	float d[3], u, v;

	rf_latlong_direction(0.5f, 0.5f, d);
	ASSERT_NEAR(d[0], 0, 1e-6);
	ASSERT_NEAR(d[1], 0, 1e-6);
	ASSERT_NEAR(d[2], 1, 1e-6);
	rf_latlong_direction(0.75f, 0.5f, d);
	ASSERT_NEAR(d[0], -1, 1e-6);
	ASSERT_NEAR(d[2], 0, 1e-6);
	rf_latlong_direction(0.25f, 0.5f, d);
	ASSERT_NEAR(d[0], 1, 1e-6);
	rf_latlong_direction(0.5f, 0.0f, d);
	ASSERT_NEAR(d[1], 1, 1e-6);
	rf_latlong_direction(0.3f, 0.8f, d);
	rf_latlong_position(d, &u, &v);
	ASSERT_NEAR(u, 0.3, 1e-6);
	ASSERT_NEAR(v, 0.8, 1e-6);
}

TEST(direction_roundtrip)
{
	int f, k;

	for (f = 0; f < 6; f++)
		for (k = 0; k < 50; k++) {
			float u = (float)((k * 37) % 50) / 50.0f + 0.01f;
			float v = (float)((k * 13) % 50) / 50.0f + 0.01f;
			float d[3], u2, v2;

			rf_cube_direction((enum rf_face)f, u, v, d);
			ASSERT_EQ(rf_cube_face(d, &u2, &v2), f);
			ASSERT_NEAR(u2, u, 1e-6);
			ASSERT_NEAR(v2, v, 1e-6);
		}
}

TEST(solid_angles_sum_to_sphere)
{
	size_t n = 16, i, j;
	double sum = 0.0;

	for (j = 0; j < n; j++)
		for (i = 0; i < n; i++)
			sum += rf_cube_texel_solid_angle(n, i, j);
	ASSERT_NEAR(6.0 * sum, 4.0 * M_PI, 1e-9);
	/* a corner texel sees less than a centre texel */
	ASSERT(rf_cube_texel_solid_angle(n, 0, 0) < rf_cube_texel_solid_angle(n, 7, 7));
}

/* A smooth function of direction, to fill cubes with. */
static void
smooth(const float d[3], float rgb[3])
{
	float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);

	rgb[0] = 2.0f + d[0] / len;
	rgb[1] = 2.0f + d[1] / len - 0.5f * d[2] / len;
	rgb[2] = 3.0f + d[2] / len;
}

static rf_cubemap *
smooth_cube(size_t n)
{
	rf_cubemap *c;
	size_t i, j;
	int f;

	if (rf_cubemap_create(&c, n, 0) < 0)
		return NULL;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float d[3];

				rf_cube_direction((enum rf_face)f, (i + 0.5f) / n, (j + 0.5f) / n, d);
				smooth(d, rf_cubemap_texel(c, 0, (enum rf_face)f, i, j));
			}
	rf_cubemap_seal_level(c, 0);
	rf_cubemap_box_chain(c, 0);
	return c;
}

/*
 * Directions on each of the 12 edges, nudged onto one face and then onto
 * the other, read the same value at every level, the 1x1 and 2x2 levels
 * included: the chain is seamless.
 */
TEST(seamless_across_all_edges)
{
	rf_cubemap *c = smooth_cube(16);
	size_t level;
	int axis, sa, sb, k, edges = 0;
	double worst = 0.0;

	ASSERT(c);
	ASSERT_EQ(rf_cubemap_levels(c), 5);
	for (axis = 0; axis < 3; axis++)
		for (sa = -1; sa <= 1; sa += 2)
			for (sb = -1; sb <= 1; sb += 2) {
				/* The edge runs along `axis`; the other two are at sa, sb. */
				int a = (axis + 1) % 3, b = (axis + 2) % 3;

				edges++;
				for (k = 0; k < 9; k++) {
					float t = -0.8f + 0.2f * (float)k;

					for (level = 0; level < rf_cubemap_levels(c); level++) {
						float d1[3], d2[3], c1[3], c2[3], u, v;
						const float eps = 1e-4f;
						int ch;

						d1[axis] = d2[axis] = t;
						d1[a] = (float)sa;
						d1[b] = (float)sb * (1 - eps);
						d2[a] = (float)sa * (1 - eps);
						d2[b] = (float)sb;
						ASSERT(rf_cube_face(d1, &u, &v) != rf_cube_face(d2, &u, &v));
						rf_cubemap_sample_level(c, level, d1, c1);
						rf_cubemap_sample_level(c, level, d2, c2);
						for (ch = 0; ch < 3; ch++) {
							double diff = fabs((double)c1[ch] - c2[ch]);

							if (diff > worst)
								worst = diff;
							ASSERT_NEAR(c1[ch], c2[ch], 2e-3);
						}
					}
				}
			}
	ASSERT_EQ(edges, 12);
	printf("# worst difference across an edge: %g\n", worst);
	rf_cubemap_destroy(c);
}

/* The three faces meeting at a corner agree there too. */
TEST(seamless_at_corners)
{
	rf_cubemap *c = smooth_cube(4);
	int sx, sy, sz;
	size_t level;

	ASSERT(c);
	for (level = 0; level < rf_cubemap_levels(c); level++)
		for (sx = -1; sx <= 1; sx += 2)
			for (sy = -1; sy <= 1; sy += 2)
				for (sz = -1; sz <= 1; sz += 2) {
					const float e = 1e-4f;
					float dx[3] = { (float)sx, sy * (1 - e), sz * (1 - e) };
					float dy[3] = { sx * (1 - e), (float)sy, sz * (1 - e) };
					float dz[3] = { sx * (1 - e), sy * (1 - e), (float)sz };
					float a[3], b[3], d[3];

					rf_cubemap_sample_level(c, level, dx, a);
					rf_cubemap_sample_level(c, level, dy, b);
					rf_cubemap_sample_level(c, level, dz, d);
					ASSERT_NEAR(a[0], b[0], 2e-3);
					ASSERT_NEAR(a[0], d[0], 2e-3);
					ASSERT_NEAR(a[2], d[2], 2e-3);
				}
	rf_cubemap_destroy(c);
}

TEST(trilinear_between_levels)
{
	rf_cubemap *c = smooth_cube(16);
	float d[3] = { 0.3f, -0.7f, 0.5f }, a[3], b[3], m[3], lo[3], hi[3];

	ASSERT(c);
	rf_cubemap_sample_level(c, 1, d, a);
	rf_cubemap_sample_level(c, 2, d, b);
	rf_cubemap_sample(c, d, 1.25f, m);
	ASSERT_NEAR(m[1], 0.75 * a[1] + 0.25 * b[1], 1e-5);
	/* lod is clamped to the chain */
	rf_cubemap_sample(c, d, -3.0f, lo);
	rf_cubemap_sample_level(c, 0, d, a);
	ASSERT_NEAR(lo[2], a[2], 1e-6);
	rf_cubemap_sample(c, d, 99.0f, hi);
	rf_cubemap_sample_level(c, rf_cubemap_levels(c) - 1, d, b);
	ASSERT_NEAR(hi[0], b[0], 1e-6);
	rf_cubemap_sample(c, d, NAN, lo);
	rf_cubemap_sample_level(c, 0, d, a);
	ASSERT_NEAR(lo[0], a[0], 1e-6);
	rf_cubemap_destroy(c);
}

TEST(box_chain_keeps_the_mean)
{
	rf_cubemap *c = smooth_cube(32);
	double m0[3], mk[3];
	size_t k;

	ASSERT(c);
	rf_cubemap_level_mean(c, 0, m0);
	/* The mean of 2 + x over the sphere is 2. */
	ASSERT_NEAR(m0[0], 2.0, 1e-3);
	for (k = 1; k < rf_cubemap_levels(c); k++) {
		rf_cubemap_level_mean(c, k, mk);
		ASSERT_NEAR(mk[0], m0[0], 2e-2);
		ASSERT_NEAR(mk[2], m0[2], 2e-2);
	}
	rf_cubemap_destroy(c);
}

TEST(bad_sizes_refused)
{
	rf_cubemap *c;

	ASSERT(rf_cubemap_create(&c, 0, 1) < 0);
	ASSERT(rf_cubemap_create(&c, 12, 4) < 0); /* 12 6 3: three levels at most */
	ASSERT_EQ(rf_cubemap_create(&c, 12, 3), 0);
	ASSERT_EQ(rf_cubemap_level_size(c, 2), 3);
	rf_cubemap_destroy(c);
	ASSERT_EQ(rf_cubemap_create(&c, 256, 0), 0);
	ASSERT_EQ(rf_cubemap_levels(c), 9);
	rf_cubemap_destroy(c);
}

/* Irradiance from 9 coefficients, by hand.  A sky of radiance 1 all
 * round: E = pi at any normal.  Radiance 1 above the horizon (y > 0), 0
 * below: L00 = 2 pi Y00 = 1.7725, L1,y = 0.4886 pi, band 2's zonal term
 * integrates 3 y^2 - 1 over the hemisphere to 0, so E(up) = pi Y00 L00
 * + (2 pi / 3) Y1 L1,y = pi/2 + pi/2 = pi (exact: the hemisphere), E(down)
 * = 0, E(horizontal) = pi / 2. */
TEST(irradiance_by_hand)
{
	rf_cubemap *c;
	const float up[3] = { 0, 1, 0 }, down[3] = { 0, -2, 0 }, side[3] = { 1, 0, 0 };
	float sh[27], e[3];
	size_t i, j;
	int f;

	ASSERT_EQ(rf_cubemap_create(&c, 64, 1), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < 64; j++)
			for (i = 0; i < 64; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);

				t[0] = t[1] = t[2] = 1.0f;
			}
	rf_cubemap_sh9(c, 0, sh);
	rf_sh9_irradiance(sh, up, e);
	ASSERT_NEAR(e[0], M_PI, 1e-4);
	rf_sh9_irradiance(sh, side, e);
	ASSERT_NEAR(e[2], M_PI, 1e-4);
	for (f = 0; f < 6; f++)
		for (j = 0; j < 64; j++)
			for (i = 0; i < 64; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j), d[3];

				rf_cube_direction((enum rf_face)f, (i + 0.5f) / 64, (j + 0.5f) / 64, d);
				t[0] = t[1] = t[2] = d[1] > 0 ? 1.0f : 0.0f;
			}
	rf_cubemap_sh9(c, 0, sh);
	ASSERT_NEAR(sh[0], 2 * M_PI * 0.282094792, 2e-3);
	rf_sh9_irradiance(sh, up, e);
	ASSERT_NEAR(e[1], M_PI, 5e-3);
	rf_sh9_irradiance(sh, down, e);
	ASSERT_NEAR(e[1], 0, 5e-3);
	rf_sh9_irradiance(sh, side, e);
	ASSERT_NEAR(e[1], M_PI / 2, 5e-3);
	rf_cubemap_destroy(c);
}

/* The irradiance cube by cosine convolution: E / pi = 1 under a uniform
 * sky; for the upper-hemisphere sky 1 up, 0 down, 1/2 sideways (exact
 * values, to the discretisation of 32 texels a face); and the 9
 * coefficients' E / pi against it on the embedded room: within 10 % at
 * each of six directions (its windows are sharp: three bands cannot
 * follow them everywhere) and 4 % in RMS. */
TEST(irradiance_cube)
{
	rf_cubemap *c, *irr, *room;
	const float up[3] = { 0, 1, 0 }, down[3] = { 0, -1, 0 }, side[3] = { 0, 0, 1 };
	float rgb[3], sh[27], e[3];
	double rms = 0.0;
	size_t i, j;
	int f, k;

	ASSERT_EQ(rf_cubemap_create(&c, 64, 1), 0);
	ASSERT_EQ(rf_cubemap_create(&irr, 8, 1), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < 64; j++)
			for (i = 0; i < 64; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j), d[3];

				rf_cube_direction((enum rf_face)f, (i + 0.5f) / 64, (j + 0.5f) / 64, d);
				t[0] = 1.0f;
				t[1] = d[1] > 0 ? 1.0f : 0.0f;
				t[2] = 0.0f;
			}
	rf_cubemap_seal_level(c, 0);
	ASSERT_EQ(rf_cubemap_irradiance(c, 0, irr), 0);
	rf_cubemap_sample_level(irr, 0, up, rgb);
	ASSERT_NEAR(rgb[0], 1, 3e-3);
	ASSERT_NEAR(rgb[1], 1, 0.02);
	rf_cubemap_sample_level(irr, 0, down, rgb);
	ASSERT_NEAR(rgb[1], 0, 0.02);
	rf_cubemap_sample_level(irr, 0, side, rgb);
	ASSERT_NEAR(rgb[0], 1, 3e-3);
	ASSERT_NEAR(rgb[1], 0.5, 0.02);
	ASSERT(rgb[2] == 0.0f);
	/* the room: the convolution and the 9 coefficients agree */
	ASSERT_EQ(rf_cubemap_create(&room, 64, 1), 0);
	rf_default_environment_cube(room);
	ASSERT_EQ(rf_cubemap_irradiance(room, 0, irr), 0);
	rf_cubemap_sh9(room, 0, sh);
	for (k = 0; k < 6; k++) {
		float d[3] = { 0, 0, 0 };

		d[k / 2] = k & 1 ? -1.0f : 1.0f;
		d[(k / 2 + 1) % 3] = 0.3f;
		rf_cubemap_sample_level(irr, 0, d, rgb);
		rf_sh9_irradiance(sh, d, e);
		for (f = 0; f < 3; f++) {
			double rel = (e[f] / M_PI - rgb[f]) / rgb[f];

			ASSERT(fabs(rel) <= 0.10);
			rms += rel * rel;
		}
	}
	ASSERT(sqrt(rms / 18) <= 0.04);
	rf_cubemap_destroy(room);
	rf_cubemap_destroy(irr);
	rf_cubemap_destroy(c);
}

/* A sky gradient and a small sun against brute-force cosine integration
 * over the same texels.  L(d) = 1 + 0.5 d.y is linear, which bands 0 and
 * 1 carry exactly; the sun (radiance 200 within 8 degrees of s) is where
 * three bands ring.  For a point light of irradiance 1 at angle t from
 * the normal the 9 coefficients give 1/4 + cos(t)/2 + (5/16) P2(cos t)
 * (the lobe keeps pi, 2 pi/3 and pi/4 of bands 0 to 2) against
 * max(cos t, 0): off by at most 3/32 = 0.09375, at t = 90 degrees, so any
 * light of total L Omega is off by at most 0.09375 L Omega.  The check
 * asks for that bound everywhere and for most of it at right angles to
 * the sun (so that the sums are the 9 coefficients, not the integral).
 * The irradiance cube is the brute force itself at its texel centres. */
static void
sky_and_sun(const float d[3], const float s[3], float cos_sun, float *l)
{
	float c = d[0] * s[0] + d[1] * s[1] + d[2] * s[2];

	*l = 1.0f + 0.5f * d[1] + (c >= cos_sun ? 200.0f : 0.0f);
}

static double
brute_irradiance(const rf_cubemap *c, size_t n, const float nrm[3])
{
	double e = 0;
	size_t i, j;
	int f;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float d[3];
				double len, cosn;

				rf_cube_direction((enum rf_face)f, (i + 0.5f) / n, (j + 0.5f) / n, d);
				len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
				cosn = (nrm[0] * d[0] + nrm[1] * d[1] + nrm[2] * d[2]) / len;
				if (cosn > 0)
					e += rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j)[0] * cosn *
					     rf_cube_texel_solid_angle(n, i, j);
			}
	return e;
}

TEST(irradiance_sky_and_sun)
{
	enum { N = 32, M = 8 };
	const float s[3] = { 0.3f / 0.98994949f, 0.8f / 0.98994949f, 0.5f / 0.98994949f };
	const float cos_sun = (float)cos(8 * M_PI / 180);
	/* perpendicular to s: (0.5, 0, -0.3) normalised */
	const float perp[3] = { 0.857492926f, 0, -0.514495755f };
	rf_cubemap *c, *irr;
	double sun = 0, worst = 0;
	float sh[27], e[3];
	size_t i, j;
	int f;

	ASSERT_EQ(rf_cubemap_create(&c, N, 1), 0);
	ASSERT_EQ(rf_cubemap_create(&irr, M, 1), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < N; j++)
			for (i = 0; i < N; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j), d[3], len;

				rf_cube_direction((enum rf_face)f, (i + 0.5f) / N, (j + 0.5f) / N, d);
				len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
				d[0] /= len;
				d[1] /= len;
				d[2] /= len;
				sky_and_sun(d, s, cos_sun, &t[0]);
				t[1] = t[2] = t[0];
				if (d[0] * s[0] + d[1] * s[1] + d[2] * s[2] >= cos_sun)
					sun += 200 * rf_cube_texel_solid_angle(N, i, j);
			}
	rf_cubemap_seal_level(c, 0);
	/* the sun is a few texels, about pi (8 degrees)^2 = 0.061 sr */
	ASSERT(sun > 200 * 0.05 && sun < 200 * 0.07);
	rf_cubemap_sh9(c, 0, sh);
	ASSERT_EQ(rf_cubemap_irradiance(c, 0, irr), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < M; j++)
			for (i = 0; i < M; i++) {
				float d[3], rgb[3], len;
				double bf;

				rf_cube_direction((enum rf_face)f, (i + 0.5f) / M, (j + 0.5f) / M, d);
				len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
				d[0] /= len;
				d[1] /= len;
				d[2] /= len;
				bf = brute_irradiance(c, N, d);
				rf_sh9_irradiance(sh, d, e);
				ASSERT(fabs(e[0] - bf) <= 0.09375 * sun + 0.01);
				if (fabs(e[0] - bf) > worst)
					worst = fabs(e[0] - bf);
				rf_cubemap_sample_level(irr, 0, d, rgb);
				ASSERT_NEAR(rgb[0] * M_PI, bf, 1e-4 * bf);
			}
	rf_sh9_irradiance(sh, perp, e);
	ASSERT(fabs(e[0] - brute_irradiance(c, N, perp)) >= 0.06 * sun);
	printf("# sky and sun: 9 coefficients off by at most %.4f of the sun's L Omega\n",
	       worst / sun);
	rf_cubemap_destroy(irr);
	rf_cubemap_destroy(c);
}

TEST(mapping_values)
{
	enum rf_mapping m;

	/* The spec's values: at r = 0.5, unity 4.05 and linear 3. */
	ASSERT_NEAR(rf_roughness_to_lod(RF_MAPPING_UNITY, 6, 0.5f), 4.05, 1e-5);
	ASSERT_NEAR(rf_roughness_to_lod(RF_MAPPING_LINEAR, 6, 0.5f), 3.0, 1e-6);
	ASSERT_NEAR(rf_roughness_to_lod(RF_MAPPING_UNITY, 6, 0.25f), 6 * 0.25 * (1.7 - 0.175), 1e-5);
	/* exact: alpha 0.25, power 2/0.0625 - 2 = 30, quartered 7.5, back:
	 * (2 / 9.5)^(1/4) = 0.677371 */
	ASSERT_NEAR(rf_roughness_to_lod(RF_MAPPING_EXACT, 1, 0.5f), pow(2 / 9.5, 0.25), 1e-6);
	/* all three agree at the ends */
	for (m = RF_MAPPING_UNITY; m <= RF_MAPPING_EXACT; m++) {
		ASSERT_NEAR(rf_roughness_to_lod(m, 6, 0.0f), 0.0, 1e-6);
		ASSERT_NEAR(rf_roughness_to_lod(m, 6, 1.0f), 6.0, 1e-5);
		ASSERT_NEAR(rf_roughness_to_lod(m, 6, 2.0f), 6.0, 1e-5);
		ASSERT_NEAR(rf_lod_to_roughness(m, 6, 9.0f), 1.0, 1e-6);
	}
	ASSERT_EQ(rf_mapping_parse("exact", &m), 0);
	ASSERT_EQ(m, RF_MAPPING_EXACT);
	ASSERT(rf_mapping_parse("cubic", &m) < 0);
}

TEST(mapping_roundtrips)
{
	enum rf_mapping m;
	int k;

	for (m = RF_MAPPING_UNITY; m <= RF_MAPPING_EXACT; m++)
		for (k = 0; k <= 60; k++) {
			float lod = 0.1f * (float)k;
			float r = rf_lod_to_roughness(m, 6, lod);
			float back = rf_roughness_to_lod(m, 6, r);

			ASSERT(r >= 0.0f && r <= 1.0f);
			ASSERT_NEAR(back, lod, 2e-4);
			if (k > 0) /* monotonic */
				ASSERT(r > rf_lod_to_roughness(m, 6, lod - 0.1f));
		}
}

int
main(void)
{
	RUN(orientation_matches_openexr);
	RUN(latlong_axes);
	RUN(direction_roundtrip);
	RUN(solid_angles_sum_to_sphere);
	RUN(seamless_across_all_edges);
	RUN(seamless_at_corners);
	RUN(trilinear_between_levels);
	RUN(box_chain_keeps_the_mean);
	RUN(bad_sizes_refused);
	RUN(irradiance_by_hand);
	RUN(irradiance_cube);
	RUN(irradiance_sky_and_sun);
	RUN(mapping_values);
	RUN(mapping_roundtrips);
	TAP_DONE();
}
