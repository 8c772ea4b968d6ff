/* Internal: the image module's table, shared by image.c (the caller,
 * in libreflect) and oiio.cpp (the module, which alone links
 * OpenImageIO). */
#ifndef REFLECT_IMAGE_MODULE_H
#define REFLECT_IMAGE_MODULE_H

#include "reflect/reflect.h"

/* The module's writer; image.c wraps it in an rf_image_writer, whose
 * other kinds are libreflect's own (writers.h). */
struct rf__module_writer;

#define RF_IMAGE_MODULE_NAME "reflect-oiio.so"
#define RF_IMAGE_MODULE_ENTRY "rf__image_module"

/* libreflect's bounds (bounds.c), which read_level calls with the size
 * its header gives and the format's name, before it allocates anything:
 * 0 goes on; an error (its message in err) is returned as it is. */
typedef int rf__image_check_fn(const char *path, const char *format, size_t width,
                               size_t height, size_t nchannels, char *err, size_t errlen);

struct rf__image_api {
	size_t size; /* sizeof(struct rf__image_api) in the module */
	int (*read_level)(rf_image **img, const char *path, size_t level,
	                  rf__image_check_fn *check, char *err, size_t errlen);
	int (*count_levels)(const char *path, size_t *nlevels, char *err, size_t errlen);
	void (*free_image)(rf_image *img);
	size_t (*width)(const rf_image *img);
	size_t (*height)(const rf_image *img);
	size_t (*nchannels)(const rf_image *img);
	const char *(*channel)(const rf_image *img, size_t i);
	const float *(*pixels)(const rf_image *img);
	const char *(*attribute)(const rf_image *img, const char *name);
	int (*type_for_path)(const char *path);
	int (*writer_open)(struct rf__module_writer **w, const char *path, size_t width,
	                   size_t height, size_t nchannels, const char *const *names,
	                   enum rf_pixel_type type, char *err, size_t errlen);
	int (*writer_write_rows)(struct rf__module_writer *w, size_t y, size_t nrows,
	                         const float *pixels, char *err, size_t errlen);
	int (*writer_close)(struct rf__module_writer *w, char *err, size_t errlen);
	int (*write_levels)(const char *path, size_t nlevels, const size_t *w,
	                    const size_t *h, size_t nchannels, const char *const *names,
	                    const float *const *pixels, const char *const *attributes,
	                    enum rf_pixel_type type, char *err, size_t errlen);
};

#endif
