/*
 * The raytraced mode against references worked out here: a brute-force
 * integral of the GGX lobe against the box room over a fine grid of
 * directions, box projection at lod 0 for a mirror, and a transcription
 * of the write-up's loop (spec 7.2, 7.3) for estimator=original.
 */
#include <math.h>

#include "reflect/host.h"
#include "reflect/shading.h"
#include "tap.h"

#define ENV_SIZE 32

static char msg[512];
static rf_cubemap *env;
static rf_plugin_host *host;
static const struct rf_probe probe = { { 0.0f, 1.5f, 0.0f }, { -3, 0, -2 }, { 3, 3, 2 }, 1, 0.0f, 0 };

/* The default room at 32 texels a face, with the host's services. */
static int
setup(void)
{
	if (rf_cubemap_create(&env, ENV_SIZE, 1) < 0)
		return -1;
	rf_default_environment_cube(env);
	if (rf_plugin_host_create(&host) < 0)
		return -1;
	rf_plugin_host_set_probe(host, &probe);
	rf_plugin_host_set_environment(host, env, RF_MAPPING_DEFAULT, 0);
	return rf_plugin_host_set_radiance(host, env);
}

/* One pixel through the mode with the given parameters: spec.R G B. */
static int
shade(const char *spec, const float in[13], uint32_t x, uint32_t y, float out[3])
{
	const struct rf_plugin *p;
	struct rf_span span;
	rf_module *m;
	double values[16];
	void *state;
	int rc = -1;

	msg[0] = '\0';
	if (rf_module_load(&m, "raytraced", RF_KIND_SHADE, msg, sizeof(msg)) < 0)
		return -1;
	p = rf_module_plugin(m);
	if (rf_plugin_parse_params(p, spec, values, msg, sizeof(msg)) == 0 &&
	    p->create(rf_plugin_host_table(host), values, &state, msg, sizeof(msg)) == 0) {
		memset(&span, 0, sizeof(span));
		span.size = sizeof(span);
		span.npix = 1;
		span.x = x;
		span.y = y;
		span.width = span.height = 1000;
		span.in = in;
		span.out = out;
		p->run(state, &span);
		p->destroy(state);
		rc = 0;
	}
	rf_module_unload(m);
	return rc;
}

static void
pixel(float in[13], const float p[3], const float n[3], const float v[3], float pr)
{
	int i;

	/* P N V roughness, then the optional Ng */
	for (i = 0; i < 3; i++) {
		in[i] = p[i];
		in[3 + i] = n[i];
		in[6 + i] = v[i];
		in[10 + i] = n[i];
	}
	in[9] = pr;
}

static void
unit(float v[3])
{
	float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);

	v[0] /= l;
	v[1] /= l;
	v[2] /= l;
}

/* Radiance along directions from p, as the mode reads it at lod 0. */
static void
radiance(const float p[3], size_t n, const float *dirs, float *rgb)
{
	const struct rf_host *t = rf_plugin_host_table(host);
	float *look = malloc(n * 3 * sizeof(float)), *dist = malloc(n * sizeof(float));
	float *jac = malloc(n * sizeof(float)), *x = malloc(n * 4 * sizeof(float));
	float *rgba = malloc(n * 4 * sizeof(float)), *lod = x + 3 * n;
	size_t i;

	t->project_rays(t->ctx, (uint32_t)n, p, dirs, look, dist, jac);
	for (i = 0; i < n; i++) {
		x[i] = look[3 * i];
		x[n + i] = look[3 * i + 1];
		x[2 * n + i] = look[3 * i + 2];
		lod[i] = 0.0f;
	}
	t->sample_radiance(t->ctx, (uint32_t)n, x, x + n, x + 2 * n, lod, rgba);
	for (i = 0; i < n; i++)
		memcpy(rgb + 3 * i, rgba + 4 * i, 3 * sizeof(float));
	free(look);
	free(dist);
	free(jac);
	free(x);
	free(rgba);
}

static double
lambda(double alpha2, double c)
{
	return 0.5 * (sqrt(1.0 + alpha2 * (1.0 - c * c) / (c * c)) - 1.0);
}

