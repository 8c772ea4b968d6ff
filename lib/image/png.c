/*
 * PNG files through libpng, written row by row as they arrive.  PNG is
 * what the last stage of a pipeline writes most: going through
 * OpenImageIO cost 120 MB and a quarter of a second of loading, and its
 * zlib settings made the export several times slower than moving the same
 * bytes through a pipe.
 */
#include <errno.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/image-internal.h"
#include "image/writers.h"
#include "util/util.h"

/*
 * zlib settings, chosen by measuring the spec channels of bench/pipeline's
 * 1920x1080 render, levels 1 to 6 with each filter: level 2 with the Up
 * filter encoded it in 0.05 s of CPU for 1.18 MB, where OpenImageIO's
 * level 6 with adaptive filters took 0.18 s for 0.96 MB.  Levels 1 to 3
 * cost about the same; Up made the smallest files of the cheap filters.
 */
#define PNG_ZLIB_LEVEL 2
#define PNG_ROW_FILTER PNG_FILTER_UP
/* libpng's IDAT chunks are as large as its output buffer: fewer, larger
 * writes. */
#define PNG_ZBUF_BYTES (64 * 1024)

struct rf__png_writer {
	png_structp png;
	png_infop info;
	FILE *fp;
	size_t width, nchannels;
	int sixteen;          /* 16 bits a sample, else 8 */
	unsigned char *row;   /* one row, as stored */
	int failed;           /* the first error's status, returned again after */
	int io_errno;         /* errno of the first failed write */
	char reason[256];     /* libpng's message, when it is libpng's error */
	char path[];
};

/* libpng reports through these two; its errors do not return (they jump
 * back to the setjmp of the call that failed), and a library prints
 * nothing, warnings included. */
static void
on_error(png_structp png, png_const_charp msg)
{
	struct rf__png_writer *w = png_get_error_ptr(png);

	if (!w->reason[0])
		rf__format(w->reason, sizeof(w->reason), "%s", msg);
	png_longjmp(png, 1);
}

/* rf__png_encode's: no writer to hold a reason; the status says it. */
static void
on_memory_error(png_structp png, png_const_charp msg)
{
	(void)msg;
	png_longjmp(png, 1);
}

