/*
 * Image files, through a module that libreflect loads the first time an
 * image is read or written.  OpenImageIO brings some 250 shared libraries
 * with it; linking them into every tool would cost each one a quarter of a
 * second and 130 MB before its first pixel, and most stages of a pipeline
 * never touch an image file.
 */
#include <dlfcn.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "image_module.h"
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
	*img = NULL;
	return module(err, errlen) ? api->read_level(img, path, 0, err, errlen) : RF_EIMAGE;
}

int
rf_image_read_level(rf_image **img, const char *path, size_t level, char *err,
                    size_t errlen)
{
	*img = NULL;
	return module(err, errlen) ? api->read_level(img, path, level, err, errlen)
	                           : RF_EIMAGE;
}

int
rf_image_count_levels(const char *path, size_t *nlevels, char *err, size_t errlen)
{
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

int
rf_image_type_for_path(const char *path)
{
	return module(NULL, 0) ? api->type_for_path(path) : -1;
}

int
rf_image_writer_open(rf_image_writer **w, const char *path, size_t width, size_t height,
                     size_t nchannels, const char *const *names, enum rf_pixel_type type,
                     char *err, size_t errlen)
{
	*w = NULL;
	return module(err, errlen) ? api->writer_open(w, path, width, height, nchannels,
	                                              names, type, err, errlen)
	                           : RF_EIMAGE;
}

int
rf_image_writer_write_rows(rf_image_writer *w, size_t y, size_t nrows,
                           const float *pixels, char *err, size_t errlen)
{
	return api->writer_write_rows(w, y, nrows, pixels, err, errlen);
}

int
rf_image_writer_close(rf_image_writer *w, char *err, size_t errlen)
{
	return w ? api->writer_close(w, err, errlen) : 0;
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
