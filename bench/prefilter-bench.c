/*
 * Benchmark of the GGX prefilter: a sky with a small bright sun, a
 * 256-per-face HDR cube (the embedded room) and a 2048x1024 lat-long of
 * it, to a full chain at the default settings.  Prints single-thread CPU
 * time, wall time on every core, GGX samples per second, and the error
 * against the brute-force convolution of each level (for the sun, every
 * texel near it and a sample of the rest; elsewhere a sample).  Not part
 * of make check.  Arguments: runs (medians), threads, samples, and which
 * (all, sun, sun-time without the errors, room).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "envmap/envmap-internal.h" /* the brute-force reference */
#include "reflect/envmap.h"

static double
seconds(clockid_t clock)
{
	struct timespec t;

	clock_gettime(clock, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

/* Runs the prefilter `runs` times; median CPU and wall seconds. */
static rf_cubemap *
timed(const rf_cubemap *src, size_t levels, unsigned samples, int threads, int runs,
      double *cpu, double *wall)
{
	double c[9], w[9];
	rf_cubemap *out = NULL;
	int r;

	for (r = 0; r < runs; r++) {
		struct rf_prefilter_options o;
		char err[256];
		double c0, w0;

		rf_cubemap_destroy(out);
		rf_cubemap_create(&out, rf_cubemap_size(src), levels);
		rf_prefilter_defaults(&o);
		o.samples = samples;
		o.nthreads = threads;
		c0 = seconds(CLOCK_PROCESS_CPUTIME_ID);
		w0 = seconds(CLOCK_MONOTONIC);
		if (rf_prefilter(src, out, &o, err, sizeof(err)) < 0) {
			fprintf(stderr, "prefilter-bench: %s\n", err);
			exit(1);
		}
		c[r] = seconds(CLOCK_PROCESS_CPUTIME_ID) - c0;
		w[r] = seconds(CLOCK_MONOTONIC) - w0;
	}
	qsort(c, (size_t)runs, sizeof(double), cmp_double);
	qsort(w, (size_t)runs, sizeof(double), cmp_double);
	*cpu = c[runs / 2];
	*wall = w[runs / 2];
	return out;
}

/* Relative RMS error of a level against brute force on `count` texels
 * spread over the level by a fixed hash. */
static double
level_error(const rf_cubemap *src, const rf_cubemap *out, size_t level, size_t count,
            float roughness)
{
	size_t n = rf_cubemap_level_size(out, level), k, total = 6 * n * n;
	float *dirs = malloc(count * 3 * sizeof(float)), *ref = malloc(count * 3 * sizeof(float));
	double se = 0, sum = 0;
	size_t *idx = malloc(count * sizeof(size_t));
	int ch;

	if (count > total)
		count = total;
	for (k = 0; k < count; k++) {
		uint32_t h = (uint32_t)k * 2654435761u + (uint32_t)level * 40503u;
		size_t t, f, i, j;

		h ^= h >> 15;
		h *= 2246822519u;
		h ^= h >> 13;
		t = count == total ? k : h % total;
		f = t / (n * n);
		j = (t / n) % n;
		i = t % n;
		idx[k] = t;
		rf_cube_direction((enum rf_face)f, (i + 0.5f) / n, (j + 0.5f) / n, dirs + 3 * k);
	}
	rf__prefilter_brute_texels(src, dirs, count, roughness, ref);
	for (k = 0; k < count; k++) {
		size_t t = idx[k];
		const float *p = rf_cubemap_texel_const(out, level, (enum rf_face)(t / (n * n)),
		                                        t % n, (t / n) % n);

		for (ch = 0; ch < 3; ch++) {
			se += ((double)p[ch] - ref[3 * k + ch]) * ((double)p[ch] - ref[3 * k + ch]);
			sum += ref[3 * k + ch];
		}
	}
	free(dirs);
	free(ref);
	free(idx);
	return sqrt(se / (3.0 * count)) / (sum / (3.0 * count));
}

/*
 * The sun environment: a sky whose radiance falls from 1.2 at the
 * horizon to 0.4 at the zenith (bluer above), a ground of 0.3 below, and
 * a sun 1.5 degrees across of radiance 4000 at 35 degrees up, off every
 * axis.  Texels are means of 8 x 8 points, so the sun's edge is its
 * coverage.  Deterministic: no clock, no random numbers.
 */
static const float sun_dir[3] = { 0.5540323f, 0.5735764f, -0.6033345f };

static void
sky(const float d[3], double rgb[3])
{
	double cos_r = cos(0.75 * M_PI / 180.0), y = d[1];

	if ((double)d[0] * sun_dir[0] + (double)d[1] * sun_dir[1] + (double)d[2] * sun_dir[2] > cos_r) {
		rgb[0] = 4000.0, rgb[1] = 3900.0, rgb[2] = 3700.0;
	} else if (y < 0.0) {
		rgb[0] = 0.3, rgb[1] = 0.28, rgb[2] = 0.25;
	} else {
		rgb[0] = 1.2 - 0.9 * y;
		rgb[1] = 1.2 - 0.7 * y;
		rgb[2] = 1.2 - 0.4 * y;
	}
}

static rf_cubemap *
sun_environment(size_t n)
{
	enum { SS = 8 };
	rf_cubemap *c;
	size_t i, j;
	int f, a, b, ch;

	if (rf_cubemap_create(&c, n, 1) < 0)
		return NULL;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);
				double acc[3] = { 0, 0, 0 }, rgb[3];

				for (b = 0; b < SS; b++)
					for (a = 0; a < SS; a++) {
						float d[3];
						double len;

						rf_cube_direction((enum rf_face)f, (i + (a + 0.5f) / SS) / n,
						                  (j + (b + 0.5f) / SS) / n, d);
						len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] +
						           (double)d[2] * d[2]);
						for (ch = 0; ch < 3; ch++)
							d[ch] = (float)(d[ch] / len);
						sky(d, rgb);
						for (ch = 0; ch < 3; ch++)
							acc[ch] += rgb[ch];
					}
				for (ch = 0; ch < 3; ch++)
					t[ch] = (float)(acc[ch] / (SS * SS));
			}
	rf_cubemap_seal_level(c, 0);
	return c;
}

