/* Reading the stream: header, then rows in blocks, frames until EOF. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#define MAGIC "#?REFLECT"
#define STREAM_VERSION 1

struct rf_reader {
	FILE *fp;
	char *name;
	rf_header *h;
	struct rf_raw_input raw;
	char *raw_channels;
	int headerless;
	size_t frame;      /* index of the current frame, counting from 0 */
	size_t frames;     /* frames started */
	size_t row;        /* next row of the current frame */
	size_t ncomp;
	size_t row_floats; /* ncols * ncomp */
	int swap;
	size_t line;       /* ascii data: current line of the input */
	char err[512];
};

static int
fail(rf_reader *r, int status, const char *fmt, ...) RF__PRINTF(3, 4);

static int
fail(rf_reader *r, int status, const char *fmt, ...)
{
	char msg[400];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	if (r->frames > 1)
		rf__format(r->err, sizeof(r->err), "'%s': frame %zu: %s", r->name,
		           r->frame + 1, msg);
	else
		rf__format(r->err, sizeof(r->err), "'%s': %s", r->name, msg);
	return status;
}

int
rf_reader_open(rf_reader **rp, FILE *fp, const char *name,
               const struct rf_raw_input *raw)
{
	rf_reader *r;

	*rp = NULL;
	if (!(r = calloc(1, sizeof(*r))))
		return RF_ENOMEM;
	r->fp = fp;
	if (!(r->name = strdup(name ? name : "<stdin>")))
		goto nomem;
	if (raw) {
		r->headerless = 1;
		r->raw = *raw;
		if (!raw->channels || !(r->raw_channels = strdup(raw->channels)))
			goto nomem;
		r->raw.channels = r->raw_channels;
	}
	*rp = r;
	return 0;
nomem:
	rf_reader_close(r);
	return RF_ENOMEM;
}

void
rf_reader_close(rf_reader *r)
{
	if (!r)
		return;
	rf_header_free(r->h);
	free(r->name);
	free(r->raw_channels);
	free(r);
}

const char *
rf_reader_error(const rf_reader *r)
{
	return r->err;
}

size_t
rf_reader_rows_left(const rf_reader *r)
{
	return r->h ? rf_header_nrows(r->h) - r->row : 0;
}

size_t
rf_reader_frame_index(const rf_reader *r)
{
	return r->frame;
}

/* Reads one header line without its newline.  Returns its length, -1 at
 * EOF before any byte, or -2 when it is longer than the limit. */
static long
read_line(FILE *fp, char *buf, size_t size, int *binary)
{
	size_t n = 0;
	int c;

	*binary = 0;
	while ((c = getc(fp)) != EOF && c != '\n') {
		if (c == '\0' || (c < 0x20 && c != '\t' && c != '\r'))
			*binary = 1;
		if (n + 1 >= size)
			return -2;
		buf[n++] = (char)c;
	}
	if (c == EOF && n == 0)
		return -1;
	if (n && buf[n - 1] == '\r')
		n--; /* tolerate CRLF from editors on other systems */
	buf[n] = '\0';
	return (long)n;
}

/* A size value: a decimal integer, at least 1. */
static int
parse_size(rf_reader *r, size_t lineno, const char *key, const char *s, size_t *out)
{
	unsigned long long v;
	const char *p = s;
	char *end;

	while (*p == ' ')
		p++;
	if (*p == '-')
		return fail(r, RF_EFORMAT, "header line %zu: %s is negative ('%s')",
		            lineno, key, s);
	if (*p < '0' || *p > '9')
		return fail(r, RF_EFORMAT,
		            "header line %zu: %s is not a number ('%s')", lineno, key, s);
	errno = 0;
	v = strtoull(p, &end, 10);
	while (*end == ' ')
		end++;
	if (*end)
		return fail(r, RF_EFORMAT,
		            "header line %zu: %s is not a number ('%s')", lineno, key, s);
	if (errno == ERANGE || v > SIZE_MAX)
		return fail(r, RF_ETOOBIG, "header line %zu: %s is too large ('%s')",
		            lineno, key, s);
	if (v == 0)
		return fail(r, RF_EFORMAT, "header line %zu: %s must be at least 1",
		            lineno, key);
	*out = (size_t)v;
	return 0;
}