/*
 * The integral of f(V,L) (N.L) L(P,L) dL, F = 1, by brute force: the
 * hemisphere about N cut into 1200 x 2400 cells of polar angle and
 * azimuth, each weighted by its solid angle sin(t) dt dphi.
 */
static void
brute_force(const float in[13], int separable, double out[3])
{
	const size_t nt = 1200, np = 2400;
	const float *p = in, *n = in + 3, *v = in + 6;
	double alpha = (double)in[9] * in[9], a2 = alpha * alpha, nv = 0, sum[3] = { 0 };
	float tx[3], ty[3], *dirs = malloc(np * 3 * sizeof(float));
	float *rgb = malloc(np * 3 * sizeof(float));
	size_t i, j;
	int k;

	for (k = 0; k < 3; k++)
		nv += (double)n[k] * v[k];
	/* any frame about n will do */
	tx[0] = n[1];
	tx[1] = -n[0];
	tx[2] = 0;
	if (fabsf(n[2]) > 0.9f) {
		tx[0] = 0;
		tx[1] = n[2];
		tx[2] = -n[1];
	}
	unit(tx);
	ty[0] = n[1] * tx[2] - n[2] * tx[1];
	ty[1] = n[2] * tx[0] - n[0] * tx[2];
	ty[2] = n[0] * tx[1] - n[1] * tx[0];
	for (i = 0; i < nt; i++) {
		double t = (i + 0.5) * (M_PI / 2) / nt, dw = sin(t) * (M_PI / 2 / nt) * (2 * M_PI / np);
		double cl = cos(t);

		for (j = 0; j < np; j++) {
			double ph = (j + 0.5) * 2 * M_PI / np;

			for (k = 0; k < 3; k++)
				dirs[3 * j + k] = (float)(sin(t) * cos(ph) * tx[k] +
				                          sin(t) * sin(ph) * ty[k] + cl * n[k]);
		}
		radiance(p, np, dirs, rgb);
		for (j = 0; j < np; j++) {
			double h[3], hl = 0, nh = 0, d, g;

			for (k = 0; k < 3; k++) {
				h[k] = dirs[3 * j + k] + v[k];
				hl += h[k] * h[k];
			}
			hl = sqrt(hl);
			for (k = 0; k < 3; k++)
				nh += n[k] * h[k] / hl;
			d = a2 / (M_PI * pow(nh * nh * (a2 - 1) + 1, 2));
			g = separable ? 1 / ((1 + lambda(a2, nv)) * (1 + lambda(a2, cl)))
			              : 1 / (1 + lambda(a2, nv) + lambda(a2, cl));
			/* f (N.L) = D G / (4 N.V) */
			for (k = 0; k < 3; k++)
				sum[k] += d * g / (4 * nv) * rgb[3 * j + k] * dw;
		}
	}
	for (k = 0; k < 3; k++)
		out[k] = sum[k];
	free(dirs);
	free(rgb);
}

/* R G B as reflect-shade --final makes it for a white metal. */
static void
final_rgb(const float in[13], const float spec[3], double rgb[3])
{
	float a, b, nv = in[3] * in[6] + in[4] * in[7] + in[5] * in[8];
	int k;

	rf_dfg_lookup(nv, in[9], &a, &b);
	for (k = 0; k < 3; k++)
		rgb[k] = (double)spec[k] * (a + b);
}

