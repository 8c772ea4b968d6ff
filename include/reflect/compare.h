/*
 * libreflect: comparing two images value by value, as reflect-compare(1)
 * does: the statistics of the difference over the pixels that count,
 * the truth README's eroded mask, and a heat map.  Included by
 * reflect/reflect.h; a program may include either.
 */
#ifndef REFLECT_COMPARE_H
#define REFLECT_COMPARE_H

#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A picture to compare: a reflect stream's first frame (path "-": the
 * standard input) or an image file of any type the image layer reads,
 * told apart by the stream's magic, its pixels as floats, channels
 * interleaved, rows top first. */
typedef struct rf_picture rf_picture;

RF_EXTERN int rf_picture_read(rf_picture **p, const char *path, char *err, size_t errlen);
RF_EXTERN void rf_picture_destroy(rf_picture *p);
RF_EXTERN size_t rf_picture_width(const rf_picture *p);
RF_EXTERN size_t rf_picture_height(const rf_picture *p);
RF_EXTERN size_t rf_picture_nchannels(const rf_picture *p);
RF_EXTERN const char *rf_picture_channel(const rf_picture *p, size_t i);
/* The index of a channel, or RF_ECHANNEL. */
RF_EXTERN int rf_picture_find_channel(const rf_picture *p, const char *name);
RF_EXTERN const float *rf_picture_pixels(const rf_picture *p);

/* The pixels that count, keep[y width + x] = 1: those whose mask (every
 * stride floats from mask) is at least 0.5 and whose neighbours within
 * erode pixels (a square of 2 erode + 1) are on the mask too and, when
 * objid is not NULL, on the same object; pixels nearer the frame's edge
 * than erode do not count.  Erode 1 with objid is the path-traced
 * references' scoring mask (reflect-compare(1)). */
RF_EXTERN void rf_compare_mask(unsigned char *keep, size_t width, size_t height,
                               const float *mask, const float *objid, size_t stride,
                               unsigned erode);

/* The difference A - B of nch channels: A's channel k is a[a_col[k]] of
 * pixels a_stride floats apart, B's likewise. */
struct rf_compare_input {
	const float *a, *b;
	size_t a_stride, b_stride;
	const int *a_col, *b_col;
	size_t nch;
	size_t width, height;
	const unsigned char *keep; /* NULL: every pixel */
};

struct rf_compare_stats {
	size_t npixels;   /* pixels compared */
	size_t nvalues;   /* of them, values whose A and B are finite */
	size_t nonfinite; /* values where A or B is NaN or infinite */
	double rmse;      /* over the finite values */
	double mean_b;    /* the mean of B over the same values */
	double rel_rmse;  /* rmse / mean_b (+inf when mean_b is 0 and rmse is not) */
	double psnr;      /* 20 log10(peak / rmse), +inf for identical images */
	double max_error; /* the largest |A - B| (+inf with a value not finite) */
	size_t max_x, max_y, max_channel; /* where it is */
	size_t nover;     /* pixels with a value over the threshold (or not finite) */
	size_t nwarn;     /* the same over the warning threshold */
};

/* The statistics, with peak for PSNR, threshold for nover and warn for
 * nwarn, in one pass. */
RF_EXTERN void rf_compare_stats(struct rf_compare_stats *st, const struct rf_compare_input *in,
                                double peak, double threshold, double warn);

/* The width of a heat map of a width-pixel image: the image and, at its
 * right, the colour bar. */
RF_EXTERN size_t rf_compare_heatmap_width(size_t width, size_t height);
/* A heat map of the per-pixel error (the RMS of the channels' |A - B|),
 * 0 to scale, as display RGB (3 floats a pixel, rf_compare_heatmap_width
 * x height of them): a ramp from black through violet, red and orange to
 * pale yellow, magenta where a value is not finite, dark grey where the
 * pixel does not count; at the right, the colour bar labelled 0 and
 * scale. */
RF_EXTERN void rf_compare_heatmap(float *rgb, const struct rf_compare_input *in, double scale);

#ifdef __cplusplus
}
#endif

#endif
