/*
 * What an image's header may claim before its pixels are allocated.  A
 * header is input like any other: a 913-byte Radiance HDR file saying
 * 20000 x 20000 cost 4.8 GB and 20 s before its reader found the data
 * missing.  Every reader checks here first: libreflect's own (OpenEXR,
 * PNG) and the image module's, which calls back before it allocates.
 *
 * Two bounds.  The values (width x height x channels) are at most 2^28,
 * 1 GB of floats: a 16k x 16k cube face of RGBA.  And the file must be
 * able to hold them.  A file that stores its pixels as they are, or by
 * run lengths that cannot shrink them below a known size, must have that
 * many bytes: Radiance HDR, whose scanlines are flat (4 bytes a pixel) or
 * run-length coded (a 4-byte marker, then at best 2 bytes for 127 equal
 * values of each of 4 components).  For the others the most that a byte
 * of file can give is bounded by a ratio, VALUES_PER_BYTE.
 */
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "image/readers.h"
#include "util/util.h"

#define VALUES_MAX ((size_t)1 << 28)

/*
 * Values a byte of a compressed file may hold at most.  The most
 * compressible content is a constant colour; 2048 x 2048 RGB images of
 * one colour, written by OpenImageIO 2.4, hold per byte: Radiance HDR
 * 44, OpenEXR PIZ 73, TIFF LZW 107, OpenEXR ZIP 135, TIFF ZIP 182, JPEG
 * 189, OpenEXR DWAA 919, WebP 1677, GIF 2600, OpenEXR DWAB 3649, JPEG
 * 2000 47127 (267 bytes: its size hardly grows with the image).  Deflate
 * itself cannot pass 1032 bytes a byte.  2^16 passes all of them with
 * room, and holds a 913-byte file to 60 million values.
 */
#define VALUES_PER_BYTE ((uintmax_t)1 << 16)

/* A Radiance HDR scanline of n pixels at its smallest: flat when the
 * format allows no run lengths (fewer than 8 or more than 32767 pixels),
 * else the marker and each component in runs of 127. */
static uintmax_t
hdr_row_bytes(size_t n)
{
	uintmax_t flat = 4 * (uintmax_t)n, rle = 4 + 4 * 2 * (((uintmax_t)n + 126) / 127);

	if (n < 8 || n > 0x7fff)
		return flat;
	return rle < flat ? rle : flat;
}

int
rf__hdr_shape(const unsigned char *buf, size_t len, struct rf__hdr_shape *s)
{
	size_t i = 0, line, k;
	unsigned long v[2];
	char axis[2], sign[2];

	memset(s, 0, sizeof(*s));
	if (len < 2 || buf[0] != '#' || buf[1] != '?')
		return -1;
	/* the header's lines, up to the empty one */
	for (;;) {
		line = i;
		while (i < len && buf[i] != '\n')
			i++;
		if (i >= len)
			return -1;
		i++;
		if (i - line == 1)
			break;
	}
	/* "-Y N +X M" (or another orientation): N scanlines of M pixels */
	for (k = 0; k < 2; k++) {
		unsigned long n = 0;
		size_t digits = 0;

		while (i < len && buf[i] == ' ')
			i++;
		if (i + 2 > len || (buf[i] != '-' && buf[i] != '+') ||
		    (buf[i + 1] != 'X' && buf[i + 1] != 'Y'))
			return -1;
		sign[k] = (char)buf[i];
		axis[k] = (char)buf[i + 1];
		i += 2;
		while (i < len && buf[i] == ' ')
			i++;
		while (i < len && buf[i] >= '0' && buf[i] <= '9' && digits < 10) {
			n = n * 10 + (unsigned long)(buf[i++] - '0');
			digits++;
		}
		if (!digits || (i < len && buf[i] >= '0' && buf[i] <= '9'))
			return -1;
		v[k] = n;
	}
	(void)sign;
	while (i < len && (buf[i] == ' ' || buf[i] == '\r'))
		i++;
	if (i >= len || buf[i] != '\n' || axis[0] == axis[1])
		return -1;
	s->scanlines = v[0];
	s->length = v[1];
	s->data = i + 1;
	return 0;
}

/* The bytes a Radiance HDR file needs for its header's size, or 0 when
 * its header cannot be read here (the reader will say why). */
static uintmax_t
hdr_needs(const char *path, size_t *w, size_t *h)
{
	unsigned char buf[65536];
	struct rf__hdr_shape s;
	ssize_t n;
	int fd;

	if ((fd = open(path, O_RDONLY | O_CLOEXEC)) < 0)
		return 0;
	n = read(fd, buf, sizeof(buf));
	close(fd);
	if (n <= 0 || rf__hdr_shape(buf, (size_t)n, &s) < 0)
		return 0;
	*w = s.length;
	*h = s.scanlines;
	return rf__hdr_bytes(&s);
}

uintmax_t
rf__hdr_bytes(const struct rf__hdr_shape *s)
{
	uintmax_t row = hdr_row_bytes(s->length);

	if (s->scanlines && row > (UINTMAX_MAX - s->data) / s->scanlines)
		return UINTMAX_MAX;
	return s->data + row * s->scanlines;
}

int
rf__image_bounds(const char *path, const char *format, size_t w, size_t h, size_t nch,
                 char *err, size_t errlen)
{
	uintmax_t size, values, need = 0;
	struct stat st;
	size_t hw = 0, hh = 0;

	if (!w || !h || !nch || w > VALUES_MAX / nch || h > VALUES_MAX / (w * nch)) {
		rf__format(err, errlen, "'%s': a %zux%zu image of %zu channels is out of range",
		           path, w, h, nch);
		return RF_ETOOBIG;
	}
	if (stat(path, &st) < 0 || !S_ISREG(st.st_mode))
		return 0; /* the reader says why */
	size = (uintmax_t)st.st_size;
	values = (uintmax_t)w * h * nch;
	if (format && !strcmp(format, "hdr") && (need = hdr_needs(path, &hw, &hh)) > 0) {
		if (need > size) {
			rf__format(err, errlen, "'%s': a %zux%zu image of %zu channels is out "
			           "of range: its %ju bytes cannot hold it (%ju needed)", path,
			           hw, hh, nch, size, need);
			return RF_ETOOBIG;
		}
		return 0;
	}
	if (values / VALUES_PER_BYTE > size) {
		rf__format(err, errlen, "'%s': a %zux%zu image of %zu channels is out of range: "
		           "its %ju bytes cannot hold it", path, w, h, nch, size);
		return RF_ETOOBIG;
	}
	return 0;
}