static void
on_warning(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

/* Every write is checked, so that a full disk is an error and not a
 * short file. */
static void
write_data(png_structp png, png_bytep data, size_t len)
{
	struct rf__png_writer *w = png_get_io_ptr(png);

	errno = 0;
	if (fwrite(data, 1, len, w->fp) != len) {
		w->io_errno = errno ? errno : EIO;
		png_error(png, strerror(w->io_errno));
	}
}

static void
flush_data(png_structp png)
{
	struct rf__png_writer *w = png_get_io_ptr(png);

	errno = 0;
	if (fflush(w->fp) != 0) {
		w->io_errno = errno ? errno : EIO;
		png_error(png, strerror(w->io_errno));
	}
}

/* The error as a message; the system's reason when a write failed. */
static int
report(struct rf__png_writer *w, char *err, size_t errlen)
{
	if (!w->failed)
		w->failed = w->io_errno ? RF_EIO : RF_EIMAGE;
	rf__format(err, errlen, "cannot write '%s': %s", w->path,
	           w->io_errno ? strerror(w->io_errno)
	                       : w->reason[0] ? w->reason : "libpng failed");
	return w->failed;
}

static void
destroy(struct rf__png_writer *w)
{
	if (w->png)
		png_destroy_write_struct(&w->png, &w->info);
	if (w->fp)
		fclose(w->fp);
	free(w->row);
	free(w);
}

/* The header: size, colour type, the sRGB chunk (with the gAMA and cHRM
 * chunks that stand for it in readers that know no sRGB) and the zlib
 * settings.  0, or -1 after an error. */
static int
write_header(struct rf__png_writer *w, size_t height)
{
	static const int colour[] = { PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
	                              PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA };

	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	png_set_write_fn(w->png, w, write_data, flush_data);
	/* libpng refuses images wider or taller than a million pixels unless
	 * told otherwise; the format allows 2^31 - 1. */
	png_set_user_limits(w->png, 0x7fffffff, 0x7fffffff);
	png_set_IHDR(w->png, w->info, (png_uint_32)w->width, (png_uint_32)height,
	             w->sixteen ? 16 : 8, colour[w->nchannels - 1], PNG_INTERLACE_NONE,
	             PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	/* What OpenImageIO wrote: the values are sRGB-encoded (even with
	 * --srgb=off, a documented bug of reflect-export), absolute
	 * colorimetric intent. */
	png_set_sRGB_gAMA_and_cHRM(w->png, w->info, PNG_sRGB_INTENT_ABSOLUTE);
	png_set_compression_level(w->png, PNG_ZLIB_LEVEL);
	png_set_filter(w->png, PNG_FILTER_TYPE_BASE, PNG_ROW_FILTER);
	png_set_compression_buffer_size(w->png, PNG_ZBUF_BYTES);
	png_write_info(w->png, w->info);
	return 0;
}

int
rf__png_writer_open(struct rf__png_writer **wp, const char *path, size_t width,
                    size_t height, size_t nchannels, enum rf_pixel_type type,
                    char *err, size_t errlen)
{
	struct rf__png_writer *w;
	size_t rowbytes, len = strlen(path);
	int rc;

	*wp = NULL;
	if (!width || !height || width > 0x7fffffff || height > 0x7fffffff ||
	    nchannels < 1 || nchannels > 4 ||
	    (type != RF_PIXEL_UINT8 && type != RF_PIXEL_UINT16) ||
	    rf__mul3(width, nchannels, type == RF_PIXEL_UINT16 ? 2 : 1, &rowbytes) < 0) {
		rf__format(err, errlen, "cannot write '%s': bad image size", path);
		return RF_EINVAL;
	}
	if (!(w = calloc(1, sizeof(*w) + len + 1)) || !(w->row = malloc(rowbytes))) {
		free(w);
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		return RF_ENOMEM;
	}
	memcpy(w->path, path, len + 1);
	w->width = width;
	w->nchannels = nchannels;
	w->sixteen = type == RF_PIXEL_UINT16;
	if (!(w->fp = fopen(path, "wb"))) {
		rf__format(err, errlen, "cannot write '%s': %s", path, strerror(errno));
		destroy(w);
		return RF_EIO;
	}
	if (!(w->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, w, on_error,
	                                       on_warning)) ||
	    !(w->info = png_create_info_struct(w->png))) {
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		destroy(w);
		return RF_ENOMEM;
	}
	if (write_header(w, height) < 0) {
		rc = report(w, err, errlen);
		destroy(w);
		return rc;
	}
	*wp = w;
	return 0;
}

/* round(clamp(v, 0, 1) * max), halves rounded up, NaN as 0: the
 * quantisation reflect-export(1) documents, as OpenImageIO did it. */
static unsigned
quantise(float v, float max)
{
	float s;
	unsigned i;

	if (!(v > 0.0f))
		return 0;
	if (v >= 1.0f)
		return (unsigned)max;
	s = v * max;
	i = (unsigned)s;
	return i + (s - (float)i >= 0.5f); /* s - i is exact */
}

/* Outside write_rows so that no variable of its loop lives across the
 * setjmp there. */
static void
put_rows(struct rf__png_writer *w, size_t nrows, const float *pixels)
{
	size_t n = w->width * w->nchannels, y, i;
	unsigned char *row = w->row;

	for (y = 0; y < nrows; y++, pixels += n) {
		if (w->sixteen)
			for (i = 0; i < n; i++) {
				unsigned q = quantise(pixels[i], 65535.0f);

				row[2 * i] = (unsigned char)(q >> 8); /* big-endian */
				row[2 * i + 1] = (unsigned char)q;
			}
		else
			for (i = 0; i < n; i++)
				row[i] = (unsigned char)quantise(pixels[i], 255.0f);
		png_write_row(w->png, row);
	}
}

int
rf__png_writer_write_rows(struct rf__png_writer *w, size_t nrows, const float *pixels,
                          char *err, size_t errlen)
{
	if (w->failed)
		return report(w, err, errlen);
	if (setjmp(png_jmpbuf(w->png)))
		return report(w, err, errlen);
	put_rows(w, nrows, pixels);
	return 0;
}

static int
write_end(struct rf__png_writer *w)
{
	if (setjmp(png_jmpbuf(w->png)))
		return -1;
	png_write_end(w->png, NULL);
	return 0;
}

int
rf__png_writer_close(struct rf__png_writer *w, char *err, size_t errlen)
{
	int rc = 0;

	if (!w)
		return 0;
	if (w->failed || write_end(w) < 0)
		rc = report(w, err, errlen);
	png_destroy_write_struct(&w->png, &w->info);
	/* The last bytes are written here: a full disk may show only now. */
	errno = 0;
	if ((fflush(w->fp) != 0 || ferror(w->fp)) && !rc) {
		w->io_errno = errno ? errno : EIO;
		rc = report(w, err, errlen);
	}
	if (fclose(w->fp) != 0 && !rc) {
		w->io_errno = errno ? errno : EIO;
		rc = report(w, err, errlen);
	}
	w->fp = NULL;
	destroy(w);
	return rc;
}

/* The encoded bytes of a PNG made in memory, grown as libpng writes. */
struct png_memory {
	unsigned char *data;
	size_t len, cap;
	int nomem;
};

static void
write_memory(png_structp png, png_bytep data, size_t len)
{
	struct png_memory *m = png_get_io_ptr(png);

	if (len > m->cap - m->len) {
		size_t cap = m->cap ? m->cap : 4096;
		unsigned char *p;

		while (len > cap - m->len && cap < (size_t)-1 / 2)
			cap *= 2;
		if (len > cap - m->len || !(p = realloc(m->data, cap))) {
			m->nomem = 1;
			png_error(png, "out of memory");
		}
		m->data = p;
		m->cap = cap;
	}
	memcpy(m->data + m->len, data, len);
	m->len += len;
}

static void
flush_memory(png_structp png)
{
	(void)png;
}

/* Outside rf__png_encode so that no variable of its loop lives across
 * the setjmp there. */
static void
encode_rows(png_structp png, png_infop info, const float *pixels, size_t width, size_t height,
            size_t nchannels, unsigned char *row)
{
	static const int colour[] = { PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA,
	                              PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA };
	const size_t n = width * nchannels;
	size_t y, i;

	png_set_user_limits(png, 0x7fffffff, 0x7fffffff);
	png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8,
	             colour[nchannels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
	             PNG_FILTER_TYPE_DEFAULT);
	png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
	png_set_compression_level(png, PNG_ZLIB_LEVEL);
	png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ROW_FILTER);
	png_set_compression_buffer_size(png, PNG_ZBUF_BYTES);
	png_write_info(png, info);
	for (y = 0; y < height; y++, pixels += n) {
		for (i = 0; i < n; i++)
			row[i] = (unsigned char)quantise(pixels[i], 255.0f);
		png_write_row(png, row);
	}
	png_write_end(png, NULL);
}

