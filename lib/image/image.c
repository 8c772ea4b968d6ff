/*
 * Image files, through a module that libreflect loads the first time an
 * image is read or written.  OpenImageIO brings some 250 shared libraries
 * with it; linking them into every tool would cost each one a quarter of a
 * second and 130 MB before its first pixel, and most stages of a pipeline
 * never touch an image file.
 *
 * PNG and scanline OpenEXR, the two types a pipeline writes, are written
 * by libreflect itself (png.c, exr.c) and never load the
 * module: loading it would cost the last stage of every pipeline those
 * 130 MB.  OpenEXR and PNG files are read by libreflect too (exr_read.c,
 * png_read.c), the environments, references and maps a pipeline reads.
 * Everything else goes through the module.
 */
#include <ctype.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image/module.h"
#include "image/readers.h"
#include "image/writers.h"
#include "util/util.h"

#ifndef REFLECT_MODULEDIR_REL
#define REFLECT_MODULEDIR_REL "reflect"
#endif
#ifndef REFLECT_MODULEDIR
#define REFLECT_MODULEDIR "/usr/local/lib/reflect"
#endif

static pthread_once_t once = PTHREAD_ONCE_INIT;
static const struct rf__image_api *api;
static char load_error[1024];
/* Why the module is not there: RF_ENOMEM when there was no room for it. */
static int load_status = RF_EIMAGE;

static const struct rf__image_api *
try_module(const char *path)
{
	const struct rf__image_api *(*entry)(void);
	const struct rf__image_api *a;
	void *handle, *sym;

	if (!(handle = dlopen(path, RTLD_NOW | RTLD_LOCAL))) {
		rf__format(load_error, sizeof(load_error), "cannot load the image module "
		           "'%s': %s", path, dlerror());
		return NULL;
	}
	if (!(sym = dlsym(handle, RF_IMAGE_MODULE_ENTRY))) {
		rf__format(load_error, sizeof(load_error), "'%s' is not reflect's image "
		           "module", path);
		dlclose(handle);
		return NULL;
	}
	memcpy(&entry, &sym, sizeof(entry));
	a = entry();
	if (!a || a->size != sizeof(struct rf__image_api)) {
		rf__format(load_error, sizeof(load_error), "'%s' is an image module of "
		           "another build of reflect; reinstall reflect", path);
		dlclose(handle);
		return NULL;
	}
	return a; /* kept loaded for the life of the process */
}

/*
 * The address space the module takes as it loads: measured at 434 MB
 * (VmSize before and after, OpenImageIO 2.4 on Debian 12), most of it
 * the mappings of its libraries and the stacks of threads that their
 * constructors start.  Under a limit (ulimit -v) that leaves less, a
 * constructor fails in dlopen, where nothing can catch it: log4cplus's
 * threw std::system_error through dlopen and the process aborted, others
 * crashed.  So the module is not loaded then.
 */
#define MODULE_ADDRESS_SPACE ((size_t)448 << 20)

/* 0 when the limit on address space leaves room to load the module. */
static int
room_for_module(void)
{
	struct rlimit rl;
	unsigned long pages = 0;
	size_t used;
	FILE *fp;

	if (getrlimit(RLIMIT_AS, &rl) < 0 || rl.rlim_cur == RLIM_INFINITY)
		return 0;
	if ((fp = fopen("/proc/self/statm", "r"))) {
		if (fscanf(fp, "%lu", &pages) != 1)
			pages = 0;
		fclose(fp);
	}
	used = (size_t)pages * (size_t)sysconf(_SC_PAGESIZE);
	if ((size_t)rl.rlim_cur > used && (size_t)rl.rlim_cur - used >= MODULE_ADDRESS_SPACE)
		return 0;
	rf__format(load_error, sizeof(load_error), "cannot load the image module: it "
	           "takes some %zu MB of address space, and the limit (ulimit -v) "
	           "leaves %zu MB", MODULE_ADDRESS_SPACE >> 20,
	           (size_t)rl.rlim_cur > used ? ((size_t)rl.rlim_cur - used) >> 20 : 0);
	return RF_ENOMEM;
}

/* REFLECT_IMAGE_MODULE, else next to libreflect itself (an uninstalled
 * build keeps both in lib/.libs), else the installed module directory. */
