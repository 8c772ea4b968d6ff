/*
 * Comparing two images (reflect/compare.h): the statistics of A - B over
 * the pixels that count, the eroded mask of ../shared/truth's scoring,
 * and a heat map with its colour bar.  Sums in double: a 1080p frame has
 * six million values, and float sums would lose their last digits.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "reflect/reflect.h"

void
rf_compare_mask(unsigned char *keep, size_t width, size_t height, const float *mask,
                const float *objid, size_t stride, unsigned erode)
{
	size_t x, y;

	for (y = 0; y < height; y++)
		for (x = 0; x < width; x++) {
			const size_t p = y * width + x;
			const size_t y0 = y > erode ? y - erode : 0, x0 = x > erode ? x - erode : 0;
			const size_t y1 = y + erode < height ? y + erode : height - 1;
			const size_t x1 = x + erode < width ? x + erode : width - 1;
			/* the whole neighbourhood must be in the frame, as the
			 * truth README's scoring has it */
			unsigned char k = mask[p * stride] >= 0.5f && y >= erode && x >= erode &&
			                  y + erode < height && x + erode < width;
			size_t qx, qy;

			for (qy = y0; k && qy <= y1; qy++)
				for (qx = x0; k && qx <= x1; qx++) {
					const size_t q = qy * width + qx;

					k = mask[q * stride] >= 0.5f &&
					    (!objid || objid[q * stride] == objid[p * stride]);
				}
			keep[p] = k;
		}
}

void
rf_compare_stats(struct rf_compare_stats *st, const struct rf_compare_input *in, double peak,
                 double threshold, double warn)
{
	double sum2 = 0.0, sumb = 0.0;
	size_t x, y, k;

	memset(st, 0, sizeof(*st));
	for (y = 0; y < in->height; y++)
		for (x = 0; x < in->width; x++) {
			const size_t p = y * in->width + x;
			const float *a = in->a + p * in->a_stride, *b = in->b + p * in->b_stride;
			int over = 0, warned = 0;

			if (in->keep && !in->keep[p])
				continue;
			st->npixels++;
			for (k = 0; k < in->nch; k++) {
				const double va = a[in->a_col[k]], vb = b[in->b_col[k]];
				double d;

				if (!isfinite(va) || !isfinite(vb)) {
					st->nonfinite++;
					over = warned = 1;
					if (st->max_error < INFINITY) {
						st->max_error = INFINITY;
						st->max_x = x;
						st->max_y = y;
						st->max_channel = k;
					}
					continue;
				}
				d = fabs(va - vb);
				st->nvalues++;
				sum2 += d * d;
				sumb += vb;
				over |= d > threshold;
				warned |= d > warn;
				if (d > st->max_error) {
					st->max_error = d;
					st->max_x = x;
					st->max_y = y;
					st->max_channel = k;
				}
			}
			st->nover += (size_t)over;
			st->nwarn += (size_t)warned;
		}
	if (st->nvalues) {
		st->rmse = sqrt(sum2 / (double)st->nvalues);
		st->mean_b = sumb / (double)st->nvalues;
	}
	st->rel_rmse = st->mean_b != 0.0 ? st->rmse / fabs(st->mean_b)
	                                 : (st->rmse > 0.0 ? INFINITY : 0.0);
	st->psnr = st->rmse > 0.0 ? 20.0 * log10(peak / st->rmse) : INFINITY;
}

/* Columns of the colour bar and its margin. */
#define BAR_GAP 4
#define BAR_WIDTH 16

/* Font pixels a label pixel: 2 on pictures of 180 rows or more. */
static size_t
label_scale(size_t height)
{
	return height >= 180 ? 2 : 1;
}

size_t
rf_compare_heatmap_width(size_t width, size_t height)
{
	/* room for a label of 8 characters (%.3g's longest: 1.23e-05) */
	return width + BAR_GAP + BAR_WIDTH + (8 * 6 + 8) * label_scale(height);
}

/* The ramp at t in [0, 1]: control points of our own choosing, dark to
 * light so that it reads in grey too. */
static void
ramp(double t, float rgb[3])
{
	static const float stops[6][3] = {
		{ 0.00f, 0.00f, 0.02f }, { 0.25f, 0.05f, 0.45f }, { 0.65f, 0.10f, 0.40f },
		{ 0.92f, 0.30f, 0.10f }, { 0.99f, 0.70f, 0.15f }, { 0.99f, 0.98f, 0.75f },
	};
	double s;
	int i, k;

	t = t > 0.0 ? (t < 1.0 ? t : 1.0) : 0.0;
	s = t * 5.0;
	i = (int)s;
	if (i > 4)
		i = 4;
	s -= i;
	for (k = 0; k < 3; k++)
		rgb[k] = (float)(stops[i][k] + s * (stops[i + 1][k] - stops[i][k]));
}

void
rf_compare_heatmap(float *rgb, const struct rf_compare_input *in, double scale)
{
	const size_t w = in->width, h = in->height, ow = rf_compare_heatmap_width(w, h);
	const size_t ls = label_scale(h);
	char text[32];
	size_t x, y, k;

	for (y = 0; y < h; y++) {
		float *row = rgb + y * ow * 3;

		for (x = 0; x < ow * 3; x++)
			row[x] = 0.0f;
		for (x = 0; x < w; x++) {
			const size_t p = y * w + x;
			const float *a = in->a + p * in->a_stride, *b = in->b + p * in->b_stride;
			double e = 0.0;
			int bad = 0;

			if (in->keep && !in->keep[p]) {
				row[3 * x] = row[3 * x + 1] = row[3 * x + 2] = 0.15f;
				continue;
			}
			for (k = 0; k < in->nch; k++) {
				const double d = (double)a[in->a_col[k]] - b[in->b_col[k]];

				bad |= !isfinite(d);
				e += d * d;
			}
			if (bad) {
				row[3 * x] = row[3 * x + 2] = 1.0f;
				continue;
			}
			ramp(scale > 0.0 ? sqrt(e / (double)in->nch) / scale : 0.0, row + 3 * x);
		}
		/* the bar: scale at the top, 0 at the bottom */
		for (x = w + BAR_GAP; x < w + BAR_GAP + BAR_WIDTH; x++)
			ramp(h > 1 ? 1.0 - (double)y / (double)(h - 1) : 1.0, row + 3 * x);
	}
	snprintf(text, sizeof(text), "%.3g", scale);
	rf_image_label(rgb, ow, h, w + BAR_GAP + BAR_WIDTH - 3 * ls, 0, text, ls);
	rf_image_label(rgb, ow, h, w + BAR_GAP + BAR_WIDTH - 3 * ls,
	               h > (9 + 14) * ls ? h - (9 + 14) * ls : 0, "0", ls);
}
