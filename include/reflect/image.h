/*
 * libreflect: image files and their display encoding.  Included by
 * reflect/reflect.h; a program may include either.
 */
#ifndef REFLECT_IMAGE_H
#define REFLECT_IMAGE_H

#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * Images through OpenImageIO (EXR, HDR, PNG, JPEG, TIFF and the rest),
 * but for writing PNG (8 and 16 bits, 1 to 4 channels) and scanline
 * OpenEXR (half and float), which libreflect does itself, without loading
 * OpenImageIO.  Reading loads the whole first subimage as floats, rows
 * top first; 8- and 16-bit sRGB files are returned as stored (0..1), not
 * linearised.
 */
typedef struct rf_image rf_image;

/* Image I/O lives in a module loaded on first use; 0 when it loads, else
 * RF_EIMAGE and err saying why (the other functions report it too).
 * Writing PNG and OpenEXR does not need it. */
RF_EXTERN int rf_image_module_check(char *err, size_t errlen);

RF_EXTERN int rf_image_read(rf_image **img, const char *path, char *err,
                            size_t errlen);
RF_EXTERN void rf_image_destroy(rf_image *img);
RF_EXTERN size_t rf_image_width(const rf_image *img);
RF_EXTERN size_t rf_image_height(const rf_image *img);
RF_EXTERN size_t rf_image_nchannels(const rf_image *img);
RF_EXTERN const char *rf_image_channel(const rf_image *img, size_t i);
RF_EXTERN const float *rf_image_pixels(const rf_image *img);
/* A string attribute of the file (e.g. "envmap", "oiio:ColorSpace"), or
 * NULL. */
RF_EXTERN const char *rf_image_attribute(const rf_image *img, const char *name);

/* Writing in blocks of rows, so a frame never has to be held whole. */
typedef struct rf_image_writer rf_image_writer;

enum rf_pixel_type {
	RF_PIXEL_FLOAT = 0,
	RF_PIXEL_HALF = 1,
	RF_PIXEL_UINT8 = 2,
	RF_PIXEL_UINT16 = 3
};

RF_EXTERN int rf_image_writer_open(rf_image_writer **w, const char *path,
                                   size_t width, size_t height, size_t nchannels,
                                   const char *const *names, enum rf_pixel_type type,
                                   char *err, size_t errlen);
/* Rows y .. y+nrows-1 as floats, channels interleaved; rows in order.
 * A failure's message is rf_image_writer_error's. */
RF_EXTERN int rf_image_writer_write_rows(rf_image_writer *w, size_t y, size_t nrows,
                                         const float *pixels);
RF_EXTERN const char *rf_image_writer_error(const rf_image_writer *w);
/* Closes the file; returns its last error. */
RF_EXTERN int rf_image_writer_close(rf_image_writer *w, char *err, size_t errlen);
/* The pixel type a file name's extension stores best (8-bit for PNG and
 * JPEG, float for EXR and HDR), or -1 for an extension no plugin writes.
 * PNG and EXR are answered without loading the module. */
RF_EXTERN int rf_image_type_for_path(const char *path);

/* A MIP-mapped image (OpenEXR, tiled): levels 0..nlevels-1 of sizes
 * w[k] x h[k], all with the same channels; string attributes as
 * NULL-terminated key, value pairs. */
RF_EXTERN int rf_image_write_levels(const char *path, size_t nlevels, const size_t *w,
                                    const size_t *h, size_t nchannels,
                                    const char *const *names,
                                    const float *const *pixels,
                                    const char *const *attributes,
                                    enum rf_pixel_type type, char *err, size_t errlen);
/* The number of MIP levels of a file's first image (1 when it has none). */
RF_EXTERN int rf_image_count_levels(const char *path, size_t *nlevels, char *err,
                                    size_t errlen);
/* Reads one MIP level of a file's first image. */
RF_EXTERN int rf_image_read_level(rf_image **img, const char *path, size_t level,
                                  char *err, size_t errlen);

/* Draws text (letters, digits, " .,:=-+_/()'?") in white on a darkened
 * box, its corner 4 s pixels from (x0, y0), s pixels a font pixel (0 is
 * 1), into RGB float pixels of a width x height picture; what falls
 * outside it is left out.  A 5x9 bitmap font of reflect's own, so that
 * pictures are the same on every machine. */
RF_EXTERN void rf_image_label(float *px, size_t width, size_t height, size_t x0, size_t y0,
                              const char *text, size_t s);

