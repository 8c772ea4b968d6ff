/* Environment images in their layouts, to and from cubes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "reflect/envmap.h"

/* Where a face sits in a layout: slot column and row (in faces) and
 * whether it is turned by 180 degrees.  Crosses are the cube unfolded as
 * seen from inside: the middle row reads +X +Z -X -Z from left to right,
 * as the lat-long's centre (+Z) turns toward -X on its right. */
struct slot {
	int col, row, turned;
};

static const struct slot cube_slots[6] = {
	{ 0, 0, 0 }, { 0, 1, 0 }, { 0, 2, 0 }, { 0, 3, 0 }, { 0, 4, 0 }, { 0, 5, 0 },
};
static const struct slot hcross_slots[6] = {
	{ 0, 1, 0 }, { 2, 1, 0 }, { 1, 0, 1 }, { 1, 2, 1 }, { 1, 1, 0 }, { 3, 1, 0 },
};
static const struct slot vcross_slots[6] = {
	{ 0, 1, 0 }, { 2, 1, 0 }, { 1, 0, 1 }, { 1, 2, 1 }, { 1, 1, 0 }, { 1, 3, 1 },
};

static const struct slot *
slots_of(enum rf_layout layout)
{
	switch (layout) {
	case RF_LAYOUT_CUBE: return cube_slots;
	case RF_LAYOUT_HCROSS: return hcross_slots;
	case RF_LAYOUT_VCROSS: return vcross_slots;
	default: return NULL;
	}
}

int
rf_layout_parse(const char *name, enum rf_layout *out)
{
	static const struct { const char *name; enum rf_layout layout; } names[] = {
		{ "auto", RF_LAYOUT_AUTO }, { "latlong", RF_LAYOUT_LATLONG },
		{ "cube", RF_LAYOUT_CUBE }, { "vcross", RF_LAYOUT_VCROSS },
		{ "hcross", RF_LAYOUT_HCROSS }, { "mirrorball", RF_LAYOUT_MIRRORBALL },
		{ "angular", RF_LAYOUT_ANGULAR },
	};
	size_t i;

	for (i = 0; i < sizeof(names) / sizeof(names[0]); i++)
		if (!strcmp(name, names[i].name)) {
			*out = names[i].layout;
			return 0;
		}
	return RF_EINVAL;
}

const char *
rf_layout_name(enum rf_layout layout)
{
	switch (layout) {
	case RF_LAYOUT_AUTO: return "auto";
	case RF_LAYOUT_LATLONG: return "latlong";
	case RF_LAYOUT_CUBE: return "cube";
	case RF_LAYOUT_VCROSS: return "vcross";
	case RF_LAYOUT_HCROSS: return "hcross";
	case RF_LAYOUT_MIRRORBALL: return "mirrorball";
	case RF_LAYOUT_ANGULAR: return "angular";
	}
	return "?";
}

void
rf_layout_size(enum rf_layout layout, size_t face, size_t *w, size_t *h)
{
	switch (layout) {
	case RF_LAYOUT_CUBE: *w = face; *h = 6 * face; break;
	case RF_LAYOUT_VCROSS: *w = 3 * face; *h = 4 * face; break;
	case RF_LAYOUT_HCROSS: *w = 4 * face; *h = 3 * face; break;
	default: *w = 4 * face; *h = 2 * face; break;
	}
}

int
rf_layout_detect(size_t w, size_t h, const char *envmap, enum rf_layout *out,
                 char *err, size_t errlen)
{
	if (envmap && !strcmp(envmap, "latlong"))
		*out = RF_LAYOUT_LATLONG;
	else if (envmap && !strcmp(envmap, "cube"))
		*out = RF_LAYOUT_CUBE;
	else if (w && h == 6 * w)
		*out = RF_LAYOUT_CUBE;
	else if (w == 2 * h)
		*out = RF_LAYOUT_LATLONG;
	else if (3 * h == 4 * w)
		*out = RF_LAYOUT_VCROSS;
	else if (4 * h == 3 * w)
		*out = RF_LAYOUT_HCROSS;
	else if (w == h) {
		rf__format(err, errlen, "a square %zux%zu image may be a mirror ball or an "
		           "angular map: give --layout=mirrorball or --layout=angular", w, h);
		return RF_EINVAL;
	} else {
		rf__format(err, errlen, "cannot tell the layout of a %zux%zu image "
		           "(lat-long is 2:1, a cube N x 6N, crosses 3:4 or 4:3); "
		           "give one", w, h);
		return RF_EINVAL;
	}
	return 0;
}

