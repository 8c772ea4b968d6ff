/* Unit tests of the GGX prefilter against brute force, and its energy. */
#include "envmap/envmap-internal.h" /* the brute-force reference */
#include "reflect/envmap.h"
#include "tap.h"

static rf_cubemap *
default_room(size_t n)
{
	rf_cubemap *c;

	if (rf_cubemap_create(&c, n, 1) < 0)
		return NULL;
	rf_default_environment_cube(c);
	return c;
}

static rf_cubemap *
prefiltered(const rf_cubemap *src, size_t levels, unsigned samples,
            enum rf_prefilter_method method, int threads)
{
	struct rf_prefilter_options o;
	rf_cubemap *out;
	char err[256];

	rf_prefilter_defaults(&o);
	o.samples = samples;
	o.method = method;
	o.nthreads = threads;
	if (rf_cubemap_create(&out, rf_cubemap_size(src), levels) < 0)
		return NULL;
	if (rf_prefilter(src, out, &o, err, sizeof(err)) < 0) {
		printf("# %s\n", err);
		rf_cubemap_destroy(out);
		return NULL;
	}
	return out;
}

/* Relative RMS difference of a level: RMS over texels and channels
 * divided by the reference's mean. */
static double
level_error(const rf_cubemap *a, const rf_cubemap *ref, size_t level)
{
	size_t n = rf_cubemap_level_size(ref, level), i, j;
	double se = 0.0, sum = 0.0, count = 0.0;
	int f, ch;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				const float *p = rf_cubemap_texel_const(a, level, (enum rf_face)f, i, j);
				const float *q = rf_cubemap_texel_const(ref, level, (enum rf_face)f, i, j);

				for (ch = 0; ch < 3; ch++) {
					se += ((double)p[ch] - q[ch]) * ((double)p[ch] - q[ch]);
					sum += q[ch];
					count += 1.0;
				}
			}
	return sqrt(se / count) / (sum / count);
}

/*
 * At 32 texels per face, every level of the filtered chain is within 2%
 * RMS of the brute-force convolution with the default 64 samples, and
 * more samples bring it closer.
 */
TEST(filtered_matches_brute_force)
{
	rf_cubemap *src = default_room(32);
	rf_cubemap *ref = prefiltered(src, 6, 0, RF_PREFILTER_BRUTE, 2);
	rf_cubemap *f16 = prefiltered(src, 6, 16, RF_PREFILTER_FILTERED, 2);
	rf_cubemap *f64 = prefiltered(src, 6, 64, RF_PREFILTER_FILTERED, 2);
	rf_cubemap *f512 = prefiltered(src, 6, 512, RF_PREFILTER_FILTERED, 2);
	double e16 = 0, e64 = 0, e512 = 0;
	size_t k;

	ASSERT(src && ref && f16 && f64 && f512);
	for (k = 1; k < 6; k++) {
		double a = level_error(f16, ref, k), b = level_error(f64, ref, k);
		double c = level_error(f512, ref, k);

		printf("# level %zu: relative RMS error 16 samples %.4f, 64 %.4f, 512 %.4f\n",
		       k, a, b, c);
		ASSERT(b < 0.02);
		e16 += a;
		e64 += b;
		e512 += c;
	}
	ASSERT(e64 < e16);
	ASSERT(e512 < e64);
	/* level 0 is the source itself */
	ASSERT(level_error(f64, src, 0) == 0.0);
	rf_cubemap_destroy(src);
	rf_cubemap_destroy(ref);
	rf_cubemap_destroy(f16);
	rf_cubemap_destroy(f64);
	rf_cubemap_destroy(f512);
}

