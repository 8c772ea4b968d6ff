/*
 * Benchmark of the GGX prefilter: a 256-per-face HDR cube (the embedded
 * room) and a 2048x1024 lat-long of it, to a full chain at the default
 * settings.  Prints single-thread CPU time, wall time on every core, GGX
 * samples per second, and the error against the brute-force convolution
 * on a sample of texels of each level.  Not part of make check.
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

	if (runs < 1 || runs > 9)
		runs = 3;
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
