/*
 * The uncompressed texels of GPU texture files, shared by the DDS and KTX
 * readers and the KTX writer (texel.h).
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "envmap/texel.h"
#include "reflect/reflect.h"

static uint32_t
le32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	       (uint32_t)p[3] << 24;
}

static float
f32_of(const unsigned char *p)
{
	uint32_t u = le32(p);
	float f;

	memcpy(&f, &u, sizeof(f));
	return f;
}

/* A float of 5 exponent bits (bias 15) and mbits mantissa bits, no sign:
 * half floats (with the sign done by the caller) and the 11- and 10-bit
 * floats of R11G11B10 share it. */
static float
small_float(unsigned e, unsigned m, unsigned mbits)
{
	if (e == 0)
		return ldexpf((float)m, -14 - (int)mbits); /* denormal */
	if (e == 31)
		return m ? NAN : INFINITY;
	return ldexpf((float)(m | (1u << mbits)), (int)e - 15 - (int)mbits);
}

static float
half_to_float(unsigned h)
{
	float v = small_float((h >> 10) & 31u, h & 1023u, 10);

	return h & 0x8000u ? -v : v;
}

void
rf__texel_decode(const struct rf__texel_format *fmt, const unsigned char *p, float rgb[3])
{
	uint32_t u;
	int c;

	switch (fmt->kind) {
	case RF__TEXEL_F32:
		for (c = 0; c < 3; c++)
			rgb[c] = f32_of(p + 4 * (fmt->nch == 1 ? 0 : c));
		break;
	case RF__TEXEL_F16:
		for (c = 0; c < 3; c++)
			rgb[c] = half_to_float((unsigned)p[2 * c] | (unsigned)p[2 * c + 1] << 8);
		break;
	case RF__TEXEL_R11G11B10:
		u = le32(p);
		rgb[0] = small_float((u >> 6) & 31u, u & 63u, 6);
		rgb[1] = small_float((u >> 17) & 31u, (u >> 11) & 63u, 6);
		rgb[2] = small_float((u >> 27) & 31u, (u >> 22) & 31u, 5);
		break;
	case RF__TEXEL_RGB9E5:
		/* Three 9-bit mantissas without a hidden bit, one exponent
		 * (bias 15): m * 2^(e - 15 - 9). */
		u = le32(p);
		for (c = 0; c < 3; c++)
			rgb[c] = ldexpf((float)((u >> (9 * c)) & 511u), (int)(u >> 27) - 24);
		break;
	case RF__TEXEL_RGBA8:
	case RF__TEXEL_BGRA8:
		for (c = 0; c < 3; c++) {
			float v = (float)p[fmt->kind == RF__TEXEL_BGRA8 ? 2 - c : c] / 255.0f;

			rgb[c] = fmt->srgb ? rf_srgb_decode(v) : v;
		}
		break;
	}
}

unsigned
rf__float_to_half(float v)
{
	uint32_t u, a, h, rest;
	unsigned sign;

	memcpy(&u, &v, sizeof(u));
	sign = (unsigned)(u >> 16) & 0x8000u;
	a = u & 0x7fffffffu;
	if (a > 0x7f800000u)
		return sign | 0x7e00u; /* NaN stays NaN */
	if (a >= 0x477ff000u)
		return sign | 0x7c00u; /* 65520 and up round past 65504 */
	if (a < 0x38800000u) {
		/* Below 2^-14 a half is a multiple of 2^-24: the scaling is
		 * exact, so one rounding to the nearest integer (ties to
		 * even, the default mode) is the whole conversion. */
		float f;

		memcpy(&f, &a, sizeof(f));
		return sign | (unsigned)lrintf(f * 16777216.0f);
	}
	/* Rebias the exponent (127 to 15) and drop 13 mantissa bits; a
	 * carry out of the mantissa rightly bumps the exponent. */
	a -= 112u << 23;
	h = a >> 13;
	rest = a & 0x1fffu;
	if (rest > 0x1000u || (rest == 0x1000u && (h & 1u)))
		h++;
	return sign | (unsigned)h;
}

void
rf__texel_store_gl_row(rf_cubemap *c, size_t level, int f, size_t j,
                       const unsigned char *row, const struct rf__texel_format *fmt,
                       struct rf__nonfinite *nf)
{
	size_t n = rf_cubemap_level_size(c, level), i, ri, rj;
	int ch;

	for (i = 0; i < n; i++) {
		float *t;

		rf__gl_texel(f, n, i, j, &ri, &rj);
		t = rf_cubemap_texel(c, level, (enum rf_face)f, ri, rj);
		rf__texel_decode(fmt, row + i * fmt->bytes, t);
		for (ch = 0; ch < 3; ch++)
			if (!rf__texel_ok(t[ch])) {
				rf__nonfinite_note(nf, level, f, i, j, ch, t[ch]);
				t[ch] = 0.0f;
			}
	}
}
