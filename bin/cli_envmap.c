/* Loading an environment from the options every tool shares. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli_envmap.h"

void
envmap_opts_init(struct envmap_opts *o)
{
	memset(o, 0, sizeof(*o));
	o->layout = RF_LAYOUT_AUTO;
	o->srgb = -1;
	o->decode.multiplier = 1.0f;
	o->decode.exponent = 1.0f;
	o->decode.intensity = 1.0f;
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
		if (rf_layout_parse(arg, &o->layout) < 0)
			die("--layout: '%s' is not auto, latlong, cube, vcross or hcross", arg);
	} else if (!strcmp(name, "prefiltered")) {
		o->prefiltered = 1;
	} else if (!strcmp(name, "srgb")) {
		if (!strcmp(arg, "on"))
			o->srgb = 1;
		else if (!strcmp(arg, "off"))
			o->srgb = 0;
		else if (!strcmp(arg, "auto"))
			o->srgb = -1;
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
		o->decode.rgbm = 1;
		o->decode.multiplier = v[0];
		o->decode.exponent = v[1];
	} else if (!strcmp(name, "intensity")) {
		o->decode.intensity = parse_positive(name, arg);
	} else if (!strcmp(name, "size")) {
		o->size = parse_count(arg, 's', 1, 1 << 14);
		if (o->size & (o->size - 1))
			die("--size: %zu is not a power of two", o->size);
	} else {
		return 0;
	}
	return 1;
}

static void
report_nonfinite(const struct envmap_opts *o, const char *path, size_t bad)
{
	if (!bad)
		return;
	if (o->strict)
		die("'%s': %zu texel values are NaN or infinite (-S refuses them)", path, bad);
	warn("'%s': replaced %zu NaN or infinite texel values with 0", path, bad);
}

/* An image of one face: checks it is square and of size n (0: any). */
static rf_image *
read_face(const char *path, size_t *n)
{
	char err[1024];
	rf_image *img;
	int rc;

	if ((rc = rf_image_read(&img, path, err, sizeof(err))) < 0)
		die_status(rc == RF_ENOMEM ? rc : RF_EINVAL, err);
	if (rf_image_width(img) != rf_image_height(img))
		die("'%s': a face must be square, not %zux%zu", path, rf_image_width(img),
		    rf_image_height(img));
	if (*n && rf_image_width(img) != *n)
		die("'%s': faces differ in size (%zu, not %zu like the first)", path,
		    rf_image_width(img), *n);
	*n = rf_image_width(img);
	return img;
}

/* "%d" takes 0..5, "%s" takes px nx py ny pz nz. */
static void
face_path(char *buf, size_t size, const char *pattern, int face)
{
	static const char *const names[6] = { "px", "nx", "py", "ny", "pz", "nz" };
	const char *pct = strchr(pattern, '%');

	if (!pct || (pct[1] != 'd' && pct[1] != 's') || strchr(pct + 1, '%'))
		die("--env: '%s' needs one %%d (faces 0..5) or %%s (px nx py ny pz nz)",
		    pattern);
	if (pct[1] == 'd')
		snprintf(buf, size, "%.*s%d%s", (int)(pct - pattern), pattern, face, pct + 2);
	else
		snprintf(buf, size, "%.*s%s%s", (int)(pct - pattern), pattern, names[face],
		         pct + 2);
}

static int
is_srgb(const struct envmap_opts *o, const rf_image *img)
{
	const char *cs = rf_image_attribute(img, "oiio:ColorSpace");

	if (o->srgb >= 0)
		return o->srgb;
	return cs && !strcasecmp(cs, "sRGB");
}

rf_cubemap *
envmap_cube_new(size_t size, size_t levels)
{
	char err[256];
	rf_cubemap *c;
	int rc;

	if ((rc = rf_cubemap_check_size(size, levels, err, sizeof(err))) < 0)
		die("%s", err);
	if ((rc = rf_cubemap_new(&c, size, levels)) < 0) {
		if (rc == RF_EINVAL)
			die("a cube of %zu texels cannot have %zu levels", size, levels);
		die_status(rc, NULL);
	}
	return c;
}

