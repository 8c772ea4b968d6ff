/*
 * truthscore SHADED REFERENCE: the relative RMSE of R G B over the mask
 * eroded by one pixel per object, as ../shared/truth/README.md scores
 * (a pixel counts when it and its 8 neighbours lie on the same
 * reflective object): RMSE over pixels and channels / mean reference.
 * SHADED carries mask and objid; both are reflect streams of one frame.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/reflect.h"

static float *
load(const char *path, const rf_header **hp, rf_reader **rp)
{
	FILE *fp = fopen(path, "rb");
	const rf_header *h;
	float *px;

	if (!fp || rf_reader_open(rp, fp, path, NULL) < 0 || rf_reader_next_frame(*rp, &h) != 1) {
		fprintf(stderr, "truthscore: cannot read '%s'\n", path);
		exit(2);
	}
	px = malloc(rf_header_ncols(h) * rf_header_nrows(h) * rf_header_nchannels(h) *
	            sizeof(float));
	if (!px || rf_reader_read_rows(*rp, px, rf_header_nrows(h)) < 0) {
		fprintf(stderr, "truthscore: cannot read the rows of '%s'\n", path);
		exit(2);
	}
	*hp = h;
	return px;
}

static int
channel(const rf_header *h, const char *name)
{
	int c = rf_header_find_channel(h, name);

	if (c < 0) {
		fprintf(stderr, "truthscore: no channel '%s'\n", name);
		exit(2);
	}
	return c;
}

int
main(int argc, char **argv)
{
	const rf_header *ha, *hb;
	rf_reader *ra, *rb;
	float *a, *b;
	size_t w, h, na, nb, x, y, n = 0;
	double sum2 = 0, sum = 0;
	int c[3], cr[3], mask, obj, k, dx, dy;

	if (argc != 3) {
		fprintf(stderr, "usage: truthscore SHADED REFERENCE\n");
		return 2;
	}
	a = load(argv[1], &ha, &ra);
	b = load(argv[2], &hb, &rb);
	w = rf_header_ncols(ha);
	h = rf_header_nrows(ha);
	if (rf_header_ncols(hb) != w || rf_header_nrows(hb) != h) {
		fprintf(stderr, "truthscore: the images differ in size\n");
		return 2;
	}
	na = rf_header_nchannels(ha);
	nb = rf_header_nchannels(hb);
	mask = channel(ha, "mask");
	obj = channel(ha, "objid");
	for (k = 0; k < 3; k++) {
		c[k] = channel(ha, (const char[]){ "RGB"[k], 0 });
		cr[k] = channel(hb, (const char[]){ "RGB"[k], 0 });
	}
	for (y = 1; y + 1 < h; y++)
		for (x = 1; x + 1 < w; x++) {
			const float *p = a + (y * w + x) * na;
			int keep = p[mask] >= 0.5f;

			for (dy = -1; dy <= 1 && keep; dy++)
				for (dx = -1; dx <= 1 && keep; dx++) {
					const float *q = a + ((y + dy) * w + x + dx) * na;

					keep = q[mask] >= 0.5f && q[obj] == p[obj];
				}
			if (!keep)
				continue;
			for (k = 0; k < 3; k++) {
				double d = p[c[k]] - b[(y * w + x) * nb + cr[k]];

				sum2 += d * d;
				sum += b[(y * w + x) * nb + cr[k]];
			}
			n++;
		}
	if (!n) {
		fprintf(stderr, "truthscore: no pixel on a reflective object\n");
		return 2;
	}
	printf("%zu %.6f\n", n, sqrt(sum2 / (3.0 * n)) / (sum / (3.0 * n)));
	rf_reader_close(ra);
	rf_reader_close(rb);
	free(a);
	free(b);
	return 0;
}
