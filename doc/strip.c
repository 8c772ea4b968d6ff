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
 * with a built-in 5x9 bitmap font, SCALE pixels a font pixel (default:
 * the height / 90, at least 1).  The font is ours so that the picture is
 * the same on every machine, fonts installed or not.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "reflect/reflect.h"

#define GLYPH_W 5
#define GLYPH_H 9
#define RULE 2

/* Rows 0..8 of each glyph, '#' set; x-height rows 2..6, descenders 7..8. */
static const struct {
	char c;
	const char *rows[GLYPH_H];
} font[] = {
	{ 'a', { ".....", ".....", ".###.", "....#", ".####", "#...#", ".####", ".....", "....." } },
	{ 'b', { "#....", "#....", "####.", "#...#", "#...#", "#...#", "####.", ".....", "....." } },
	{ 'c', { ".....", ".....", ".####", "#....", "#....", "#....", ".####", ".....", "....." } },
	{ 'd', { "....#", "....#", ".####", "#...#", "#...#", "#...#", ".####", ".....", "....." } },
	{ 'e', { ".....", ".....", ".###.", "#...#", "#####", "#....", ".####", ".....", "....." } },
	{ 'f', { "..##.", ".#...", "####.", ".#...", ".#...", ".#...", ".#...", ".....", "....." } },
	{ 'g', { ".....", ".....", ".####", "#...#", "#...#", "#...#", ".####", "....#", ".###." } },
	{ 'h', { "#....", "#....", "####.", "#...#", "#...#", "#...#", "#...#", ".....", "....." } },
	{ 'i', { "..#..", ".....", ".##..", "..#..", "..#..", "..#..", ".###.", ".....", "....." } },
	{ 'j', { "...#.", ".....", "..##.", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.." } },
	{ 'k', { "#....", "#....", "#..#.", "#.#..", "##...", "#.#..", "#..#.", ".....", "....." } },
	{ 'l', { ".##..", "..#..", "..#..", "..#..", "..#..", "..#..", ".###.", ".....", "....." } },
	{ 'm', { ".....", ".....", "##.#.", "#.#.#", "#.#.#", "#.#.#", "#.#.#", ".....", "....." } },
	{ 'n', { ".....", ".....", "####.", "#...#", "#...#", "#...#", "#...#", ".....", "....." } },
	{ 'o', { ".....", ".....", ".###.", "#...#", "#...#", "#...#", ".###.", ".....", "....." } },
	{ 'p', { ".....", ".....", "####.", "#...#", "#...#", "#...#", "####.", "#....", "#...." } },
	{ 'q', { ".....", ".....", ".####", "#...#", "#...#", "#...#", ".####", "....#", "....#" } },
	{ 'r', { ".....", ".....", "#.##.", "##..#", "#....", "#....", "#....", ".....", "....." } },
	{ 's', { ".....", ".....", ".####", "#....", ".###.", "....#", "####.", ".....", "....." } },
	{ 't', { ".#...", ".#...", "####.", ".#...", ".#...", ".#...", "..##.", ".....", "....." } },
	{ 'u', { ".....", ".....", "#...#", "#...#", "#...#", "#...#", ".####", ".....", "....." } },
	{ 'v', { ".....", ".....", "#...#", "#...#", "#...#", ".#.#.", "..#..", ".....", "....." } },
	{ 'w', { ".....", ".....", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#.", ".....", "....." } },
	{ 'x', { ".....", ".....", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", ".....", "....." } },
	{ 'y', { ".....", ".....", "#...#", "#...#", "#...#", "#...#", ".####", "....#", ".###." } },
	{ 'z', { ".....", ".....", "#####", "...#.", "..#..", ".#...", "#####", ".....", "....." } },
	{ '0', { ".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###.", ".....", "....." } },
	{ '1', { "..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###.", ".....", "....." } },
	{ '2', { ".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####", ".....", "....." } },
	{ '3', { "####.", "....#", "....#", ".###.", "....#", "....#", "####.", ".....", "....." } },
	{ '4', { "...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#.", ".....", "....." } },
	{ '5', { "#####", "#....", "####.", "....#", "....#", "#...#", ".###.", ".....", "....." } },
	{ '6', { ".###.", "#....", "#....", "####.", "#...#", "#...#", ".###.", ".....", "....." } },
	{ '7', { "#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#...", ".....", "....." } },
	{ '8', { ".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###.", ".....", "....." } },
	{ '9', { ".###.", "#...#", "#...#", ".####", "....#", "....#", ".###.", ".....", "....." } },
	{ ' ', { ".....", ".....", ".....", ".....", ".....", ".....", ".....", ".....", "....." } },
	{ '.', { ".....", ".....", ".....", ".....", ".....", ".....", "..#..", ".....", "....." } },
	{ ',', { ".....", ".....", ".....", ".....", ".....", ".....", "..#..", ".#...", "....." } },
	{ ':', { ".....", ".....", ".....", "..#..", ".....", ".....", "..#..", ".....", "....." } },
	{ '=', { ".....", ".....", ".....", "#####", ".....", "#####", ".....", ".....", "....." } },
	{ '-', { ".....", ".....", ".....", ".....", ".###.", ".....", ".....", ".....", "....." } },
	{ '+', { ".....", ".....", "..#..", "..#..", "#####", "..#..", "..#..", ".....", "....." } },
	{ '_', { ".....", ".....", ".....", ".....", ".....", ".....", ".....", "#####", "....." } },
	{ '/', { "....#", "...#.", "...#.", "..#..", ".#...", ".#...", "#....", ".....", "....." } },
	{ '(', { "...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#.", ".....", "....." } },
	{ ')', { ".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#...", ".....", "....." } },
	{ '\'', { "..#..", "..#..", ".....", ".....", ".....", ".....", ".....", ".....", "....." } },
	{ '?', { ".###.", "#...#", "....#", "...#.", "..#..", ".....", "..#..", ".....", "....." } },
};

static const char *argv0 = "strip";

static void
die(const char *msg, const char *what)
{
	fprintf(stderr, "%s: %s%s%s\n", argv0, msg, what ? ": " : "", what ? what : "");
	exit(1);
}

static const char *const *
glyph(char c)
{
	size_t i;

	if (c >= 'A' && c <= 'Z')
		c = (char)(c - 'A' + 'a');
	for (i = 0; i < sizeof(font) / sizeof(font[0]); i++)
		if (font[i].c == c)
			return font[i].rows;
	return glyph('?');
}

/* Darkens a box behind the text, then draws it in white. */
static void
label(float *px, size_t width, size_t height, size_t x0, const char *text, size_t s)
{
	size_t len = strlen(text), pad = 3 * s, m = 4 * s, i, x, y;
	size_t bw = len * (GLYPH_W + 1) * s - s + 2 * pad, bh = GLYPH_H * s + 2 * pad;

	for (y = m; y < m + bh && y < height; y++)
		for (x = x0 + m; x < x0 + m + bw && x < width; x++)
			for (i = 0; i < 3; i++)
				px[(y * width + x) * 3 + i] *= 0.3f;
	for (i = 0; i < len; i++) {
		const char *const *g = glyph(text[i]);
		size_t gx = x0 + m + pad + i * (GLYPH_W + 1) * s, r, c;

		for (r = 0; r < GLYPH_H; r++)
			for (c = 0; c < GLYPH_W; c++) {
				if (g[r][c] != '#')
					continue;
				for (y = m + pad + r * s; y < m + pad + (r + 1) * s; y++)
					for (x = gx + c * s; x < gx + (c + 1) * s; x++)
						if (y < height && x < width)
							px[(y * width + x) * 3] = px[(y * width + x) * 3 + 1] =
							px[(y * width + x) * 3 + 2] = 1.0f;
			}
	}
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
		label(px, width, height, x0, argv[optind + k], scale);
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