static int
check_magic(rf_reader *r, const char *line)
{
	size_t n = strlen(MAGIC);
	char *end;
	long v;

	if (strncmp(line, MAGIC, n)) {
		char shown[24];
		size_t i;

		for (i = 0; line[i] && i + 1 < sizeof(shown); i++)
			shown[i] = (unsigned char)line[i] >= 0x20 &&
			                   (unsigned char)line[i] < 0x7f
			           ? line[i] : '?';
		shown[i] = '\0';
		return fail(r, RF_EFORMAT,
		            "not a reflect stream: expected '#?REFLECT1', got '%s'", shown);
	}
	errno = 0;
	v = strtol(line + n, &end, 10);
	if (end == line + n || *end || errno || v < 1)
		return fail(r, RF_EFORMAT, "bad stream identifier '%.40s'", line);
	if (v != STREAM_VERSION)
		return fail(r, RF_EVERSION,
		            "stream version %ld is newer than this reader's (%d); "
		            "upgrade reflect", v, STREAM_VERSION);
	return 0;
}

/* CHANNELS=: names separated by spaces, each valid and given once. */
static int
parse_channels(rf_reader *r, const char *list)
{
	char name[RF_HEADER_LINE_MAX + 1];
	const char *p = list;
	size_t n;
	int rc;

	for (;;) {
		p += strspn(p, " \t");
		if (!*p)
			break;
		n = strcspn(p, " \t");
		memcpy(name, p, n);
		name[n] = '\0';
		p += n;
		if (!rf_channel_name_valid(name))
			return fail(r, RF_EFORMAT, "CHANNELS: '%.80s' is not a valid "
			            "channel name (1 to %d printable characters, no ',' "
			            "or '=')", name, RF_CHANNEL_NAME_MAX);
		if (rf_header_find_channel(r->h, name) >= 0)
			return fail(r, RF_EFORMAT, "CHANNELS: channel '%s' is named twice",
			            name);
		if ((rc = rf_header_add_channel(r->h, name)) < 0)
			return fail(r, rc, "CHANNELS: more than %d channels",
			            RF_CHANNELS_MAX);
	}
	if (!rf_header_nchannels(r->h))
		return fail(r, RF_EFORMAT, "CHANNELS names no channel");
	return 0;
}

