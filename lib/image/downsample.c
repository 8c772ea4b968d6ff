/*
 * Resolving a supersampled frame: a frame f times larger than the picture
 * (reflect-gbuffer --supersample=f) becomes the picture, each pixel
 * filtered from the samples around it.
 *
 * The filter is separable, so rows are filtered across as they arrive and
 * kept, already f times narrower, in a ring just deep enough for one
 * output row's vertical taps: a 1080p picture supersampled 4 times holds
 * 4 narrow rows of 1920 pixels for the box and 10 for the default
 * Gaussian, where the whole frame would be 33 million samples.
 * Weights are normalised over the samples inside the frame, so a constant
 * stays constant at the borders too.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/image.h"

/* One output coordinate's taps: samples first .. first+count-1. */
struct taps {
	size_t first, count;
	size_t weight; /* index of the first weight */
};

struct rf_downsampler {
	size_t width, height, nch, factor;
	size_t out_width, out_height;
	unsigned char *nearest; /* per channel: the centre sample, not the filter */
	struct taps *tx, *ty;
	float *wx, *wy;
	size_t ring_rows;
	size_t burst;   /* output rows the last input row can complete at once */
	float *ring;    /* ring_rows narrow rows, out_width * nch each */
	size_t in_row;  /* input rows received */
	size_t out_row; /* output rows written */
};

/* The taps of every output coordinate along an axis of n samples. */
static int
make_taps(struct taps **taps, float **weights, size_t n, size_t factor,
          enum rf_resolve_filter filter, double sigma, size_t *widest)
{
	size_t nout = n / factor, x, s, lo, hi, k = 0, span;
	double radius = filter == RF_RESOLVE_BOX ? 0.5 : 3 * sigma;
	struct taps *t;
	float *w;

	/* Samples within radius output pixels of a centre: at most this many. */
	span = filter == RF_RESOLVE_BOX ? factor
	                                : (size_t)ceil(2 * radius * (double)factor) + 1;
	if (!(t = calloc(nout, sizeof(*t))) || !(w = calloc(nout * span, sizeof(*w)))) {
		free(t);
		return RF_ENOMEM;
	}
	*widest = 0;
	for (x = 0; x < nout; x++) {
		double centre = (double)x + 0.5, sum = 0;

		if (filter == RF_RESOLVE_BOX) {
			lo = x * factor;
			hi = lo + factor;
		} else {
			/* Sample s sits at (s + 0.5)/factor output pixels. */
			double a = (centre - radius) * (double)factor - 0.5;
			double b = (centre + radius) * (double)factor - 0.5;

			lo = a <= 0 ? 0 : (size_t)ceil(a);
			hi = b < 0 ? 0 : (size_t)floor(b) + 1;
			if (hi > n)
				hi = n;
			if (hi - lo > span)
				hi = lo + span;
		}
		t[x].first = lo;
		t[x].count = hi - lo;
		t[x].weight = k;
		for (s = lo; s < hi; s++) {
			double d = ((double)s + 0.5) / (double)factor - centre;
			double v = filter == RF_RESOLVE_BOX ? 1 : exp(-d * d / (2 * sigma * sigma));

			w[k + s - lo] = (float)v;
			sum += v;
		}
		for (s = lo; s < hi; s++)
			w[k + s - lo] = (float)(w[k + s - lo] / sum);
		k += hi - lo;
		if (hi - lo > *widest)
			*widest = hi - lo;
	}
	*taps = t;
	*weights = w;
	return 0;
}

