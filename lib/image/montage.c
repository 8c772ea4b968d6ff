/*
 * A labelled grid of pictures (reflect-montage(1)): colour cells display-
 * encoded as reflect-export encodes them, grey cells the same on one
 * channel, and the channels that are no colour made visible: a scalar
 * (a distance, a roughness, a weight) in false colour over its range with
 * a colour bar, a vector (a normal, a direction) as (v - lo)/(hi - lo)
 * per component.  Cells sit in slots the size of the largest, left to
 * right, top to bottom, a dark rule between them.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/image.h"

#define RULE 2
#define BAR 14 /* the colour bar's height, in pixels, at label scale 1 */

/* A perceptually ordered ramp, dark blue to yellow, through five stops. */
static void
ramp(float t, float rgb[3])
{
	static const float stops[5][3] = {
		{ 0.05f, 0.03f, 0.25f }, { 0.35f, 0.05f, 0.55f }, { 0.75f, 0.2f, 0.45f },
		{ 0.98f, 0.5f, 0.2f }, { 0.98f, 0.95f, 0.35f }
	};
	float x = (t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t) * 4.0f;
	int k = x >= 4.0f ? 3 : (int)x, c;

	x -= (float)k;
	for (c = 0; c < 3; c++)
		rgb[c] = stops[k][c] + x * (stops[k + 1][c] - stops[k][c]);
}

/* The finite range of channel c of a cell's pixels. */
static void
range(const struct rf_montage_cell *cell, size_t c, float *lo, float *hi)
{
	size_t i, n = cell->width * cell->height;

	*lo = INFINITY;
	*hi = -INFINITY;
	for (i = 0; i < n; i++) {
		float v = cell->pixels[i * cell->nchannels + c];

		if (isfinite(v)) {
			*lo = v < *lo ? v : *lo;
			*hi = v > *hi ? v : *hi;
		}
	}
	if (!(*lo <= *hi))
		*lo = *hi = 0.0f;
}

static void
put_cell(const struct rf_montage_cell *cell, const struct rf_montage_options *o,
         float *px, size_t width, size_t x0, size_t y0, size_t scale)
{
	const size_t w = cell->width, h = cell->height, nch = cell->nchannels;
	float lo = cell->lo, hi = cell->hi;
	size_t x, y, c;

	if (cell->map == RF_MONTAGE_FALSE && !cell->has_range)
		range(cell, 0, &lo, &hi);
	if (cell->map == RF_MONTAGE_VECTOR && !cell->has_range) {
		lo = -1.0f;
		hi = 1.0f;
	}
	for (y = 0; y < h; y++)
		for (x = 0; x < w; x++) {
			const float *p = cell->pixels + (y * w + x) * nch;
			float *q = px + ((y0 + y) * width + x0 + x) * 3;

			switch (cell->map) {
			case RF_MONTAGE_FALSE:
				ramp(hi > lo ? (p[0] - lo) / (hi - lo) : 0.5f, q);
				break;
			case RF_MONTAGE_VECTOR:
				for (c = 0; c < 3; c++) {
					float t = hi > lo ? (p[c < nch ? c : 0] - lo) / (hi - lo) : 0.5f;

					q[c] = isfinite(t) ? (t < 0 ? 0 : t > 1 ? 1 : t) : 0.0f;
				}
				break;
			case RF_MONTAGE_GREY:
				q[0] = q[1] = q[2] = p[0];
				rf_display_encode(q, 1, 3, 3, o->scale, o->tone, o->srgb);
				break;
			default:
				for (c = 0; c < 3; c++)
					q[c] = p[c < nch ? c : 0];
				rf_display_encode(q, 1, 3, 3, o->scale, o->tone, o->srgb);
				break;
			}
		}
	if (cell->map == RF_MONTAGE_FALSE && h > BAR * scale + 2) {
		/* the bar along the foot of the cell, its two ends labelled */
		char text[64];
		const size_t bar = BAR * scale;

		for (y = h - bar; y < h; y++)
			for (x = 0; x < w; x++)
				ramp((float)x / (float)(w > 1 ? w - 1 : 1),
				     px + ((y0 + y) * width + x0 + x) * 3);
		snprintf(text, sizeof(text), "%.3g", (double)lo);
		rf_image_label(px, width, y0 + h, x0, y0 + h - bar - 10 * scale, text, scale);
		snprintf(text, sizeof(text), "%.3g", (double)hi);
		rf_image_label(px, width, y0 + h,
		               x0 + (w > (strlen(text) + 2) * 6 * scale
		                     ? w - (strlen(text) + 2) * 6 * scale : 0),
		               y0 + h - bar - 10 * scale, text, scale);
	}
	if (cell->label && *cell->label)
		rf_image_label(px, width, y0 + h, x0, y0, cell->label, scale);
}

int
rf_montage(const struct rf_montage_cell *cells, size_t n,
           const struct rf_montage_options *o, float **out, size_t *width,
           size_t *height)
{
	size_t cols = o->columns && o->columns < n ? o->columns : n, rows, cw = 0, ch = 0;
	size_t k, scale;
	float *px;

	*out = NULL;
	if (!n || !cols)
		return RF_EINVAL;
	for (k = 0; k < n; k++) {
		if (!cells[k].width || !cells[k].height || !cells[k].nchannels ||
		    !cells[k].pixels)
			return RF_EINVAL;
		cw = cells[k].width > cw ? cells[k].width : cw;
		ch = cells[k].height > ch ? cells[k].height : ch;
	}
	rows = (n + cols - 1) / cols;
	*width = cols * cw + (cols - 1) * RULE;
	*height = rows * ch + (rows - 1) * RULE;
	/* The limits of a frame (reflect-stream(5)), before any is made. */
	if (*width > RF_FRAME_SIDE_MAX || *height > RF_FRAME_SIDE_MAX ||
	    *width * *height > RF_FRAME_PIXELS_MAX)
		return RF_ETOOBIG;
	if (!(px = calloc(*width * *height * 3, sizeof(float))))
		return RF_ENOMEM;
	scale = o->label_scale ? o->label_scale : ch / 90 ? ch / 90 : 1;
	for (k = 0; k < n; k++)
		put_cell(&cells[k], o, px, *width, (k % cols) * (cw + RULE),
		         (k / cols) * (ch + RULE), scale);
	*out = px;
	return 0;
}