/* Parses one header; the identifier line is already in `line`. */
static int
parse_header(rf_reader *r, char *line)
{
	size_t ncols = 0, nrows = 0, ncomp = 0, lineno = 1, total;
	int have_format = 0, big_endian = -1, binary, rc;
	enum rf_format format = RF_FORMAT_FLOAT;
	char *channels = NULL;
	const char *v;
	long len;

	if ((rc = check_magic(r, line)) < 0)
		return rc;
	for (;;) {
		len = read_line(r->fp, line, RF_HEADER_LINE_MAX + 2, &binary);
		lineno++;
		if (len == -1) {
			rc = fail(r, RF_ETRUNCATED,
			          "header ends at line %zu without the empty line "
			          "that closes it", lineno);
			goto out;
		}
		if (len == -2) {
			rc = fail(r, RF_EFORMAT,
			          "header line %zu is longer than %d bytes", lineno,
			          RF_HEADER_LINE_MAX);
			goto out;
		}
		if (binary) {
			rc = fail(r, RF_EFORMAT,
			          "header line %zu holds binary data", lineno);
			goto out;
		}
		if (len == 0)
			break;
		if (!strncmp(line, "NCOLS=", 6)) {
			if (ncols) goto dup;
			if ((rc = parse_size(r, lineno, "NCOLS", line + 6, &ncols)) < 0)
				goto out;
		} else if (!strncmp(line, "NROWS=", 6)) {
			if (nrows) goto dup;
			if ((rc = parse_size(r, lineno, "NROWS", line + 6, &nrows)) < 0)
				goto out;
		} else if (!strncmp(line, "NCOMP=", 6)) {
			if (ncomp) goto dup;
			if ((rc = parse_size(r, lineno, "NCOMP", line + 6, &ncomp)) < 0)
				goto out;
		} else if (!strncmp(line, "CHANNELS=", 9)) {
			if (channels) goto dup;
			if (!(channels = strdup(line + 9))) {
				rc = RF_ENOMEM;
				goto out;
			}
		} else if (!strncmp(line, "BigEndian=", 10)) {
			if (big_endian >= 0) goto dup;
			v = line + 10;
			if (strcmp(v, "0") && strcmp(v, "1")) {
				rc = fail(r, RF_EFORMAT,
				          "header line %zu: BigEndian must be 0 or 1, not '%s'",
				          lineno, v);
				goto out;
			}
			big_endian = *v == '1';
		} else if (!strncmp(line, "FORMAT=", 7)) {
			char *e = line + strlen(line);

			if (have_format) goto dup;
			while (e > line + 7 && e[-1] == ' ')
				*--e = '\0';
			if (!strcmp(line + 7, "float")) {
				format = RF_FORMAT_FLOAT;
			} else if (!strcmp(line + 7, "ascii")) {
				format = RF_FORMAT_ASCII;
			} else {
				rc = fail(r, RF_EFORMAT,
				          "header line %zu: FORMAT '%s' is not supported "
				          "(float or ascii)", lineno, line + 7);
				goto out;
			}
			have_format = 1;
		} else if ((rc = rf__header_push_line(r->h, line)) < 0) {
			rc = fail(r, rc, "header line %zu: %s", lineno,
			          rc == RF_ETOOBIG ? "too many header lines"
			                           : rf_strerror(rc));
			goto out;
		}
	}
	if (!ncols || !nrows || !ncomp || !channels || !have_format) {
		rc = fail(r, RF_EFORMAT, "header has no %s line",
		          !ncols ? "NCOLS" : !nrows ? "NROWS" : !ncomp ? "NCOMP"
		          : !channels ? "CHANNELS" : "FORMAT");
		goto out;
	}
	if (rf__mul3(ncols, nrows, ncomp, &total) ||
	    rf__mul3(total, sizeof(float), 1, &total)) {
		rc = fail(r, RF_ETOOBIG,
		          "NCOLS*NROWS*NCOMP (%zu*%zu*%zu) overflows the size of memory",
		          ncols, nrows, ncomp);
		goto out;
	}
	if (ncomp > RF_CHANNELS_MAX) {
		rc = fail(r, RF_ETOOBIG, "NCOMP=%zu is more than %d channels", ncomp,
		          RF_CHANNELS_MAX);
		goto out;
	}
	if (ncols * ncomp * sizeof(float) > RF_ROW_BYTES_MAX) {
		rc = fail(r, RF_ETOOBIG, "a row of NCOLS=%zu by NCOMP=%zu floats is "
		          "larger than %zu MiB", ncols, ncomp,
		          (size_t)(RF_ROW_BYTES_MAX >> 20));
		goto out;
	}
	if ((rc = parse_channels(r, channels)) < 0)
		goto out;
	if (rf_header_nchannels(r->h) != ncomp) {
		rc = fail(r, RF_EFORMAT, "NCOMP=%zu but CHANNELS names %zu channels",
		          ncomp, rf_header_nchannels(r->h));
		goto out;
	}
	if (format == RF_FORMAT_FLOAT && big_endian < 0) {
		rc = fail(r, RF_EFORMAT, "header has no BigEndian line for float data");
		goto out;
	}
	rf_header_set_size(r->h, ncols, nrows);
	rf__header_set_format(r->h, format, big_endian > 0);
	r->ncomp = ncomp;
	r->row_floats = ncols * ncomp;
	{
		const unsigned one = 1;
		int host_big = *(const unsigned char *)&one == 0;

		r->swap = format == RF_FORMAT_FLOAT && (big_endian > 0) != host_big;
	}
	rc = 0;
	goto out;
dup:
	{
		size_t k = strcspn(line, "=");

		rc = fail(r, RF_EFORMAT, "header line %zu: %.*s given twice", lineno,
		          (int)k, line);
	}
out:
	free(channels);
	return rc;
}

