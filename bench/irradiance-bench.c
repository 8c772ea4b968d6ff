/*
 * Benchmark of the diffuse light's set-up: the 9 coefficients of a
 * 256-per-face cube (the embedded room), and its irradiance cube.
 * Prints the median wall time of 21 runs (5 for the cube).  Not part of
 * make check; bench/diffuse runs it beside the shading figures.
 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "reflect/envmap.h"

static double
now(void)
{
	struct timespec t;

	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int
cmp_double(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return x < y ? -1 : x > y;
}

int
main(void)
{
	double t[21], sink = 0;
	rf_cubemap *room, *irr;
	float sh[27];
	int r;

	if (rf_cubemap_create(&room, 256, 1) < 0 || rf_cubemap_create(&irr, 32, 1) < 0)
		return 1;
	rf_default_environment_cube(room);
	rf_cubemap_seal_level(room, 0);
	for (r = 0; r < 21; r++) {
		double t0 = now();

		rf_cubemap_sh9(room, 0, sh);
		t[r] = now() - t0;
		sink += sh[0];
	}
	qsort(t, 21, sizeof(t[0]), cmp_double);
	printf("sh9 of a 256-per-face cube: %.2f ms (median of 21; min %.2f)\n",
	       1e3 * t[10], 1e3 * t[0]);
	for (r = 0; r < 5; r++) {
		double t0 = now();

		if (rf_cubemap_irradiance(room, 0, irr) < 0)
			return 1;
		t[r] = now() - t0;
	}
	qsort(t, 5, sizeof(t[0]), cmp_double);
	printf("irradiance cube, 32 a face, from it: %.1f ms (median of 5)\n", 1e3 * t[2]);
	rf_cubemap_destroy(irr);
	rf_cubemap_destroy(room);
	return sink == 12345.678;
}