TEST(exact_converges_to_the_integral)
{
	/* On the floor, on a wall, near a corner; three roughnesses. */
	static const float cases[][10] = {
		{ 0.5f, 0.0f, 0.3f, 0, 1, 0, 0.3f, 0.6f, 0.8f, 0.5f },
		{ -2.9f, 1.2f, 0.4f, 1, 0, 0, 0.7f, 0.2f, -0.5f, 0.3f },
		{ 2.5f, 0.3f, 1.6f, 0, 1, 0, -0.6f, 0.3f, -0.7f, 0.8f },
	};
	double white_error = 0, mis_error = 0;
	size_t c;
	int sep, k;

	for (c = 0; c < sizeof(cases) / sizeof(cases[0]); c++)
		for (sep = 0; sep < 2; sep++) {
			float in[13], v[3] = { cases[c][6], cases[c][7], cases[c][8] }, spec[3];
			double want[3], got[3], err = 0, mag = 0;

			unit(v);
			pixel(in, cases[c], cases[c] + 3, v, cases[c][9]);
			brute_force(in, sep, want);
			/* Hammersley's points converge fast: 0.03 % at most here,
			 * where the two maskings differ by up to 7 %. */
			ASSERT_EQ(shade(sep ? "samples=10000:pattern=deterministic:masking=separable"
			                    : "samples=10000:pattern=deterministic",
			                in, 17, 23, spec), 0);
			final_rgb(in, spec, got);
			for (k = 0; k < 3; k++) {
				err += fabs(got[k] - want[k]);
				mag += want[k];
			}
			printf("# case %zu %s: %.5f %.5f %.5f (brute force %.5f %.5f %.5f), "
			       "relative error %.4f\n", c, sep ? "separable" : "correlated",
			       got[0], got[1], got[2], want[0], want[1], want[2], err / mag);
			ASSERT(mag > 0.1);
			ASSERT(err / mag < 0.003);
			/* White noise: the HDR windows make it noisier (2 % at 10,000
			 * rays measured at these pixels); within 1 % on average. */
			ASSERT_EQ(shade(sep ? "samples=10000:pattern=white:masking=separable"
			                    : "samples=10000:pattern=white",
			                in, 17, 23, spec), 0);
			final_rgb(in, spec, got);
			for (k = 0, err = 0; k < 3; k++)
				err += fabs(got[k] - want[k]);
			ASSERT(err / mag < 0.03);
			white_error += err / mag;
			/* The mixture of sampler=mis converges to the same integral
			 * (its weights undo its density), pattern by pattern. */
			ASSERT_EQ(shade(sep ? "samples=10000:pattern=deterministic:sampler=mis:"
			                      "masking=separable"
			                    : "samples=10000:pattern=deterministic:sampler=mis",
			                in, 17, 23, spec), 0);
			final_rgb(in, spec, got);
			for (k = 0, err = 0; k < 3; k++)
				err += fabs(got[k] - want[k]);
			printf("# sampler=mis: relative error %.4f\n", err / mag);
			ASSERT(err / mag < 0.003);
			ASSERT_EQ(shade(sep ? "samples=10000:pattern=white:sampler=mis:"
			                      "masking=separable"
			                    : "samples=10000:pattern=white:sampler=mis",
			                in, 17, 23, spec), 0);
			final_rgb(in, spec, got);
			for (k = 0, err = 0; k < 3; k++)
				err += fabs(got[k] - want[k]);
			ASSERT(err / mag < 0.03);
			mis_error += err / mag;
		}
	printf("# white noise at 10,000 rays: mean relative error %.4f, with sampler=mis "
	       "%.4f\n", white_error / 6, mis_error / 6);
	ASSERT(white_error / 6 < 0.01);
	ASSERT(mis_error / 6 < 0.01);
}

TEST(a_mirror_is_box_projection_at_lod_0)
{
	const float p[3] = { 0.5f, 0.0f, 0.3f }, n[3] = { 0, 1, 0 };
	float v[3] = { 0.3f, 0.6f, 0.8f }, in[13], spec[3], r[3], want[3], a, b;
	static const float prs[] = { 0.0f, 0.01f, 0.03f };
	size_t i;
	int k;

	unit(v);
	for (k = 0; k < 3; k++)
		r[k] = 2 * v[1] * n[k] - v[k];
	radiance(p, 1, r, want);
	for (i = 0; i < sizeof(prs) / sizeof(prs[0]); i++) {
		pixel(in, p, n, v, prs[i]);
		ASSERT_EQ(shade("samples=16", in, 3, 4, spec), 0);
		rf_dfg_lookup(v[1], prs[i], &a, &b);
		for (k = 0; k < 3; k++)
			ASSERT_NEAR(spec[k] * (a + b), want[k], 2e-3 * want[k] + 1e-6);
	}
}

