/* Internal: the image writers libreflect holds itself, for the two file
 * types a pipeline writes (PNG, scanline OpenEXR), so that writing them
 * never loads the OpenImageIO module.  image.c chooses between them and
 * the module, and checks the order of the rows for all of them.
 *
 * Each writer takes rows in order (image.c has checked it) and reports
 * errors as "cannot write 'PATH': reason": RF_EIO when the system refused
 * (the reason is then strerror's), RF_EIMAGE when the library did.  After
 * an error, further writes return it again; close always frees. */
#ifndef REFLECT_IMAGE_WRITERS_H
#define REFLECT_IMAGE_WRITERS_H

#include "reflect/reflect.h"

/* PNG through libpng: 8- or 16-bit, 1 to 4 channels (grey, grey and
 * alpha, RGB, RGBA), values clamped to [0, 1] and rounded to the nearest
 * integer, tagged sRGB. */
struct rf__png_writer;

int rf__png_writer_open(struct rf__png_writer **w, const char *path, size_t width,
                        size_t height, size_t nchannels, enum rf_pixel_type type,
                        char *err, size_t errlen);
int rf__png_writer_write_rows(struct rf__png_writer *w, size_t nrows,
                              const float *pixels, char *err, size_t errlen);
int rf__png_writer_close(struct rf__png_writer *w, char *err, size_t errlen);

/* Scanline OpenEXR through OpenEXR's C core: half or float, the channels
 * named (NULL: OpenImageIO's defaults, Y or R G B A channel4 ...),
 * ZIP-compressed; at most one block of rows is held. */
struct rf__exr_writer;

int rf__exr_writer_open(struct rf__exr_writer **w, const char *path, size_t width,
                        size_t height, size_t nchannels, const char *const *names,
                        enum rf_pixel_type type, char *err, size_t errlen);
int rf__exr_writer_write_rows(struct rf__exr_writer *w, size_t nrows,
                              const float *pixels, char *err, size_t errlen);
int rf__exr_writer_close(struct rf__exr_writer *w, char *err, size_t errlen);

#endif