/* A constant environment stays constant at every level. */
TEST(constant_stays_constant)
{
	rf_cubemap *src, *out;
	size_t k, i, j, n;
	int f;

	ASSERT_EQ(rf_cubemap_create(&src, 16, 1), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < 16; j++)
			for (i = 0; i < 16; i++) {
				float *t = rf_cubemap_texel(src, 0, (enum rf_face)f, i, j);

				t[0] = 0.5f;
				t[1] = 2.0f;
				t[2] = 7.0f;
			}
	rf_cubemap_seal_level(src, 0);
	out = prefiltered(src, 5, 64, RF_PREFILTER_FILTERED, 1);
	ASSERT(out);
	for (k = 0; k < 5; k++) {
		n = rf_cubemap_level_size(out, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++) {
					const float *t = rf_cubemap_texel_const(out, k, (enum rf_face)f, i, j);

					ASSERT_NEAR(t[0], 0.5, 0.5e-4);
					ASSERT_NEAR(t[1], 2.0, 2e-4);
					ASSERT_NEAR(t[2], 7.0, 7e-4);
				}
	}
	rf_cubemap_destroy(out);
	rf_cubemap_destroy(src);
}

/* A dim room plus a sun of angular radius `radius` (radians) and
 * radiance `power` around direction `sun`, supersampled into level 0. */
static rf_cubemap *
sun_cube(size_t n, const float sun[3], double radius, float power)
{
	enum { SS = 8 };
	double cos_r = cos(radius), len = sqrt(sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]);
	rf_cubemap *c;
	size_t i, j;
	int f, a, b;

	if (rf_cubemap_create(&c, n, 1) < 0)
		return NULL;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);
				int in = 0;

				for (b = 0; b < SS; b++)
					for (a = 0; a < SS; a++) {
						float d[3];
						double dl;

						rf_cube_direction((enum rf_face)f, (i + (a + 0.5f) / SS) / n,
						                  (j + (b + 0.5f) / SS) / n, d);
						dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
						if ((d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2]) / (dl * len) > cos_r)
							in++;
					}
				t[0] = t[1] = t[2] = 0.2f + power * (float)in / (SS * SS);
			}
	rf_cubemap_seal_level(c, 0);
	return c;
}

static void
check_energy(const float sun[3], const char *where)
{
	/* a sun of 1.5 degrees radius (under 2), radiance 2000 */
	rf_cubemap *src = sun_cube(256, sun, 1.5 * M_PI / 180.0, 2000.0f);
	rf_cubemap *out;
	double m0[3], mk[3];
	size_t k;

	if (!src) {
		tap_current_failed = 1;
		return;
	}
	/* The default chain: 256 .. 4, steps 6; check down to 8x8 (level 5). */
	out = prefiltered(src, 7, 64, RF_PREFILTER_FILTERED, 2);
	if (!out) {
		tap_current_failed = 1;
		rf_cubemap_destroy(src);
		return;
	}
	rf_cubemap_level_mean(out, 0, m0);
	for (k = 1; k <= 5; k++) {
		rf_cubemap_level_mean(out, k, mk);
		printf("# sun near %s: level %zu mean %.5f, level 0 %.5f (%+.2f%%)\n", where,
		       k, mk[0], m0[0], 100.0 * (mk[0] / m0[0] - 1.0));
		if (fabs(mk[0] / m0[0] - 1.0) > 0.02)
			tap_current_failed = 1;
	}
	rf_cubemap_destroy(out);
	rf_cubemap_destroy(src);
}

TEST(sun_energy_near_face_centre)
{
	const float sun[3] = { 0.1f, 0.05f, 1.0f };

	check_energy(sun, "a face centre");
}

TEST(sun_energy_near_corner)
{
	const float sun[3] = { 0.97f, 0.95f, -1.0f };

	check_energy(sun, "a cube corner");
}

/* A sky (radiance 1.2 at the horizon to 0.4 at the zenith, bluer above,
 * 0.3 below) and a sun of angular radius `radius` and radiance `power`:
 * an outdoor environment, supersampled into level 0. */
