/*
 * Loading an environment from a path: the embedded room, a stream (from
 * a file, a pipe or standard input), six face images, a chain as one
 * file per level, a DDS or KTX cube, a MIP-mapped OpenEXR chain, or one
 * image in any layout.  The tools' --env, --layout, --prefiltered, --srgb,
 * --rgbm, --intensity and --size are the fields of rf_envmap_options.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "envmap/envmap-internal.h"
#include "stream/stream-internal.h"
#include "reflect/image.h"

/* What one load carries along: the options, the count of replaced
 * texels, and the message buffer. */
struct load {
	const struct rf_envmap_options *o;
	size_t nonfinite;
	char *err;
	size_t errlen;
};

static int load_path(struct load *ld, const char *path, rf_cubemap **c,
                     struct rf_chain_info *info);

void
rf_envmap_options_init(struct rf_envmap_options *o)
{
	memset(o, 0, sizeof(*o));
	o->layout = RF_LAYOUT_AUTO;
	o->srgb = -1;
	o->strict = 1;
	o->decode.multiplier = 1.0f;
	o->decode.exponent = 1.0f;
	o->decode.intensity = 1.0f;
}

/* A cube, or a message: over the memory limit, or levels the size
 * cannot halve to. */
static int
cube_new(struct load *ld, rf_cubemap **c, size_t size, size_t levels)
{
	int rc;

	if ((rc = rf_cubemap_check_size(size, levels, ld->err, ld->errlen)) < 0)
		return rc;
	if ((rc = rf_cubemap_create(c, size, levels)) == RF_EINVAL)
		rf__format(ld->err, ld->errlen, "a cube of %zu texels cannot have %zu levels",
		           size, levels);
	return rc;
}

/* What a reader met: an environment with a NaN or infinite value is
 * refused, naming the first, unless the options repair it (each such
 * value 0, counted for the caller to report). */
static int
count_nonfinite(struct load *ld, const char *path, const struct rf__nonfinite *nf)
{
	char where[128];

	if (nf->count && ld->o->strict) {
		rf__nonfinite_where(nf, where, sizeof(where));
		rf__format(ld->err, ld->errlen, "'%s': %s (%zu such value%s in all; "
		           "--nonfinite=zero replaces them with 0)", path, where, nf->count,
		           nf->count == 1 ? "" : "s");
		return RF_EINVAL;
	}
	ld->nonfinite += nf->count;
	return 0;
}

/* An image's own status, except that only running out of memory is a
 * system error: a file that cannot be decoded is bad input. */
static int
image_status(int rc)
{
	return rc == RF_ENOMEM ? rc : RF_EINVAL;
}

/* An image of one face: square, and of size *n unless *n is 0. */
static int
read_face(struct load *ld, const char *path, size_t *n, rf_image **img)
{
	int rc;

	if ((rc = rf_image_read(img, path, ld->err, ld->errlen)) < 0)
		return image_status(rc);
	if (rf_image_width(*img) != rf_image_height(*img))
		rf__format(ld->err, ld->errlen, "'%s': a face must be square, not %zux%zu",
		           path, rf_image_width(*img), rf_image_height(*img));
	else if (*n && rf_image_width(*img) != *n)
		rf__format(ld->err, ld->errlen, "'%s': faces differ in size (%zu, not %zu "
		           "like the first)", path, rf_image_width(*img), *n);
	else {
		*n = rf_image_width(*img);
		return 0;
	}
	rf_image_destroy(*img);
	*img = NULL;
	return RF_EINVAL;
}

/* "%d" takes 0..5, "%s" takes px nx py ny pz nz. */
static int
face_path(struct load *ld, char *buf, size_t size, const char *pattern, int face)
{
	static const char *const names[6] = { "px", "nx", "py", "ny", "pz", "nz" };
	const char *pct = strchr(pattern, '%');

	if (!pct || (pct[1] != 'd' && pct[1] != 's') || strchr(pct + 1, '%')) {
		rf__format(ld->err, ld->errlen, "--env: '%s' needs one %%d (faces 0..5) or "
		           "%%s (px nx py ny pz nz)", pattern);
		return RF_EINVAL;
	}
	if (pct[1] == 'd')
		snprintf(buf, size, "%.*s%d%s", (int)(pct - pattern), pattern, face, pct + 2);
	else
		snprintf(buf, size, "%.*s%s%s", (int)(pct - pattern), pattern, names[face],
		         pct + 2);
	return 0;
}

