/*
 * libFuzzer harness for the check a glTF file meets before assimp reads
 * it (lib/scene/gltf_check.c): our own walk of its JSON, of a .glb's
 * chunks, and of every size the file claims against the bytes behind
 * it.  The input is written as in.glb when it starts with glTF's magic,
 * else as in.gltf, into a scratch folder that also holds the buffers a
 * URI may name: buffer.bin (92 bytes) and "a b.bin" (12 bytes, for
 * %20).  A refusal must be a library status with one printable line
 * naming the file; what passes must hold material entries as the walk
 * promises them (texture sets of -1 or whole, mirror -1, 0 or 1), and
 * the entries are set and freed either way, whatever the caller's struct
 * held.  assimp's own parsers are not fuzzed here (tests/fuzz.am says
 * why).
 */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/reflect.h"
#include "scene/scene-internal.h"

#define HARNESS "fuzz-gltf"
#include "harness.h"

static void
write_file(const char *dir, const char *name, const void *data, size_t size)
{
	char path[600];
	FILE *fp;

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	check((fp = fopen(path, "wb")) != NULL, "cannot write a scratch file");
	check(fwrite(data, 1, size, fp) == size && fclose(fp) == 0,
	      "cannot write a scratch file");
}

static const char *
setup(void)
{
	static const char *dir;
	unsigned char bytes[92];
	size_t i;

	if (dir)
		return dir;
	dir = scratch_dir();
	for (i = 0; i < sizeof(bytes); i++)
		bytes[i] = (unsigned char)i;
	write_file(dir, "buffer.bin", bytes, 92);
	write_file(dir, "a b.bin", bytes, 12);
	return dir;
}

static void
check_materials(const struct rf__gltf_info *info)
{
	size_t i;
	int k;

	check(info->nmaterials == 0 || info->materials != NULL, "materials lost");
	for (i = 0; i < info->nmaterials; i++) {
		const struct rf__gltf_material *m = &info->materials[i];

		for (k = 0; k < RF__GLTF_TEXTURES; k++)
			check(m->texcoord[k] >= -1 && m->texcoord[k] < 1000000000,
			      "a texture set out of range");
		check(m->mirror >= -1 && m->mirror <= 1, "a mirror flag that is not -1, 0 or 1");
		check(!m->name || strlen(m->name) < (size_t)16 << 10,
		      "a name longer than the input");
	}
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const char *dir = setup();
	struct rf__gltf_info info;
	char path[600], err[1024] = "";
	int glb = size >= 4 && !memcmp(data, "glTF", 4), rc;

	snprintf(path, sizeof(path), "%s/%s", dir, glb ? "in.glb" : "in.gltf");
	write_file(dir, glb ? "in.glb" : "in.gltf", data, size);
	memset(&info, 0xa5, sizeof(info));
	rc = rf__gltf_check(path, &info, err, sizeof(err));
	if (rc < 0) {
		check(rc == RF_EFORMAT || rc == RF_ETOOBIG || rc == RF_EIO || rc == RF_ENOMEM,
		      "a refusal that is no status of the check");
		check_message(err);
		check(rc == RF_ENOMEM || strstr(err, path) != NULL,
		      "a refusal that does not name the file");
	} else
		check(rc == 0, "a status that is neither 0 nor a refusal");
	check_materials(&info);
	rf__gltf_info_free(&info);
	remove(path);
	return 0;
}
