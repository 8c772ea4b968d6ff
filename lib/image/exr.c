/*
 * Scanline OpenEXR files through OpenEXR's C core, a block of rows at a
 * time as they arrive.  The C core is a small C library (zlib its only
 * dependency), where OpenImageIO loads some 250 libraries; and writing it
 * here holds one chunk of rows (16 with ZIP), never the image.
 *
 * The file is what OpenImageIO wrote: one scanline part, ZIP compression,
 * increasing lines, the channels named, half or float; minus its capDate
 * attribute (the time of writing), so that the same input makes the same
 * file.
 */
#include <errno.h>
#include <fcntl.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/writers.h"
#include "util/util.h"

/* zlib's level for the ZIP chunks: OpenEXR's C++ library's (and so
 * OpenImageIO's) default, which makes files of the same size.  The C
 * core's own default, 6, took twice the time on bench/pipeline's
 * 1920x1080 render in half (0.40 s of CPU against 0.22 s) for files 4%
 * smaller; level 1 took 0.16 s for files 8% larger. */
#define EXR_ZIP_LEVEL 4

struct rf__exr_writer {
	exr_context_t ctx;
	exr_encode_pipeline_t enc; /* points into itself: never copied */
	int enc_ready;
	int fd;
	size_t width, height, nchannels;
	int *source;          /* the input channel of each channel in file order */
	size_t chunk_rows;    /* rows in a chunk (16 with ZIP) */
	size_t y;             /* the first row of the chunk being filled */
	size_t filled;        /* rows of it received */
	float *buf;           /* chunk_rows rows, channels interleaved */
	int failed;           /* the first error's status, returned again after */
	int io_errno;         /* errno of the first failed write */
	char reason[256];     /* the first message of the library */
	char path[];
};

/* The writer whose call into the library is under way, for the error
 * handler: the handler cannot ask the context for its user data, as the
 * library holds the context's lock while it reports (that deadlocks). */
static _Thread_local struct rf__exr_writer *calling;

/* The library's messages: the first one kept, nothing printed (its
 * default handler prints to stderr). */
static void
on_error(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
	struct rf__exr_writer *w = calling;

	(void)ctx;
	if (w && !w->reason[0])
		rf__format(w->reason, sizeof(w->reason), "%s",
		           msg && *msg ? msg : exr_get_default_error_message(code));
}

/* pwrite(2), checked: the library writes the chunk offset table last, at
 * the start of the file, so the file must be seekable (a pipe is not). */
static int64_t
write_fn(exr_const_context_t ctx, void *user, const void *buffer, uint64_t size,
         uint64_t offset, exr_stream_error_func_ptr_t error_cb)
{
	struct rf__exr_writer *w = user;
	const char *p = buffer;
	uint64_t done = 0;
	ssize_t n;

	while (done < size) {
		n = pwrite(w->fd, p + done, (size_t)(size - done), (off_t)(offset + done));
		if (n < 0 && errno == EINTR)
			continue;
		if (n <= 0) {
			if (!w->io_errno)
				w->io_errno = n < 0 ? errno : EIO;
			error_cb(ctx, EXR_ERR_WRITE_IO, "%s", strerror(w->io_errno));
			return -1;
		}
		done += (uint64_t)n;
	}
	return (int64_t)size;
}

/* The error as a message: the system's reason when a write failed, else
 * the library's. */
static int
report(struct rf__exr_writer *w, exr_result_t rv, char *err, size_t errlen)
{
	if (!w->failed)
		w->failed = w->io_errno ? RF_EIO : rv == EXR_ERR_OUT_OF_MEMORY ? RF_ENOMEM
		                                                               : RF_EIMAGE;
	rf__format(err, errlen, "cannot write '%s': %s", w->path,
	           w->io_errno ? strerror(w->io_errno)
	           : w->reason[0] ? w->reason : exr_get_default_error_message(rv));
	return w->failed;
}

static void
destroy(struct rf__exr_writer *w)
{
	if (w->enc_ready)
		exr_encoding_destroy(w->ctx, &w->enc);
	if (w->ctx)
		exr_finish(&w->ctx);
	if (w->fd >= 0)
		close(w->fd);
	free(w->source);
	free(w->buf);
	free(w);
}

/* OpenImageIO's names for channels that have none. */
static void
default_name(char *buf, size_t size, size_t nchannels, size_t c)
{
	static const char *const rgba[] = { "R", "G", "B", "A" };

	if (nchannels == 1)
		rf__format(buf, size, "Y");
	else if (c < 4)
		rf__format(buf, size, "%s", rgba[c]);
	else
		rf__format(buf, size, "channel%zu", c);
}

