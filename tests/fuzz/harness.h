/*
 * What the harnesses share: check(), which aborts naming the harness
 * (HARNESS, defined before this file is included) and what broke; the
 * rule for a library's message, one printable line that says something;
 * and a small environment whose texels vary by face, level and
 * position, so that a read that lands on the wrong texel shows.
 */
#ifndef REFLECT_FUZZ_HARNESS_H
#define REFLECT_FUZZ_HARNESS_H

#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "reflect/envmap.h"

#ifndef HARNESS
#error "define HARNESS, the harness's name, before including harness.h"
#endif

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static inline void
check(int cond, const char *what)
{
	if (!cond) {
		fprintf(stderr, HARNESS ": %s\n", what);
		abort();
	}
}

static inline void
check_message(const char *err)
{
	const char *c;

	check(err[0] != '\0', "a refusal without a message");
	for (c = err; *c; c++)
		check((unsigned char)*c >= 0x20 && *c != 0x7f, "a control byte in a message");
}

/* The harness's scratch folder, HARNESS-PID under $TMPDIR (else /tmp),
 * for readers that take a path: made on first use, and emptied and
 * removed at exit so that a replay leaves nothing behind. */
static inline char *
scratch_path(void)
{
	static char path[400];

	return path;
}

static inline void
scratch_remove(void)
{
	const char *dir = scratch_path();
	char path[700];
	struct dirent *e;
	DIR *d;

	if (!(d = opendir(dir)))
		return;
	while ((e = readdir(d)))
		if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) {
			snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
			unlink(path);
		}
	closedir(d);
	rmdir(dir);
}

static inline const char *
scratch_dir(void)
{
	const char *tmp = getenv("TMPDIR");
	char *dir = scratch_path();

	if (!dir[0]) {
		snprintf(dir, 400, "%s/" HARNESS "-%ld", tmp && *tmp == '/' ? tmp : "/tmp",
		         (long)getpid());
		check(mkdir(dir, 0700) == 0, "cannot make the scratch folder");
		atexit(scratch_remove);
	}
	return dir;
}

/* Made once, kept for the process: 8 texels a face, 4 levels. */
static inline rf_cubemap *
environment(void)
{
	static rf_cubemap *c;
	size_t k, i, j, n;
	int f;

	if (c)
		return c;
	check(rf_cubemap_create(&c, 8, 4) == 0, "cubemap_create");
	for (k = 0; k < 4; k++) {
		n = rf_cubemap_level_size(c, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++) {
					float *t = rf_cubemap_texel(c, k, (enum rf_face)f, i, j);

					t[0] = 1.0f + (float)f + 0.1f * (float)i;
					t[1] = 2.0f + 0.1f * (float)j;
					t[2] = 1.0f + (float)k;
				}
		rf_cubemap_seal_level(c, k);
	}
	return c;
}

#endif