static int
skip_rest(rf_reader *r)
{
	float buf[4096];
	size_t rows, left;
	int rc;

	if (!r->h)
		return 0;
	rows = rf_block_rows(rf_header_ncols(r->h), r->ncomp, sizeof(buf));
	if (rows * r->row_floats > sizeof(buf) / sizeof(float)) {
		float *big = malloc(r->row_floats * sizeof(float));

		if (!big)
			return RF_ENOMEM;
		while (rf_reader_rows_left(r))
			if ((rc = rf_reader_read_rows(r, big, 1)) < 0) {
				free(big);
				return rc;
			}
		free(big);
		return 0;
	}
	while ((left = rf_reader_rows_left(r)))
		if ((rc = rf_reader_read_rows(r, buf, rows < left ? rows : left)) < 0)
			return rc;
	return 0;
}

int
rf_reader_next_frame(rf_reader *r, const rf_header **hp)
{
	char line[RF_HEADER_LINE_MAX + 2];
	int c, binary, rc;
	long len;

	*hp = NULL;
	if ((rc = skip_rest(r)) < 0)
		return rc;
	rf_header_free(r->h);
	if (!(r->h = rf_header_new()))
		return RF_ENOMEM;
	r->row = 0;
	/* Between frames of ascii data there may be blank lines. */
	do
		c = getc(r->fp);
	while (r->frames && (c == '\n' || c == ' ' || c == '\t' || c == '\r'));
	if (c == EOF) {
		rf_header_free(r->h);
		r->h = NULL;
		if (ferror(r->fp))
			return fail(r, RF_EIO, "read error: %s", strerror(errno));
		if (!r->frames)
			return fail(r, RF_EFORMAT, "empty input: no stream header");
		return 0;
	}
	ungetc(c, r->fp);
	r->frame = r->frames++;
	r->line = 0;
	if (r->headerless) {
		if ((rc = rf_header_set_size(r->h, r->raw.ncols, r->raw.nrows)) < 0)
			return fail(r, rc, "headerless input needs -x and -y of at least 1");
		if ((rc = rf_header_set_channels(r->h, r->raw.channels)) < 0)
			return fail(r, rc, "bad channel list '%s'", r->raw.channels);
		r->ncomp = rf_header_nchannels(r->h);
		if (r->ncomp * r->raw.ncols * sizeof(float) > RF_ROW_BYTES_MAX)
			return fail(r, RF_ETOOBIG, "a row of headerless input is too large");
		r->row_floats = r->raw.ncols * r->ncomp;
		r->swap = 0;
		rf__header_set_format(r->h, r->raw.format, 0);
		*hp = r->h;
		return 1;
	}
	len = read_line(r->fp, line, sizeof(line), &binary);
	if (len == -2 || binary || strncmp(line, "#?", 2))
		return fail(r, RF_EFORMAT, "not a reflect stream: expected "
		            "'#?REFLECT1' at the start%s",
		            r->frames > 1 ? " of the frame (more data than the "
		                            "previous header said?)" : "");
	if ((rc = parse_header(r, line)) < 0)
		return rc;
	*hp = r->h;
	return 1;
}

static void
swap32(float *buf, size_t n)
{
	uint32_t *u = (uint32_t *)buf;
	size_t i;

	for (i = 0; i < n; i++)
		u[i] = __builtin_bswap32(u[i]);
}

