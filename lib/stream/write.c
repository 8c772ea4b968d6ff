/* Writing the stream: header (with the data aligned to 4 bytes), rows. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stream/stream-internal.h"

struct rf_writer {
	FILE *fp;
	char *name;
	struct rf_writer_options opt;
	unsigned long long offset; /* bytes written since the stream began */
	size_t ncols, nrows, ncomp, row;
	int in_frame;
	int begun;  /* a header was written */
	int failed; /* rf_writer_fail: no more frames */
	char err[512];
};

static int
fail_io(rf_writer *w)
{
	int e = errno;

	rf__format(w->err, sizeof(w->err), "cannot write '%s': %s", w->name,
	           strerror(e ? e : EIO));
	errno = e;
	return RF_EIO;
}

int
rf_writer_open(rf_writer **wp, FILE *fp, const char *name,
               const struct rf_writer_options *opt)
{
	rf_writer *w;

	*wp = NULL;
	if (!(w = calloc(1, sizeof(*w))))
		return RF_ENOMEM;
	if (!(w->name = strdup(name ? name : "<stdout>"))) {
		free(w);
		return RF_ENOMEM;
	}
	w->fp = fp;
	if (opt)
		w->opt = *opt;
	*wp = w;
	return 0;
}

void
rf_writer_close(rf_writer *w)
{
	if (!w)
		return;
	free(w->name);
	free(w);
}

const char *
rf_writer_error(const rf_writer *w)
{
	return w->err;
}

static int
put(rf_writer *w, const char *s, size_t n)
{
	if (fwrite(s, 1, n, w->fp) != n)
		return fail_io(w);
	w->offset += n;
	return 0;
}

static int
putline(rf_writer *w, const char *s)
{
	size_t n = strlen(s);

	if (put(w, s, n) < 0 || put(w, "\n", 1) < 0)
		return RF_EIO;
	return 0;
}

static int
write_header(rf_writer *w, const rf_header *h)
{
	char line[RF_HEADER_LINE_MAX + 64];
	const char *s;
	size_t i, n;
	const unsigned one = 1;
	int big = *(const unsigned char *)&one == 0;

	if (putline(w, RF__STREAM_IDENT) < 0)
		return RF_EIO;
	for (i = 0; (s = rf_header_line(h, i)); i++)
		if (putline(w, s) < 0)
			return RF_EIO;
	snprintf(line, sizeof(line), "NCOLS=%zu\nNROWS=%zu\nNCOMP=%zu",
	           rf_header_ncols(h), rf_header_nrows(h), rf_header_nchannels(h));
	if (putline(w, line) < 0 || put(w, "CHANNELS=", 9) < 0)
		return RF_EIO;
	for (i = 0; i < rf_header_nchannels(h); i++) {
		s = rf_header_channel(h, i);
		if ((i && put(w, " ", 1) < 0) || put(w, s, strlen(s)) < 0)
			return RF_EIO;
	}
	if (put(w, "\n", 1) < 0)
		return RF_EIO;
	if (w->opt.format == RF_FORMAT_ASCII)
		return putline(w, "FORMAT=ascii\n");
	if (putline(w, big ? "BigEndian=1" : "BigEndian=0") < 0)
		return RF_EIO;
	/* Pad FORMAT so that the data starts on a 4-byte boundary, as
	 * Radiance does, so the data can be mapped and read in place. */
	n = (size_t)(4 - (w->offset + strlen("FORMAT=float\n\n")) % 4) % 4;
	memcpy(line, "FORMAT=float", 12);
	memset(line + 12, ' ', n);
	memcpy(line + 12 + n, "\n\n", 3);
	return put(w, line, 14 + n);
}

int
rf_writer_begin_frame(rf_writer *w, const rf_header *h)
{
	int rc;

	if (w->in_frame && w->row < w->nrows) {
		rf__format(w->err, sizeof(w->err),
		           "'%s': frame ended after %zu of %zu rows", w->name, w->row,
		           w->nrows);
		return RF_EINVAL;
	}
	w->ncols = rf_header_ncols(h);
	w->nrows = rf_header_nrows(h);
	w->ncomp = rf_header_nchannels(h);
	if (!w->ncols || !w->nrows || !w->ncomp) {
		rf__format(w->err, sizeof(w->err), "'%s': frame has no %s", w->name,
		           !w->ncomp ? "channels" : "pixels");
		return RF_EINVAL;
	}
	if (!w->opt.no_header) {
		/* Every header line must be one a reader takes. */
		size_t len = strlen("CHANNELS="), i;

		for (i = 0; i < w->ncomp; i++)
			len += strlen(rf_header_channel(h, i)) + (i ? 1 : 0);
		if (len > RF_HEADER_LINE_MAX) {
			rf__format(w->err, sizeof(w->err),
			           "'%s': the CHANNELS line of %zu channels would be "
			           "%zu bytes, more than the %d a header line may hold",
			           w->name, w->ncomp, len, RF_HEADER_LINE_MAX);
			return RF_ETOOBIG;
		}
	}
	if (w->failed) {
		rf__format(w->err, sizeof(w->err), "'%s': the stream was ended as failed",
		           w->name);
		return RF_EINVAL;
	}
	w->row = 0;
	w->in_frame = 1;
	if (!w->opt.no_header && (rc = write_header(w, h)) < 0)
		return rc;
	w->begun = !w->opt.no_header;
	return 0;
}