/*
 * Relative RMS error of a level of the sun environment against brute
 * force, as over every texel: the texels within 0.25 radians of the sun
 * (where the halo is, and all of the old error) each, the rest a fixed
 * sample of 1024 standing for all of them; a level of at most 6 x 32^2
 * texels whole.  *p99: the 99th-percentile relative error of a texel
 * near the sun, *worst the largest.
 */
static double
sun_level_error(const rf_cubemap *src, const rf_cubemap *out, size_t level,
                float roughness, double *p99, double *worst)
{
	size_t n = rf_cubemap_level_size(out, level), total = 6 * n * n, t, k;
	size_t nnear = 0, nfar = 0, want_far = 1024, far_total = 0;
	int all = total <= 6 * 32 * 32, ch;
	float *dirs = malloc(total * 3 * sizeof(float)), *ref;
	size_t *idx = malloc(total * sizeof(size_t));
	double *rel = malloc(total * sizeof(double));
	double se_near = 0, sum_near = 0, se_far = 0, sum_far = 0, far_scale;
	unsigned char *pick = calloc(total, 1);

	/* classify: near (1), far (0); pick the far sample by a fixed hash */
	for (t = 0; t < total; t++) {
		float d[3];
		double len;

		rf_cube_direction((enum rf_face)(t / (n * n)), (t % n + 0.5f) / n,
		                  ((t / n) % n + 0.5f) / n, d);
		len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
		if (all || (d[0] * sun_dir[0] + d[1] * sun_dir[1] + d[2] * sun_dir[2]) / len >
		               cos(0.25))
			pick[t] = 1;
		else
			far_total++;
	}
	if (!all)
		for (k = 0; nfar < want_far && nfar < far_total; k++) {
			uint32_t h = (uint32_t)k * 2654435761u + (uint32_t)level * 40503u;

			h ^= h >> 15;
			h *= 2246822519u;
			h ^= h >> 13;
			t = h % total;
			if (!pick[t]) {
				pick[t] = 2;
				nfar++;
			}
		}
	for (t = 0, k = 0; t < total; t++)
		if (pick[t]) {
			idx[k] = t;
			rf_cube_direction((enum rf_face)(t / (n * n)), (t % n + 0.5f) / n,
			                  ((t / n) % n + 0.5f) / n, dirs + 3 * k);
			k++;
		}
	ref = malloc(k * 3 * sizeof(float));
	rf__prefilter_brute_texels(src, dirs, k, roughness, ref);
	for (t = 0; t < k; t++) {
		size_t i = idx[t];
		const float *p = rf_cubemap_texel_const(out, level, (enum rf_face)(i / (n * n)),
		                                        i % n, (i / n) % n);
		double se = 0, sum = 0;

		for (ch = 0; ch < 3; ch++) {
			se += ((double)p[ch] - ref[3 * t + ch]) * ((double)p[ch] - ref[3 * t + ch]);
			sum += ref[3 * t + ch];
		}
		if (pick[i] == 1) {
			se_near += se;
			sum_near += sum;
			rel[nnear++] = sqrt(se / 3.0) / (sum / 3.0);
		} else {
			se_far += se;
			sum_far += sum;
		}
	}
	far_scale = nfar ? (double)far_total / (double)nfar : 0.0;
	qsort(rel, nnear, sizeof(double), cmp_double);
	*p99 = nnear ? rel[(size_t)(0.99 * (double)(nnear - 1))] : 0.0;
	*worst = nnear ? rel[nnear - 1] : 0.0;
	free(dirs);
	free(ref);
	free(idx);
	free(rel);
	free(pick);
	return sqrt((se_near + far_scale * se_far) / (3.0 * total)) /
	       ((sum_near + far_scale * sum_far) / (3.0 * total));
}