/*
 * sampler=mis against the lobe alone: the squared error of 4, 16 and 64
 * white-noise rays (the three-column table, and a five-column one)
 * against the brute-force integral, over 64 pixels (64 draws) at
 * each of the three pixels of the test above, the footprint made that of
 * 10^6 rays (frames) so that both read level 0 as the integral does and
 * the error is the noise alone.  The room's windows are bright (HDR) and
 * small: where the mixture is taken (the floor's pixel sees a window) it
 * must find them; elsewhere the bytes are the lobe's alone.
 */
TEST(mis_lowers_the_error_at_equal_rays)
{
	static const float cases[][10] = {
		{ 0.5f, 0.0f, 0.3f, 0, 1, 0, 0.3f, 0.6f, 0.8f, 0.5f },
		{ -2.9f, 1.2f, 0.4f, 1, 0, 0, 0.7f, 0.2f, -0.5f, 0.3f },
		{ 2.5f, 0.3f, 1.6f, 0, 1, 0, -0.6f, 0.3f, -0.7f, 0.8f },
	};
	static const unsigned rays[] = { 4, 16, 64 };
	size_t c, r;
	int mixed = 0;

	for (c = 0; c < sizeof(cases) / sizeof(cases[0]); c++) {
		float in[13], v[3] = { cases[c][6], cases[c][7], cases[c][8] }, spec[2][3];
		double want[3], got[3], mag = 0;
		int k;

		unit(v);
		pixel(in, cases[c], cases[c] + 3, v, cases[c][9]);
		brute_force(in, 1, want);
		for (k = 0; k < 3; k++)
			mag += want[k] / 3;
		for (r = 0; r < sizeof(rays) / sizeof(rays[0]); r++) {
			double se[2] = { 0, 0 };
			char opts[2][128];
			uint32_t x;
			int s, differ = 0;

			snprintf(opts[0], sizeof(opts[0]),
			         "samples=%u:pattern=white:masking=separable:frames=1000000", rays[r]);
			snprintf(opts[1], sizeof(opts[1]), "%s:sampler=mis", opts[0]);
			for (x = 0; x < 64; x++) {
				for (s = 0; s < 2; s++) {
					ASSERT_EQ(shade(opts[s], in, x, 7, spec[s]), 0);
					final_rgb(in, spec[s], got);
					for (k = 0; k < 3; k++)
						se[s] += (got[k] - want[k]) * (got[k] - want[k]) /
						         (mag * mag);
				}
				differ += memcmp(spec[0], spec[1], sizeof(spec[0])) != 0;
			}
			/* Where the mixture is not worth it (the table's judgement)
			 * the lobe alone gives the same bytes. */
			printf("# case %zu: relative RMSE of %u rays, vndf %.4f, mis %.4f%s\n", c,
			       rays[r], sqrt(se[0] / 192), sqrt(se[1] / 192),
			       differ ? "" : " (the lobe alone)");
			ASSERT(differ == 0 || differ == 64);
			if (differ)
				ASSERT(se[1] < 0.8 * se[0]);
			mixed += differ > 0;
		}
	}
	ASSERT(mixed > 0);
}

TEST(mis_refuses_the_original_estimator)
{
	float in[13], spec[3];
	const float p[3] = { 0.5f, 0.0f, 0.3f }, n[3] = { 0, 1, 0 }, v[3] = { 0, 1, 0 };

	pixel(in, p, n, v, 0.5f);
	ASSERT(shade("sampler=mis:estimator=original", in, 0, 0, spec) < 0);
	ASSERT(strstr(msg, "estimator=exact") != NULL);
}

/* ---- the write-up's loop, transcribed (spec 7.2, 7.3) ------------------- */

static double
radinv(uint32_t i)
{
	i = (i << 16) | (i >> 16);
	i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
	i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
	i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
	i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
	return (double)(i >> 8) / 16777216.0;
}

