/*
 * libFuzzer harness for the DDS cube reader: the input is written to a
 * memory file and read by its /proc path, as a file on disk would be.
 * A cube that reads must hold finite texels only (the reader zeroes and
 * counts the others); a refusal must say why in one printable line.  The
 * memory limit keeps a forged header from asking for gigabytes.
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

#define HARNESS "fuzz-dds"
#include "harness.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rf_chain_info info;
	char path[64], err[1024] = "";
	size_t bad, k, f, i, j, n;
	rf_cubemap *c;
	int fd;

	setenv("REFLECT_MAX_CUBE_MB", "64", 1);
	if ((fd = memfd_create("fuzz.dds", 0)) < 0)
		return 0;
	if (write(fd, data, size) != (ssize_t)size) {
		close(fd);
		return 0;
	}
	snprintf(path, sizeof(path), "/proc/self/fd/%d", fd);
	if (rf_chain_read_dds(&c, &info, &bad, path, err, sizeof(err)) < 0) {
		check(err[0] != '\0', "an error without a message");
		for (i = 0; err[i]; i++)
			check((unsigned char)err[i] >= 0x20 && err[i] != 0x7f,
			      "a control character in a message");
		close(fd);
		return 0;
	}
	for (k = 0; k < rf_cubemap_levels(c); k++) {
		n = rf_cubemap_level_size(c, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++) {
					const float *t = rf_cubemap_texel_const(c, k, (enum rf_face)f, i, j);

					check(isfinite(t[0]) && isfinite(t[1]) && isfinite(t[2]),
					      "a texel that is not finite");
				}
	}
	rf_cubemap_destroy(c);
	close(fd);
	return 0;
}
