/* Reading the stream: header, then rows in blocks, frames until EOF. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "stream/stream-internal.h"

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
	size_t last_nrows; /* rows of the frame before (for a trailer's message) */
	size_t ncomp;
	size_t row_floats; /* ncols * ncomp */
	int swap;
	/* rf_reader_map_rows: whether the input is a regular file (-1 not
	 * yet known), and the one mapping held. */
	int mappable;
	void *map;
	size_t map_len;
	int status; /* the first error: every later call returns it again */
	char err[1100];
	/* rf_reader_crop: the tile's header (NULL: no crop), its first
	 * column and row in the frame read, its size, the rows given out,
	 * and a row of the frame read to cut it from */
	rf_header *crop_h;
	size_t crop_x, crop_y, crop_w, crop_rows, crop_done;
	float *crop_row;
	size_t crop_cap; /* floats crop_row holds */
};

/* A message is one line of text whatever the input held: control
 * characters (a tab in a header value, say) become '?'. */
static void
printable(char *s)
{
	for (; *s; s++)
		if ((unsigned char)*s < 0x20 || *s == 0x7f)
			*s = '?';
}

static int
fail(rf_reader *r, int status, const char *fmt, ...) RF__PRINTF(3, 4);

static int
fail(rf_reader *r, int status, const char *fmt, ...)
{
	char msg[1000];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof(msg), fmt, ap);
	va_end(ap);
	if (r->frames > 1)
		rf__format(r->err, sizeof(r->err), "'%s': frame %zu: %s", r->name,
		           r->frame + 1, msg);
	else
		rf__format(r->err, sizeof(r->err), "'%s': %s", r->name, msg);
	printable(r->err);
	if (status != RF_EINVAL) /* a bad call leaves the stream as it was */
		r->status = status;
	return status;
}

