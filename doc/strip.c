/*
 * strip: display images side by side, each labelled, for ./demo and the
 * pictures of the documentation (not installed).
 *
 *	strip -o OUT [-s SCALE] LABEL=IMAGE...
 *
 * The images (already display-encoded: PNG, JPEG...) must have the same
 * height; their first three channels are laid left to right, a dark
 * two-pixel rule between them, and LABEL (up to the last '=', so that
 * "approx:clamp=0=a.png" works) is drawn in each one's top left corner
 * with the library's built-in font (rf_image_label), SCALE pixels a font
 * pixel (default: the height / 90, at least 1).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "reflect/reflect.h"

#define RULE 2

static const char *argv0 = "strip";

static void
die(const char *msg, const char *what)
{
	fprintf(stderr, "%s: %s%s%s\n", argv0, msg, what ? ": " : "", what ? what : "");
	exit(1);
}

int
main(int argc, char **argv)
{
	static const char *const names[] = { "R", "G", "B" };
	const char *out = NULL;
	char err[1024];
	rf_image **img;
	rf_image_writer *w;
	size_t n, k, width = 0, height = 0, scale = 0, x0 = 0, x, y;
	float *px;
	int c, type;

	while ((c = getopt(argc, argv, "o:s:")) != -1) {
		switch (c) {
		case 'o': out = optarg; break;
		case 's': scale = strtoul(optarg, NULL, 10); break;
		default: die("usage: strip -o OUT [-s SCALE] LABEL=IMAGE...", NULL);
		}
	}
	if (!out || optind >= argc)
		die("usage: strip -o OUT [-s SCALE] LABEL=IMAGE...", NULL);
	n = (size_t)(argc - optind);
	if (!(img = calloc(n, sizeof(*img))))
		die("out of memory", NULL);
	for (k = 0; k < n; k++) {
		char *eq = strrchr(argv[optind + k], '=');

		if (!eq)
			die("not LABEL=IMAGE", argv[optind + k]);
		if (rf_image_read(&img[k], eq + 1, err, sizeof(err)) < 0)
			die(err, NULL);
		if (rf_image_nchannels(img[k]) < 3)
			die("fewer than 3 channels", eq + 1);
		if (k && rf_image_height(img[k]) != height)
			die("the images differ in height", eq + 1);
		height = rf_image_height(img[k]);
		width += rf_image_width(img[k]) + (k ? RULE : 0);
	}
	if (!scale)
		scale = height / 90 ? height / 90 : 1;
	if (!(px = calloc(width * height * 3, sizeof(float))))
		die("out of memory", NULL);
	for (k = 0; k < n; k++) {
		size_t iw = rf_image_width(img[k]), nch = rf_image_nchannels(img[k]);
		const float *src = rf_image_pixels(img[k]);

		for (y = 0; y < height; y++)
			for (x = 0; x < iw; x++)
				memcpy(px + (y * width + x0 + x) * 3, src + (y * iw + x) * nch,
				       3 * sizeof(float));
		*strrchr(argv[optind + k], '=') = '\0';
		rf_image_label(px, width, height, x0, 0, argv[optind + k], scale);
		x0 += iw + RULE; /* the rule stays black (calloc) */
		rf_image_destroy(img[k]);
	}
	if ((type = rf_image_type_for_path(out)) < 0)
		die("no image type for that name", out);
	if (rf_image_writer_open(&w, out, width, height, 3, names, (enum rf_pixel_type)type,
	                         err, sizeof(err)) < 0)
		die(err, NULL);
	if (rf_image_writer_write_rows(w, 0, height, px) < 0)
		die(rf_image_writer_error(w), NULL);
	if (rf_image_writer_close(w, err, sizeof(err)) < 0)
		die(err, NULL);
	free(px);
	free(img);
	return 0;
}