static int
is_srgb(const struct rf_envmap_options *o, const rf_image *img)
{
	const char *cs = rf_image_attribute(img, "oiio:ColorSpace");

	if (o->srgb >= 0)
		return o->srgb;
	return cs && !strcasecmp(cs, "sRGB");
}

/* An image in a layout; faces: the image is six face files of that many
 * texels stacked (pattern path), and a bad value is named in its own. */
static int
load_pixels(struct load *ld, const char *path, const float *px, size_t w, size_t h,
            size_t nch, enum rf_layout layout, int srgb, size_t faces, rf_cubemap **c)
{
	struct rf_decode dc = ld->o->decode;
	struct rf__nonfinite nf = { 0 };
	char why[1024], one[4096];
	size_t face;
	int rc;

	dc.srgb = srgb;
	if (layout == RF_LAYOUT_AUTO)
		layout = ld->o->layout;
	if ((layout == RF_LAYOUT_AUTO &&
	     rf_layout_detect(w, h, NULL, &layout, why, sizeof(why)) < 0) ||
	    rf_layout_check(layout, w, h, &face, why, sizeof(why)) < 0) {
		rf__format(ld->err, ld->errlen, "'%s': %s", path, why);
		return RF_EINVAL;
	}
	if (ld->o->size)
		face = ld->o->size;
	if ((rc = cube_new(ld, c, face, 1)) < 0)
		return rc;
	if ((rc = rf__envmap_from_pixels(*c, px, w, h, nch, layout, &dc, &nf, why,
	                                 sizeof(why))) < 0) {
		rf__format(ld->err, ld->errlen, "'%s': %s", path, why);
		rc = RF_EINVAL;
	} else {
		if (faces && nf.count && face_path(ld, one, sizeof(one), path,
		                                   (int)(nf.y / faces)) == 0) {
			path = one;
			nf.y %= faces;
		}
		rc = count_nonfinite(ld, path, &nf);
	}
	if (rc < 0) {
		rf_cubemap_destroy(*c);
		*c = NULL;
	}
	return rc;
}

static int
load_faces(struct load *ld, const char *pattern, rf_cubemap **c)
{
	char path[4096];
	rf_image *faces[6] = { 0 };
	size_t n = 0, nch = 0, f, j;
	float *px = NULL;
	int rc = 0, srgb = 0;

	for (f = 0; f < 6 && rc == 0; f++) {
		if ((rc = face_path(ld, path, sizeof(path), pattern, (int)f)) < 0 ||
		    (rc = read_face(ld, path, &n, &faces[f])) < 0)
			break;
		if (f && rf_image_nchannels(faces[f]) != rf_image_nchannels(faces[0])) {
			rf__format(ld->err, ld->errlen, "'%s': faces differ in channels", path);
			rc = RF_EINVAL;
		}
	}
	if (rc == 0) {
		nch = rf_image_nchannels(faces[0]);
		if (nch != 1 && nch != 3 && nch != 4) {
			rf__format(ld->err, ld->errlen, "'%s': a face has 1, 3 or 4 channels, "
			           "not %zu", path, nch);
			rc = RF_EINVAL;
		} else if (!(px = malloc(n * 6 * n * nch * sizeof(float)))) {
			rc = RF_ENOMEM;
		}
	}
	if (rc == 0) {
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				memcpy(px + ((f * n + j) * n) * nch,
				       rf_image_pixels(faces[f]) + j * n * nch,
				       n * nch * sizeof(float));
		srgb = is_srgb(ld->o, faces[0]);
	}
	for (f = 0; f < 6; f++)
		rf_image_destroy(faces[f]);
	if (rc == 0)
		rc = load_pixels(ld, pattern, px, n, 6 * n, nch, RF_LAYOUT_CUBE, srgb, n, c);
	free(px);
	return rc;
}

/*
 * A chain as one file per level (--prefiltered with %d in the name): %d
 * counts levels from 0 until a file is missing; each file holds one cube
 * in any layout, half the size of the one before.
 */
static int
load_level_files(struct load *ld, const char *pattern, rf_cubemap **c,
                 struct rf_chain_info *info)
{
	struct rf_envmap_options one = *ld->o;
	const struct rf_envmap_options *all = ld->o;
	rf_cubemap *levels[16];
	char path[4096];
	size_t n, k;
	const char *pct = strchr(pattern, '%');
	int rc = 0;