/* The part, its channels and the header, written.  The library keeps the
 * channels sorted by name; source maps them back. */
static exr_result_t
write_header(struct rf__exr_writer *w, const char *const *names, exr_pixel_type_t ptype)
{
	const exr_attr_chlist_t *list;
	char name[32];
	exr_result_t rv;
	int part, k;
	size_t c;

	if ((rv = exr_add_part(w->ctx, NULL, EXR_STORAGE_SCANLINE, &part)) ||
	    (rv = exr_initialize_required_attr_simple(w->ctx, part, (int32_t)w->width,
	                                              (int32_t)w->height,
	                                              EXR_COMPRESSION_ZIP)))
		return rv;
	/* Said here: the library says only "Invalid argument to function". */
	for (c = 0; names && c < w->nchannels; c++) {
		size_t j;

		if (!names[c] || !names[c][0]) {
			rf__format(w->reason, sizeof(w->reason), "channel %zu has no name", c);
			return EXR_ERR_INVALID_ARGUMENT;
		}
		for (j = 0; j < c; j++)
			if (!strcmp(names[j], names[c])) {
				rf__format(w->reason, sizeof(w->reason),
				           "channel '%.64s' is given twice", names[c]);
				return EXR_ERR_INVALID_ARGUMENT;
			}
	}
	for (c = 0; c < w->nchannels; c++) {
		default_name(name, sizeof(name), w->nchannels, c);
		/* Perceptually logarithmic, as OpenImageIO marks them (it
		 * matters only to the lossy B44 compression). */
		if ((rv = exr_add_channel(w->ctx, part, names ? names[c] : name, ptype,
		                          EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1)))
			return rv;
	}
	if ((rv = exr_set_zip_compression_level(w->ctx, part, EXR_ZIP_LEVEL)) ||
	    (rv = exr_get_channels(w->ctx, part, &list)))
		return rv;
	for (k = 0; k < list->num_channels; k++) {
		for (c = 0; c < w->nchannels; c++) {
			default_name(name, sizeof(name), w->nchannels, c);
			if (!strcmp(list->entries[k].name.str, names ? names[c] : name))
				break;
		}
		if (c == w->nchannels) {
			rf__format(w->reason, sizeof(w->reason), "channel '%s' was renamed",
			           list->entries[k].name.str);
			return EXR_ERR_INVALID_ARGUMENT;
		}
		w->source[k] = (int)c;
	}
	return exr_write_header(w->ctx);
}

static int
writer_open(struct rf__exr_writer **wp, const char *path, size_t width, size_t height,
            size_t nchannels, const char *const *names, enum rf_pixel_type type,
            char *err, size_t errlen)
{
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	struct rf__exr_writer *w;
	size_t len = strlen(path), nbuf;
	exr_result_t rv;
	int32_t rows;
	int rc;

	*wp = NULL;
	if (!width || !height || width > INT32_MAX || height > INT32_MAX || !nchannels ||
	    nchannels > 1024 || (type != RF_PIXEL_HALF && type != RF_PIXEL_FLOAT) ||
	    /* The library takes a row's length in bytes as an int32_t. */
	    width * nchannels * sizeof(float) > INT32_MAX) {
		rf__format(err, errlen, "cannot write '%s': bad image size", path);
		return RF_EINVAL;
	}
	if (!(w = calloc(1, sizeof(*w) + len + 1)) ||
	    !(w->source = calloc(nchannels, sizeof(*w->source)))) {
		free(w);
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		return RF_ENOMEM;
	}
	memcpy(w->path, path, len + 1);
	w->fd = -1;
	w->width = width;
	w->height = height;
	w->nchannels = nchannels;
	/* Opened here, not by the library, for the system's reason when it
	 * cannot be. */
	if ((w->fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)) < 0) {
		rf__format(err, errlen, "cannot write '%s': %s", path, strerror(errno));
		destroy(w);
		return RF_EIO;
	}
	init.error_handler_fn = on_error;
	init.user_data = w;
	init.write_fn = write_fn;
	if ((rv = exr_start_write(&w->ctx, path, EXR_WRITE_FILE_DIRECTLY, &init)) ||
	    (rv = write_header(w, names, type == RF_PIXEL_HALF ? EXR_PIXEL_HALF
	                                                       : EXR_PIXEL_FLOAT)) ||
	    (rv = exr_get_scanlines_per_chunk(w->ctx, 0, &rows))) {
		rc = report(w, rv, err, errlen);
		destroy(w);
		return rc;
	}
	w->chunk_rows = (size_t)rows;
	if (rf__mul3(w->chunk_rows, width, nchannels, &nbuf) < 0 ||
	    !(w->buf = malloc(nbuf * sizeof(float)))) {
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		destroy(w);
		return RF_ENOMEM;
	}
	*wp = w;
	return 0;
}