static rf_cubemap *
sky_cube(size_t n, const float sun[3], double radius, double power)
{
	enum { SS = 8 };
	double cos_r = cos(radius), len = sqrt(sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]);
	rf_cubemap *c;
	size_t i, j;
	int f, a, b, ch;

	if (rf_cubemap_create(&c, n, 1) < 0)
		return NULL;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);
				double acc[3] = { 0, 0, 0 };

				for (b = 0; b < SS; b++)
					for (a = 0; a < SS; a++) {
						float d[3];
						double dl, y;

						rf_cube_direction((enum rf_face)f, (i + (a + 0.5f) / SS) / n,
						                  (j + (b + 0.5f) / SS) / n, d);
						dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
						y = d[1] / dl;
						if ((d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2]) / (dl * len) > cos_r) {
							acc[0] += power;
							acc[1] += 0.975 * power;
							acc[2] += 0.925 * power;
						} else if (y < 0.0) {
							acc[0] += 0.3;
							acc[1] += 0.28;
							acc[2] += 0.25;
						} else {
							acc[0] += 1.2 - 0.9 * y;
							acc[1] += 1.2 - 0.7 * y;
							acc[2] += 1.2 - 0.4 * y;
						}
					}
				for (ch = 0; ch < 3; ch++)
					t[ch] = (float)(acc[ch] / (SS * SS));
			}
	rf_cubemap_seal_level(c, 0);
	return c;
}

/*
 * A sun 1.5 degrees across of radiance 4000 on a sky: at the default 64
 * samples every level is within 1% RMS of brute force, near a face
 * centre and near a cube corner (the samples alone, without the bright
 * texels apart, left level 1 7% and 42% off), and the bytes are the
 * same on one thread and on three.
 */
static void
check_sun(const float sun[3], const char *where)
{
	rf_cubemap *src = sky_cube(32, sun, 0.75 * M_PI / 180.0, 4000.0);
	rf_cubemap *ref = src ? prefiltered(src, 6, 0, RF_PREFILTER_BRUTE, 2) : NULL;
	rf_cubemap *one = src ? prefiltered(src, 6, 64, RF_PREFILTER_FILTERED, 1) : NULL;
	rf_cubemap *three = src ? prefiltered(src, 6, 64, RF_PREFILTER_FILTERED, 3) : NULL;
	size_t k, n, i, j;
	int f;

	if (!src || !ref || !one || !three) {
		TAP_FAIL("sun near %s: no cube", where);
		goto out;
	}
	for (k = 1; k < 6; k++) {
		double e = level_error(one, ref, k);

		printf("# sun near %s: level %zu relative RMS error %.4f\n", where, k, e);
		if (!(e < 0.01))
			TAP_FAIL("sun near %s: level %zu is %.2f%% off brute force", where, k,
			         100.0 * e);
		n = rf_cubemap_level_size(one, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++)
					if (memcmp(rf_cubemap_texel_const(one, k, (enum rf_face)f, i, j),
					           rf_cubemap_texel_const(three, k, (enum rf_face)f, i, j),
					           3 * sizeof(float)))
						TAP_FAIL("sun near %s: level %zu face %d texel %zu,%zu differs "
						         "between 1 and 3 threads", where, k, f, i, j);
	}
out:
	rf_cubemap_destroy(src);
	rf_cubemap_destroy(ref);
	rf_cubemap_destroy(one);
	rf_cubemap_destroy(three);
}

TEST(sun_on_sky_matches_brute_force_at_face_centre)
{
	const float sun[3] = { 0.1f, 0.05f, 1.0f };

	check_sun(sun, "a face centre");
}

TEST(sun_on_sky_matches_brute_force_at_corner)
{
	const float sun[3] = { 0.97f, 0.95f, -1.0f };

	check_sun(sun, "a cube corner");
}

/* The same bytes with one thread and with three. */
TEST(deterministic_across_threads)
{
	rf_cubemap *src = default_room(16);
	rf_cubemap *a = prefiltered(src, 5, 64, RF_PREFILTER_FILTERED, 1);
	rf_cubemap *b = prefiltered(src, 5, 64, RF_PREFILTER_FILTERED, 3);
	size_t k, i, j, n;
	int f;

	ASSERT(src && a && b);
	for (k = 0; k < 5; k++) {
		n = rf_cubemap_level_size(a, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++)
					ASSERT(!memcmp(rf_cubemap_texel_const(a, k, (enum rf_face)f, i, j),
					               rf_cubemap_texel_const(b, k, (enum rf_face)f, i, j),
					               3 * sizeof(float)));
	}
	rf_cubemap_destroy(src);
	rf_cubemap_destroy(a);
	rf_cubemap_destroy(b);
}