	if (!pct || pct[1] != 'd' || strchr(pct + 1, '%')) {
		rf__format(ld->err, ld->errlen, "--env: '%s' needs one %%d to number the "
		           "levels", pattern);
		return RF_EINVAL;
	}
	one.prefiltered = 0;
	ld->o = &one;
	for (n = 0; n < 16; n++) {
		struct stat st;

		snprintf(path, sizeof(path), "%.*s%zu%s", (int)(pct - pattern), pattern, n,
		         pct + 2);
		if (stat(path, &st) < 0) {
			if (n == 0) {
				rf__format(ld->err, ld->errlen, "cannot open '%s': %s", path,
				           strerror(errno));
				rc = RF_ENOTFOUND;
			}
			break;
		}
		if ((rc = load_path(ld, path, &levels[n], info)) < 0)
			break;
		if (n && rf_cubemap_size(levels[n]) * 2 != rf_cubemap_size(levels[n - 1])) {
			rf__format(ld->err, ld->errlen, "'%s': level %zu has faces of %zu texels, "
			           "not half the %zu of level %zu", path, n,
			           rf_cubemap_size(levels[n]), rf_cubemap_size(levels[n - 1]),
			           n - 1);
			rf_cubemap_destroy(levels[n]);
			rc = RF_EINVAL;
			break;
		}
	}
	ld->o = all;
	if (rc == 0)
		rc = cube_new(ld, c, rf_cubemap_size(levels[0]), n);
	for (k = 0; k < n; k++) {
		if (rc == 0)
			rf__cubemap_copy_level(*c, k, levels[k], 0);
		rf_cubemap_destroy(levels[k]);
	}
	if (rc < 0)
		return rc;
	memset(info, 0, sizeof(*info));
	info->prefiltered = 1;
	info->mapping = RF_MAPPING_DEFAULT;
	info->steps = (float)(n - 1);
	info->base_copied = 1;
	return 0;
}

static int
load_stream(struct load *ld, FILE *fp, const char *name, rf_cubemap **c,
            struct rf_chain_info *info)
{
	struct rf__nonfinite nf = { 0 };
	rf_reader *r;
	int rc;

	if ((rc = rf_reader_open(&r, fp, name, NULL)) < 0)
		return rc;
	rc = rf__chain_read_stream(c, info, r, NULL, &nf, ld->err, ld->errlen);
	rf_reader_close(r);
	if (rc == 0 && (rc = count_nonfinite(ld, name, &nf)) < 0) {
		rf_cubemap_destroy(*c);
		*c = NULL;
	}
	if (rc == 0 && ld->o->prefiltered)
		info->prefiltered = 1;
	return rc;
}

/* A MIP-mapped N x 6N file: a chain when reflect wrote it or the user
 * says it is one (--prefiltered); 1 to read it as a raw image instead. */
static int
load_chain_file(struct load *ld, const char *path, rf_cubemap **c,
                struct rf_chain_info *info)
{
	struct rf__nonfinite nf = { 0 };
	char why[1024];
	size_t levels;
	int rc, ours;

	if (rf_image_count_levels(path, &levels, why, sizeof(why)) < 0 || levels < 2)
		return 1;
	if ((rc = rf__chain_read_file(c, info, &ours, &nf, path, ld->err, ld->errlen)) < 0) {
		if (ld->o->prefiltered)
			return image_status(rc);
		return 1; /* not a cube chain: an ordinary image */
	}
	if (!ours && !ld->o->prefiltered) {
		rf_cubemap_destroy(*c);
		*c = NULL;
		memset(info, 0, sizeof(*info));
		info->mapping = RF_MAPPING_DEFAULT;
		info->base_copied = 1;
		return 1;
	}
	/* read as an image, the same values would be refused the same way */
	if ((rc = count_nonfinite(ld, path, &nf)) < 0) {
		rf_cubemap_destroy(*c);
		*c = NULL;
		return rc;
	}
	if (ld->o->prefiltered)
		info->prefiltered = 1;
	if (!info->steps)
		info->steps = (float)(rf_cubemap_levels(*c) - 1);
	return 0;
}