int
rf_downsampler_create(rf_downsampler **dp, size_t width, size_t height, size_t nch,
                      size_t factor, enum rf_resolve_filter filter, double sigma,
                      const unsigned char *nearest)
{
	rf_downsampler *d;
	size_t widest_x, widest_y;
	int rc;

	*dp = NULL;
	if (!factor || !nch || !width || !height || width % factor || height % factor ||
	    (filter != RF_RESOLVE_BOX && filter != RF_RESOLVE_GAUSSIAN) ||
	    (filter == RF_RESOLVE_GAUSSIAN &&
	     !(sigma >= RF_RESOLVE_SIGMA_MIN && sigma <= RF_RESOLVE_SIGMA_MAX)))
		return RF_EINVAL;
	if (!(d = calloc(1, sizeof(*d))))
		return RF_ENOMEM;
	d->width = width;
	d->height = height;
	d->nch = nch;
	d->factor = factor;
	d->out_width = width / factor;
	d->out_height = height / factor;
	if (!(d->nearest = calloc(nch, 1))) {
		rf_downsampler_destroy(d);
		return RF_ENOMEM;
	}
	if (nearest)
		memcpy(d->nearest, nearest, nch);
	if ((rc = make_taps(&d->tx, &d->wx, width, factor, filter, sigma, &widest_x)) < 0 ||
	    (rc = make_taps(&d->ty, &d->wy, height, factor, filter, sigma, &widest_y)) < 0) {
		rf_downsampler_destroy(d);
		return rc;
	}
	/* The centre sample of an output row is one of its taps. */
	d->ring_rows = widest_y;
	/* At the bottom, the rows whose taps the frame's end clips all
	 * complete with its last row. */
	d->burst = filter == RF_RESOLVE_BOX ? 0 : (size_t)ceil(3 * sigma) + 1;
	if (!(d->ring = malloc(d->ring_rows * d->out_width * nch * sizeof(float)))) {
		rf_downsampler_destroy(d);
		return RF_ENOMEM;
	}
	*dp = d;
	return 0;
}

void
rf_downsampler_destroy(rf_downsampler *d)
{
	if (!d)
		return;
	free(d->nearest);
	free(d->tx);
	free(d->ty);
	free(d->wx);
	free(d->wy);
	free(d->ring);
	free(d);
}

size_t
rf_downsampler_width(const rf_downsampler *d)
{
	return d->out_width;
}

size_t
rf_downsampler_height(const rf_downsampler *d)
{
	return d->out_height;
}

size_t
rf_downsampler_max_rows(const rf_downsampler *d, size_t nrows)
{
	size_t n = nrows / d->factor + 2 + d->burst;

	return n < d->out_height ? n : d->out_height;
}

/* One input row, filtered across into its ring slot. */
static void
narrow_row(rf_downsampler *d, const float *in, float *out)
{
	size_t nch = d->nch, half = d->factor / 2, x, s, c;

	for (x = 0; x < d->out_width; x++) {
		const struct taps *t = &d->tx[x];
		const float *w = d->wx + t->weight;
		const float *src = in + t->first * nch;
		float *dst = out + x * nch;

		for (c = 0; c < nch; c++)
			dst[c] = 0;
		for (s = 0; s < t->count; s++)
			for (c = 0; c < nch; c++)
				dst[c] += w[s] * src[s * nch + c];
		for (c = 0; c < nch; c++)
			if (d->nearest[c])
				dst[c] = in[(x * d->factor + half) * nch + c];
	}
}

static const float *
ring_row(const rf_downsampler *d, size_t row)
{
	return d->ring + (row % d->ring_rows) * d->out_width * d->nch;
}

/* Output row y from its taps, all of them in the ring. */
static void
resolve_row(const rf_downsampler *d, size_t y, float *out)
{
	const struct taps *t = &d->ty[y];
	const float *w = d->wy + t->weight;
	size_t n = d->out_width * d->nch, s, i, c;
	const float *centre = ring_row(d, y * d->factor + d->factor / 2);

	for (i = 0; i < n; i++)
		out[i] = 0;
	for (s = 0; s < t->count; s++) {
		const float *src = ring_row(d, t->first + s);

		for (i = 0; i < n; i++)
			out[i] += w[s] * src[i];
	}
	for (i = 0; i < d->out_width; i++)
		for (c = 0; c < d->nch; c++)
			if (d->nearest[c])
				out[i * d->nch + c] = centre[i * d->nch + c];
}

int
rf_downsampler_push(rf_downsampler *d, const float *rows, size_t nrows, float *out,
                    size_t *nout)
{
	size_t in_n = d->width * d->nch, out_n = d->out_width * d->nch, r;

	*nout = 0;
	if (nrows > d->height - d->in_row)
		return RF_EINVAL;
	for (r = 0; r < nrows; r++) {
		size_t row = d->in_row++;

		narrow_row(d, rows + r * in_n,
		           d->ring + (row % d->ring_rows) * out_n);
		/* Every output row whose last tap has arrived. */
		while (d->out_row < d->out_height) {
			const struct taps *t = &d->ty[d->out_row];

			if (t->first + t->count > d->in_row)
				break;
			resolve_row(d, d->out_row++, out + *nout * out_n);
			++*nout;
		}
	}
	return 0;
}
