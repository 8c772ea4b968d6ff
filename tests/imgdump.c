/* imgdump: prints an image as text through rf_image_read, for the tests.
 *
 *	imgdump [-8 | -16] FILE
 *
 * First line "WIDTH HEIGHT NCHANNELS", second line the channel names, then
 * one line per pixel (rows top first), values separated by spaces: as
 * floats (%.9g), or with -8 / -16 as the stored integers round(v * 255)
 * or round(v * 65535). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "reflect/reflect.h"

int
main(int argc, char **argv)
{
	const char *path;
	char err[1024];
	rf_image *img;
	const float *px;
	size_t w, h, n, i, c;
	double scale = 0;

	if (argc == 3 && !strcmp(argv[1], "-8"))
		scale = 255;
	else if (argc == 3 && !strcmp(argv[1], "-16"))
		scale = 65535;
	else if (argc != 2) {
		fprintf(stderr, "usage: imgdump [-8 | -16] FILE\n");
		return 1;
	}
	path = argv[argc - 1];
	if (rf_image_read(&img, path, err, sizeof(err)) < 0) {
		fprintf(stderr, "imgdump: %s\n", err);
		return 1;
	}
	w = rf_image_width(img);
	h = rf_image_height(img);
	n = rf_image_nchannels(img);
	px = rf_image_pixels(img);
	printf("%zu %zu %zu\n", w, h, n);
	for (c = 0; c < n; c++)
		printf("%s%s", c ? " " : "", rf_image_channel(img, c));
	printf("\n");
	for (i = 0; i < w * h; i++)
		for (c = 0; c < n; c++) {
			double v = px[i * n + c];

			if (scale > 0)
				printf("%.0f", floor(v * scale + 0.5));
			else
				printf("%.9g", v);
			putchar(c + 1 < n ? ' ' : '\n');
		}
	rf_image_destroy(img);
	return fflush(stdout) || ferror(stdout) ? 1 : 0;
}