/* The vector kernel (used where the CPU has one) adds the same samples
 * as the scalar loop, in another order and with fused multiply-adds: the
 * two agree to rounding, which next to a sun 10^4 times brighter than the
 * room reaches some 1e-5 of a texel (a sample's position moves by an ulp
 * across a steep edge).  13
 * samples leave a tail of 5 for the scalar loop after one block of 8;
 * 64 fill whole blocks; the sun puts large and small values side by side. */
TEST(vector_kernel_matches_scalar)
{
	const float sun[3] = { 0.97f, 0.95f, -1.0f };
	rf_cubemap *src = sun_cube(32, sun, 0.03, 2000.0f);
	unsigned counts[2] = { 13, 64 }, c;
	size_t k, i, j, n;
	int f, ch;

	ASSERT(src);
	for (c = 0; c < 2; c++) {
		rf_cubemap *v, *s;

		unsetenv("REFLECT_SIMD");
		v = prefiltered(src, 6, counts[c], RF_PREFILTER_FILTERED, 2);
		setenv("REFLECT_SIMD", "off", 1);
		s = prefiltered(src, 6, counts[c], RF_PREFILTER_FILTERED, 2);
		unsetenv("REFLECT_SIMD");
		ASSERT(v && s);
		for (k = 1; k < 6; k++) {
			n = rf_cubemap_level_size(v, k);
			for (f = 0; f < 6; f++)
				for (j = 0; j < n; j++)
					for (i = 0; i < n; i++) {
						const float *a = rf_cubemap_texel_const(v, k, (enum rf_face)f, i, j);
						const float *b = rf_cubemap_texel_const(s, k, (enum rf_face)f, i, j);

						for (ch = 0; ch < 3; ch++)
							if (!(fabsf(a[ch] - b[ch]) <= 1e-4f * fabsf(b[ch])))
								TAP_FAIL("%u samples, level %zu face %d texel %zu,%zu "
								         "channel %d: vector %.9g, scalar %.9g",
								         counts[c], k, f, i, j, ch, (double)a[ch],
								         (double)b[ch]);
					}
		}
		rf_cubemap_destroy(v);
		rf_cubemap_destroy(s);
	}
	rf_cubemap_destroy(src);
}

TEST(bad_parameters_refused)
{
	rf_cubemap *src = default_room(8), *one, *out;
	struct rf_prefilter_options o;
	char err[256] = "";

	ASSERT(src);
	rf_prefilter_defaults(&o);
	ASSERT_EQ(rf_cubemap_create(&one, 8, 1), 0);
	ASSERT(rf_prefilter(src, one, &o, err, sizeof(err)) < 0);
	ASSERT(strstr(err, "one level"));
	ASSERT_EQ(rf_cubemap_create(&out, 8, 3), 0);
	o.samples = 0;
	ASSERT(rf_prefilter(src, out, &o, err, sizeof(err)) < 0);
	ASSERT(strstr(err, "sample count 0"));
	o.samples = 64;
	o.steps = -1.0f;
	ASSERT(rf_prefilter(src, out, &o, err, sizeof(err)) < 0);
	rf_cubemap_destroy(one);
	rf_cubemap_destroy(out);
	rf_cubemap_destroy(src);
}

/* A NaN in the source reached every texel whose lobe read it, and an
 * infinity whole levels: the source is refused, naming the texel, and
 * out is left alone. */
