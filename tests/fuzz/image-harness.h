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
#include "harness.h"

/* Reads data as an image file: one that reads is within the bounds
 * (2^28 values, every pixel there, every channel named); a refusal says
 * why in one printable line.  The module is never loaded: a file the
 * native reader leaves to it is refused as the module missing. */
static void
image_run(const uint8_t *data, size_t size)
{
	char path[64], err[1024] = "";
	volatile float sum = 0;
	size_t w, h, n, i;
	rf_image *img;
	int fd;

	setenv("REFLECT_IMAGE_MODULE", "/nonexistent/reflect-oiio.so", 1);
	if ((fd = memfd_create(HARNESS, 0)) < 0)
		return;
	if (write(fd, data, size) != (ssize_t)size) {
		close(fd);
		return;
	}
	snprintf(path, sizeof(path), "/proc/self/fd/%d", fd);
	if (rf_image_read(&img, path, err, sizeof(err)) < 0) {
		check_message(err);
		close(fd);
		return;
	}
	w = rf_image_width(img);
	h = rf_image_height(img);
	n = rf_image_nchannels(img);
	check(w && h && n, "an empty image read");
	check(w <= ((size_t)1 << 28) / n && h <= ((size_t)1 << 28) / (w * n),
	      "an image past 2^28 values read");
	check(w * h * n / 65536 <= size, "more values than the file can hold");
	for (i = 0; i < n; i++)
		check(rf_image_channel(img, i) != NULL, "a channel without a name");
	/* every value is there (the sanitizers see one that is not) */
	for (i = 0; i < w * h * n; i++)
		sum += rf_image_pixels(img)[i];
	(void)sum;
	rf_image_destroy(img);
	close(fd);
}

#endif
