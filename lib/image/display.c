/* Turning linear radiance into display values. */
#include <math.h>

#include "reflect/reflect.h"

float
rf_srgb_encode(float x)
{
	if (!(x > 0.0f))
		return 0.0f;
	if (x >= 1.0f)
		return 1.0f;
	return x <= 0.0031308f ? 12.92f * x : 1.055f * powf(x, 1.0f / 2.4f) - 0.055f;
}

float
rf_srgb_decode(float x)
{
	if (!(x > 0.0f))
		return 0.0f;
	return x <= 0.04045f ? x / 12.92f : powf((x + 0.055f) / 1.055f, 2.4f);
}

/* Narkowicz's fit of the ACES reference rendering transform. */
static float
filmic(float x)
{
	return x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f);
}

static float
clamp01(float x)
{
	return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
}

void
rf_display_encode(float *v, size_t npix, size_t nchannels, size_t ncolour,
                  float scale, enum rf_tone tone, int srgb)
{
	size_t i, c;

	for (i = 0; i < npix; i++, v += nchannels)
		for (c = 0; c < nchannels; c++) {
			float x = v[c];

			if (c < ncolour) {
				x *= scale;
				if (tone == RF_TONE_FILMIC && x > 0.0f)
					x = x < 1e4f ? filmic(x) : 1.0f;
				x = clamp01(x);
				if (srgb)
					x = rf_srgb_encode(x);
			} else {
				x = clamp01(x);
			}
			v[c] = x;
		}
}

void
rf_file_encode(float *px, size_t npix, size_t nch, const unsigned char *alpha,
               const struct rf_file_encoding *e)
{
	size_t i, c;

	/* Stream colour is premultiplied by A (OpenEXR's convention); 8- and
	 * 16-bit files hold straight colour, so divide where A > 0. */
	if (e->integer && nch == 4)
		for (i = 0; i < npix; i++) {
			float a = px[i * nch + 3];

			if (a > 0.0f)
				for (c = 0; c < 3; c++)
					px[i * nch + c] /= a;
		}
	for (c = 0; c < nch; c++) {
		if (!e->integer && (alpha[c] || (e->tone == RF_TONE_NONE && !e->srgb))) {
			if (!alpha[c] && e->scale != 1.0f)
				for (i = 0; i < npix; i++)
					px[i * nch + c] *= e->scale;
			continue;
		}
		for (i = 0; i < npix; i++)
			rf_display_encode(px + i * nch + c, 1, 1, alpha[c] ? 0 : 1, e->scale,
			                  e->tone, e->srgb);
	}
	if (e->nonneg)
		for (i = 0; i < npix * nch; i++)
			if (!(px[i] > 0.0f))
				px[i] = 0.0f; /* RGBE would make garbage of it */
}