/*
 * Resolving a supersampled frame (reflect-gbuffer --supersample): a
 * width x height frame of nchannels becomes one factor times smaller on
 * each axis, each pixel the box average of its factor x factor samples or
 * a Gaussian of standard deviation sigma output pixels (taps within 3
 * sigma, weights normalised over the frame) around its centre.  Channels
 * marked in nearest (NULL: none) take the sample at the pixel's centre
 * (for an even factor, the one just below and right of it) instead, for
 * identifiers such as objid.  Rows go in top first, in blocks of any
 * size; each push writes the output rows it completes.
 */
typedef struct rf_downsampler rf_downsampler;

enum rf_resolve_filter {
	RF_RESOLVE_BOX = 0,
	RF_RESOLVE_GAUSSIAN = 1
};

#define RF_RESOLVE_SIGMA_DEFAULT 0.4
#define RF_RESOLVE_SIGMA_MIN 0.1
#define RF_RESOLVE_SIGMA_MAX 4.0

/* RF_EINVAL unless width and height are multiples of factor >= 1 and
 * sigma (for the Gaussian) lies in [RF_RESOLVE_SIGMA_MIN, _MAX]. */
RF_EXTERN int rf_downsampler_create(rf_downsampler **d, size_t width, size_t height,
                                    size_t nchannels, size_t factor,
                                    enum rf_resolve_filter filter, double sigma,
                                    const unsigned char *nearest);
RF_EXTERN void rf_downsampler_destroy(rf_downsampler *d);
RF_EXTERN size_t rf_downsampler_width(const rf_downsampler *d);
RF_EXTERN size_t rf_downsampler_height(const rf_downsampler *d);
/* At most how many output rows a push of nrows input rows completes. */
RF_EXTERN size_t rf_downsampler_max_rows(const rf_downsampler *d, size_t nrows);
/* Takes nrows input rows; writes *nout finished output rows to out.
 * RF_EINVAL past the frame's last row. */
RF_EXTERN int rf_downsampler_push(rf_downsampler *d, const float *rows, size_t nrows,
                                  float *out, size_t *nout);

/* Display encoding: exposure scale, an optional tone curve, sRGB. */
enum rf_tone {
	RF_TONE_NONE = 0,  /* clamp to [0, 1] only */
	RF_TONE_FILMIC = 1 /* a fitted ACES-like filmic curve */
};

/* Encodes the first ncolour of every pixel's nchannels in place; other
 * channels (alpha) are only clamped.  NaN becomes 0. */
RF_EXTERN void rf_display_encode(float *values, size_t npix, size_t nchannels,
                                 size_t ncolour, float scale, enum rf_tone tone,
                                 int srgb);

/* How stream values become the values a file of some pixel type holds
 * (reflect-export(1)). */
struct rf_file_encoding {
	float scale;       /* exposure: 2^stops */
	enum rf_tone tone;
	int srgb;
	int integer;       /* 8 or 16 bits: straight colour, clamped to [0, 1] */
	int nonneg;        /* the format holds no negative values (RGBE) */
};
/* Encodes npix pixels of nch channels in place; alpha[c] marks the alpha
 * channels.  Integer files get straight colour (divided by A where
 * there are 4 channels and A > 0), every channel clamped and colour
 * display-encoded; float files get colour scaled, and display-encoded
 * only with a tone curve or sRGB, so that HDR values survive. */
RF_EXTERN void rf_file_encode(float *px, size_t npix, size_t nch,
                              const unsigned char *alpha,
                              const struct rf_file_encoding *e);

/*
 * A labelled grid of pictures (reflect-montage(1)), display-encoded RGB
 * floats in *out (free it), cells left to right and top to bottom in
 * slots the size of the largest, `columns` a row (0: one row).
 */
enum rf_montage_map {
	RF_MONTAGE_COLOUR = 0, /* R G B, display-encoded with the options */
	RF_MONTAGE_GREY = 1,   /* one channel, display-encoded as grey */
	RF_MONTAGE_FALSE = 2,  /* one channel in false colour over lo..hi, a bar */
	RF_MONTAGE_VECTOR = 3  /* three components, (v - lo)/(hi - lo) each */
};

struct rf_montage_cell {
	const char *label;
	const float *pixels;  /* width x height x nchannels */
	size_t width, height, nchannels;
	enum rf_montage_map map;
	int has_range;        /* lo, hi given; else: the finite range (false
	                         colour), -1..1 (vectors) */
	float lo, hi;
};

struct rf_montage_options {
	size_t columns;
	float scale;          /* exposure of colour cells: 2^stops */
	enum rf_tone tone;
	int srgb;
	size_t label_scale;   /* 0: the cells' height / 90 */
};

RF_EXTERN int rf_montage(const struct rf_montage_cell *cells, size_t n,
                         const struct rf_montage_options *o, float **out,
                         size_t *width, size_t *height);

#ifdef __cplusplus
}
#endif

#endif
