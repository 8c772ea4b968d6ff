/*
 * libFuzzer harness for the bounds an image header meets before the
 * image module reads it (lib/image/bounds.c): the Radiance HDR header as
 * the bounds parse it (its resolution line and where its data starts),
 * and the check the module calls back with the header's size.  The input
 * is written to a memory file, as the check reads a file.  What the check
 * lets through must be within 2^28 values and, for HDR, no more than the
 * file holds at its smallest coding; a refusal says why in one printable
 * line.  The module itself (OpenImageIO) is not fuzzed here.
 */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "image/readers.h"
#include "reflect/reflect.h"

#define HARNESS "fuzz-hdr"
#include "harness.h"

static void
check_refusal(int rc, const char *err)
{
	check(rc == RF_ETOOBIG, "a refusal that is not RF_ETOOBIG");
	check_message(err);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct rf__hdr_shape s;
	char path[64], err[1024] = "";
	size_t w = 0, h = 0, c = 0;
	int fd, rc;

	if ((fd = memfd_create("fuzz.hdr", 0)) < 0)
		return 0;
	if (write(fd, data, size) != (ssize_t)size) {
		close(fd);
		return 0;
	}
	snprintf(path, sizeof(path), "/proc/self/fd/%d", fd);
	if (rf__hdr_shape(data, size, &s) == 0) {
		check(s.data <= size, "the data starts past the end of the file");
		err[0] = '\0';
		rc = rf__image_bounds(path, "hdr", s.length, s.scanlines, 3, err, sizeof(err));
		if (rc == 0) {
			check(s.length && s.scanlines &&
			      s.length <= ((size_t)1 << 28) / 3 / s.scanlines,
			      "an HDR image past 2^28 values let through");
			check(rf__hdr_bytes(&s) <= size, "an HDR image its file cannot hold "
			      "let through");
		} else {
			check_refusal(rc, err);
		}
	}
	/* any other format: the size from the input's first bytes */
	if (size >= 6) {
		w = (size_t)data[0] << 8 | data[1];
		h = (size_t)data[2] << 8 | data[3];
		c = data[4] & 7;
		err[0] = '\0';
		rc = rf__image_bounds(path, data[5] & 1 ? "tiff" : NULL, w, h, c, err,
		                      sizeof(err));
		if (rc == 0)
			check(w && h && c && w * h * c <= ((size_t)1 << 28) &&
			      w * h * c / 65536 <= size, "an image past its bounds let through");
		else
			check_refusal(rc, err);
	}
	close(fd);
	return 0;
}