/* Encodes and writes the chunk that starts at row w->y, from rows of
 * floats with the channels interleaved: the library converts to half. */
static exr_result_t
write_chunk(struct rf__exr_writer *w, const float *rows)
{
	exr_chunk_info_t info;
	exr_result_t rv;
	int k;

	if ((rv = exr_write_scanline_chunk_info(w->ctx, 0, (int)w->y, &info)))
		return rv;
	if (w->enc_ready)
		rv = exr_encoding_update(w->ctx, 0, &info, &w->enc);
	else if (!(rv = exr_encoding_initialize(w->ctx, 0, &info, &w->enc)))
		w->enc_ready = 1;
	if (rv)
		return rv;
	for (k = 0; k < w->enc.channel_count; k++) {
		exr_coding_channel_info_t *ch = &w->enc.channels[k];

		ch->encode_from_ptr = (const uint8_t *)(rows + w->source[k]);
		ch->user_data_type = EXR_PIXEL_FLOAT;
		ch->user_bytes_per_element = (int16_t)sizeof(float);
		ch->user_pixel_stride = (int32_t)(w->nchannels * sizeof(float));
		ch->user_line_stride = (int32_t)(w->width * w->nchannels * sizeof(float));
	}
	if (!w->enc.convert_and_pack_fn &&
	    (rv = exr_encoding_choose_default_routines(w->ctx, 0, &w->enc)))
		return rv;
	return exr_encoding_run(w->ctx, 0, &w->enc);
}

static int
write_rows(struct rf__exr_writer *w, size_t nrows, const float *pixels, char *err,
           size_t errlen)
{
	size_t rowlen = w->width * w->nchannels, want, n;
	exr_result_t rv;

	if (w->failed)
		return report(w, EXR_ERR_UNKNOWN, err, errlen);
	while (nrows > 0) {
		/* The rows of the chunk being filled, the last one shorter. */
		want = w->height - w->y < w->chunk_rows ? w->height - w->y : w->chunk_rows;
		if (!w->filled && nrows >= want) {
			/* A whole chunk in the caller's rows: no copy. */
			if ((rv = write_chunk(w, pixels)))
				return report(w, rv, err, errlen);
			n = want;
			w->y += want;
		} else {
			n = want - w->filled < nrows ? want - w->filled : nrows;
			memcpy(w->buf + w->filled * rowlen, pixels, n * rowlen * sizeof(float));
			if ((w->filled += n) == want) {
				if ((rv = write_chunk(w, w->buf)))
					return report(w, rv, err, errlen);
				w->y += want;
				w->filled = 0;
			}
		}
		pixels += n * rowlen;
		nrows -= n;
	}
	return 0;
}

static int
writer_close(struct rf__exr_writer *w, char *err, size_t errlen)
{
	exr_result_t rv;
	int rc = 0;

	if (w->failed)
		rc = report(w, EXR_ERR_UNKNOWN, err, errlen);
	if (w->enc_ready) {
		exr_encoding_destroy(w->ctx, &w->enc);
		w->enc_ready = 0;
	}
	/* The chunk offset table is written here. */
	if ((rv = exr_finish(&w->ctx)) && !rc)
		rc = report(w, rv, err, errlen);
	if (close(w->fd) != 0 && !rc) {
		w->io_errno = errno;
		rc = report(w, EXR_ERR_UNKNOWN, err, errlen);
	}
	w->fd = -1;
	destroy(w);
	return rc;
}

int
rf__exr_writer_open(struct rf__exr_writer **wp, const char *path, size_t width,
                    size_t height, size_t nchannels, const char *const *names,
                    enum rf_pixel_type type, char *err, size_t errlen)
{
	int rc = writer_open(wp, path, width, height, nchannels, names, type, err, errlen);

	calling = NULL;
	return rc;
}

int
rf__exr_writer_write_rows(struct rf__exr_writer *w, size_t nrows, const float *pixels,
                          char *err, size_t errlen)
{
	int rc;

	calling = w;
	rc = write_rows(w, nrows, pixels, err, errlen);
	calling = NULL;
	return rc;
}

int
rf__exr_writer_close(struct rf__exr_writer *w, char *err, size_t errlen)
{
	int rc;

	if (!w)
		return 0;
	calling = w;
	rc = writer_close(w, err, errlen);
	calling = NULL;
	return rc;
}