/* The sun environment at `samples`: times, and the error per level. */
static double
report_sun(const rf_cubemap *src, unsigned samples, int runs, int threads, int errors)
{
	size_t levels = 7, k;
	double cpu1, wall1, cpun, walln, worst = 0;
	rf_cubemap *out;

	out = timed(src, levels, samples, 1, runs, &cpu1, &wall1);
	rf_cubemap_destroy(timed(src, levels, samples, threads, runs, &cpun, &walln));
	printf("256x256 sun environment (1.5 degrees, 4000, on a sky), %u samples at "
	       "level 1\n", samples);
	printf("  1 thread : %.3f s cpu, %.3f s wall\n", cpu1, wall1);
	printf("  %d threads: %.3f s cpu, %.3f s wall\n", threads, cpun, walln);
	if (!errors) {
		rf_cubemap_destroy(out);
		return 0.0;
	}
	printf("  level  roughness  rel. RMS  p99 near sun  worst near sun\n");
	for (k = 1; k < levels; k++) {
		float r = rf_lod_to_roughness(RF_MAPPING_UNITY, (float)(levels - 1), (float)k);
		double p99, w, e = sun_level_error(src, out, k, r, &p99, &w);

		printf("  %5zu  %9.3f  %7.3f%%  %11.3f%%  %13.3f%%\n", k, (double)r, 100.0 * e,
		       100.0 * p99, 100.0 * w);
		if (e > worst)
			worst = e;
	}
	printf("  worst level error %.2f%%\n", 100.0 * worst);
	rf_cubemap_destroy(out);
	return worst;
}

