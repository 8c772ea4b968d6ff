/*
 * libFuzzer harness for the cache of prefiltered environments: a small
 * raw environment is prefiltered once through the cache, which writes
 * its entry; then the input's bytes are written over that entry and the
 * same environment asked for again.  Whatever the entry holds, the chain
 * that comes back must be the one first made, bit for bit (a damaged
 * entry is made again, an entry equal in its texels is read): never a
 * NaN, never another chain.
 */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "reflect/envmap.h"
#include "reflect/shading.h"

#define HARNESS "fuzz-cache"
#include "harness.h"

#define SIZE 8

static char dir[400], entry[512];
static rf_cubemap *reference;

static void
note(void *arg, const char *msg)
{
	size_t i;

	(void)arg;
	check(msg[0] != '\0', "an empty note");
	for (i = 0; msg[i]; i++)
		check((unsigned char)msg[i] >= 0x20 && msg[i] != 0x7f,
		      "a control character in a note");
}

/* The raw environment: texels that differ by face and place. */
static rf_cubemap *
source(void)
{
	rf_cubemap *c;
	size_t i, j;
	int f;

	check(rf_cubemap_create(&c, SIZE, 1) == 0, "cubemap_create");
	for (f = 0; f < 6; f++)
		for (j = 0; j < SIZE; j++)
			for (i = 0; i < SIZE; i++) {
				float *t = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);

				t[0] = 0.5f + (float)f;
				t[1] = 0.25f * (float)i;
				t[2] = 0.125f * (float)j;
			}
	rf_cubemap_seal_level(c, 0);
	return c;
}

/* The chain the shading pass gets for the source, through the cache. */
static rf_cubemap *
chain(void)
{
	struct rf_shade_env_options so;
	struct rf_chain_info info;
	enum rf_mapping mapping;
	char err[1024];
	rf_cubemap *env;
	float steps;

	memset(&so, 0, sizeof(so));
	memset(&info, 0, sizeof(info));
	info.mapping = RF_MAPPING_DEFAULT;
	info.base_copied = 1;
	so.samples = 4;
	so.nthreads = 1;
	so.cache_dir = dir;
	so.note = note;
	if (rf_shade_environment(&env, &mapping, &steps, source(), &info, "fuzz", &so, err,
	                         sizeof(err)) < 0) {
		fprintf(stderr, "fuzz-cache: %s\n", err);
		abort();
	}
	return env;
}

/* The scratch cache and its one entry. */
static void
setup(void)
{
	struct dirent *e;
	DIR *d;

	snprintf(dir, sizeof(dir), "%s", scratch_dir());
	reference = chain();
	check((d = opendir(dir)) != NULL, "no cache directory");
	while ((e = readdir(d)))
		if (strstr(e->d_name, ".rfl") && e->d_name[0] != '.')
			snprintf(entry, sizeof(entry), "%s/%s", dir, e->d_name);
	closedir(d);
	check(entry[0] != '\0', "no cache entry written");
}

static void
same(const rf_cubemap *a, const rf_cubemap *b)
{
	size_t k, j, n;
	int f;

	check(rf_cubemap_levels(a) == rf_cubemap_levels(b) &&
	      rf_cubemap_size(a) == rf_cubemap_size(b), "a chain of other levels");
	for (k = 0; k < rf_cubemap_levels(a); k++) {
		n = rf_cubemap_level_size(a, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				check(!memcmp(rf_cubemap_texel_const(a, k, (enum rf_face)f, 0, j),
				              rf_cubemap_texel_const(b, k, (enum rf_face)f, 0, j),
				              3 * n * sizeof(float)),
				      "a chain that is not the environment's");
	}
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	rf_cubemap *env;
	FILE *fp;

	setenv("REFLECT_MAX_CUBE_MB", "64", 1);
	if (!reference)
		setup();
	check((fp = fopen(entry, "wb")) != NULL, "cannot write the entry");
	check(fwrite(data, 1, size, fp) == size && fclose(fp) == 0, "cannot write the entry");
	env = chain();
	same(env, reference);
	rf_cubemap_destroy(env);
	return 0;
}
