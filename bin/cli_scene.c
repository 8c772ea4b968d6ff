/* Loading a scene for the tools that read one (reflect-gbuffer,
 * reflect-capture, reflect-trace, and capture: environments). */
#include <errno.h>
#include <string.h>

#include "cli.h"
#include "reflect/scene.h"

int
cli_read_scene(rf_scene **s, const char *path, char *err, size_t errlen)
{
	FILE *fp;
	int rc;

	if (!path || !strcmp(path, "default"))
		return rf_scene_default(s, err, errlen);
	if (!strcmp(path, "-"))
		fp = stdin;
	else if (!(fp = fopen(path, "r"))) {
		snprintf(err, errlen, "cannot open '%s': %s", path, strerror(errno));
		return RF_ENOTFOUND;
	}
	rc = rf_scene_read(s, fp, fp == stdin ? "<stdin>" : path, err, errlen);
	if (fp != stdin)
		fclose(fp);
	return rc;
}

rf_scene *
cli_load_scene(const char *path)
{
	char err[4096 + 1024]; /* a path, and what is wrong at its line */
	rf_scene *s;
	int rc;

	if ((rc = cli_read_scene(&s, path, err, sizeof(err))) < 0)
		die_status(rc, err);
	return s;
}