static rf_cubemap *
load_pixels(const struct envmap_opts *o, const char *path, const float *px, size_t w,
            size_t h, size_t nch, enum rf_layout layout, int srgb)
{
	struct rf_decode dc = o->decode;
	char err[1024];
	rf_cubemap *c;
	size_t face, bad;
	int rc;

	dc.srgb = srgb;
	if (layout == RF_LAYOUT_AUTO)
		layout = o->layout;
	if (layout == RF_LAYOUT_AUTO &&
	    rf_layout_detect(w, h, NULL, &layout, err, sizeof(err)) < 0)
		die("'%s': %s", path, err);
	if (rf_layout_check(layout, w, h, &face, err, sizeof(err)) < 0)
		die("'%s': %s", path, err);
	if (o->size)
		face = o->size;
	c = envmap_cube_new(face, 1);
	if ((rc = rf_envmap_from_pixels(c, px, w, h, nch, layout, &dc, &bad, err,
	                                sizeof(err))) < 0)
		die("'%s': %s", path, err);
	report_nonfinite(o, path, bad);
	return c;
}

static rf_cubemap *
load_faces(const struct envmap_opts *o)
{
	char path[4096];
	rf_image *faces[6];
	size_t n = 0, nch, f, j;
	float *px;
	rf_cubemap *c;
	int srgb;

	for (f = 0; f < 6; f++) {
		face_path(path, sizeof(path), o->path, (int)f);
		faces[f] = read_face(path, &n);
		if (f && rf_image_nchannels(faces[f]) != rf_image_nchannels(faces[0]))
			die("'%s': faces differ in channels", path);
	}
	nch = rf_image_nchannels(faces[0]);
	if (nch != 1 && nch != 3 && nch != 4)
		die("'%s': a face has 1, 3 or 4 channels, not %zu", path, nch);
	px = emalloc(n * 6 * n * nch * sizeof(float));
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			memcpy(px + ((f * n + j) * n) * nch,
			       rf_image_pixels(faces[f]) + j * n * nch, n * nch * sizeof(float));
	srgb = is_srgb(o, faces[0]);
	for (f = 0; f < 6; f++)
		rf_image_free(faces[f]);
	c = load_pixels(o, o->path, px, n, 6 * n, nch, RF_LAYOUT_CUBE, srgb);
	free(px);
	return c;
}

/*
 * A chain as one file per level (--prefiltered with %d in the name): %d
 * counts levels from 0 until a file is missing; each file holds one cube
 * in any layout, half the size of the one before.
 */
static rf_cubemap *
load_level_files(const struct envmap_opts *o, struct rf_chain_info *info)
{
	rf_cubemap *levels[16], *c;
	char path[4096];
	struct envmap_opts one = *o;
	size_t n = 0, k, f, i, j;
	const char *pct = strchr(o->path, '%');

	if (!pct || pct[1] != 'd' || strchr(pct + 1, '%'))
		die("--env: '%s' needs one %%d to number the levels", o->path);
	one.prefiltered = 0;
	for (n = 0; n < 16; n++) {
		struct stat st;

		snprintf(path, sizeof(path), "%.*s%zu%s", (int)(pct - o->path), o->path, n,
		         pct + 2);
		if (stat(path, &st) < 0) {
			if (n == 0)
				die("cannot open '%s':", path);
			break;
		}
		one.path = path;
		levels[n] = envmap_load(&one, info);
		if (n && rf_cubemap_size(levels[n]) * 2 != rf_cubemap_size(levels[n - 1]))
			die("'%s': level %zu has faces of %zu texels, not half the %zu of level "
			    "%zu", path, n, rf_cubemap_size(levels[n]),
			    rf_cubemap_size(levels[n - 1]), n - 1);
	}
	c = envmap_cube_new(rf_cubemap_size(levels[0]), n);
	for (k = 0; k < n; k++) {
		size_t m = rf_cubemap_level_size(c, k);

		for (f = 0; f < 6; f++)
			for (j = 0; j < m; j++)
				for (i = 0; i < m; i++)
					memcpy(rf_cubemap_texel(c, k, (enum rf_face)f, i, j),
					       rf_cubemap_texel_const(levels[k], 0, (enum rf_face)f, i, j),
					       3 * sizeof(float));
		rf_cubemap_seal_level(c, k);
		rf_cubemap_free(levels[k]);
	}
	memset(info, 0, sizeof(*info));
	info->prefiltered = 1;
	info->mapping = RF_MAPPING_DEFAULT;
	info->steps = (float)(n - 1);
	info->base_copied = 1;
	return c;
}