static void
load(void)
{
	const char *env = getenv("REFLECT_IMAGE_MODULE");
	char path[4096];
	Dl_info info;

	if ((load_status = room_for_module()) < 0)
		return;
	load_status = RF_EIMAGE;
	if (env && *env) {
		api = try_module(env);
		return;
	}
	if (dladdr((void *)load, &info) && info.dli_fname && strrchr(info.dli_fname, '/')) {
		const char *slash = strrchr(info.dli_fname, '/');
		struct stat st;

		snprintf(path, sizeof(path), "%.*s/%s", (int)(slash - info.dli_fname),
		           info.dli_fname, RF_IMAGE_MODULE_NAME);
		if ((api = try_module(path)))
			return;
		/* One that is there but will not load says why; the installed
		 * one is the fallback only for a module that is not there. */
		if (stat(path, &st) == 0)
			return;
		/* An installed tree, moved: the module's directory beside the
		 * library (pkglibdir is libdir/PACKAGE). */
		snprintf(path, sizeof(path), "%.*s/%s/%s", (int)(slash - info.dli_fname),
		           info.dli_fname, REFLECT_MODULEDIR_REL, RF_IMAGE_MODULE_NAME);
		if ((api = try_module(path)) || stat(path, &st) == 0)
			return;
	}
	snprintf(path, sizeof(path), "%s/%s", REFLECT_MODULEDIR, RF_IMAGE_MODULE_NAME);
	api = try_module(path);
}

static const struct rf__image_api *
module(char *err, size_t errlen)
{
	pthread_once(&once, load);
	if (!api && err)
		rf__format(err, errlen, "%s", load_error);
	return api;
}

int
rf_image_module_check(char *err, size_t errlen)
{
	return module(err, errlen) ? 0 : load_status;
}

/* REFLECT_READERS=module reads OpenEXR and PNG through the module as
 * before, to compare the two readers. */
static int
own_readers(void)
{
	const char *v = getenv("REFLECT_READERS");

	return !v || strcmp(v, "module");
}

/* An image: read by libreflect itself, or by the module (mod). */
struct rf_image {
	void *mod;
	struct rf__image_data own;
};

static int
wrap_module(rf_image **img, void *mod)
{
	if (!(*img = calloc(1, sizeof(**img)))) {
		api->free_image(mod);
		return RF_ENOMEM;
	}
	(*img)->mod = mod;
	return 0;
}

int
rf_image_read(rf_image **img, const char *path, char *err, size_t errlen)
{
	return rf_image_read_level(img, path, 0, err, errlen);
}

int
rf_image_read_level(rf_image **img, const char *path, size_t level, char *err,
                    size_t errlen)
{
	rf_image *mod = NULL;
	int rc;

	*img = NULL;
	if ((rc = rf__regular_file(path, err, errlen)) < 0)
		return rc;
	if (own_readers() && (rf__is_exr(path) || rf__is_png(path))) {
		struct rf__image_data data;

		if (rf__is_exr(path))
			rc = rf__exr_read_level(&data, path, level, err, errlen);
		else if (level) {
			rf__format(err, errlen, "'%s' has 1 level, not %zu", path, level + 1);
			return RF_EINVAL;
		} else
			rc = rf__png_read(&data, path, err, errlen);
		if (rc != RF_ENOTFOUND) {
			if (rc < 0)
				return rc;
			if (!(*img = calloc(1, sizeof(**img)))) {
				rf__image_data_free(&data);
				return RF_ENOMEM;
			}
			(*img)->own = data;
			return 0;
		}
	}
	if (!module(err, errlen))
		return load_status;
	if ((rc = api->read_level(&mod, path, level, rf__image_bounds, err, errlen)) < 0)
		return rc;
	return wrap_module(img, mod);
}

int
rf_image_count_levels(const char *path, size_t *nlevels, char *err, size_t errlen)
{
	int rc;

	if ((rc = rf__regular_file(path, err, errlen)) < 0)
		return rc;
	if (own_readers() && rf__is_exr(path) &&
	    (rc = rf__exr_count_levels(path, nlevels, err, errlen)) != RF_ENOTFOUND)
		return rc;
	if (own_readers() && rf__is_png(path)) {
		*nlevels = 1;
		return 0;
	}
	return module(err, errlen) ? api->count_levels(path, nlevels, err, errlen)
	                           : load_status;
}

void
rf_image_destroy(rf_image *img)
{
	if (!img)
		return;
	if (img->mod)
		api->free_image(img->mod);
	rf__image_data_free(&img->own);
	free(img);
}

