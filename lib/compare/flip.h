/* Internal: FLIP's parts (lib/compare/flip.c), exported for the unit
 * tests alone (tests/unit/test-flip.c). */
#ifndef REFLECT_COMPARE_FLIP_H
#define REFLECT_COMPARE_FLIP_H

#include "reflect/reflect.h"

/* The filters at ppd pixels per degree, 2 radius + 1 taps each (radius
 * from rf__flip_*_radius), taps[k] at k - radius pixels.  The spatial
 * (contrast sensitivity) filters, one dimension of each separable part:
 * y (achromatic), cx (red-green), cz1 and cz2 (blue-yellow, a sum of two
 * Gaussians: the 2D kernel is cz1 (x) cz1 + cz2 (x) cz2); y's and cx's
 * taps sum to 1, and so do the blue-yellow kernel's in 2D.  The feature
 * filters: a Gaussian g (summing to 1) and its first and second
 * derivatives dg and ddg, whose positive taps sum to 1 and negative ones
 * to -1. */
RF_EXTERN int rf__flip_spatial_radius(double ppd);
RF_EXTERN int rf__flip_feature_radius(double ppd);
RF_EXTERN void rf__flip_spatial_filters(double ppd, float *y, float *cx, float *cz1, float *cz2);
RF_EXTERN void rf__flip_feature_filters(double ppd, float *g, float *dg, float *ddg);

/* Colour: linear sRGB (D65) to YCxCz (the opponent space of the spatial
 * filters: Y = 116 y - 16, Cx = 500 (x - y), Cz = 200 (y - z), x, y, z
 * relative to the white); YCxCz back to linear sRGB; linear sRGB to
 * CIELAB with the Hunt adjustment (a and b scaled by L / 100). */
RF_EXTERN void rf__flip_rgb_to_ycxcz(const float rgb[3], float ycc[3]);
RF_EXTERN void rf__flip_ycxcz_to_rgb(const float ycc[3], float rgb[3]);
RF_EXTERN void rf__flip_rgb_to_lab_hunt(const float rgb[3], float lab[3]);
/* The colour error of two Hunt-adjusted CIELAB colours: HyAB distance to
 * the power 0.7, remapped to [0, 1] (cmax: the green-blue distance,
 * rf__flip_cmax). */
RF_EXTERN float rf__flip_color_error(const float lab_a[3], const float lab_b[3], float cmax);
RF_EXTERN float rf__flip_cmax(void);

/* HDR-FLIP's tone mapper (ACES, as the HDR-FLIP paper fits it) of one
 * linear value; the value it maps to 0.85 (the top of the automatic
 * exposures); sRGB decoding of one display value. */
RF_EXTERN float rf__flip_aces(float x);
RF_EXTERN double rf__flip_aces_inverse_085(void);
RF_EXTERN float rf__flip_srgb_decode(float v);

#endif