/* A DDS cube: its mip levels as a chain with --prefiltered, else its
 * level 0 as a raw environment. */
static int
load_dds(struct load *ld, const char *path, rf_cubemap **c, struct rf_chain_info *info)
{
	struct rf__nonfinite nf = { 0 };
	rf_cubemap *chain;
	int rc;

	if ((rc = rf__chain_read_dds(&chain, info, &nf, path, ld->err, ld->errlen)) < 0)
		return image_status(rc);
	if ((rc = count_nonfinite(ld, path, &nf)) < 0 ||
	    ld->o->prefiltered || rf_cubemap_levels(chain) == 1) {
		/* one level is raw (rf_envmap_load), not a chain */
		if (rc < 0)
			rf_cubemap_destroy(chain);
		else
			*c = chain;
		if (ld->o->prefiltered)
			info->prefiltered = 1;
		return rc;
	}
	if ((rc = cube_new(ld, c, rf_cubemap_size(chain), 1)) == 0)
		rf__cubemap_copy_level(*c, 0, chain, 0);
	rf_cubemap_destroy(chain);
	info->prefiltered = 0;
	return rc;
}

/* A KTX cube: its levels as a chain when reflect wrote it or with
 * --prefiltered, else its level 0 as a raw environment. */
static int
load_ktx(struct load *ld, const char *path, rf_cubemap **c, struct rf_chain_info *info)
{
	struct rf__nonfinite nf = { 0 };
	rf_cubemap *chain;
	int rc, ours;

	if ((rc = rf__chain_read_ktx(&chain, info, &ours, &nf, path, ld->err,
	                             ld->errlen)) < 0)
		return image_status(rc);
	if ((rc = count_nonfinite(ld, path, &nf)) < 0) {
		rf_cubemap_destroy(chain);
		return rc;
	}
	if (ours || ld->o->prefiltered) {
		if (ld->o->prefiltered)
			info->prefiltered = 1;
		*c = chain;
		return 0;
	}
	if ((rc = cube_new(ld, c, rf_cubemap_size(chain), 1)) == 0)
		rf__cubemap_copy_level(*c, 0, chain, 0);
	rf_cubemap_destroy(chain);
	memset(info, 0, sizeof(*info));
	info->mapping = RF_MAPPING_DEFAULT;
	info->base_copied = 1;
	return rc;
}

/*
 * The environment file, opened without waiting for a writer: a regular
 * file, or (*piped) a pipe such as --env=<(reflect-prefilter ...), which
 * can only carry a stream.  A FIFO nobody writes to then reads as empty
 * instead of blocking the open for ever; devices and directories, and
 * anything but a file when a stream's header named it, are refused.
 */
static int
open_env_file(struct load *ld, const char *path, FILE **fpp, int *piped)
{
	struct stat st;
	int fd, flags;

	*piped = 0;
	if ((fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC)) < 0 || fstat(fd, &st) < 0)
		goto fail;
	if (!S_ISREG(st.st_mode) && (!S_ISFIFO(st.st_mode) || ld->o->from_header)) {
		rf__format(ld->err, ld->errlen, "cannot open '%s': not a regular file (%s%s)",
		           path, rf__file_kind(st.st_mode),
		           S_ISFIFO(st.st_mode) ? ", named by PROBE_ENV" : "");
		close(fd);
		return RF_EINVAL;
	}
	*piped = S_ISFIFO(st.st_mode);
	if ((flags = fcntl(fd, F_GETFL)) < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0 ||
	    !(*fpp = fdopen(fd, "rb")))
		goto fail;
	return 0;
fail:
	rf__format(ld->err, ld->errlen, "cannot open '%s': %s", path, strerror(errno));
	if (fd >= 0)
		close(fd);
	return RF_ENOTFOUND;
}

static int
has_suffix(const char *s, const char *suffix)
{
	size_t n = strlen(s), m = strlen(suffix);

	return n >= m && !strcasecmp(s + n - m, suffix);
}