static void
original(const float in[13], unsigned k, double out[3])
{
	const float *P = in, *N = in + 3, *V = in + 6;
	double a = (double)in[9] * in[9], s = N[2] >= 0 ? 1 : -1, aa = 1 / (s + N[2]);
	double b = N[0] * N[1] * aa, c = N[0] * s;
	double X[3] = { c * N[0] * aa - 1, s * b, c }, Y[3] = { b, N[1] * N[1] * aa - s, N[1] };
	double v[3] = { 0, 0, 0 }, sum[3] = { 0, 0, 0 };
	unsigned i, count = 0;
	int j;

	for (j = 0; j < 3; j++) {
		v[0] += X[j] * V[j];
		v[1] += Y[j] * V[j];
		v[2] += N[j] * V[j];
	}
	for (i = 0; i < k; i++) {
		double u1 = (i + 0.5) / k, u2 = radinv(i), vh[3], l, t1[3], t2[3], r, ph;
		double p1, p2, w, nh[3], h[3], hl, cc, lo[3], L[3], nl;
		float Lf[3], rgb[3];

		vh[0] = a * v[0];
		vh[1] = a * v[1];
		vh[2] = v[2];
		l = sqrt(vh[0] * vh[0] + vh[1] * vh[1] + vh[2] * vh[2]);
		for (j = 0; j < 3; j++)
			vh[j] /= l;
		if (vh[2] < 0.9999) {
			/* normalize(cross((0,0,1), Vh)) */
			l = sqrt(vh[0] * vh[0] + vh[1] * vh[1]);
			t1[0] = -vh[1] / l;
			t1[1] = vh[0] / l;
			t1[2] = 0;
		} else {
			t1[0] = 1;
			t1[1] = t1[2] = 0;
		}
		t2[0] = vh[1] * t1[2] - vh[2] * t1[1];
		t2[1] = vh[2] * t1[0] - vh[0] * t1[2];
		t2[2] = vh[0] * t1[1] - vh[1] * t1[0];
		r = sqrt(u1);
		ph = 2 * M_PI * u2;
		p1 = r * cos(ph);
		p2 = r * sin(ph);
		w = (1 + vh[2]) / 2;
		p2 = (1 - w) * sqrt(1 - p1 * p1) + w * p2;
		for (j = 0; j < 3; j++)
			nh[j] = p1 * t1[j] + p2 * t2[j] + sqrt(fmax(0, 1 - p1 * p1 - p2 * p2)) * vh[j];
		h[0] = a * nh[0];
		h[1] = a * nh[1];
		h[2] = fmax(0, nh[2]);
		hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
		cc = 0;
		for (j = 0; j < 3; j++) {
			h[j] /= hl;
			cc += v[j] * h[j];
		}
		cc = cc < 0 ? 0 : cc > 1 ? 1 : cc;
		for (j = 0; j < 3; j++)
			lo[j] = 2 * cc * h[j] - v[j];
		nl = 0;
		for (j = 0; j < 3; j++) {
			L[j] = lo[0] * X[j] + lo[1] * Y[j] + lo[2] * N[j];
			nl += N[j] * L[j];
		}
		if (nl < 0.001)
			continue;
		for (j = 0; j < 3; j++)
			Lf[j] = (float)L[j];
		radiance(P, 1, Lf, rgb);
		for (j = 0; j < 3; j++)
			sum[j] += rgb[j];
		count++;
	}
	for (j = 0; j < 3; j++)
		out[j] = sum[j] / count;
}

TEST(original_is_the_write_ups_loop)
{
	static const float cases[][10] = {
		{ 0.5f, 0.0f, 0.3f, 0, 1, 0, 0.3f, 0.6f, 0.8f, 0.5f },
		{ -2.9f, 1.2f, 0.4f, 1, 0, 0, 0.7f, 0.05f, -0.5f, 0.9f },
		{ 1.0f, 2.99f, -1.0f, 0, -1, 0, 0.1f, -0.3f, 0.9f, 0.2f },
	};
	size_t c;
	int k;

	for (c = 0; c < sizeof(cases) / sizeof(cases[0]); c++) {
		float in[13], v[3] = { cases[c][6], cases[c][7], cases[c][8] }, spec[3];
		double want[3];

		unit(v);
		pixel(in, cases[c], cases[c] + 3, v, cases[c][9]);
		original(in, 256, want);
		ASSERT_EQ(shade("samples=256:pattern=deterministic:estimator=original", in, 5,
		                6, spec), 0);
		for (k = 0; k < 3; k++)
			ASSERT_NEAR(spec[k], want[k], 1e-4 * want[k] + 1e-5);
	}
}

