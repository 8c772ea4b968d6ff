/*
 * libFuzzer harness for the scene parser and the ray caster: the input is
 * a scene's text.  A scene that parses is traced through a 4 x 3 image
 * from its camera; one that does not must say why in one printable line
 * that names the file.  See tests/fuzz/README.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/scene.h"

#define HARNESS "fuzz-scene"
#include "harness.h"

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	char err[1024] = "";
	struct rf_camera cam;
	rf_scene *s;
	size_t i, x, y;

	if (rf_scene_parse(&s, (const char *)data, size, "fuzz.scene", err, sizeof(err)) < 0) {
		check(err[0] != '\0', "an error without a message");
		check(!strncmp(err, "fuzz.scene", 10), "a message that does not name the file");
		for (i = 0; err[i]; i++)
			check((unsigned char)err[i] >= 0x20 && err[i] != 0x7f,
			      "a control character in a message");
		return 0;
	}
	check(rf_scene_nprobes(s) >= 1, "a scene without its room");
	rf_scene_camera(s, &cam);
	if (rf_camera_check(&cam, err, sizeof(err)) == 0)
		for (y = 0; y < 3; y++)
			for (x = 0; x < 4; x++) {
				double dir[3];
				struct rf_hit hit;

				rf_camera_ray(&cam, 4, 3, x + 0.5, y + 0.5, dir);
				check(isfinite(dir[0]) && isfinite(dir[1]) && isfinite(dir[2]),
				      "a camera ray that is not finite");
				(void)rf_scene_trace(s, cam.position, dir, &hit);
				(void)rf_scene_inside(s, cam.position);
			}
	rf_scene_destroy(s);
	return 0;
}