/* Returns the worst level error. */
static double
report(const char *name, const rf_cubemap *src, unsigned samples, int runs, int threads)
{
	size_t levels = 7, k;
	double cpu1, wall1, cpun, walln, total = 0, worst = 0;
	rf_cubemap *out;

	for (k = 1; k < levels; k++) {
		size_t n = rf_cubemap_level_size(src, 0) >> k;

		total += 6.0 * (double)(n * n) * (double)rf_prefilter_level_samples(samples, k);
	}
	out = timed(src, levels, samples, 1, runs, &cpu1, &wall1);
	rf_cubemap_destroy(timed(src, levels, samples, threads, runs, &cpun, &walln));
	printf("%s, %u samples at level 1 (x3 per level), %.1f M GGX samples\n", name,
	       samples, total / 1e6);
	printf("  1 thread : %.3f s cpu, %.3f s wall, %.1f M samples/s\n", cpu1, wall1,
	       total / cpu1 / 1e6);
	printf("  %d threads: %.3f s cpu, %.3f s wall\n", threads, cpun, walln);
	printf("  relative RMS error against brute force (sampled texels):");
	for (k = 1; k < levels; k++) {
		float r = rf_lod_to_roughness(RF_MAPPING_UNITY, (float)(levels - 1), (float)k);
		double e = level_error(src, out, k, k == 1 ? 48 : 192, r);

		printf(" %.4f", e);
		if (e > worst)
			worst = e;
	}
	printf("\n  worst level error %.2f%%\n", 100.0 * worst);
	rf_cubemap_destroy(out);
	return worst;
}

int
main(int argc, char **argv)
{
	int runs = argc > 1 ? atoi(argv[1]) : 3, threads = argc > 2 ? atoi(argv[2]) : 2;
	unsigned samples = argc > 3 ? (unsigned)atoi(argv[3]) : 64;
	rf_cubemap *cube, *ll;
	float *px;
	size_t bad;
	char err[256];

	const char *which = argc > 4 ? argv[4] : "all";

	if (runs < 1 || runs > 9)
		runs = 3;
	if (strcmp(which, "room")) {
		rf_cubemap *sun = sun_environment(256);

		report_sun(sun, samples, runs, threads, strcmp(which, "sun-time"));
		rf_cubemap_destroy(sun);
		if (!strncmp(which, "sun", 3))
			return 0;
	}
	rf_cubemap_create(&cube, 256, 1);
	rf_default_environment_cube(cube);
	/* The default count, then the smallest count (in steps of 32) whose
	 * worst level is within the 2% bound. */
	if (report("256x256 cube (the embedded HDR room)", cube, samples, runs, threads) > 0.02)
		for (samples += 32; samples <= 512; samples += 32)
			if (report("256x256 cube at more samples", cube, samples, runs,
			           threads) <= 0.02)
				break;
	/* The same room as a 2048x1024 lat-long, read as reflect reads files. */
	px = malloc(2048 * 1024 * 3 * sizeof(float));
	rf_envmap_to_pixels(cube, 0, RF_LAYOUT_LATLONG, px, 2048, 1024);
	rf_cubemap_create(&ll, 256, 1);
	{
		double c0 = seconds(CLOCK_PROCESS_CPUTIME_ID);

		if (rf_envmap_from_pixels(ll, px, 2048, 1024, 3, RF_LAYOUT_LATLONG, NULL, &bad,
		                          err, sizeof(err)) < 0) {
			fprintf(stderr, "prefilter-bench: %s\n", err);
			return 1;
		}
		printf("2048x1024 lat-long to a 256 cube: %.3f s cpu\n",
		       seconds(CLOCK_PROCESS_CPUTIME_ID) - c0);
	}
	report("2048x1024 lat-long as a 256 cube", ll, samples, runs, threads);
	free(px);
	rf_cubemap_destroy(cube);
	rf_cubemap_destroy(ll);
	return 0;
}
