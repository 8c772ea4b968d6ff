/*
 * Diffuse light from an environment: its radiance projected onto the 9
 * real spherical harmonics of bands 0 to 2, and the irradiance at a
 * normal from them (Ramamoorthi and Hanrahan 2001: the cosine lobe keeps
 * pi, 2 pi / 3 and pi / 4 of bands 0, 1 and 2, and three bands carry all
 * but about 1 % of the irradiance of any environment).  Texels weighed by
 * their solid angles, in double: 9 x 3 sums over a whole level.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/envmap.h"

/* The 9 basis functions at a unit direction. */
static void
basis(const double d[3], double y[9])
{
	const double x = d[0], yy = d[1], z = d[2];

	y[0] = 0.282094792;
	y[1] = 0.488602512 * yy;
	y[2] = 0.488602512 * z;
	y[3] = 0.488602512 * x;
	y[4] = 1.092548431 * x * yy;
	y[5] = 1.092548431 * yy * z;
	y[6] = 0.315391565 * (3.0 * z * z - 1.0);
	y[7] = 1.092548431 * x * z;
	y[8] = 0.546274215 * (x * x - yy * yy);
}

void
rf_cubemap_sh9(const rf_cubemap *c, size_t level, float sh[27])
{
	size_t n = rf_cubemap_level_size(c, level), i, j;
	double sum[27] = { 0 };
	int f, k, ch;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				const double w = rf_cube_texel_solid_angle(n, i, j);
				const float *p = rf_cubemap_texel_const(c, level, (enum rf_face)f, i, j);
				float df[3];
				double d[3], y[9], len;

				rf_cube_direction((enum rf_face)f, ((float)i + 0.5f) / (float)n,
				                  ((float)j + 0.5f) / (float)n, df);
				len = sqrt((double)df[0] * df[0] + (double)df[1] * df[1] +
				           (double)df[2] * df[2]);
				for (k = 0; k < 3; k++)
					d[k] = df[k] / len;
				basis(d, y);
				for (k = 0; k < 9; k++)
					for (ch = 0; ch < 3; ch++)
						sum[3 * k + ch] += w * y[k] * p[ch];
			}
	for (k = 0; k < 27; k++)
		sh[k] = (float)sum[k];
}

void
rf_sh9_irradiance(const float sh[27], const float n[3], float rgb[3])
{
	static const double band[9] = { M_PI, 2.0 * M_PI / 3, 2.0 * M_PI / 3, 2.0 * M_PI / 3,
		                        M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4, M_PI / 4 };
	double d[3] = { n[0], n[1], n[2] }, y[9], len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
	int k, ch;

	if (!(len > 0.0) || !isfinite(len)) {
		rgb[0] = rgb[1] = rgb[2] = 0.0f;
		return;
	}
	for (k = 0; k < 3; k++)
		d[k] /= len;
	basis(d, y);
	for (ch = 0; ch < 3; ch++) {
		double e = 0.0;

		for (k = 0; k < 9; k++)
			e += band[k] * y[k] * sh[3 * k + ch];
		/* ringing of the truncated series can dip below 0 */
		rgb[ch] = e > 0.0 ? (float)e : 0.0f;
	}
}

/* Face size of the cube the cosine convolution reads: the lobe spans a
 * hemisphere, so 32 texels a face lose nothing of it. */
#define IRRADIANCE_SOURCE_SIZE 32

int
rf_cubemap_irradiance(const rf_cubemap *src, size_t level, rf_cubemap *out)
{
	size_t n = rf_cubemap_level_size(src, level), m, no = rf_cubemap_size(out);
	size_t levels = 1, k, count, i, j, q;
	rf_cubemap *tmp = NULL;
	const rf_cubemap *from = src;
	size_t from_level = level;
	double *dirs;
	float *rad;
	int f, rc;

	/* a box-filtered copy no larger than the convolution needs */
	if (n > IRRADIANCE_SOURCE_SIZE) {
		for (m = n; m > IRRADIANCE_SOURCE_SIZE && !(m & 1); m /= 2)
			levels++;
		if ((rc = rf_cubemap_create(&tmp, n, levels)) < 0)
			return rc;
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++)
					memcpy(rf_cubemap_texel(tmp, 0, (enum rf_face)f, i, j),
					       rf_cubemap_texel_const(src, level, (enum rf_face)f, i, j),
					       3 * sizeof(float));
		rf_cubemap_seal_level(tmp, 0);
		rf_cubemap_box_chain(tmp, 0);
		from = tmp;
		from_level = levels - 1;
	}
	m = rf_cubemap_level_size(from, from_level);
	count = 6 * m * m;
	dirs = malloc(count * 4 * sizeof(double));
	rad = malloc(count * 3 * sizeof(float));
	if (!dirs || !rad) {
		free(dirs);
		free(rad);
		rf_cubemap_destroy(tmp);
		return RF_ENOMEM;
	}
	/* each source texel's unit direction, solid angle and radiance */
	for (q = 0, f = 0; f < 6; f++)
		for (j = 0; j < m; j++)
			for (i = 0; i < m; i++, q++) {
				float d[3];
				double len;

				rf_cube_direction((enum rf_face)f, ((float)i + 0.5f) / (float)m,
				                  ((float)j + 0.5f) / (float)m, d);
				len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
				for (k = 0; k < 3; k++)
					dirs[4 * q + k] = d[k] / len;
				dirs[4 * q + 3] = rf_cube_texel_solid_angle(m, i, j);
				memcpy(rad + 3 * q,
				       rf_cubemap_texel_const(from, from_level, (enum rf_face)f, i, j),
				       3 * sizeof(float));
			}
	for (f = 0; f < 6; f++)
		for (j = 0; j < no; j++)
			for (i = 0; i < no; i++) {
				float d[3], *t = rf_cubemap_texel(out, 0, (enum rf_face)f, i, j);
				double nrm[3], len, e[3] = { 0, 0, 0 };

				rf_cube_direction((enum rf_face)f, ((float)i + 0.5f) / (float)no,
				                  ((float)j + 0.5f) / (float)no, d);
				len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
				for (k = 0; k < 3; k++)
					nrm[k] = d[k] / len;
				for (q = 0; q < count; q++) {
					const double *w = dirs + 4 * q;
					double c = nrm[0] * w[0] + nrm[1] * w[1] + nrm[2] * w[2];

					if (c > 0.0) {
						c *= w[3];
						e[0] += c * rad[3 * q];
						e[1] += c * rad[3 * q + 1];
						e[2] += c * rad[3 * q + 2];
					}
				}
				for (k = 0; k < 3; k++)
					t[k] = (float)(e[k] / M_PI);
			}
	rf_cubemap_seal_level(out, 0);
	free(dirs);
	free(rad);
	rf_cubemap_destroy(tmp);
	return 0;
}