int
rf_layout_check(enum rf_layout layout, size_t w, size_t h, size_t *face, char *err,
                size_t errlen)
{
	size_t n = 0, ew, eh;

	switch (layout) {
	case RF_LAYOUT_LATLONG:
		if (w < 4 || w != 2 * h) {
			rf__format(err, errlen, "a lat-long image is twice as wide as "
			           "high, not %zux%zu", w, h);
			return RF_EINVAL;
		}
		for (n = 1; 2 * n <= w / 4; n *= 2)
			;
		*face = n;
		return 0;
	case RF_LAYOUT_MIRRORBALL:
	case RF_LAYOUT_ANGULAR:
		if (w < 2 || w != h) {
			rf__format(err, errlen, "%s is square, not %zux%zu",
			           layout == RF_LAYOUT_MIRRORBALL ? "a mirror-ball image"
			                                          : "an angular map", w, h);
			return RF_EINVAL;
		}
		/* a face of about the pixels a quarter turn spans */
		for (n = 1; 2 * n <= w / 4; n *= 2)
			;
		*face = n;
		return 0;
	case RF_LAYOUT_CUBE: n = w; break;
	case RF_LAYOUT_VCROSS: n = w / 3; break;
	case RF_LAYOUT_HCROSS: n = w / 4; break;
	default:
		rf__format(err, errlen, "no layout given");
		return RF_EINVAL;
	}
	rf_layout_size(layout, n, &ew, &eh);
	if (!n || ew != w || eh != h) {
		rf__format(err, errlen, "a %s image of faces N is %s, not %zux%zu",
		           rf_layout_name(layout),
		           layout == RF_LAYOUT_CUBE ? "N x 6N"
		           : layout == RF_LAYOUT_VCROSS ? "3N x 4N" : "4N x 3N", w, h);
		return RF_EINVAL;
	}
	if (n & 1 && n != 1) {
		rf__format(err, errlen, "faces of %zu texels: an odd size cannot "
		           "make a mip chain", n);
		return RF_EINVAL;
	}
	*face = n;
	return 0;
}

/* Radiance of every pixel: RGB floats, decoded, non-finite made 0 (and
 * noted, as is a value that decoding took past the float range). */
static float *
decode_pixels(const float *px, size_t w, size_t h, size_t nch,
              const struct rf_decode *dc, struct rf__nonfinite *nf)
{
	float *out = malloc(w * h * 3 * sizeof(float));
	size_t i;
	int c;

	if (!out)
		return NULL;
	for (i = 0; i < w * h; i++) {
		const float *p = px + i * nch;
		float v[3], a = nch >= 4 ? p[3] : 1.0f, scale = dc->intensity;

		for (c = 0; c < 3; c++) {
			v[c] = nch >= 3 ? p[c] : p[0];
			if (!isfinite(v[c])) {
				rf__nonfinite_note(nf, 0, -1, i % w, i / w, c, v[c]);
				v[c] = 0.0f;
			}
		}
		if (!isfinite(a)) {
			rf__nonfinite_note(nf, 0, -1, i % w, i / w, 3, a);
			a = 0.0f;
		}
		if (dc->srgb)
			for (c = 0; c < 3; c++)
				v[c] = rf_srgb_decode(v[c]);
		if (dc->rgbm)
			scale *= dc->multiplier * powf(a > 0.0f ? a : 0.0f, dc->exponent);
		for (c = 0; c < 3; c++) {
			float x = v[c] * scale;

			if (!rf__texel_ok(x)) {
				rf__nonfinite_note(nf, 0, -1, i % w, i / w, c, x);
				x = 0.0f;
			}
			out[3 * i + (size_t)c] = x;
		}
	}
	return out;
}