size_t
rf_image_width(const rf_image *img)
{
	return img->mod ? api->width(img->mod) : img->own.width;
}

size_t
rf_image_height(const rf_image *img)
{
	return img->mod ? api->height(img->mod) : img->own.height;
}

size_t
rf_image_nchannels(const rf_image *img)
{
	return img->mod ? api->nchannels(img->mod) : img->own.nchannels;
}

const char *
rf_image_channel(const rf_image *img, size_t i)
{
	if (img->mod)
		return api->channel(img->mod, i);
	return i < img->own.nchannels ? img->own.names[i] : NULL;
}

const float *
rf_image_pixels(const rf_image *img)
{
	return img->mod ? api->pixels(img->mod) : img->own.pixels;
}

const char *
rf_image_attribute(const rf_image *img, const char *name)
{
	size_t i;

	if (img->mod)
		return api->attribute(img->mod, name);
	for (i = 0; i < img->own.nattr; i++)
		if (!strcmp(img->own.attr[2 * i], name))
			return img->own.attr[2 * i + 1];
	return NULL;
}

/* The extension of a file name in lowercase, "" when it has none (or one
 * too long to be one). */
static void
extension(const char *path, char ext[8])
{
	const char *dot = strrchr(path, '.');
	size_t i;

	ext[0] = '\0';
	if (!dot || strchr(dot, '/') || strlen(dot + 1) >= 8)
		return;
	for (i = 0; dot[1 + i]; i++)
		ext[i] = (char)tolower((unsigned char)dot[1 + i]);
	ext[i] = '\0';
}

int
rf_image_type_for_path(const char *path)
{
	char ext[8];

	extension(path, ext);
	if (!strcmp(ext, "png"))
		return RF_PIXEL_UINT8;
	if (!strcmp(ext, "exr"))
		return RF_PIXEL_FLOAT;
	return module(NULL, 0) ? api->type_for_path(path) : -1;
}

/* Who writes a file: libreflect (PNG at 8 and 16 bits, 1 to 4 channels;
 * OpenEXR in half and float), else the module (PNG of floats, say, which
 * OpenImageIO converts its own way). */
enum writer_kind { WRITER_MODULE, WRITER_PNG, WRITER_EXR };

struct rf_image_writer {
	enum writer_kind kind;
	union {
		struct rf__module_writer *module;
		struct rf__png_writer *png;
		struct rf__exr_writer *exr;
	} u;
	size_t height, next_row;
	char error[1024];         /* the last write's, for rf_image_writer_error */
	rf_output *out;           /* the file written, renamed to path at close */
	char path[];
};

/* Frees a writer whose file is not to be kept: its temporary file goes. */
static void
discard(rf_image_writer *w)
{
	rf_output_discard(w->out);
	free(w);
}

/* A sub-writer's message names the file it was handed: name the path. */
static void
name_path(const rf_image_writer *w, char *err, size_t errlen)
{
	const char *temp = w->out ? rf_output_file(w->out) : NULL;
	char *at, out[1024];
	size_t tl;

	if (!temp || !strcmp(temp, w->path) || !err || !(at = strstr(err, temp)))
		return;
	tl = strlen(temp);
	rf__format(out, sizeof(out), "%.*s%s%s", (int)(at - err), err, w->path, at + tl);
	rf__format(err, errlen, "%s", out);
}

static enum writer_kind
writer_kind(const char *path, size_t nchannels, enum rf_pixel_type type)
{
	char ext[8];

	extension(path, ext);
	if (!strcmp(ext, "png") && (type == RF_PIXEL_UINT8 || type == RF_PIXEL_UINT16) &&
	    nchannels >= 1 && nchannels <= 4)
		return WRITER_PNG;
	if (!strcmp(ext, "exr") && (type == RF_PIXEL_HALF || type == RF_PIXEL_FLOAT))
		return WRITER_EXR;
	return WRITER_MODULE;
}

int
rf_image_writer_open(rf_image_writer **wp, const char *path, size_t width,
                     size_t height, size_t nchannels, const char *const *names,
                     enum rf_pixel_type type, char *err, size_t errlen)
{
	size_t len = strlen(path);
	const char *file;
	rf_image_writer *w;
	int rc;

