/* Cube chains as MIP-mapped OpenEXR cubes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "reflect/envmap.h"

/* A 2x box filter of an image, for the levels past the cube's; sides
 * round down, as OpenEXR's MIP levels do. */
static float *
halve(const float *px, size_t w, size_t h, size_t *w2, size_t *h2)
{
	size_t x, y, c;
	float *out;

	*w2 = w > 1 ? w / 2 : 1;
	*h2 = h > 1 ? h / 2 : 1;
	if (!(out = malloc(*w2 * *h2 * 3 * sizeof(float))))
		return NULL;
	for (y = 0; y < *h2; y++)
		for (x = 0; x < *w2; x++)
			for (c = 0; c < 3; c++) {
				size_t x0 = 2 * x < w ? 2 * x : w - 1, x1 = 2 * x + 1 < w ? 2 * x + 1 : w - 1;
				size_t y0 = 2 * y < h ? 2 * y : h - 1, y1 = 2 * y + 1 < h ? 2 * y + 1 : h - 1;

				out[(y * *w2 + x) * 3 + c] =
				        0.25f * (px[(y0 * w + x0) * 3 + c] + px[(y0 * w + x1) * 3 + c] +
				                 px[(y1 * w + x0) * 3 + c] + px[(y1 * w + x1) * 3 + c]);
			}
	return out;
}

int
rf_chain_write_file(const rf_cubemap *c, const struct rf_chain_info *info,
                    const char *path, char *err, size_t errlen)
{
	static const char *const names[] = { "R", "G", "B" };
	size_t n = rf_cubemap_size(c), levels = rf_cubemap_levels(c), total, k;
	size_t w[32], h[32];
	float *px[32] = { 0 };
	char nlev[32], steps[32], samples[32], sh9[27 * 18];
	const char *attrs[20];
	float sh[27];
	size_t used = 0;
	int rc = 0, a = 0;

	/* OpenEXR's chain goes down to 1x1, each side halved rounding down. */
	w[0] = n;
	h[0] = 6 * n;
	for (k = 1; k < 32 && (w[k - 1] > 1 || h[k - 1] > 1); k++) {
		w[k] = w[k - 1] > 1 ? w[k - 1] / 2 : 1;
		h[k] = h[k - 1] > 1 ? h[k - 1] / 2 : 1;
	}
	total = k;
	for (k = 0; k < total; k++) {
		if (k < levels) {
			if (!(px[k] = malloc(w[k] * h[k] * 3 * sizeof(float)))) {
				rc = RF_ENOMEM;
				goto out;
			}
			rf_envmap_to_pixels(c, k, RF_LAYOUT_CUBE, px[k], w[k], h[k]);
		} else {
			size_t w2, h2;

			if (!(px[k] = halve(px[k - 1], w[k - 1], h[k - 1], &w2, &h2))) {
				rc = RF_ENOMEM;
				goto out;
			}
		}
	}
	rf__format(nlev, sizeof(nlev), "%zu", levels);
	rf__format(steps, sizeof(steps), "%.9g", (double)info->steps);
	rf__format(samples, sizeof(samples), "%u", info->samples);
	attrs[a++] = "textureformat";
	attrs[a++] = "CubeFace Environment";
	attrs[a++] = "reflect:levels";
	attrs[a++] = nlev;
	attrs[a++] = "reflect:prefilter";
	attrs[a++] = info->prefiltered ? "ggx" : "box";
	attrs[a++] = "reflect:mapping";
	attrs[a++] = rf_mapping_name(info->mapping);
	attrs[a++] = "reflect:steps";
	attrs[a++] = steps;
	attrs[a++] = "reflect:samples";
	attrs[a++] = samples;
	attrs[a++] = "reflect:base";
	attrs[a++] = info->base_copied ? "copied" : "filtered";
	/* The diffuse light's coefficients from the float level 0, which
	 * the file keeps only in half precision. */
	rf_cubemap_sh9(c, 0, sh);
	for (k = 0; k < 27; k++)
		used += (size_t)snprintf(sh9 + used, sizeof(sh9) - used, "%s%.9g",
		                         k ? " " : "", (double)sh[k]);
	attrs[a++] = "reflect:irradianceSH9";
	attrs[a++] = sh9;
	attrs[a] = NULL;
	rc = rf_image_write_levels(path, total, w, h, 3, names, (const float *const *)px,
	                           attrs, RF_PIXEL_HALF, err, errlen);
out:
	for (k = 0; k < 32; k++)
		free(px[k]);
	return rc;
}

