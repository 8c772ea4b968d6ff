/* Loading a scene for the tools that read one (reflect-gbuffer,
 * reflect-capture). */
#include <string.h>

#include "cli.h"
#include "reflect/scene.h"

rf_scene *
cli_load_scene(const char *path)
{
	char err[4096 + 1024]; /* a path, and what is wrong at its line */
	rf_scene *s;
	FILE *fp;
	int rc;

	if (!path || !strcmp(path, "default")) {
		if ((rc = rf_scene_default(&s, err, sizeof(err))) < 0)
			die_status(rc, err);
		return s;
	}
	if (!strcmp(path, "-"))
		fp = stdin;
	else if (!(fp = fopen(path, "r")))
		die("cannot open '%s':", path);
	rc = rf_scene_read(&s, fp, fp == stdin ? "<stdin>" : path, err, sizeof(err));
	if (fp != stdin)
		fclose(fp);
	if (rc < 0)
		die_status(rc, err);
	return s;
}