/* Bilinear lat-long lookup, wrapping in longitude, clamped at the poles. */
static void
latlong_bilinear(const float *img, size_t w, size_t h, float u, float v, float rgb[3])
{
	float s = u * (float)w - 0.5f, t = v * (float)h - 0.5f;
	float fs = floorf(s), ft = floorf(t), a = s - fs, b = t - ft;
	long i0 = (long)fs, j0 = (long)ft, i1, j1;
	int c;

	i1 = i0 + 1;
	i0 = ((i0 % (long)w) + (long)w) % (long)w;
	i1 = ((i1 % (long)w) + (long)w) % (long)w;
	j1 = j0 + 1;
	j0 = j0 < 0 ? 0 : j0 >= (long)h ? (long)h - 1 : j0;
	j1 = j1 < 0 ? 0 : j1 >= (long)h ? (long)h - 1 : j1;
	for (c = 0; c < 3; c++)
		rgb[c] = (1 - b) * ((1 - a) * img[((size_t)j0 * w + (size_t)i0) * 3 + (size_t)c] +
		                    a * img[((size_t)j0 * w + (size_t)i1) * 3 + (size_t)c]) +
		         b * ((1 - a) * img[((size_t)j1 * w + (size_t)i0) * 3 + (size_t)c] +
		              a * img[((size_t)j1 * w + (size_t)i1) * 3 + (size_t)c]);
}

/* A lat-long image and its 2x box-filtered copies, so a texel reads a
 * copy whose pixels are about its own size: taps alone cannot average
 * the many pixels a texel covers near the poles. */
struct latlong_pyramid {
	size_t levels;
	size_t w[16], h[16];
	float *px[16];
};

static int
latlong_pyramid(struct latlong_pyramid *p, float *img, size_t w, size_t h)
{
	size_t k, x, y, c;

	memset(p, 0, sizeof(*p));
	p->px[0] = img;
	p->w[0] = w;
	p->h[0] = h;
	for (k = 1; k < 16 && !(p->w[k - 1] & 1) && !(p->h[k - 1] & 1) && p->w[k - 1] > 4; k++) {
		size_t pw = p->w[k - 1];
		const float *src = p->px[k - 1];

		p->w[k] = pw / 2;
		p->h[k] = p->h[k - 1] / 2;
		if (!(p->px[k] = malloc(p->w[k] * p->h[k] * 3 * sizeof(float))))
			return RF_ENOMEM;
		for (y = 0; y < p->h[k]; y++)
			for (x = 0; x < p->w[k]; x++)
				for (c = 0; c < 3; c++)
					p->px[k][(y * p->w[k] + x) * 3 + c] = 0.25f *
					        (src[((2 * y) * pw + 2 * x) * 3 + c] +
					         src[((2 * y) * pw + 2 * x + 1) * 3 + c] +
					         src[((2 * y + 1) * pw + 2 * x) * 3 + c] +
					         src[((2 * y + 1) * pw + 2 * x + 1) * 3 + c]);
	}
	p->levels = k;
	return 0;
}

static void
latlong_pyramid_free(struct latlong_pyramid *p)
{
	size_t k;

	for (k = 1; k < p->levels; k++)
		free(p->px[k]);
}