static rf_cubemap *
load_stream(const struct envmap_opts *o, FILE *fp, const char *name,
            struct rf_chain_info *info)
{
	char err[1024];
	rf_reader *r;
	rf_cubemap *c;
	int rc;

	cli_guard_mapped(name);
	if ((rc = rf_reader_open(&r, fp, name, NULL)) < 0)
		die_status(rc, NULL);
	rc = rf_chain_read_stream(&c, info, r, err, sizeof(err));
	rf_reader_close(r);
	if (rc < 0)
		die_status(rc, err);
	if (o->prefiltered)
		info->prefiltered = 1;
	return c;
}

/* A MIP-mapped N x 6N file: a chain when reflect wrote it or the user
 * says it is one (--prefiltered); NULL to read it as a raw image. */
static rf_cubemap *
load_chain_file(const struct envmap_opts *o, struct rf_chain_info *info)
{
	char err[1024];
	size_t levels;
	rf_cubemap *c;
	int rc, ours;

	if (rf_image_count_levels(o->path, &levels, err, sizeof(err)) < 0 || levels < 2)
		return NULL;
	if ((rc = rf_chain_read_file(&c, info, &ours, o->path, err, sizeof(err))) < 0) {
		if (o->prefiltered)
			die_status(rc == RF_ENOMEM ? rc : RF_EINVAL, err);
		return NULL; /* not a cube chain: an ordinary image */
	}
	if (!ours && !o->prefiltered) {
		rf_cubemap_free(c);
		memset(info, 0, sizeof(*info));
		info->mapping = RF_MAPPING_DEFAULT;
		info->base_copied = 1;
		return NULL;
	}
	if (o->prefiltered)
		info->prefiltered = 1;
	if (!info->steps)
		info->steps = (float)(rf_cubemap_levels(c) - 1);
	return c;
}

/* A DDS cube: its mip levels as a chain with --prefiltered, else its
 * level 0 as a raw environment. */
static rf_cubemap *
load_dds(const struct envmap_opts *o, struct rf_chain_info *info)
{
	char err[1024];
	size_t bad = 0, f, i, j, n;
	rf_cubemap *c, *raw;
	int rc;

	if ((rc = rf_chain_read_dds(&c, info, &bad, o->path, err, sizeof(err))) < 0)
		die_status(rc == RF_ENOMEM ? rc : RF_EINVAL, err);
	report_nonfinite(o, o->path, bad);
	if (o->prefiltered || rf_cubemap_levels(c) == 1)
		return c;
	n = rf_cubemap_size(c);
	raw = envmap_cube_new(n, 1);
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++)
				memcpy(rf_cubemap_texel(raw, 0, (enum rf_face)f, i, j),
				       rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j),
				       3 * sizeof(float));
	rf_cubemap_seal_level(raw, 0);
	rf_cubemap_free(c);
	info->prefiltered = 0;
	return raw;
}

/*
 * The environment file, opened without waiting for a writer: a regular
 * file, or (*piped) a pipe such as --env=<(reflect-prefilter ...), which
 * can only carry a stream.  A FIFO nobody writes to then reads as empty
 * instead of blocking the open for ever; devices and directories, and
 * anything but a file when a stream's header named it, are refused.
 */
