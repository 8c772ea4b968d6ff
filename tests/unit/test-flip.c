/* FLIP's parts by hand: the colour transforms on known colours, the
 * filters' normalisation, the remap's ends, the tone mapper, and flat
 * pictures, whose FLIP is their colour error alone. */
#include <math.h>
#include <stdlib.h>

#include "compare/flip.h" /* the parts: no public interface */
#include "reflect/reflect.h"
#include "tap.h"

#define NEAR(a, b, tol) ASSERT(fabs((double)(a) - (double)(b)) <= (tol))

static void
test_ycxcz(void)
{
	static const float white[3] = { 1, 1, 1 }, black[3] = { 0, 0, 0 };
	static const float c[3] = { 0.8f, 0.3f, 0.1f };
	float ycc[3], back[3];
	int k;

	/* the white is Y 100 with no chroma, black -16 */
	rf__flip_rgb_to_ycxcz(white, ycc);
	NEAR(ycc[0], 100.0, 1e-4);
	NEAR(ycc[1], 0.0, 1e-4);
	NEAR(ycc[2], 0.0, 1e-4);
	rf__flip_rgb_to_ycxcz(black, ycc);
	NEAR(ycc[0], -16.0, 1e-6);
	/* there and back */
	rf__flip_rgb_to_ycxcz(c, ycc);
	rf__flip_ycxcz_to_rgb(ycc, back);
	for (k = 0; k < 3; k++)
		NEAR(back[k], c[k], 1e-5);
}

static void
test_lab(void)
{
	static const float grey[3] = { 0.18f, 0.18f, 0.18f }, white[3] = { 1, 1, 1 };
	float lab[3];

	/* L = 116 cbrt(0.18) - 16, greys have no a or b */
	rf__flip_rgb_to_lab_hunt(grey, lab);
	NEAR(lab[0], 49.496108, 1e-4);
	NEAR(lab[1], 0.0, 1e-4);
	NEAR(lab[2], 0.0, 1e-4);
	rf__flip_rgb_to_lab_hunt(white, lab);
	NEAR(lab[0], 100.0, 1e-4);
}

static void
test_remap(void)
{
	static const float green[3] = { 0, 1, 0 }, blue[3] = { 0, 0, 1 };
	const float cmax = rf__flip_cmax();
	float g[3], b[3], l[3];

	/* the HyAB distance of Hunt-adjusted green and blue, ^0.7 */
	NEAR(cmax, 41.276098, 1e-3);
	rf__flip_rgb_to_lab_hunt(green, g);
	rf__flip_rgb_to_lab_hunt(blue, b);
	NEAR(rf__flip_color_error(g, b, cmax), 1.0, 1e-6);
	NEAR(rf__flip_color_error(g, g, cmax), 0.0, 0.0);
	/* the knee: pc cmax maps to pt, from either side */
	l[0] = 0;
	l[1] = 0;
	l[2] = 0;
	g[0] = (float)pow(0.4 * cmax, 1.0 / 0.7);
	g[1] = g[2] = 0;
	NEAR(rf__flip_color_error(g, l, cmax), 0.95, 1e-5);
}

static double
sum(const float *f, int n, int sign)
{
	double s = 0;
	int k;

	for (k = 0; k < n; k++)
		if (!sign || (sign > 0 && f[k] > 0) || (sign < 0 && f[k] < 0))
			s += f[k];
	return s;
}

static void
test_filters(void)
{
	const double ppd = rf_flip_ppd(0.7, 0.7, 3840);
	const int rs = rf__flip_spatial_radius(ppd), rf = rf__flip_feature_radius(ppd);
	float y[64], cx[64], cz1[64], cz2[64], g[64], dg[64], ddg[64];
	double s1, s2;
	int k;

	NEAR(ppd, 67.020643, 1e-5);
	/* 3 sqrt(0.04 / (2 pi^2)) 67.02 = 9.05; 3 (0.5 0.082 67.02) = 8.24 */
	ASSERT_EQ(rs, 10);
	ASSERT_EQ(rf, 9);
	rf__flip_spatial_filters(ppd, y, cx, cz1, cz2);
	NEAR(sum(y, 2 * rs + 1, 0), 1.0, 1e-6);
	NEAR(sum(cx, 2 * rs + 1, 0), 1.0, 1e-6);
	s1 = sum(cz1, 2 * rs + 1, 0);
	s2 = sum(cz2, 2 * rs + 1, 0);
	NEAR(s1 * s1 + s2 * s2, 1.0, 1e-6);
	for (k = 0; k < rs; k++) {
		NEAR(y[k], y[2 * rs - k], 0.0);
		ASSERT(y[k] < y[k + 1]);
	}
	rf__flip_feature_filters(ppd, g, dg, ddg);
	NEAR(sum(g, 2 * rf + 1, 0), 1.0, 1e-6);
	NEAR(sum(dg, 2 * rf + 1, 1), 1.0, 1e-6);
	NEAR(sum(dg, 2 * rf + 1, -1), -1.0, 1e-6);
	NEAR(sum(ddg, 2 * rf + 1, 1), 1.0, 1e-6);
	NEAR(sum(ddg, 2 * rf + 1, -1), -1.0, 1e-6);
	for (k = 0; k <= rf; k++) {
		NEAR(dg[k], -dg[2 * rf - k], 0.0);
		NEAR(ddg[k], ddg[2 * rf - k], 0.0);
	}
	ASSERT(dg[rf] == 0.0f);
	/* negative within a standard deviation (2.75 pixels), positive
	 * beyond */
	ASSERT(ddg[rf - 2] < 0 && ddg[rf - 3] > 0);
}

