/* Writing the glTF files the scene tests load: a scratch folder, files
 * in it, base64 for buffers held in data URIs, and a scene read as if
 * from a file in that folder.  Static, for the unit tests that include
 * it (after tap.h). */
#ifndef REFLECT_TESTS_GLTF_WRITE_H
#define REFLECT_TESTS_GLTF_WRITE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/scene.h"

/* The test's scratch folder (mkdtemp'ed by main). */
static char dir[256];

static void
put(const char *name, const void *data, size_t n)
{
	char path[512];
	FILE *fp;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	fp = fopen(path, "wb");
	if (!fp || fwrite(data, 1, n, fp) != n || fclose(fp) != 0)
		printf("# cannot write %s\n", path);
}

static void
put_text(const char *name, const char *text)
{
	put(name, text, strlen(text));
}

static char *
b64(const void *data, size_t n)
{
	static const char tab[] =
		"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	const unsigned char *d = data;
	char *out = malloc(4 * (n / 3 + 1) + 1), *o = out;
	size_t i;

	for (i = 0; i < n; i += 3) {
		unsigned v = (unsigned)d[i] << 16 | (i + 1 < n ? (unsigned)d[i + 1] << 8 : 0) |
		             (i + 2 < n ? d[i + 2] : 0);

		*o++ = tab[v >> 18 & 63];
		*o++ = tab[v >> 12 & 63];
		*o++ = i + 1 < n ? tab[v >> 6 & 63] : '=';
		*o++ = i + 2 < n ? tab[v & 63] : '=';
	}
	*o = '\0';
	return out;
}

/* A scene from its text, relative paths taken from the scratch folder;
 * NULL, the message printed as a TAP comment, when it is refused. */
static rf_scene *
load(const char *text)
{
	char err[1024] = "", name[512];
	rf_scene *s = NULL;

	snprintf(name, sizeof(name), "%s/test.scene", dir);
	if (rf_scene_parse(&s, text, strlen(text), name, err, sizeof(err)) < 0)
		printf("# parse: %s\n", err);
	return s;
}

#endif