static FILE *
open_env_file(const struct envmap_opts *o, int *piped)
{
	struct stat st;
	FILE *fp;
	int fd, flags;

	*piped = 0;
	if ((fd = open(o->path, O_RDONLY | O_NONBLOCK | O_CLOEXEC)) < 0)
		return NULL;
	if (fstat(fd, &st) < 0) {
		close(fd);
		return NULL;
	}
	if (!S_ISREG(st.st_mode) && (!S_ISFIFO(st.st_mode) || o->from_header))
		die("cannot open '%s': not a regular file (%s)", o->path,
		    S_ISDIR(st.st_mode) ? "a directory" : S_ISFIFO(st.st_mode) ? "a FIFO, "
		    "named by PROBE_ENV" : S_ISCHR(st.st_mode) ? "a character device"
		    : "not a file");
	*piped = S_ISFIFO(st.st_mode);
	if ((flags = fcntl(fd, F_GETFL)) < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0 ||
	    !(fp = fdopen(fd, "rb"))) {
		close(fd);
		return NULL;
	}
	return fp;
}

static int
has_suffix(const char *s, const char *suffix)
{
	size_t n = strlen(s), m = strlen(suffix);

	return n >= m && !strcasecmp(s + n - m, suffix);
}

rf_cubemap *
envmap_load(const struct envmap_opts *o, struct rf_chain_info *info)
{
	char err[1024], magic[10] = "";
	rf_image *img;
	rf_cubemap *c;
	FILE *fp;
	int rc, piped;

	memset(info, 0, sizeof(*info));
	info->mapping = RF_MAPPING_DEFAULT;
	info->base_copied = 1;
	if (!o->path || !strcmp(o->path, "default")) {
		c = envmap_cube_new(o->size ? o->size : 256, 1);
		rf_default_environment_cube_threads(c, o->nthreads);
		return c;
	}
	if (!strcmp(o->path, "-")) {
		if (o->from_header)
			die("PROBE_ENV '-': a stream's header cannot name standard input; "
			    "give the environment with --env");
		return load_stream(o, stdin, "<stdin>", info);
	}
	if (strchr(o->path, '%'))
		return o->prefiltered ? load_level_files(o, info) : load_faces(o);
	if (has_suffix(o->path, ".dds"))
		return load_dds(o, info);
	if (!(fp = open_env_file(o, &piped)))
		die("cannot open '%s':", o->path);
	/* A pipe can only carry a stream: its reader says if it is none. */
	if (piped || (fread(magic, 1, 9, fp) == 9 && !memcmp(magic, "#?REFLECT", 9))) {
		if (!piped)
			rewind(fp);
		c = load_stream(o, fp, o->path, info);
		fclose(fp);
		return c;
	}
	fclose(fp);
	if ((c = load_chain_file(o, info)))
		return c;
	if ((rc = rf_image_read(&img, o->path, err, sizeof(err))) < 0)
		die_status(rc == RF_ENOMEM ? rc : RF_EINVAL, err);
	{
		const char *envmap = rf_image_attribute(img, "envmap");
		enum rf_layout layout = o->layout;

		if (layout == RF_LAYOUT_AUTO &&
		    rf_layout_detect(rf_image_width(img), rf_image_height(img), envmap,
		                     &layout, err, sizeof(err)) < 0)
			die("'%s': %s", o->path, err);
		c = load_pixels(o, o->path, rf_image_pixels(img), rf_image_width(img),
		                rf_image_height(img), rf_image_nchannels(img), layout,
		                is_srgb(o, img));
	}
	rf_image_free(img);
	if (o->prefiltered)
		info->prefiltered = 1;
	return c;
}

size_t
envmap_chain_levels(size_t size, size_t want, size_t min_size)
{
	size_t levels = 1, n = size;

	if (want) {
		for (levels = 1; levels < want; levels++, n /= 2)
			if (n & 1 || n / 2 < 1)
				die("a %zu-texel cube has no %zu levels (it halves to %zu)", size,
				    want, n);
		return levels;
	}
	while (levels < (size_t)RF_STEPS_DEFAULT + 1 && !((size >> (levels - 1)) & 1) &&
	       (size >> levels) >= min_size)
		levels++;
	return levels;
}