static int
write_ascii(rf_writer *w, const float *buf, size_t n)
{
	size_t i;

	for (i = 0; i < n; i++) {
		int sep = (i + 1) % w->ncomp ? '\t' : '\n';

		if (fprintf(w->fp, "%.9g%c", (double)buf[i], sep) < 0)
			return fail_io(w);
	}
	return 0;
}

int
rf_writer_write_rows(rf_writer *w, const float *buf, size_t nrows)
{
	size_t n;

	if (!w->in_frame || nrows > w->nrows - w->row) {
		rf__format(w->err, sizeof(w->err),
		           "'%s': more rows written than the frame has (%zu)", w->name,
		           w->nrows);
		return RF_EINVAL;
	}
	n = nrows * w->ncols * w->ncomp;
	if (w->opt.format == RF_FORMAT_ASCII) {
		if (write_ascii(w, buf, n) < 0)
			return RF_EIO;
	} else if (put(w, (const char *)buf, n * sizeof(float)) < 0) {
		return RF_EIO;
	}
	w->row += nrows;
	return 0;
}

int
rf_writer_end_frame(rf_writer *w)
{
	if (!w->in_frame || w->row != w->nrows) {
		rf__format(w->err, sizeof(w->err),
		           "'%s': frame ended after %zu of %zu rows", w->name, w->row,
		           w->nrows);
		return RF_EINVAL;
	}
	w->in_frame = 0;
	return 0;
}

/*
 * The trailer of a failed stream.  A tool that dies after its first
 * header went out would leave a stream that may end on a frame's last
 * row, which a reader cannot tell from a whole one.  So the frame begun
 * is filled with NaN (so that a reader reaches what follows where a
 * header may start), and a header follows whose keys say how many rows
 * of that frame the tool wrote (FAILED_ROWS, when it cut one) and why
 * it failed (FAILED): the reader refuses it with the message; a reader
 * from before it refuses it as a header without NCOLS.  Streams that succeed never hold it: their bytes are unchanged.
 */
int
rf_writer_fail(rf_writer *w, const char *message)
{
	char line[RF_HEADER_LINE_MAX + 1];
	float nan_row[1024];
	size_t i, left, n, cut, chunk = sizeof(nan_row) / sizeof(nan_row[0]);

	if (!w || !w->begun || w->failed)
		return 0;
	w->failed = 1;
	for (i = 0; i < chunk; i++)
		nan_row[i] = NAN;
	cut = w->in_frame ? w->row : (size_t)-1;
	if (w->in_frame) {
		/* the rest of the frame, in pieces of nan_row */
		left = (w->nrows - w->row) * w->ncols * w->ncomp;
		/* whole pixels a piece, for the ascii lines */
		chunk -= chunk % w->ncomp;
		for (; left; left -= n) {
			n = left < chunk ? left : chunk;
			if (w->opt.format == RF_FORMAT_ASCII) {
				if (write_ascii(w, nan_row, n) < 0)
					return RF_EIO;
			} else if (put(w, (const char *)nan_row, n * sizeof(float)) < 0) {
				return RF_EIO;
			}
		}
		w->row = w->nrows;
		w->in_frame = 0;
	}
	snprintf(line, sizeof(line), "FAILED=%s", message && *message ? message : "failed");
	for (i = 0; line[i]; i++)
		if ((unsigned char)line[i] < 0x20 || line[i] == 0x7f)
			line[i] = '?';
	if (putline(w, RF__STREAM_IDENT) < 0)
		return RF_EIO;
	if (cut != (size_t)-1) {
		char rows[64];

		snprintf(rows, sizeof(rows), "FAILED_ROWS=%zu", cut);
		if (putline(w, rows) < 0)
			return RF_EIO;
	}
	if (putline(w, line) < 0 || putline(w, "") < 0)
		return RF_EIO;
	if (fflush(w->fp) != 0)
		return fail_io(w);
	return 0;
}