/* The setjmp's own frame, so that nothing it returns through lives
 * across it in a register. */
static int
encode_guarded(png_structp png, png_infop info, struct png_memory *m, const float *pixels,
               size_t width, size_t height, size_t nchannels, unsigned char *row)
{
	if (setjmp(png_jmpbuf(png)))
		return m->nomem ? RF_ENOMEM : RF_EIMAGE;
	png_set_write_fn(png, m, write_memory, flush_memory);
	encode_rows(png, info, pixels, width, height, nchannels, row);
	return 0;
}

int
rf__png_encode(unsigned char **data, size_t *len, const float *pixels, size_t width,
               size_t height, size_t nchannels)
{
	struct png_memory m = { NULL, 0, 0, 0 };
	png_structp png = NULL;
	png_infop info = NULL;
	unsigned char *row;
	int rc;

	*data = NULL;
	*len = 0;
	if (!width || !height || width > 0x7fffffff || height > 0x7fffffff || nchannels < 1 ||
	    nchannels > 4 || width > (size_t)-1 / nchannels)
		return RF_EINVAL;
	if (!(row = malloc(width * nchannels)))
		return RF_ENOMEM;
	if (!(png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, on_memory_error,
	                                    on_warning)) ||
	    !(info = png_create_info_struct(png)))
		rc = RF_ENOMEM;
	else
		rc = encode_guarded(png, info, &m, pixels, width, height, nchannels, row);
	if (png)
		png_destroy_write_struct(&png, info ? &info : NULL);
	free(row);
	if (rc < 0) {
		free(m.data);
		return rc;
	}
	*data = m.data;
	*len = m.len;
	return 0;
}