static int
from_latlong(rf_cubemap *c, float *img, size_t w, size_t h)
{
	enum { MAX_TAPS = 8 };
	size_t n = rf_cubemap_level_size(c, 0), i, j;
	struct latlong_pyramid pyr;
	int f, rc;

	if ((rc = latlong_pyramid(&pyr, img, w, h)) < 0) {
		latlong_pyramid_free(&pyr);
		return rc;
	}
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float d[3], *out = rf_cubemap_texel(c, 0, (enum rf_face)f, i, j);
				double size = sqrt(rf_cube_texel_solid_angle(n, i, j)), cos_lat, pitch;
				double acc[3] = { 0, 0, 0 }, need;
				size_t level = 0;
				int k, a, b;

				/* The pixel pitch under the texel: pixels narrow as
				 * cos(latitude) toward the poles. */
				rf_cube_direction((enum rf_face)f, ((float)i + 0.5f) / (float)n,
				                  ((float)j + 0.5f) / (float)n, d);
				cos_lat = sqrt((double)d[0] * d[0] + (double)d[2] * d[2]) /
				          sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
				pitch = fmin(M_PI / (double)h, 2.0 * M_PI / (double)w * fmax(cos_lat, 1e-4));
				need = size / pitch;
				while (need > MAX_TAPS && level + 1 < pyr.levels) {
					need /= 2.0;
					level++;
				}
				k = (int)ceil(need);
				k = k < 1 ? 1 : k > 2 * MAX_TAPS ? 2 * MAX_TAPS : k;
				for (b = 0; b < k; b++)
					for (a = 0; a < k; a++) {
						float dd[3], u, v, rgb[3];

						rf_cube_direction((enum rf_face)f,
						                  ((float)i + ((float)a + 0.5f) / (float)k) / (float)n,
						                  ((float)j + ((float)b + 0.5f) / (float)k) / (float)n,
						                  dd);
						rf_latlong_position(dd, &u, &v);
						latlong_bilinear(pyr.px[level], pyr.w[level], pyr.h[level], u, v,
						                 rgb);
						acc[0] += rgb[0];
						acc[1] += rgb[1];
						acc[2] += rgb[2];
					}
				for (a = 0; a < 3; a++)
					out[a] = (float)(acc[a] / (double)(k * k));
			}
	latlong_pyramid_free(&pyr);
	return 0;
}

/* Texel (i, j) of face f of a cube layout with faces of m texels. */
static const float *
slot_texel(const float *img, size_t w, const struct slot *s, size_t m, size_t i,
           size_t j)
{
	size_t x = s->turned ? m - 1 - i : i, y = s->turned ? m - 1 - j : j;

	return img + (((size_t)s->row * m + y) * w + (size_t)s->col * m + x) * 3;
}

int
rf_envmap_from_pixels(rf_cubemap *c, const float *px, size_t w, size_t h, size_t nch,
                      enum rf_layout layout, const struct rf_decode *decode,
                      size_t *nonfinite, char *err, size_t errlen)
{
	struct rf__nonfinite nf = { 0 };
	int rc = rf__envmap_from_pixels(c, px, w, h, nch, layout, decode, &nf, err, errlen);

	*nonfinite = nf.count;
	return rc;
}

int
rf__envmap_from_pixels(rf_cubemap *c, const float *px, size_t w, size_t h, size_t nch,
                       enum rf_layout layout, const struct rf_decode *decode,
                       struct rf__nonfinite *nf, char *err, size_t errlen)
{
	struct rf_decode plain = { 0, 0, 1.0f, 1.0f, 1.0f };
	size_t n = rf_cubemap_level_size(c, 0), m, i, j, k;
	const struct slot *slots;
	rf_cubemap *tmp = NULL;
	float *img;
	int rc, f;