int
rf_chain_read_file(rf_cubemap **cp, struct rf_chain_info *info, int *is_reflect,
                   const char *path, char *err, size_t errlen)
{
	return rf__chain_read_file(cp, info, is_reflect, NULL, path, err, errlen);
}

int
rf__chain_read_file(rf_cubemap **cp, struct rf_chain_info *info, int *is_reflect,
                    struct rf__nonfinite *nf, const char *path, char *err, size_t errlen)
{
	size_t nlevels, levels = 0, n, k;
	rf_image *img = NULL;
	const char *v;
	int rc;

	*cp = NULL;
	*is_reflect = 0;
	memset(info, 0, sizeof(*info));
	info->mapping = RF_MAPPING_DEFAULT;
	info->base_copied = 1;
	if ((rc = rf_image_count_levels(path, &nlevels, err, errlen)) < 0)
		return rc;
	if ((rc = rf_image_read_level(&img, path, 0, err, errlen)) < 0)
		return rc;
	n = rf_image_width(img);
	if (rf_image_height(img) != 6 * n) {
		rf__format(err, errlen, "'%s': a MIP-mapped cube is N x 6N, not %zux%zu",
		           path, n, rf_image_height(img));
		rf_image_destroy(img);
		return RF_EFORMAT;
	}
	/* The cube levels: those still N x 6N with N even or 1. */
	while (levels < nlevels && (n >> levels) >= 1 &&
	       (levels == 0 || !((n >> (levels - 1)) & 1)))
		levels++;
	if ((v = rf_image_attribute(img, "reflect:prefilter"))) {
		char *end;
		unsigned long l;

		*is_reflect = 1;
		info->prefiltered = !strcmp(v, "ggx");
		if ((v = rf_image_attribute(img, "reflect:mapping")))
			rf_mapping_parse(v, &info->mapping);
		if ((v = rf_image_attribute(img, "reflect:steps")))
			info->steps = strtof(v, NULL);
		if ((v = rf_image_attribute(img, "reflect:samples")))
			info->samples = (unsigned)strtoul(v, NULL, 10);
		if ((v = rf_image_attribute(img, "reflect:base")))
			info->base_copied = strcmp(v, "filtered") != 0;
		if ((v = rf_image_attribute(img, "reflect:levels")) &&
		    (l = strtoul(v, &end, 10)) >= 1 && !*end && l <= levels)
			levels = l;
		if ((v = rf_image_attribute(img, "reflect:irradianceSH9"))) {
			if (rf__scan_floats(v, info->sh9, 27) < 0) {
				rf__format(err, errlen, "'%s': attribute reflect:irradianceSH9 "
				           "needs 27 finite float numbers", path);
				rc = RF_EFORMAT;
				rf_image_destroy(img);
				return rc;
			}
			info->has_sh9 = 1;
		}
	}
	if ((rc = rf_cubemap_check_size(n, levels, err, errlen)) < 0 ||
	    (rc = rf_cubemap_create(cp, n, levels)) < 0)
		goto fail;
	for (k = 0; k < levels; k++) {
		if (k && (rc = rf_image_read_level(&img, path, k, err, errlen)) < 0)
			goto fail;
		if (rf_image_nchannels(img) < 3) {
			rf__format(err, errlen, "'%s': level %zu has %zu channels, not RGB",
			           path, k, rf_image_nchannels(img));
			rc = RF_EFORMAT;
			goto fail;
		}
		rc = rf__cube_level_from_pixels(*cp, k, rf_image_pixels(img),
		                                 rf_image_width(img), rf_image_height(img),
		                                 rf_image_nchannels(img), nf, err, errlen);
		rf_image_destroy(img);
		img = NULL;
		if (rc < 0)
			goto fail;
	}
	return 0;
fail:
	rf_image_destroy(img);
	rf_cubemap_destroy(*cp);
	*cp = NULL;
	return rc;
}