static int
load_image(struct load *ld, const char *path, rf_cubemap **c, struct rf_chain_info *info)
{
	char why[1024];
	enum rf_layout layout = ld->o->layout;
	rf_image *img;
	int rc;

	if ((rc = rf_image_read(&img, path, ld->err, ld->errlen)) < 0)
		return image_status(rc);
	if (layout == RF_LAYOUT_AUTO &&
	    rf_layout_detect(rf_image_width(img), rf_image_height(img),
	                     rf_image_attribute(img, "envmap"), &layout, why,
	                     sizeof(why)) < 0) {
		rf__format(ld->err, ld->errlen, "'%s': %s", path, why);
		rc = RF_EINVAL;
	} else {
		rc = load_pixels(ld, path, rf_image_pixels(img), rf_image_width(img),
		                 rf_image_height(img), rf_image_nchannels(img), layout,
		                 is_srgb(ld->o, img), 0, c);
	}
	rf_image_destroy(img);
	if (rc == 0 && ld->o->prefiltered)
		info->prefiltered = 1;
	return rc;
}

static int
load_path(struct load *ld, const char *path, rf_cubemap **c, struct rf_chain_info *info)
{
	const size_t n = strlen(RF__STREAM_MAGIC);
	char magic[16] = "";
	FILE *fp;
	int rc, piped;

	memset(info, 0, sizeof(*info));
	info->mapping = RF_MAPPING_DEFAULT;
	info->base_copied = 1;
	if (!path || !strcmp(path, "default")) {
		if ((rc = cube_new(ld, c, ld->o->size ? ld->o->size : 256, 1)) == 0)
			rf_default_environment_cube_threads(*c, ld->o->nthreads);
		return rc;
	}
	if (!strcmp(path, "-")) {
		if (ld->o->from_header) {
			rf__format(ld->err, ld->errlen, "PROBE_ENV '-': a stream's header cannot "
			           "name standard input; give the environment with --env");
			return RF_EINVAL;
		}
		return load_stream(ld, stdin, "<stdin>", c, info);
	}
	if (strchr(path, '%'))
		return ld->o->prefiltered ? load_level_files(ld, path, c, info)
		                          : load_faces(ld, path, c);
	if (has_suffix(path, ".dds"))
		return load_dds(ld, path, c, info);
	if (has_suffix(path, ".ktx") || has_suffix(path, ".ktx2"))
		return load_ktx(ld, path, c, info);
	if ((rc = open_env_file(ld, path, &fp, &piped)) < 0)
		return rc;
	/* A pipe can only carry a stream: its reader says if it is none. */
	if (piped || (fread(magic, 1, n, fp) == n && !memcmp(magic, RF__STREAM_MAGIC, n))) {
		if (!piped)
			rewind(fp);
		rc = load_stream(ld, fp, path, c, info);
		fclose(fp);
		return rc;
	}
	fclose(fp);
	if ((rc = load_chain_file(ld, path, c, info)) <= 0)
		return rc;
	return load_image(ld, path, c, info);
}

int
rf_envmap_load(rf_cubemap **c, struct rf_chain_info *info, const char *path,
               const struct rf_envmap_options *o, size_t *nonfinite, char *err,
               size_t errlen)
{
	struct load ld = { o, 0, err, errlen };
	int rc;

	*c = NULL;
	if (errlen)
		*err = '\0';
	rc = load_path(&ld, path, c, info);
	/* A cube of one level is the environment itself, whatever its file
	 * says (a DDS or KTX is a chain by its format): sampled as a chain,
	 * every roughness would read the sharp level 0.  It is raw, and is
	 * prefiltered, unless --prefiltered asks to take its level as it is. */
	if (rc == 0 && rf_cubemap_levels(*c) == 1 && !o->prefiltered)
		info->prefiltered = 0;
	if (nonfinite)
		*nonfinite = ld.nonfinite;
	if (rc < 0 && *c) {
		rf_cubemap_destroy(*c);
		*c = NULL;
	}
	return rc;
}

int
rf_chain_levels(size_t size, size_t want, size_t min_size, size_t *levels, char *err,
                size_t errlen)
{
	size_t n = size;

	*levels = 1;
	if (want) {
		for (*levels = 1; *levels < want; (*levels)++, n /= 2)
			if (n & 1 || n / 2 < 1) {
				rf__format(err, errlen, "a %zu-texel cube has no %zu levels (it "
				           "halves to %zu)", size, want, n);
				return RF_EINVAL;
			}
		return 0;
	}
	while (*levels < (size_t)RF_STEPS_DEFAULT + 1 && !((size >> (*levels - 1)) & 1) &&
	       (size >> *levels) >= min_size)
		(*levels)++;
	return 0;
}