TEST(never_nan)
{
	const float p[3] = { 0.5f, 0.0f, 0.3f }, n[3] = { 0, 1, 0 }, below[3] = { 0, -1, 0 };
	const float grazing[3] = { 1, 0, 0 }, zero[3] = { 0, 0, 0 };
	static const char *const specs[] = { "samples=8", "samples=8:estimator=original",
	                                     "samples=8:mipoffset=1", "samples=32:sampler=mis" };
	const float *views[] = { below, grazing, zero, n };
	float in[13], spec[3];
	size_t s, i;
	int k;

	for (s = 0; s < sizeof(specs) / sizeof(specs[0]); s++)
		for (i = 0; i < 4; i++) {
			pixel(in, p, n, views[i], i == 3 ? NAN : 0.5f);
			ASSERT_EQ(shade(specs[s], in, 1, 1, spec), 0);
			for (k = 0; k < 3; k++)
				ASSERT(isfinite(spec[k]));
		}
}

/* The same pixel, 64 x 64 times, through pattern p at 4 rays: the
 * power of the image's low frequencies (0 < |k| <= 4 cycles across),
 * relative to its variance. */
static double
low_frequency_power(const char *spec)
{
	enum { N = 64 };
	const float p[3] = { 0.5f, 0.0f, 0.3f }, n[3] = { 0, 1, 0 };
	float v[3] = { 0.3f, 0.6f, 0.8f }, in[13];
	static float img[N][N];
	const struct rf_plugin *pl;
	struct rf_span span;
	rf_module *m;
	double values[16], mean = 0, var = 0, power = 0;
	void *state;
	float out[3];
	int x, y, kx, ky;

	unit(v);
	pixel(in, p, n, v, 0.5f);
	if (rf_module_load(&m, "raytraced", RF_KIND_SHADE, msg, sizeof(msg)) < 0)
		return -1;
	pl = rf_module_plugin(m);
	if (rf_plugin_parse_params(pl, spec, values, msg, sizeof(msg)) < 0 ||
	    pl->create(rf_plugin_host_table(host), values, &state, msg, sizeof(msg)) < 0)
		return -1;
	memset(&span, 0, sizeof(span));
	span.size = sizeof(span);
	span.npix = 1;
	span.in = in;
	span.out = out;
	for (y = 0; y < N; y++)
		for (x = 0; x < N; x++) {
			span.x = (uint32_t)x;
			span.y = (uint32_t)y;
			pl->run(state, &span);
			img[y][x] = out[1];
			mean += out[1];
		}
	pl->destroy(state);
	rf_module_unload(m);
	mean /= N * N;
	for (y = 0; y < N; y++)
		for (x = 0; x < N; x++)
			var += (img[y][x] - mean) * (img[y][x] - mean);
	for (ky = -4; ky <= 4; ky++)
		for (kx = -4; kx <= 4; kx++) {
			double re = 0, im = 0;

			if (!kx && !ky)
				continue;
			for (y = 0; y < N; y++)
				for (x = 0; x < N; x++) {
					double a = -2 * M_PI * (kx * x + ky * y) / N;

					re += (img[y][x] - mean) * cos(a);
					im += (img[y][x] - mean) * sin(a);
				}
			power += re * re + im * im;
		}
	return power / (var * N * N);
}

/* Blue noise puts its error at high frequencies; white noise spreads it
 * evenly, the 80 lowest of 4096 frequencies holding some 2 % of it.  The
 * room's grid lines and windows make the estimate a rough function of
 * the rotation, so less of the masks' blueness survives than they have
 * (measured: a third of white's share at one ray, a half at four). */
TEST(blue_noise_has_little_low_frequency_error)
{
	double white1 = low_frequency_power("samples=1:pattern=white");
	double blue1 = low_frequency_power("samples=1:pattern=blue");
	double white4 = low_frequency_power("samples=4:pattern=white");
	double blue4 = low_frequency_power("samples=4:pattern=blue");

	printf("# low-frequency share of the error at 1 ray: white %.4f, blue %.4f; "
	       "at 4: white %.4f, blue %.4f\n", white1, blue1, white4, blue4);
	ASSERT(white1 > 0.005 && white1 < 0.06 && white4 > 0.005 && white4 < 0.06);
	ASSERT(blue1 < 0.45 * white1);
	ASSERT(blue4 < 0.75 * white4);
}