static int
truncated(rf_reader *r, size_t got_floats, size_t got_bytes)
{
	size_t row = r->row + got_floats / r->row_floats;
	size_t in_row = got_floats % r->row_floats;
	size_t nrows = rf_header_nrows(r->h);

	if (got_bytes % sizeof(float))
		return fail(r, RF_ETRUNCATED,
		            "data ends inside a float in row %zu of %zu (channel '%s')",
		            row + 1, nrows,
		            rf_header_channel(r->h, in_row % r->ncomp));
	if (in_row)
		return fail(r, RF_ETRUNCATED,
		            "data ends in the middle of row %zu of %zu (pixel %zu of %zu)",
		            row + 1, nrows, in_row / r->ncomp + 1,
		            rf_header_ncols(r->h));
	return fail(r, RF_ETRUNCATED, "data ends after row %zu of %zu", row, nrows);
}

static int
read_float_rows(rf_reader *r, float *buf, size_t nrows)
{
	size_t want = nrows * r->row_floats * sizeof(float);
	size_t got = fread(buf, 1, want, r->fp);

	if (got < want) {
		if (ferror(r->fp))
			return fail(r, RF_EIO, "read error: %s", strerror(errno));
		return truncated(r, got / sizeof(float), got);
	}
	if (r->swap)
		swap32(buf, nrows * r->row_floats);
	return 0;
}

/* One number of ascii data; returns 1, 0 at EOF, or an error. */
static int
read_ascii_value(rf_reader *r, float *out)
{
	char tok[64];
	size_t n = 0;
	char *end;
	int c;

	do {
		c = getc(r->fp);
		if (c == '\n')
			r->line++;
	} while (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',');
	if (c == EOF)
		return 0;
	while (c != EOF && c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != ',') {
		if (n + 1 >= sizeof(tok))
			return fail(r, RF_EFORMAT, "ascii data line %zu: value too long",
			            r->line + 1);
		tok[n++] = (char)c;
		c = getc(r->fp);
	}
	if (c != EOF)
		ungetc(c, r->fp);
	tok[n] = '\0';
	*out = strtof(tok, &end);
	if (*end || end == tok) {
		size_t i;

		for (i = 0; i < n; i++)
			if ((unsigned char)tok[i] < 0x20 || (unsigned char)tok[i] >= 0x7f)
				tok[i] = '?';
		return fail(r, RF_EFORMAT, "ascii data line %zu: '%s' is not a number",
		            r->line + 1, tok);
	}
	return 1;
}

static int
read_ascii_rows(rf_reader *r, float *buf, size_t nrows)
{
	size_t n = nrows * r->row_floats, i;
	int rc;

	for (i = 0; i < n; i++) {
		if ((rc = read_ascii_value(r, buf + i)) < 0)
			return rc;
		if (rc == 0) {
			if (ferror(r->fp))
				return fail(r, RF_EIO, "read error: %s", strerror(errno));
			return truncated(r, i, i * sizeof(float));
		}
	}
	return 0;
}

int
rf_reader_read_rows(rf_reader *r, float *buf, size_t nrows)
{
	int rc;

	if (!r->h || nrows > rf_reader_rows_left(r))
		return fail(r, RF_EINVAL, "read past the last row of the frame");
	if (!nrows)
		return 0;
	if (rf_header_format(r->h) == RF_FORMAT_ASCII)
		rc = read_ascii_rows(r, buf, nrows);
	else
		rc = read_float_rows(r, buf, nrows);
	if (rc < 0)
		return rc;
	r->row += nrows;
	return 0;
}

size_t
rf_block_rows(size_t ncols, size_t ncomp, size_t bytes)
{
	size_t row = ncols * ncomp * sizeof(float);

	if (!row || row >= bytes)
		return 1;
	return bytes / row;
}
