/* The environment options every tool shares, and the library's loader
 * behind them. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_envmap.h"
#include "reflect/scene.h"

void
envmap_opts_init(struct envmap_opts *o)
{
	memset(o, 0, sizeof(*o));
	rf_envmap_options_init(&o->load);
}

static float
parse_positive(const char *name, const char *arg)
{
	char *end;
	double v;

	errno = 0;
	v = strtod(arg, &end);
	if (end == arg || *end || errno || !isfinite(v) || v <= 0.0)
		die("--%s: '%s' is not a positive number", name, arg);
	return (float)v;
}

int
envmap_opts_parse(struct envmap_opts *o, const char *name, const char *arg)
{
	if (!strcmp(name, "env")) {
		o->path = arg;
	} else if (!strcmp(name, "layout")) {
		if (rf_layout_parse(arg, &o->load.layout) < 0)
			die("--layout: '%s' is not auto, latlong, cube, vcross, hcross, mirrorball or angular", arg);
	} else if (!strcmp(name, "prefiltered")) {
		o->load.prefiltered = 1;
	} else if (!strcmp(name, "srgb")) {
		if (!strcmp(arg, "on"))
			o->load.srgb = 1;
		else if (!strcmp(arg, "off"))
			o->load.srgb = 0;
		else if (!strcmp(arg, "auto"))
			o->load.srgb = -1;
		else
			die("--srgb: '%s' is not auto, on or off", arg);
	} else if (!strcmp(name, "rgbm")) {
		float v[2];
		const char *comma = strchr(arg, ',');

		if (comma) {
			parse_floats(arg, "--rgbm", v, 2);
		} else {
			v[0] = parse_positive("rgbm", arg);
			v[1] = 1.0f;
		}
		if (!(v[0] > 0.0f) || !(v[1] > 0.0f))
			die("--rgbm: multiplier and exponent must be positive, not '%s'", arg);
		o->load.decode.rgbm = 1;
		o->load.decode.multiplier = v[0];
		o->load.decode.exponent = v[1];
	} else if (!strcmp(name, "nonfinite")) {
		if (!strcmp(arg, "error"))
			o->load.strict = 1;
		else if (!strcmp(arg, "zero"))
			o->load.strict = 0;
		else
			die("--nonfinite: '%s' is not error or zero", arg);
	} else if (!strcmp(name, "intensity")) {
		o->load.decode.intensity = parse_positive(name, arg);
	} else if (!strcmp(name, "size")) {
		o->load.size = parse_count(arg, 's', 1, 1 << 14);
		if (o->load.size & (o->load.size - 1))
			die("--size: %zu is not a power of two", o->load.size);
	} else {
		return 0;
	}
	return 1;
}

/*
 * A scene named by a stream's header (PROBE_ENV=capture:FILE#K) is a
 * file the stream chose, not the user: a parser's message quotes the
 * words it stumbled on, and would print a part of any file a stream
 * names.  Only where it stumbled is kept: "FILE:LINE:COLUMN".
 */
static void
without_content(char *err, size_t errlen, const char *file)
{
	char where[1024];
	size_t n = strlen(file);
	const char *p;

	if (strncmp(err, file, n) || err[n] != ':' || !isdigit((unsigned char)err[n + 1]))
		return; /* not the parser's: it quotes nothing of the file */
	p = err + n + 1 + strspn(err + n + 1, "0123456789");
	if (*p == ':' && isdigit((unsigned char)p[1]))
		p += 1 + strspn(p + 1, "0123456789");
	snprintf(where, sizeof(where), "%.*s", (int)(p - err), err);
	snprintf(err, errlen, "'%s' (named by the stream's header) is not a scene reflect "
	         "reads: %s; its words are not shown, since the stream, not you, named it",
	         file, where);
}

/* capture:SCENE[#K] (a probe's "env capture"): probe K (from 1) of the
 * scene file, or of the embedded scene for "default", baked as
 * reflect-capture bakes it by default: a raw environment to prefilter. */
static rf_cubemap *
capture_load(const char *spec, const struct envmap_opts *o, struct rf_chain_info *info)
{
	struct rf_capture_options co;
	const char *hash = strrchr(spec, '#');
	char file[4096], err[4096 + 1024], *end;
	unsigned long k = 1;
	rf_cubemap *c;
	rf_scene *s;
	int rc;

	snprintf(file, sizeof(file), "%.*s", (int)(hash ? (size_t)(hash - spec) : strlen(spec)),
	         spec);
	if (hash && (!(k = strtoul(hash + 1, &end, 10)) || *end))
		die("'capture:%s': '%s' is not a probe number (capture:SCENE#K, K from 1)",
		    spec, hash + 1);
	if (!strcmp(file, "<stdin>") || !strcmp(file, "-"))
		die("'capture:%s': the scene came from standard input and cannot be read "
		    "again; bake the probe with reflect-capture and give it with --env", spec);
	if ((rc = cli_read_scene(&s, file, err, sizeof(err))) < 0) {
		if (o->load.from_header)
			without_content(err, sizeof(err), file);
		die_status(rc, err);
	}
	rf_capture_options_init(&co);
	co.nthreads = o->load.nthreads > 0 ? o->load.nthreads : 1;
	if ((rc = rf_scene_capture(s, (size_t)k - 1, &co, &c, err, sizeof(err))) < 0) {
		rf_scene_destroy(s);
		die("'capture:%s': %s", spec, err);
	}
	rf_scene_destroy(s);
	memset(info, 0, sizeof(*info));
	info->mapping = RF_MAPPING_DEFAULT;
	info->base_copied = 1;
	return c;
}

rf_cubemap *
envmap_load(const struct envmap_opts *o, struct rf_chain_info *info)
{
	char err[1024];
	size_t bad;
	rf_cubemap *c;
	int rc;

	if (o->path && !strncmp(o->path, "capture:", 8))
		return capture_load(o->path + 8, o, info);
	if (o->path && strcmp(o->path, "default"))
		cli_guard_mapped(strcmp(o->path, "-") ? o->path : "<stdin>");
	if ((rc = rf_envmap_load(&c, info, o->path, &o->load, &bad, err, sizeof(err))) < 0)
		die_status(rc, err);
	if (bad)
		warn("'%s': replaced %zu NaN, infinite or out-of-range texel values with 0",
		     o->path, bad);
	return c;
}

rf_cubemap *
envmap_cube_new(size_t size, size_t levels)
{
	char err[256];
	rf_cubemap *c;
	int rc;

	if ((rc = rf_cubemap_check_size(size, levels, err, sizeof(err))) < 0)
		die("%s", err);
	if ((rc = rf_cubemap_create(&c, size, levels)) < 0) {
		if (rc == RF_EINVAL)
			die("a cube of %zu texels cannot have %zu levels", size, levels);
		die_status(rc, NULL);
	}
	return c;
}

size_t
envmap_chain_levels(size_t size, size_t want, size_t min_size)
{
	char err[256];
	size_t levels;

	if (rf_chain_levels(size, want, min_size, &levels, err, sizeof(err)) < 0)
		die("%s", err);
	return levels;
}