static void
test_tone(void)
{
	NEAR(rf__flip_aces(0.0f), 0.0, 0.0);
	NEAR(rf__flip_aces_inverse_085(), 2.1188723, 1e-6);
	NEAR(rf__flip_aces((float)rf__flip_aces_inverse_085()), 0.85, 1e-6);
	NEAR(rf__flip_aces(1e6f), 2.51 / 2.43, 1e-4);
	NEAR(rf__flip_srgb_decode(0.0f), 0.0, 0.0);
	NEAR(rf__flip_srgb_decode(1.0f), 1.0, 1e-6);
	NEAR(rf__flip_srgb_decode(0.5f), 0.21404114, 1e-6);
}

/* Flat pictures of colours a and b, 9 x 7, through rf_compare_flip. */
static void
flat(float *error, const float a[3], const float b[3], int hdr, double start)
{
	static const int col[3] = { 0, 1, 2 };
	struct rf_flip_options o = { hdr, 0, 0, 67.0, start, start, 1, 2 };
	struct rf_compare_input in = { a, b, 0, 0, col, col, 3, 9, 7, NULL };

	ASSERT(rf_compare_flip(error, &o, &in) == 0);
}

static void
test_constant(void)
{
	static const float green[3] = { 0, 1, 0 }, blue[3] = { 0, 0, 1 };
	static const float black[3] = { 0, 0, 0 }, white[3] = { 1, 1, 1 };
	float e[63];
	int i;

	/* no edges or points: FLIP is the remapped colour error alone, the
	 * same at every pixel, the frame's edge included */
	flat(e, green, blue, 0, 0);
	for (i = 0; i < 63; i++)
		NEAR(e[i], 1.0, 1e-5);
	flat(e, green, green, 0, 0);
	for (i = 0; i < 63; i++)
		NEAR(e[i], 0.0, 0.0);
	/* black and white: 100^0.7 past the knee, 0.95 + (100^0.7 - 0.4
	 * cmax) / (0.6 cmax) 0.05 */
	flat(e, black, white, 0, 0);
	for (i = 0; i < 63; i++)
		NEAR(e[i], 0.96737976, 1e-5);
	/* HDR-FLIP at one exposure of 0 stops: white tone-maps to
	 * aces(1) = 0.8038, against black */
	flat(e, black, white, 1, 0.0);
	{
		const float t = rf__flip_aces(1.0f), c[3] = { t, t, t };
		float lb[3], lw[3];

		rf__flip_rgb_to_lab_hunt(black, lb);
		rf__flip_rgb_to_lab_hunt(c, lw);
		NEAR(e[31], rf__flip_color_error(lb, lw, rf__flip_cmax()), 1e-5);
	}
}

static void
test_exposures(void)
{
	static const int col[3] = { 0, 1, 2 };
	float px[4 * 3] = { 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 2, 2, 2, 0, 0, 0 };
	struct rf_compare_input in = { px, px, 3, 3, col, col, 3, 2, 2, NULL };
	double start, stop;
	int n;

	/* luminances 0, 0.5, 0.5, 2: the largest 2, the median (upper) 0.5 */
	ASSERT(rf_flip_exposures(&in, &start, &stop, &n) == 0);
	NEAR(start, log2(2.1188723 / 2.0), 1e-6);
	NEAR(stop, log2(2.1188723 / 0.5), 1e-6);
	ASSERT_EQ(n, 2);
	/* half black: the upper median is still 0.5 */
	px[3] = px[4] = px[5] = 0;
	ASSERT(rf_flip_exposures(&in, &start, &stop, &n) == 0);
	NEAR(stop, log2(2.1188723 / 0.5), 1e-6);
	/* more than half: refused */
	px[0] = px[1] = px[2] = 0;
	ASSERT(rf_flip_exposures(&in, &start, &stop, &n) == RF_EINVAL);
}

int
main(void)
{
	RUN(test_ycxcz);
	RUN(test_lab);
	RUN(test_remap);
	RUN(test_filters);
	RUN(test_tone);
	RUN(test_constant);
	RUN(test_exposures);
	TAP_DONE();
}