TEST(non_finite_source_refused)
{
	rf_cubemap *src = default_room(8), *out;
	struct rf_prefilter_options o;
	char err[256] = "";
	const float nan = NAN;
	int method;

	ASSERT(src);
	ASSERT_EQ(rf_cubemap_create(&out, 8, 3), 0);
	rf_prefilter_defaults(&o);
	rf_cubemap_texel(src, 0, RF_FACE_NEG_Z, 6, 1)[2] = nan;
	rf_cubemap_seal_level(src, 0);
	for (method = 0; method < 2; method++) {
		o.method = (enum rf_prefilter_method)method;
		err[0] = '\0';
		ASSERT_EQ(rf_prefilter(src, out, &o, err, sizeof(err)), RF_EINVAL);
		ASSERT_STR_EQ(err, "the source's level 0, face -Z, texel (6, 1): B is nan");
	}
	rf_cubemap_texel(src, 0, RF_FACE_NEG_Z, 6, 1)[2] = INFINITY;
	ASSERT_EQ(rf_prefilter(src, out, &o, err, sizeof(err)), RF_EINVAL);
	ASSERT_STR_EQ(err, "the source's level 0, face -Z, texel (6, 1): B is inf");
	rf_cubemap_texel(src, 0, RF_FACE_NEG_Z, 6, 1)[2] = 3e38f;
	ASSERT_EQ(rf_prefilter(src, out, &o, err, sizeof(err)), RF_EINVAL);
	ASSERT_STR_EQ(err, "the source's level 0, face -Z, texel (6, 1): B is 3e+38, past a "
	                   "quarter of the float range");
	rf_cubemap_destroy(out);
	rf_cubemap_destroy(src);
}

/* Radiance near the top of what a texel may hold: a level's float sum
 * of its samples overflowed (64 x 8e37), and the chain held inf.  It
 * is their mean, as for any constant. */
TEST(bright_source_stays_finite)
{
	const float v = 8e37f;
	rf_cubemap *src, *out;
	struct rf_prefilter_options o;
	char err[256] = "";
	size_t k, n, i, j;
	int f, ch;

	ASSERT_EQ(rf_cubemap_create(&src, 8, 1), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < 8; j++)
			for (i = 0; i < 8; i++)
				for (ch = 0; ch < 3; ch++)
					rf_cubemap_texel(src, 0, (enum rf_face)f, i, j)[ch] = v;
	rf_cubemap_seal_level(src, 0);
	ASSERT_EQ(rf_cubemap_create(&out, 8, 4), 0);
	rf_prefilter_defaults(&o);
	ASSERT_EQ(rf_prefilter(src, out, &o, err, sizeof(err)), 0);
	for (k = 0; k < 4; k++) {
		n = rf_cubemap_level_size(out, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++)
					ASSERT_NEAR(rf_cubemap_texel_const(out, k, (enum rf_face)f, i,
					                                   j)[1] / v, 1.0, 1e-5);
	}
	rf_cubemap_destroy(out);
	rf_cubemap_destroy(src);
}

/* A sharp lobe at a face centre reads the texels around it: brute force
 * of a tiny roughness returns the source there. */
TEST(brute_force_limits)
{
	rf_cubemap *src = default_room(16);
	float n[3] = { 0.05f, -0.02f, 1.0f }, got[3], want[3];

	ASSERT(src);
	rf__prefilter_brute_texel(src, n, 0.02f, got);
	rf_cubemap_sample_level(src, 0, n, want);
	ASSERT_NEAR(got[0], want[0], 0.05 * want[0] + 1e-3);
	rf_cubemap_destroy(src);
}

int
main(void)
{
	RUN(filtered_matches_brute_force);
	RUN(constant_stays_constant);
	RUN(sun_energy_near_face_centre);
	RUN(sun_energy_near_corner);
	RUN(sun_on_sky_matches_brute_force_at_face_centre);
	RUN(sun_on_sky_matches_brute_force_at_corner);
	RUN(deterministic_across_threads);
	RUN(vector_kernel_matches_scalar);
	RUN(bad_parameters_refused);
	RUN(non_finite_source_refused);
	RUN(bright_source_stays_finite);
	RUN(brute_force_limits);
	TAP_DONE();
}
