/*
 * Image files, through a module that libreflect loads the first time an
 * image is read or written.  OpenImageIO brings some 250 shared libraries
 * with it; linking them into every tool would cost each one a quarter of a
 * second and 130 MB before its first pixel, and most stages of a pipeline
 * never touch an image file.
 *
 * PNG and scanline OpenEXR, the two types a pipeline writes, are written
 * by libreflect itself (image_png.c, image_exr.c) and never load the
 * module: loading it would cost the last stage of every pipeline those
 * 130 MB.  Everything else, and all reading, goes through the module.
 */
#include <ctype.h>
#include <dlfcn.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "image_module.h"
#include "image_writers.h"
#include "internal.h"

#ifndef REFLECT_MODULEDIR
#define REFLECT_MODULEDIR "/usr/local/lib/reflect"
#endif

static pthread_once_t once = PTHREAD_ONCE_INIT;
static const struct rf__image_api *api;
static char load_error[1024];

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

/* REFLECT_IMAGE_MODULE, else next to libreflect itself (an uninstalled
 * build keeps both in lib/.libs), else the installed module directory. */
static void
load(void)
{
	const char *env = getenv("REFLECT_IMAGE_MODULE");
	char path[4096];
	Dl_info info;

	if (env && *env) {
		api = try_module(env);
		return;
	}
	if (dladdr((void *)load, &info) && info.dli_fname && strrchr(info.dli_fname, '/')) {
		const char *slash = strrchr(info.dli_fname, '/');

		rf__format(path, sizeof(path), "%.*s/%s", (int)(slash - info.dli_fname),
		           info.dli_fname, RF_IMAGE_MODULE_NAME);
		if ((api = try_module(path)))
			return;
	}
	rf__format(path, sizeof(path), "%s/%s", REFLECT_MODULEDIR, RF_IMAGE_MODULE_NAME);
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
	return module(err, errlen) ? 0 : RF_EIMAGE;
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
	int rc;

	*img = NULL;
	if ((rc = rf__regular_file(path, err, errlen)) < 0)
		return rc;
	return module(err, errlen) ? api->read_level(img, path, level, err, errlen)
	                           : RF_EIMAGE;
}

int
rf_image_count_levels(const char *path, size_t *nlevels, char *err, size_t errlen)
{
	int rc;

	if ((rc = rf__regular_file(path, err, errlen)) < 0)
		return rc;
	return module(err, errlen) ? api->count_levels(path, nlevels, err, errlen)
	                           : RF_EIMAGE;
}

/* An image exists only if the module made it, so it is loaded here. */
void
rf_image_free(rf_image *img)
{
	if (img)
		api->free_image(img);
}

size_t rf_image_width(const rf_image *img) { return api->width(img); }
size_t rf_image_height(const rf_image *img) { return api->height(img); }
size_t rf_image_nchannels(const rf_image *img) { return api->nchannels(img); }
const char *rf_image_channel(const rf_image *img, size_t i) { return api->channel(img, i); }
const float *rf_image_pixels(const rf_image *img) { return api->pixels(img); }

const char *
rf_image_attribute(const rf_image *img, const char *name)
{
	return api->attribute(img, name);
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
	char path[];
};

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
	switch (w->kind) {
	case WRITER_PNG:
		rc = rf__png_writer_open(&w->u.png, path, width, height, nchannels, type,
		                         err, errlen);
		break;
	case WRITER_EXR:
		rc = rf__exr_writer_open(&w->u.exr, path, width, height, nchannels, names,
		                         type, err, errlen);
		break;
	default:
		rc = module(err, errlen) ? api->writer_open(&w->u.module, path, width, height,
		                                            nchannels, names, type, err,
		                                            errlen)
		                         : RF_EIMAGE;
	}
	if (rc < 0) {
		free(w);
		return rc;
	}
	*wp = w;
	return 0;
}

int
rf_image_writer_write_rows(rf_image_writer *w, size_t y, size_t nrows,
                           const float *pixels, char *err, size_t errlen)
{
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
	return rc;
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
	/* The module says so itself; an incomplete image is the first error. */
	if (w->next_row != w->height && w->kind != WRITER_MODULE) {
		rf__format(err, errlen, "cannot write '%s': image is incomplete", w->path);
		rc = RF_EINVAL;
	}
	free(w);
	return rc;
}

int
rf_image_write_levels(const char *path, size_t nlevels, const size_t *w, const size_t *h,
                      size_t nchannels, const char *const *names,
                      const float *const *pixels, const char *const *attributes,
                      enum rf_pixel_type type, char *err, size_t errlen)
{
	return module(err, errlen) ? api->write_levels(path, nlevels, w, h, nchannels,
	                                               names, pixels, attributes, type,
	                                               err, errlen)
	                           : RF_EIMAGE;
}