/* One pixel's values over 16 animated frames at one ray, for 16 x 16
 * pixels: the share of the series' power at the lowest frequencies (1
 * and 2 cycles in 16 frames), relative to its variance. */
static double
temporal_low_power(const char *spec)
{
	enum { F = 16, N = 16 };
	const float p[3] = { 0.5f, 0.0f, 0.3f }, n[3] = { 0, 1, 0 };
	float v[3] = { 0.3f, 0.6f, 0.8f }, in[13], out[3];
	static float series[N][N][F];
	const struct rf_plugin *pl;
	struct rf_span span;
	rf_header *frame;
	rf_module *m;
	double values[16], low = 0, var = 0;
	char key[16];
	void *state;
	int f, x, y, k;

	unit(v);
	pixel(in, p, n, v, 0.5f);
	if (rf_module_load(&m, "raytraced", RF_KIND_SHADE, msg, sizeof(msg)) < 0 ||
	    rf_header_create(&frame) < 0)
		return -1;
	pl = rf_module_plugin(m);
	if (rf_plugin_parse_params(pl, spec, values, msg, sizeof(msg)) < 0)
		return -1;
	rf_plugin_host_set_frame(host, frame);
	memset(&span, 0, sizeof(span));
	span.size = sizeof(span);
	span.npix = 1;
	span.in = in;
	span.out = out;
	for (f = 0; f < F; f++) {
		snprintf(key, sizeof(key), "%d", f);
		rf_header_set(frame, "FRAME", key);
		if (pl->create(rf_plugin_host_table(host), values, &state, msg, sizeof(msg)) < 0)
			return -1;
		for (y = 0; y < N; y++)
			for (x = 0; x < N; x++) {
				span.x = (uint32_t)x;
				span.y = (uint32_t)y;
				pl->run(state, &span);
				series[y][x][f] = out[1];
			}
		pl->destroy(state);
	}
	rf_plugin_host_set_frame(host, NULL);
	rf_header_destroy(frame);
	rf_module_unload(m);
	for (y = 0; y < N; y++)
		for (x = 0; x < N; x++) {
			double mean = 0;

			for (f = 0; f < F; f++)
				mean += series[y][x][f] / F;
			for (f = 0; f < F; f++)
				var += (series[y][x][f] - mean) * (series[y][x][f] - mean);
			for (k = 1; k <= 2; k++) {
				double re = 0, im = 0;

				for (f = 0; f < F; f++) {
					re += (series[y][x][f] - mean) * cos(2 * M_PI * k * f / F);
					im += (series[y][x][f] - mean) * sin(2 * M_PI * k * f / F);
				}
				low += 2 * (re * re + im * im); /* k and -k */
			}
		}
	return low / (var * F);
}

/* Animated, the blue pattern moves by the R2 step each frame: each
 * pixel's series over frames is low-discrepancy, its power high in
 * frequency (white noise puts a quarter of it below 3 cycles in 16
 * frames; blue some 12 %, where slices of a spatio-temporal
 * void-and-cluster volume measured 17 %). */
TEST(animated_blue_noise_is_blue_in_time)
{
	double white = temporal_low_power("samples=1:animate=1:pattern=white");
	double blue = temporal_low_power("samples=1:animate=1:pattern=blue");

	printf("# low-frequency share over 16 frames: white %.4f, blue %.4f\n", white, blue);
	ASSERT(white > 0.12 && white < 0.4);
	ASSERT(blue < 0.6 * white);
}

int
main(void)
{
	if (setup() < 0) {
		printf("# setup failed: %s\n", msg);
		return 1;
	}
	RUN(exact_converges_to_the_integral);
	RUN(a_mirror_is_box_projection_at_lod_0);
	RUN(mis_lowers_the_error_at_equal_rays);
	RUN(mis_refuses_the_original_estimator);
	RUN(original_is_the_write_ups_loop);
	RUN(never_nan);
	RUN(blue_noise_has_little_low_frequency_error);
	RUN(animated_blue_noise_is_blue_in_time);
	TAP_DONE();
}
