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

#include "envmap/envmap-internal.h"
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

/* How a face's local unit vector (a, b, 1)/len, a = 2u - 1 and b = 2v - 1,
 * lands in the world: world axis k is sign[k] times local axis perm[k]
 * (rf_cube_direction's table, read back from it). */
struct face_axes {
	int perm[3];
	double sign[3];
};

static void
face_axes(enum rf_face f, struct face_axes *ax)
{
	float c[3], ua[3], vb[3];
	int k;

	rf_cube_direction(f, 0.5f, 0.5f, c);
	rf_cube_direction(f, 1.0f, 0.5f, ua);
	rf_cube_direction(f, 0.5f, 1.0f, vb);
	for (k = 0; k < 3; k++) {
		const double da = ua[k] - c[k], db = vb[k] - c[k];

		ax->perm[k] = da != 0 ? 0 : db != 0 ? 1 : 2;
		ax->sign[k] = da != 0 ? (da > 0 ? 1 : -1) : db != 0 ? (db > 0 ? 1 : -1)
		                                             : (c[k] > 0 ? 1 : -1);
	}
}

/* Texels of a row whose directions and solid angles are made at once. */
#define SH_CHUNK 256

/* The basis functions are polynomials of degree 2 in the direction, so
 * the projection needs only the radiance's moments 1, x, y, z, xx, yy,
 * zz, xy, xz, yz.  They are summed in each face's own frame, where a
 * texel's direction and solid angle are the same on all six faces: the
 * directions, square roots and arctangents are made once per texel of a
 * face instead of once per texel of the cube, and the sums are 30 float
 * multiply-adds a texel (rows added up in double).  The faces' moments
 * are then turned into the world's by their axis permutations.  A 256
 * cube: 28 ms before, 6 ms now (bench/irradiance-bench). */
void
rf_cubemap_sh9(const rf_cubemap *c, size_t level, float sh[27])
{
	size_t n = rf_cubemap_level_size(c, level), i0, i, j, cnt;
	double m[6][3][10] = { { { 0 } } }, w0[3] = { 0 }, w1[3][3] = { { 0 } };
	double w2[3][3][3] = { { { 0 } } };
	float tw[SH_CHUNK], tx[SH_CHUNK], ty[SH_CHUNK], tz[SH_CHUNK];
	int f, k, l, ch;

	for (j = 0; j < n; j++) {
		const float b = 2.0f * ((float)j + 0.5f) / (float)n - 1.0f;

		for (i0 = 0; i0 < n; i0 += cnt) {
			cnt = n - i0 < SH_CHUNK ? n - i0 : SH_CHUNK;
			for (i = 0; i < cnt; i++) {
				const float a = 2.0f * ((float)(i0 + i) + 0.5f) / (float)n - 1.0f;
				const float inv = 1.0f / sqrtf(a * a + b * b + 1.0f);

				tw[i] = (float)rf_cube_texel_solid_angle(n, i0 + i, j);
				tx[i] = a * inv;
				ty[i] = b * inv;
				tz[i] = inv;
			}
			for (f = 0; f < 6; f++) {
				const float *p = rf_cubemap_texel_const(c, level, (enum rf_face)f, i0, j);

				for (ch = 0; ch < 3; ch++) {
					float s[10] = { 0 };

					for (i = 0; i < cnt; i++) {
						const float wl = tw[i] * p[3 * i + (size_t)ch];
						const float x = tx[i], y = ty[i], z = tz[i];

						s[0] += wl;
						s[1] += wl * x;
						s[2] += wl * y;
						s[3] += wl * z;
						s[4] += wl * x * x;
						s[5] += wl * y * y;
						s[6] += wl * z * z;
						s[7] += wl * x * y;
						s[8] += wl * x * z;
						s[9] += wl * y * z;
					}
					for (k = 0; k < 10; k++)
						m[f][ch][k] += s[k];
				}
			}
		}
	}
	for (f = 0; f < 6; f++) {
		struct face_axes ax;

		face_axes((enum rf_face)f, &ax);
		for (ch = 0; ch < 3; ch++) {
			const double *q = m[f][ch];
			/* local second moments as a symmetric matrix */
			const double q2[3][3] = { { q[4], q[7], q[8] },
			                          { q[7], q[5], q[9] },
			                          { q[8], q[9], q[6] } };

			w0[ch] += q[0];
			for (k = 0; k < 3; k++) {
				w1[ch][k] += ax.sign[k] * q[1 + ax.perm[k]];
				for (l = 0; l < 3; l++)
					w2[ch][k][l] += ax.sign[k] * ax.sign[l] *
					                q2[ax.perm[k]][ax.perm[l]];
			}
		}
	}
	for (ch = 0; ch < 3; ch++) {
		sh[0 + ch] = (float)(0.282094792 * w0[ch]);
		sh[3 + ch] = (float)(0.488602512 * w1[ch][1]);
		sh[6 + ch] = (float)(0.488602512 * w1[ch][2]);
		sh[9 + ch] = (float)(0.488602512 * w1[ch][0]);
		sh[12 + ch] = (float)(1.092548431 * w2[ch][0][1]);
		sh[15 + ch] = (float)(1.092548431 * w2[ch][1][2]);
		sh[18 + ch] = (float)(0.315391565 * (3.0 * w2[ch][2][2] - w0[ch]));
		sh[21 + ch] = (float)(1.092548431 * w2[ch][0][2]);
		sh[24 + ch] = (float)(0.546274215 * (w2[ch][0][0] - w2[ch][1][1]));
	}
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

void
rf__sh9_quadratic(const float sh[27], float q[3][9])
{
	/* the lobe's share of each band times the basis' constants */
	const double c0 = M_PI * 0.282094792, c1 = 2.0 * M_PI / 3 * 0.488602512;
	const double c2 = M_PI / 4 * 1.092548431, c6 = M_PI / 4 * 0.315391565;
	const double c8 = M_PI / 4 * 0.546274215;
	int ch;

	for (ch = 0; ch < 3; ch++) {
		q[ch][0] = (float)(c0 * sh[ch] - c6 * sh[18 + ch]);
		q[ch][1] = (float)(c1 * sh[9 + ch]);
		q[ch][2] = (float)(c1 * sh[3 + ch]);
		q[ch][3] = (float)(c1 * sh[6 + ch]);
		q[ch][4] = (float)(c2 * sh[12 + ch]);
		q[ch][5] = (float)(c2 * sh[15 + ch]);
		q[ch][6] = (float)(c2 * sh[21 + ch]);
		q[ch][7] = (float)(3.0 * c6 * sh[18 + ch]);
		q[ch][8] = (float)(c8 * sh[24 + ch]);
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
