/*
 * The light-probe layouts of a square image, as Debevec's light probe
 * gallery defines them, in its axes: the image's centre looks along +Z
 * (toward the camera that photographed the ball), its right along +X,
 * its top along +Y; (u, v) in [-1, 1]^2, v up.
 *
 *   mirror ball: the photograph of a mirrored sphere, seen from far:
 *     (u, v) = r (Dx, Dy), r = sin(acos(Dz)/2) / sqrt(Dx^2 + Dy^2)
 *     (the rim is -Z, the direction behind the ball);
 *   angular map: the angle from +Z grows with the radius:
 *     (u, v) = r (Dx, Dy), r = acos(Dz) / (pi sqrt(Dx^2 + Dy^2))
 *     (the rim is -Z too, at radius 1).
 *
 * Each texel of the cube is the mean of k x k bilinear reads of the
 * image, k from how many pixels the texel covers where it lands.
 */
#include <math.h>

#include "envmap/envmap-internal.h"

/* Where direction d lands, in pixels, and how many radians a pixel spans
 * there (along the radius). */
static void
sphere_position(enum rf_layout layout, const float d[3], size_t n, float *x, float *y,
                double *pitch)
{
	const double dx = d[0], dy = d[1], dz = d[2];
	const double len = sqrt(dx * dx + dy * dy + dz * dz);
	const double c = dz / len, s = sqrt(dx * dx + dy * dy) / len;
	const double theta = acos(c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c);
	double r, k, u, v;

	if (layout == RF_LAYOUT_MIRRORBALL) {
		r = sin(0.5 * theta);
		/* dr/dtheta = cos(theta/2)/2: a pixel (2/n in r) spans more
		 * toward the rim */
		*pitch = 2.0 / (double)n / fmax(0.5 * cos(0.5 * theta), 1e-3);
	} else {
		r = theta / M_PI;
		*pitch = 2.0 / (double)n * M_PI;
	}
	k = s > 1e-12 ? r / s : 0.0;
	u = k * dx / len;
	v = k * dy / len;
	*x = (float)((u + 1.0) * 0.5 * (double)n);
	*y = (float)((1.0 - v) * 0.5 * (double)n);
}

static void
bilinear(const float *img, size_t n, float x, float y, float rgb[3])
{
	float s = x - 0.5f, t = y - 0.5f, fs = floorf(s), ft = floorf(t), a = s - fs, b = t - ft;
	long i0 = (long)fs, j0 = (long)ft, i1 = i0 + 1, j1 = j0 + 1, m = (long)n - 1;
	int c;

	i0 = i0 < 0 ? 0 : i0 > m ? m : i0;
	i1 = i1 < 0 ? 0 : i1 > m ? m : i1;
	j0 = j0 < 0 ? 0 : j0 > m ? m : j0;
	j1 = j1 < 0 ? 0 : j1 > m ? m : j1;
	for (c = 0; c < 3; c++)
		rgb[c] = (1 - b) * ((1 - a) * img[((size_t)j0 * n + (size_t)i0) * 3 + (size_t)c] +
		                    a * img[((size_t)j0 * n + (size_t)i1) * 3 + (size_t)c]) +
		         b * ((1 - a) * img[((size_t)j1 * n + (size_t)i0) * 3 + (size_t)c] +
		              a * img[((size_t)j1 * n + (size_t)i1) * 3 + (size_t)c]);
}

int
rf__from_sphere(rf_cubemap *c, const float *img, size_t w, size_t h, enum rf_layout layout)
{
	enum { MAX_TAPS = 8 };
	size_t n = rf_cubemap_level_size(c, 0), i, j;
	int f;

	if (w != h || (layout != RF_LAYOUT_MIRRORBALL && layout != RF_LAYOUT_ANGULAR))
		return RF_EINVAL;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float d[3], x, y, *out = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);
				double size = sqrt(rf_cube_texel_solid_angle(n, i, j)), pitch;
				double acc[3] = { 0, 0, 0 };
				int k, a, b;

				rf_cube_direction((enum rf_face)f, ((float)i + 0.5f) / (float)n,
				                  ((float)j + 0.5f) / (float)n, d);
				sphere_position(layout, d, w, &x, &y, &pitch);
				k = (int)ceil(size / pitch);
				k = k < 1 ? 1 : k > MAX_TAPS ? MAX_TAPS : k;
				for (b = 0; b < k; b++)
					for (a = 0; a < k; a++) {
						float dd[3], rgb[3];

						rf_cube_direction((enum rf_face)f,
						                  ((float)i + ((float)a + 0.5f) / (float)k) / (float)n,
						                  ((float)j + ((float)b + 0.5f) / (float)k) / (float)n,
						                  dd);
						sphere_position(layout, dd, w, &x, &y, &pitch);
						bilinear(img, w, x, y, rgb);
						acc[0] += rgb[0];
						acc[1] += rgb[1];
						acc[2] += rgb[2];
					}
				for (a = 0; a < 3; a++)
					out[a] = (float)(acc[a] / (double)(k * k));
			}
	return 0;
}
