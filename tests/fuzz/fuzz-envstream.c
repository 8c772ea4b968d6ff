/*
 * libFuzzer harness for environments given as streams: the input is
 * written to a memory file and loaded by its /proc path as reflect-shade
 * --env loads a file, refusing NaN and Inf (the default) and repairing
 * them (--nonfinite=zero).  A refusal must say why in one printable
 * line; a cube that loads must hold finite texels only, and so must its
 * irradiance coefficients and, for a small raw one, the chain the
 * shading pass prefilters from it.  Input not starting as a stream is
 * left to the other readers' harnesses.
 */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "reflect/envmap.h"
#include "reflect/shading.h"

#define HARNESS "fuzz-envstream"
#include "harness.h"

static void
check_finite(const rf_cubemap *c, const char *what)
{
	size_t k, f, i, j, n;

	for (k = 0; k < rf_cubemap_levels(c); k++) {
		n = rf_cubemap_level_size(c, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++) {
					const float *t = rf_cubemap_texel_const(c, k, (enum rf_face)f, i, j);

					check(isfinite(t[0]) && isfinite(t[1]) && isfinite(t[2]), what);
				}
	}
}

/* Loads path under strict or repairing rules; 1 when it loaded. */
static int
load(const char *path, int strict)
{
	struct rf_envmap_options o;
	struct rf_shade_env_options so;
	struct rf_chain_info info;
	enum rf_mapping mapping;
	char err[1024] = "";
	rf_cubemap *c, *env;
	size_t bad = 0;
	float steps;
	int i;

	rf_envmap_options_init(&o);
	o.strict = strict;
	if (rf_envmap_load(&c, &info, path, &o, &bad, err, sizeof(err)) < 0) {
		check_message(err);
		return 0;
	}
	check(!strict || bad == 0, "a strict load that replaced values");
	check_finite(c, "a texel that is not finite");
	check(isfinite(info.steps), "steps that are not finite");
	for (i = 0; info.has_sh9 && i < 27; i++)
		check(isfinite(info.sh9[i]), "an irradiance coefficient that is not finite");
	/* a raw one as the shading pass takes it: prefiltered, if small */
	if (info.prefiltered || rf_cubemap_size(c) > 16) {
		rf_cubemap_destroy(c);
		return 1;
	}
	memset(&so, 0, sizeof(so));
	so.samples = 4;
	so.nthreads = 1;
	err[0] = '\0';
	if (rf_shade_environment(&env, &mapping, &steps, c, &info, "fuzz", &so, err,
	                         sizeof(err)) < 0) {
		check_message(err);
		return 1;
	}
	check_finite(env, "a prefiltered texel that is not finite");
	rf_cubemap_destroy(env);
	return 1;
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static const char magic[] = "#?REFLECT1";
	char path[64];
	int fd, strict_ok, repaired_ok;

	if (size < sizeof(magic) - 1 || memcmp(data, magic, sizeof(magic) - 1))
		return 0;
	setenv("REFLECT_MAX_CUBE_MB", "64", 1);
	if ((fd = memfd_create("fuzz.rfl", 0)) < 0)
		return 0;
	if (write(fd, data, size) != (ssize_t)size) {
		close(fd);
		return 0;
	}
	snprintf(path, sizeof(path), "/proc/self/fd/%d", fd);
	strict_ok = load(path, 1);
	repaired_ok = load(path, 0);
	check(!strict_ok || repaired_ok, "taken as it is, refused when repairing");
	close(fd);
	return 0;
}