	if (nch != 1 && nch != 3 && nch != 4) {
		rf__format(err, errlen, "an environment has 1, 3 or 4 channels, not %zu",
		           nch);
		return RF_EINVAL;
	}
	if (layout == RF_LAYOUT_AUTO &&
	    (rc = rf_layout_detect(w, h, NULL, &layout, err, errlen)) < 0)
		return rc;
	if ((rc = rf_layout_check(layout, w, h, &m, err, errlen)) < 0)
		return rc;
	if (!(img = decode_pixels(px, w, h, nch, decode ? decode : &plain, nf)))
		return RF_ENOMEM;
	if (layout == RF_LAYOUT_LATLONG || layout == RF_LAYOUT_MIRRORBALL ||
	    layout == RF_LAYOUT_ANGULAR) {
		rc = layout == RF_LAYOUT_LATLONG ? from_latlong(c, img, w, h)
		                                 : rf__from_sphere(c, img, w, h, layout);
		free(img);
		rf_cubemap_seal_level(c, 0);
		return rc;
	}
	for (k = 0; (m >> k) > n; k++)
		;
	if ((m >> k) != n || (k && (rc = rf_cubemap_create(&tmp, m, k + 1)) < 0)) {
		free(img);
		if (rc < 0)
			return rc;
		rf__format(err, errlen, "faces of %zu texels cannot make a cube of %zu "
		           "(only halving is supported)", m, n);
		return RF_EINVAL;
	}
	slots = slots_of(layout);
	for (f = 0; f < 6; f++)
		for (j = 0; j < m; j++)
			for (i = 0; i < m; i++)
				memcpy(rf_cubemap_texel(tmp ? tmp : c, 0, (enum rf_face)f, i, j),
				       slot_texel(img, w, &slots[f], m, i, j), 3 * sizeof(float));
	free(img);
	if (tmp) {
		rf_cubemap_seal_level(tmp, 0);
		rf_cubemap_box_chain(tmp, 0);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++)
					memcpy(rf_cubemap_texel(c, 0, (enum rf_face)f, i, j),
					       rf_cubemap_texel_const(tmp, k, (enum rf_face)f, i, j),
					       3 * sizeof(float));
		rf_cubemap_destroy(tmp);
	}
	rf_cubemap_seal_level(c, 0);
	return 0;
}

int
rf_envmap_to_pixels(const rf_cubemap *c, size_t level, enum rf_layout layout,
                    float *px, size_t w, size_t h)
{
	size_t n = rf_cubemap_level_size(c, level), i, j, ew, eh;
	const struct slot *slots = slots_of(layout);
	int f;

	if (layout == RF_LAYOUT_LATLONG) {
		for (j = 0; j < h; j++)
			for (i = 0; i < w; i++) {
				float d[3];

				rf_latlong_direction(((float)i + 0.5f) / (float)w,
				                     ((float)j + 0.5f) / (float)h, d);
				rf_cubemap_sample_level(c, level, d, px + (j * w + i) * 3);
			}
		return 0;
	}
	rf_layout_size(layout, n, &ew, &eh);
	if (!slots || ew != w || eh != h)
		return RF_EINVAL;
	memset(px, 0, w * h * 3 * sizeof(float));
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++)
				memcpy((float *)slot_texel(px, w, &slots[f], n, i, j),
				       rf_cubemap_texel_const(c, level, (enum rf_face)f, i, j),
				       3 * sizeof(float));
	return 0;
}

int
rf__cube_level_from_pixels(rf_cubemap *c, size_t level, const float *px, size_t w,
                           size_t h, size_t nch, struct rf__nonfinite *nf, char *err,
                           size_t errlen)
{
	size_t n = rf_cubemap_level_size(c, level), i, j;
	int f, ch;

	if (w != n || h != 6 * n || nch < 3) {
		rf__format(err, errlen, "level %zu is %zux%zu with %zu channels, expected "
		           "%zux%zu RGB", level, w, h, nch, n, 6 * n);
		return RF_EFORMAT;
	}
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				const float *p = px + (((size_t)f * n + j) * n + i) * nch;
				float *t = rf_cubemap_texel(c, level, (enum rf_face)f, i, j);

				for (ch = 0; ch < 3; ch++) {
					t[ch] = p[ch];
					if (!rf__texel_ok(p[ch])) {
						rf__nonfinite_note(nf, level, f, i, j, ch, p[ch]);
						t[ch] = 0.0f;
					}
				}
			}
	rf_cubemap_seal_level(c, level);
	return 0;
}
