/* What the image harnesses (fuzz-exr.c, fuzz-png.c) share: the input as
 * a file, read by libreflect's own reader, never the image module. */
#ifndef REFLECT_FUZZ_IMAGE_HARNESS_H
#define REFLECT_FUZZ_IMAGE_HARNESS_H

#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "reflect/image.h"

static void
image_check(const char *name, int cond, const char *what)
{
	if (!cond) {
		fprintf(stderr, "%s: %s\n", name, what);
		abort();
	}
}

/* Reads data as an image file: one that reads is within the bounds
 * (2^28 values, every pixel there, every channel named); a refusal says
 * why in one printable line.  The module is never loaded: a file the
 * native reader leaves to it is refused as the module missing. */
static void
image_run(const char *name, const uint8_t *data, size_t size)
{
	char path[64], err[1024] = "";
	volatile float sum = 0;
	size_t w, h, n, i;
	rf_image *img;
	int fd;

	setenv("REFLECT_IMAGE_MODULE", "/nonexistent/reflect-oiio.so", 1);
	if ((fd = memfd_create(name, 0)) < 0)
		return;
	if (write(fd, data, size) != (ssize_t)size) {
		close(fd);
		return;
	}
	snprintf(path, sizeof(path), "/proc/self/fd/%d", fd);
	if (rf_image_read(&img, path, err, sizeof(err)) < 0) {
		image_check(name, err[0] != '\0', "an error without a message");
		for (i = 0; err[i]; i++)
			image_check(name, (unsigned char)err[i] >= 0x20 && err[i] != 0x7f,
			            "a control character in a message");
		close(fd);
		return;
	}
	w = rf_image_width(img);
	h = rf_image_height(img);
	n = rf_image_nchannels(img);
	image_check(name, w && h && n, "an empty image read");
	image_check(name, w <= ((size_t)1 << 28) / n && h <= ((size_t)1 << 28) / (w * n),
	            "an image past 2^28 values read");
	image_check(name, w * h * n / 65536 <= size,
	            "more values than the file can hold");
	for (i = 0; i < n; i++)
		image_check(name, rf_image_channel(img, i) != NULL, "a channel without a name");
	/* every value is there (the sanitizers see one that is not) */
	for (i = 0; i < w * h * n; i++)
		sum += rf_image_pixels(img)[i];
	(void)sum;
	rf_image_destroy(img);
	close(fd);
}

#endif