	*wp = NULL;
	if (!(w = calloc(1, sizeof(*w) + len + 1))) {
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		return RF_ENOMEM;
	}
	memcpy(w->path, path, len + 1);
	w->kind = writer_kind(path, nchannels, type);
	w->height = height;
	if (w->kind == WRITER_MODULE && !module(err, errlen)) {
		free(w);
		return load_status;
	}
	/* Through a temporary file (lib/util/output.c): a failure leaves an
	 * old file as it was. */
	if ((rc = rf_output_begin(&w->out, path, err, errlen)) < 0) {
		free(w);
		return rc;
	}
	file = rf_output_file(w->out);
	switch (w->kind) {
	case WRITER_PNG:
		rc = rf__png_writer_open(&w->u.png, file, width, height, nchannels, type,
		                         err, errlen);
		break;
	case WRITER_EXR:
		rc = rf__exr_writer_open(&w->u.exr, file, width, height, nchannels, names,
		                         type, err, errlen);
		break;
	default:
		rc = api->writer_open(&w->u.module, file, width, height, nchannels, names, type,
		                      err, errlen);
	}
	if (rc < 0) {
		name_path(w, err, errlen);
		discard(w);
		return rc;
	}
	*wp = w;
	return 0;
}

int
rf_image_writer_write_rows(rf_image_writer *w, size_t y, size_t nrows,
                           const float *pixels)
{
	char *err = w->error;
	size_t errlen = sizeof(w->error);
	int rc;

	if (y != w->next_row || nrows > w->height - y) {
		rf__format(err, errlen, "cannot write '%s': rows out of order", w->path);
		return RF_EINVAL;
	}
	switch (w->kind) {
	case WRITER_PNG:
		rc = rf__png_writer_write_rows(w->u.png, nrows, pixels, err, errlen);
		break;
	case WRITER_EXR:
		rc = rf__exr_writer_write_rows(w->u.exr, nrows, pixels, err, errlen);
		break;
	default:
		rc = api->writer_write_rows(w->u.module, y, nrows, pixels, err, errlen);
	}
	if (rc == 0)
		w->next_row += nrows;
	else
		name_path(w, err, errlen);
	return rc;
}

const char *
rf_image_writer_error(const rf_image_writer *w)
{
	return w->error;
}

int
rf_image_writer_close(rf_image_writer *w, char *err, size_t errlen)
{
	int rc;

	if (!w)
		return 0;
	switch (w->kind) {
	case WRITER_PNG:
		rc = rf__png_writer_close(w->u.png, err, errlen);
		break;
	case WRITER_EXR:
		rc = rf__exr_writer_close(w->u.exr, err, errlen);
		break;
	default:
		rc = api->writer_close(w->u.module, err, errlen);
	}
	/* err holds a message only after a failure: the caller's buffer
	 * is not read otherwise. */
	if (rc < 0)
		name_path(w, err, errlen);
	/* The module says so itself; an incomplete image is the first error. */
	if (w->next_row != w->height && w->kind != WRITER_MODULE) {
		rf__format(err, errlen, "cannot write '%s': image is incomplete", w->path);
		rc = RF_EINVAL;
	}
	if (rc < 0) {
		discard(w);
		return rc;
	}
	rc = rf_output_commit(w->out, err, errlen);
	free(w);
	return rc;
}

int
rf_image_write_levels(const char *path, size_t nlevels, const size_t *w, const size_t *h,
                      size_t nchannels, const char *const *names,
                      const float *const *pixels, const char *const *attributes,
                      enum rf_pixel_type type, char *err, size_t errlen)
{
	rf_image_writer *t;
	int rc;

	if (!module(err, errlen))
		return load_status;
	/* Through a temporary file, as every writer: a failure leaves the
	 * old file as it was. */
	if (!(t = calloc(1, sizeof(*t) + strlen(path) + 1))) {
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		return RF_ENOMEM;
	}
	strcpy(t->path, path);
	t->kind = WRITER_MODULE;
	if ((rc = rf_output_begin(&t->out, path, err, errlen)) < 0) {
		free(t);
		return rc;
	}
	rc = api->write_levels(rf_output_file(t->out), nlevels, w, h, nchannels, names,
	                       pixels, attributes, type, err, errlen);
	if (rc < 0) {
		name_path(t, err, errlen);
		discard(t);
		return rc;
	}
	rc = rf_output_commit(t->out, err, errlen);
	free(t);
	return rc;
}
