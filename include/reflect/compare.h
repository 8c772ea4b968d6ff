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
/* Whether the picture's colour is display-encoded sRGB (its file says
 * so: a PNG, a JPEG), not linear (a stream, an OpenEXR file). */
RF_EXTERN int rf_picture_srgb(const rf_picture *p);

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

/* FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating
 * Images", HPG 2020) and HDR-FLIP (Andersson et al., "Visualizing and
 * Communicating Errors in Rendered Images", Ray Tracing Gems II, 2021):
 * the difference a viewer sees flipping between A (the test) and B (the
 * reference), 0 to 1 a pixel.  The viewing conditions are pixels per
 * degree of visual angle: rf_flip_ppd of a monitor distance metres
 * away, width metres and resolution pixels wide; the published default,
 * 0.7 m from a 0.7 m wide 3840-pixel monitor, is RF_FLIP_PPD_DEFAULT
 * (about 67). */
RF_EXTERN double rf_flip_ppd(double distance, double width, double resolution);
#define RF_FLIP_PPD_DEFAULT rf_flip_ppd(0.7, 0.7, 3840.0)

struct rf_flip_options {
	int hdr;             /* HDR-FLIP (1) or LDR-FLIP (0) */
	int a_srgb, b_srgb;  /* A's (B's) colour is display-encoded sRGB (a PNG), not linear */
	double ppd;          /* pixels per degree */
	double start, stop;  /* HDR-FLIP's exposures in stops, start <= stop */
	int nexposures;      /* HDR-FLIP's count of exposures, start to stop; 1: start alone */
	int nthreads;        /* threads over row blocks (1: the caller's alone) */
};

/* HDR-FLIP's automatic exposures from B's luminance: from the stop that
 * brings B's brightest pixel to 0.85 after tone mapping to that which
 * brings its median there, and their count, max(2, ceil(stop - start)).
 * RF_EINVAL when B's median (the upper one of an even count) or largest
 * luminance is not above 0 (more than half the picture black: give the
 * exposures). */
RF_EXTERN int rf_flip_exposures(const struct rf_compare_input *in, double *start, double *stop,
                                int *count);

/* FLIP per pixel, width x height floats into error, over every pixel
 * (in->keep is for the caller's statistics; the filters see the whole
 * picture); the channels: in->nch 3, linear RGB (or display sRGB as o
 * says), every value finite.  LDR-FLIP clamps colour to [0, 1]; HDR-FLIP
 * takes the largest LDR-FLIP over the exposures of the tone-mapped
 * pictures.  0, or RF_EINVAL (not 3 channels, bad options), RF_ENOMEM. */
RF_EXTERN int rf_compare_flip(float *error, const struct rf_flip_options *o,
                              const struct rf_compare_input *in);
/* FLIP's figures over the pixels that count (keep NULL: every pixel):
 * the mean, the largest and where it is, the pixels over threshold and
 * over warn. */
struct rf_flip_stats {
	size_t npixels;
	double mean;
	double max_error;
	size_t max_x, max_y;
	size_t nover, nwarn;
};
RF_EXTERN void rf_flip_stats(struct rf_flip_stats *st, const float *error, size_t width,
                             size_t height, const unsigned char *keep, double threshold,
                             double warn);
/* The error map, as display RGB (3 floats a pixel, width x height):
 * magma (rf_flip_magma), dark grey where the pixel does not count. */
RF_EXTERN void rf_flip_heatmap(float *rgb, const float *error, size_t width, size_t height,
                               const unsigned char *keep);
/* The magma colour map (of matplotlib, by Nathaniel J. Smith and Stefan
 * van der Walt, CC0) at 256 steps, as FLIP's error maps show it: the
 * display RGB of error (0 to 1, nearest step) into rgb[3]. */
RF_EXTERN void rf_flip_magma(float error, float rgb[3]);

#ifdef __cplusplus
}
#endif

#endif
