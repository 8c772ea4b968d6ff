/* Internal: copying interleaved pixels between layouts. */
#ifndef REFLECT_PIXELS_H
#define REFLECT_PIXELS_H

#include <stddef.h>
#include <string.h>

/*
 * Each of npix pixels of in_ncomp channels into the first in_ncomp of
 * out_ncomp >= in_ncomp: how a stage passes its input through.  The
 * channels after them are the stage's own outputs, every one of which it
 * writes.  Sixteen bytes at a time, because a memcpy or memset call per
 * pixel (a stream pixel is 80 to 120 bytes) costs more than the copy.
 */
static inline void
rf__widen_pixels(float *out, size_t out_ncomp, const float *in, size_t in_ncomp,
                 size_t npix)
{
	size_t x, c;

	for (x = 0; x < npix; x++, in += in_ncomp, out += out_ncomp) {
		for (c = 0; c + 4 <= in_ncomp; c += 4)
			memcpy(out + c, in + c, 4 * sizeof(float));
		for (; c < in_ncomp; c++)
			out[c] = in[c];
	}
}

/* A run of channels that lie side by side in one layout and in another:
 * how a stage gathers a plugin's inputs and scatters its outputs. */
struct rf__run {
	unsigned src, dst, len;
};

/* len >= 1 floats, len small: two fixed 16-byte copies cover 4 to 8 (they
 * overlap in the middle), so no call and no loop per float. */
static inline void
rf__copy_run(float *dst, const float *src, unsigned len)
{
	unsigned i;

	if (len < 4) {
		/* A channel, or the three of a vector: no loop either. */
		dst[0] = src[0];
		if (len > 1)
			dst[1] = src[1];
		if (len > 2)
			dst[2] = src[2];
		return;
	}
	if (len <= 8) {
		memcpy(dst, src, 16);
		memcpy(dst + len - 4, src + len - 4, 16);
		return;
	}
	for (i = 0; i + 4 <= len; i += 4)
		memcpy(dst + i, src + i, 16);
	for (; i < len; i++)
		dst[i] = src[i];
}

/* Runs of map (dst channel i <- src channel map[i], n of them), or of
 * its inverse with `scatter` (src channel i -> dst channel map[i]);
 * returns their number, at most n. */
static inline size_t
rf__channel_runs(const int *map, size_t n, int scatter, struct rf__run *runs)
{
	size_t i, k = 0;

	for (i = 0; i < n; i++) {
		unsigned a = scatter ? (unsigned)i : (unsigned)map[i];
		unsigned b = scatter ? (unsigned)map[i] : (unsigned)i;

		if (k && runs[k - 1].src + runs[k - 1].len == a &&
		    runs[k - 1].dst + runs[k - 1].len == b) {
			runs[k - 1].len++;
			continue;
		}
		runs[k].src = a;
		runs[k].dst = b;
		runs[k].len = 1;
		k++;
	}
	return k;
}

#endif