/* A read error of the input (not bad data): "cannot read 'f': reason". */
static int
fail_read(rf_reader *r)
{
	int e = errno ? errno : EIO;

	rf__format(r->err, sizeof(r->err), "cannot read '%s': %s", r->name,
	           strerror(e));
	printable(r->err);
	errno = e;
	return r->status = RF_EIO;
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
	r->mappable = -1;
	if (!(r->name = strdup(name ? name : "<stdin>")))
		goto nomem;
	if (raw) {
		r->headerless = 1;
		r->raw = *raw;
		if (!raw->channels) {
			rf_reader_close(r);
			return RF_EINVAL;
		}
		if (!(r->raw_channels = strdup(raw->channels)))
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
	if (r->map)
		munmap(r->map, r->map_len);
	rf_header_destroy(r->h);
	rf_header_destroy(r->crop_h);
	free(r->crop_row);
	free(r->name);
	free(r->raw_channels);
	free(r);
}

const char *
rf_reader_error(const rf_reader *r)
{
	return r->err;
}

/* Rows of the frame as the input holds it, cropped or not. */
static size_t
input_rows_left(const rf_reader *r)
{
	return r->h ? rf_header_nrows(r->h) - r->row : 0;
}

size_t
rf_reader_rows_left(const rf_reader *r)
{
	if (r->h && r->crop_h)
		return r->crop_rows - r->crop_done;
	return input_rows_left(r);
}

size_t
rf_reader_frame_index(const rf_reader *r)
{
	return r->frame;
}

/* Reads one header line without its newline (or CRLF) into buf, which
 * holds RF_HEADER_LINE_MAX + 2 bytes.  Returns its length, -1 at EOF before
 * any byte, or -2 when it is longer than RF_HEADER_LINE_MAX.  *binary is
 * set when the line holds a control character other than a tab (or the
 * CR of a CRLF ending): binary data, not a header. */
static long
read_line(FILE *fp, char *buf, int *binary)
{
	size_t n = 0, i;
	int c;

	*binary = 0;
	while ((c = getc(fp)) != EOF && c != '\n') {
		if (n > RF_HEADER_LINE_MAX) /* one more byte for a final CR */
			return -2;
		buf[n++] = (char)c;
	}
	if (c == EOF && n == 0)
		return -1;
	if (n && buf[n - 1] == '\r')
		n--; /* tolerate CRLF from editors on other systems */
	if (n > RF_HEADER_LINE_MAX)
		return -2;
	buf[n] = '\0';
	for (i = 0; i < n; i++)
		if ((unsigned char)buf[i] < 0x20 && buf[i] != '\t')
			*binary = 1;
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
		return fail(r, RF_EFORMAT, "header line %zu: %s is negative ('%.40s')",
		            lineno, key, s);
	if (*p < '0' || *p > '9')
		return fail(r, RF_EFORMAT,
		            "header line %zu: %s is not a number ('%.40s')", lineno, key, s);
	errno = 0;
	v = strtoull(p, &end, 10);
	while (*end == ' ')
		end++;
	if (*end)
		return fail(r, RF_EFORMAT,
		            "header line %zu: %s is not a number ('%.40s')", lineno, key, s);
	if (errno == ERANGE || v > SIZE_MAX)
		return fail(r, RF_ETOOBIG, "header line %zu: %s is too large ('%.40s')",
		            lineno, key, s);
	if (v == 0)
		return fail(r, RF_EFORMAT, "header line %zu: %s must be at least 1",
		            lineno, key);
	*out = (size_t)v;
	return 0;
}

/* The image format a file that is no stream starts like, and the tools
 * that read it, for the message; NULL for none of them.  b holds the
 * first n bytes of the input (n < 0: at least 8). */
#define IMAGE_HINT "; reflect-import reads images into streams, and --env takes " \
	"environments"
/* reflect-import reads images through OpenImageIO, which reads no KTX
 * and no DDS cube: those are environments, which only the environment
 * loader reads. */
#define CUBE_HINT "; DDS and KTX cubes are environments: reflect-prefilter reads " \
	"them, and reflect-shade --env takes them"

static const char *
image_kind(const char *b, long n)
{
	static const struct { const char *magic; size_t len; const char *kind; } kinds[] = {
		{ "\x76\x2f\x31\x01", 4, "an OpenEXR image" IMAGE_HINT },
		{ "\x89PNG", 4, "a PNG image" IMAGE_HINT },
		{ "\xff\xd8\xff", 3, "a JPEG image" IMAGE_HINT },
		{ "II*\0", 4, "a TIFF image" IMAGE_HINT },
		{ "MM\0*", 4, "a TIFF image" IMAGE_HINT },
		{ "DDS ", 4, "a DDS image" CUBE_HINT },
		{ "\xabKTX 11", 7, "a KTX image" CUBE_HINT },
		{ "\xabKTX 20", 7, "a KTX 2 image" CUBE_HINT },
		{ "#?RADIANCE", 10, "a Radiance HDR image" IMAGE_HINT },
		{ "#?RGBE", 6, "a Radiance HDR image" IMAGE_HINT },
	};
	size_t i;

	for (i = 0; i < sizeof(kinds) / sizeof(kinds[0]); i++)
		if ((n < 0 || (size_t)n >= kinds[i].len) && !memcmp(b, kinds[i].magic, kinds[i].len))
			return kinds[i].kind;
	return NULL;
}

int
rf_stream_sniff(const void *bytes, size_t len)
{
	size_t n = strlen(RF__STREAM_MAGIC);

	return len >= n && !memcmp(bytes, RF__STREAM_MAGIC, n);
}

static int
check_magic(rf_reader *r, const char *line)
{
	size_t n = strlen(RF__STREAM_MAGIC);
	char *end;
	long v;

	if (strncmp(line, RF__STREAM_MAGIC, n)) {
		const char *kind = image_kind(line, (long)strlen(line));
		char shown[24];
		size_t i;

		if (kind)
			return fail(r, RF_EFORMAT, "not a reflect stream: it is %s",
			            kind);

		for (i = 0; line[i] && i + 1 < sizeof(shown); i++)
			shown[i] = (unsigned char)line[i] >= 0x20 &&
			                   (unsigned char)line[i] < 0x7f
			           ? line[i] : '?';
		shown[i] = '\0';
		return fail(r, RF_EFORMAT,
		            "not a reflect stream: expected '" RF__STREAM_IDENT "', got '%s'",
		            shown);
	}
	/* The version: decimal digits and nothing else. */
	line += n;
	n = strspn(line, "0123456789");
	if (!n || line[n] || line[0] == '0')
		return fail(r, RF_EFORMAT, "bad stream identifier '" RF__STREAM_MAGIC "%.30s'",
		            line);
	errno = 0;
	v = strtol(line, &end, 10);
	if (errno == ERANGE)
		return fail(r, RF_EVERSION, "stream version %.30s is newer than this "
		            "reader's (%d); upgrade reflect", line, RF__STREAM_VERSION);
	if (v != RF__STREAM_VERSION)
		return fail(r, RF_EVERSION,
		            "stream version %ld is newer than this reader's (%d); "
		            "upgrade reflect", v, RF__STREAM_VERSION);
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
			return rc == RF_ENOMEM ? fail(r, rc, "out of memory")
			       : fail(r, rc, "CHANNELS: more than %d channels",
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
	int have_format = 0, big_endian = -1, binary, rc, cut = 0;
	unsigned long failed_rows = 0;
	enum rf_format format = RF_FORMAT_FLOAT;
	char *channels = NULL;
	const char *v;
	long len;

	if ((rc = check_magic(r, line)) < 0)
		return rc;
	for (;;) {
		len = read_line(r->fp, line, &binary);
		lineno++;
		if (len == -1) {
			if (ferror(r->fp)) {
				rc = fail_read(r);
				goto out;
			}
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
		/* the trailer of a failed stream (rf_writer_fail) */
		if (!strncmp(line, "FAILED_ROWS=", 12)) {
			failed_rows = line[12] ? strtoul(line + 12, NULL, 10) : 0;
			cut = 1;
			continue;
		}
		if (!strncmp(line, "FAILED=", 7)) {
			if (r->frames > 1 && cut)
				rc = fail(r, RF_EFAILED, "the tool that wrote the stream failed "
				          "in frame %zu, which holds only its first %lu of %zu "
				          "rows (the rest are NaN): %s", r->frames - 1,
				          failed_rows, r->last_nrows, line + 7);
			else if (r->frames > 1)
				rc = fail(r, RF_EFAILED, "the tool that wrote the stream failed "
				          "after frame %zu: %s", r->frames - 1, line + 7);
			else
				rc = fail(r, RF_EFAILED, "the tool that wrote the stream failed: %s",
				          line + 7);
			goto out;
		}
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
				rc = fail(r, RF_ENOMEM, "out of memory");
				goto out;
			}
		} else if (!strncmp(line, "BigEndian=", 10)) {
			if (big_endian >= 0) goto dup;
			v = line + 10;
			if (strcmp(v, "0") && strcmp(v, "1")) {
				rc = fail(r, RF_EFORMAT,
				          "header line %zu: BigEndian must be 0 or 1, not '%.40s'",
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
				          "header line %zu: FORMAT '%.40s' is not supported "
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

static void
swap32(void *buf, size_t n)
{
	unsigned char *p = buf;
	uint32_t u;
	size_t i;

	for (i = 0; i < n; i++, p += 4) {
		memcpy(&u, p, 4);
		u = __builtin_bswap32(u);
		memcpy(p, &u, 4);
	}
}

/* The data of the frame ended early: got_bytes of it were read after the
 * start of the current row. */
static int
truncated(rf_reader *r, size_t got_bytes)
{
	size_t got_floats = got_bytes / sizeof(float);
	size_t row = r->row + got_floats / r->row_floats;
	size_t in_row = got_floats % r->row_floats;
	size_t nrows = rf_header_nrows(r->h);

	if (got_bytes % sizeof(float))
		return fail(r, RF_ETRUNCATED,
		            "data ends inside a float in row %zu of %zu (pixel %zu of "
		            "%zu, channel '%s')", row + 1, nrows, in_row / r->ncomp + 1,
		            rf_header_ncols(r->h),
		            rf_header_channel(r->h, in_row % r->ncomp));
	if (in_row)
		return fail(r, RF_ETRUNCATED,
		            "data ends in the middle of row %zu of %zu (pixel %zu of %zu)",
		            row + 1, nrows, in_row / r->ncomp + 1,
		            rf_header_ncols(r->h));
	return fail(r, RF_ETRUNCATED, "data ends after row %zu of %zu", row, nrows);
}

/* Float data: nrows rows into buf, or skipped when buf is NULL (in pieces
 * of a fixed size, so that skipping never allocates a row). */
static int
read_float_rows(rf_reader *r, float *buf, size_t nrows)
{
	size_t want = nrows * r->row_floats * sizeof(float), got = 0, n, piece;
	unsigned char scratch[16384];

	if (buf) {
		got = fread(buf, 1, want, r->fp);
	} else {
		while (got < want) {
			piece = want - got < sizeof(scratch) ? want - got : sizeof(scratch);
			n = fread(scratch, 1, piece, r->fp);
			got += n;
			if (n < piece)
				break;
		}
	}
	if (got < want) {
		if (ferror(r->fp))
			return fail_read(r);
		return truncated(r, got);
	}
	if (buf && r->swap)
		swap32(buf, nrows * r->row_floats);
	return 0;
}

/* One token of ascii data into tok (of size 64): 1, 0 at EOF, or -1 when
 * it is too long. */
static int
read_ascii_token(FILE *fp, char *tok, size_t size)
{
	size_t n = 0;
	int c;

	do
		c = getc(fp);
	while (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',');
	if (c == EOF)
		return 0;
	while (c != EOF && c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != ',') {
		if (n + 1 >= size)
			return -1;
		tok[n++] = (char)c;
		c = getc(fp);
	}
	if (c != EOF)
		ungetc(c, fp);
	tok[n] = '\0';
	return 1;
}

/* Ascii data: numbers separated by blanks, newlines or commas. */
static int
read_ascii_rows(rf_reader *r, float *buf, size_t nrows)
{
	size_t n = nrows * r->row_floats, i, k;
	char tok[64], *end;
	float v;
	int rc;

	for (i = 0; i < n; i++) {
		size_t row = r->row + i / r->row_floats;
		size_t pixel = i % r->row_floats / r->ncomp;
		const char *chan = rf_header_channel(r->h, i % r->ncomp);

		rc = read_ascii_token(r->fp, tok, sizeof(tok));
		if (rc == 0) {
			if (ferror(r->fp))
				return fail_read(r);
			return truncated(r, i * sizeof(float));
		}
		if (rc < 0)
			return fail(r, RF_EFORMAT, "ascii data: a value longer than %zu "
			            "characters (row %zu of %zu, pixel %zu of %zu, "
			            "channel '%s')", sizeof(tok) - 1, row + 1,
			            rf_header_nrows(r->h), pixel + 1,
			            rf_header_ncols(r->h), chan);
		v = strtof(tok, &end);
		if (*end) {
			for (k = 0; tok[k]; k++)
				if ((unsigned char)tok[k] < 0x20 ||
				    (unsigned char)tok[k] >= 0x7f || tok[k] == '\'')
					tok[k] = '?';
			return fail(r, RF_EFORMAT, "ascii data: '%s' is not a number "
			            "(row %zu of %zu, pixel %zu of %zu, channel '%s')", tok,
			            row + 1, rf_header_nrows(r->h), pixel + 1,
			            rf_header_ncols(r->h), chan);
		}
		if (buf)
			buf[i] = v;
	}
	return 0;
}

static int
read_rows(rf_reader *r, float *buf, size_t nrows)
{
	int rc;

	if (rf_header_format(r->h) == RF_FORMAT_ASCII)
		rc = read_ascii_rows(r, buf, nrows);
	else
		rc = read_float_rows(r, buf, nrows);
	if (rc < 0)
		return rc;
	r->row += nrows;
	return 0;
}

/* Skips what is left of the current frame, without holding a row. */
static int
skip_rest(rf_reader *r)
{
	size_t left;

	if (!r->h || !(left = input_rows_left(r)))
		return 0;
	return read_rows(r, NULL, left);
}

/* Whether c may separate frames: blank lines between frames of ascii
 * data.  Never for headerless float data, where any byte is data. */
static int
frame_gap(const rf_reader *r, int c)
{
	if (!r->frames || (r->headerless && r->raw.format != RF_FORMAT_ASCII))
		return 0;
	return c == '\n' || c == ' ' || c == '\t' || c == '\r';
}

static int
begin_headerless(rf_reader *r)
{
	size_t total;
	int rc;

	if ((rc = rf_header_set_size(r->h, r->raw.ncols, r->raw.nrows)) < 0)
		return fail(r, rc, "headerless input needs -x and -y of at least 1 "
		            "(got %zu and %zu)", r->raw.ncols, r->raw.nrows);
	if ((rc = rf_header_set_channels(r->h, r->raw.channels)) < 0)
		return fail(r, rc, rc == RF_ENOMEM ? "out of memory"
		            : "bad channel list '%.200s' (names of 1 to 63 printable "
		              "characters, each given once)", r->raw.channels);
	r->ncomp = rf_header_nchannels(r->h);
	if (rf__mul3(r->raw.ncols, r->raw.nrows, r->ncomp * sizeof(float), &total))
		return fail(r, RF_ETOOBIG, "headerless input of %zu x %zu pixels by "
		            "%zu channels overflows the size of memory", r->raw.ncols,
		            r->raw.nrows, r->ncomp);
	if (r->raw.ncols * r->ncomp * sizeof(float) > RF_ROW_BYTES_MAX)
		return fail(r, RF_ETOOBIG, "a row of %zu pixels by %zu channels is "
		            "larger than %zu MiB", r->raw.ncols, r->ncomp,
		            (size_t)(RF_ROW_BYTES_MAX >> 20));
	r->row_floats = r->raw.ncols * r->ncomp;
	r->swap = 0;
	rf__header_set_format(r->h, r->raw.format, 0);
	return 0;
}

int
rf_reader_next_frame(rf_reader *r, const rf_header **hp)
{
	char line[RF_HEADER_LINE_MAX + 2];
	int c, binary, rc;
	const char *kind;
	long len;

	*hp = NULL;
	if (r->status)
		return r->status;
	if ((rc = skip_rest(r)) < 0)
		return rc;
	r->last_nrows = r->h ? rf_header_nrows(r->h) : 0;
	rf_header_destroy(r->h);
	rf_header_destroy(r->crop_h);
	r->crop_h = NULL;
	r->row = 0;
	if (rf_header_create(&r->h) < 0)
		return fail(r, RF_ENOMEM, "out of memory");
	do
		c = getc(r->fp);
	while (frame_gap(r, c));
	if (c == EOF) {
		rf_header_destroy(r->h);
		r->h = NULL;
		if (ferror(r->fp))
			return fail_read(r);
		if (!r->frames)
			return fail(r, RF_EFORMAT, r->headerless ? "empty input"
			            : "empty input: no stream header");
		return 0;
	}
	ungetc(c, r->fp);
	r->frame = r->frames++;
	if (r->headerless) {
		if ((rc = begin_headerless(r)) < 0)
			goto bad;
		*hp = r->h;
		return 1;
	}
	len = read_line(r->fp, line, &binary);
	kind = len != -1 && r->frames == 1 && strncmp(line, "#?", 2)
	           ? image_kind(line, len < 0 ? -1 : len) : NULL;
	if (kind) {
		rc = fail(r, RF_EFORMAT, "not a reflect stream: it is %s", kind);
		goto bad;
	}
	if (len < 0 || binary || strncmp(line, "#?", 2)) {
		rc = fail(r, RF_EFORMAT, "not a reflect stream: expected "
		          "'" RF__STREAM_IDENT "' at the start%s",
		          r->frames > 1 ? " of the frame (more data than the "
		                          "previous header said?)" : "");
		goto bad;
	}
	if ((rc = parse_header(r, line)) < 0)
		goto bad;
	*hp = r->h;
	return 1;
bad:
	/* A frame that failed has no rows to read or skip. */
	rf_header_destroy(r->h);
	r->h = NULL;
	return rc;
}

/* A tile's rows: the frame's rows above it skipped, each of its rows
 * read whole and the tile's columns kept. */
static int
read_cropped(rf_reader *r, float *buf, size_t nrows)
{
	const size_t w = r->crop_w * r->ncomp;
	size_t i;
	int rc;

	if (r->row < r->crop_y && (rc = read_rows(r, NULL, r->crop_y - r->row)) < 0)
		return rc;
	for (i = 0; i < nrows; i++, buf += w) {
		if ((rc = read_rows(r, r->crop_row, 1)) < 0)
			return rc;
		memcpy(buf, r->crop_row + r->crop_x * r->ncomp, w * sizeof(float));
	}
	r->crop_done += nrows;
	return 0;
}

int
rf_reader_crop(rf_reader *r, size_t x0, size_t y0, size_t x1, size_t y1,
               const rf_header **hp)
{
	struct rf_region g, t;
	size_t ncols, nrows;
	int rc;

	*hp = r->crop_h ? r->crop_h : r->h;
	if (r->status)
		return r->status;
	if (!r->h || r->row || r->crop_h)
		return fail(r, RF_EINVAL, "a frame is cropped before its rows are read, once");
	ncols = rf_header_ncols(r->h);
	nrows = rf_header_nrows(r->h);
	if (rf_header_region(r->h, &g) < 0)
		return fail(r, RF_EFORMAT, "frame %zu: " RF_KEY_REGION " '%.200s' is not X0 Y0 "
		            "WIDTH HEIGHT of a full frame that holds the frame's %zux%zu pixels",
		            r->frame, rf_header_get(r->h, RF_KEY_REGION), ncols, nrows);
	if (x1 <= x0 || y1 <= y0)
		return fail(r, RF_EINVAL, "the region %zu,%zu,%zu,%zu holds no pixel "
		            "(X0,Y0,X1,Y1 with X0 < X1 and Y0 < Y1)", x0, y0, x1, y1);
	if (x0 < g.x0 || y0 < g.y0 || x1 > g.x0 + ncols || y1 > g.y0 + nrows)
		return fail(r, RF_EINVAL, "frame %zu holds pixels %zu,%zu,%zu,%zu of a %zux%zu "
		            "frame, not all of the region %zu,%zu,%zu,%zu", r->frame, g.x0, g.y0,
		            g.x0 + ncols, g.y0 + nrows, g.width, g.height, x0, y0, x1, y1);
	if (r->crop_cap < r->row_floats) {
		float *row = realloc(r->crop_row, r->row_floats * sizeof(float));

		if (!row)
			return fail(r, RF_ENOMEM, "out of memory");
		r->crop_row = row;
		r->crop_cap = r->row_floats;
	}
	t.x0 = x0;
	t.y0 = y0;
	t.width = g.width;
	t.height = g.height;
	if ((rc = rf_header_dup(&r->crop_h, r->h)) < 0 ||
	    (rc = rf_header_set_size(r->crop_h, x1 - x0, y1 - y0)) < 0 ||
	    (rc = rf_header_set_region(r->crop_h, &t)) < 0) {
		rf_header_destroy(r->crop_h);
		r->crop_h = NULL;
		return fail(r, rc, "out of memory");
	}
	r->crop_x = x0 - g.x0;
	r->crop_y = y0 - g.y0;
	r->crop_w = x1 - x0;
	r->crop_rows = y1 - y0;
	r->crop_done = 0;
	*hp = r->crop_h;
	return 0;
}

int
rf_reader_read_rows(rf_reader *r, float *buf, size_t nrows)
{
	if (r->status)
		return r->status;
	if (!r->h || nrows > rf_reader_rows_left(r))
		return fail(r, RF_EINVAL, "read past the last row of the frame");
	if (!nrows)
		return 0;
	if (!buf)
		return fail(r, RF_EINVAL, "no buffer to read rows into");
	if (r->crop_h)
		return read_cropped(r, buf, nrows);
	return read_rows(r, buf, nrows);
}

/*
 * Mapping instead of reading: for a file in the page cache, fread copies
 * every byte once more (a fifth of a streaming stage's time), where a
 * mapping lets the stage read the cache itself.  One block is mapped at a
 * time, so what the process holds stays bounded by a block.
 */
int
rf_reader_map_rows(rf_reader *r, size_t nrows, const float **rows)
{
	long page = sysconf(_SC_PAGESIZE);
	size_t want;
	off_t pos, start;
	struct stat st;
	void *m;

	*rows = NULL;
	if (r->status)
		return r->status;
	if (!r->h || nrows > rf_reader_rows_left(r))
		return fail(r, RF_EINVAL, "read past the last row of the frame");
	if (r->map) {
		munmap(r->map, r->map_len);
		r->map = NULL;
	}
	if (r->crop_h)
		return 0;
	if (r->mappable < 0)
		r->mappable = fstat(fileno(r->fp), &st) == 0 && S_ISREG(st.st_mode) && page > 0;
	if (!r->mappable || !nrows || r->swap || rf_header_format(r->h) != RF_FORMAT_FLOAT)
		return 0;
	/* The size again: a file may grow while we read it. */
	if (fstat(fileno(r->fp), &st) < 0 || (pos = ftello(r->fp)) < 0 || pos % 4)
		return 0;
	want = nrows * r->row_floats * sizeof(float);
	if (st.st_size - pos < (off_t)want)
		return 0; /* data that ends early: the reading path says where */
	start = pos - pos % page;
	m = mmap(NULL, want + (size_t)(pos - start), PROT_READ, MAP_PRIVATE,
	         fileno(r->fp), start);
	if (m == MAP_FAILED)
		return 0;
	if (fseeko(r->fp, pos + (off_t)want, SEEK_SET) < 0) {
		munmap(m, want + (size_t)(pos - start));
		return fail_read(r);
	}
	r->map = m;
	r->map_len = want + (size_t)(pos - start);
	r->row += nrows;
	*rows = (const float *)((const char *)m + (pos - start));
	return 0;
}

size_t
rf_block_rows(size_t ncols, size_t ncomp, size_t bytes)
{
	size_t row;

	if (rf__mul3(ncols, ncomp, sizeof(float), &row) || !row || row >= bytes)
		return 1;
	return bytes / row;
}
