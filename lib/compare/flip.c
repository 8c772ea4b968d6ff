/*
 * FLIP and HDR-FLIP (reflect/compare.h), from the papers: Andersson,
 * Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild, "FLIP: A
 * Difference Evaluator for Alternating Images" (HPG 2020), and Andersson,
 * Nilsson, Shirley and Akenine-Moller, "Visualizing and Communicating
 * Errors in Rendered Images" (Ray Tracing Gems II, 2021).
 *
 * Both pictures go to YCxCz, are filtered by the contrast sensitivity of
 * each opponent channel and compared in Hunt-adjusted CIELAB (HyAB);
 * their luminance's edges and points are compared apart, and the
 * feature difference raises the colour error to a power below 1.  The
 * filters are separable, so each pass is a horizontal sweep of every row
 * into whole-picture sums and a vertical one out of them: two batches of
 * row blocks on the pool, each row its own work, so that any thread
 * count gives the same bytes.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "compare/flip.h"
#include "util/pool.h"
#include "reflect/reflect.h"

/* The papers' constants: the colour error's exponent qc and the remap's
 * knee (pc of cmax to pt), the feature filters' width w in degrees and
 * the feature error's exponent qf. */
#define FLIP_QC 0.7
#define FLIP_PC 0.4
#define FLIP_PT 0.95
#define FLIP_W 0.082
#define FLIP_QF 0.5

/* The spatial filters' Gaussians, a sqrt(pi / b) exp(-pi^2 x^2 / b) of x
 * in degrees: achromatic, red-green, and the blue-yellow pair. */
static const double csf_a[4] = { 1.0, 1.0, 34.1, 13.5 };
static const double csf_b[4] = { 0.0047, 0.0053, 0.04, 0.025 };

/* D65, the white of sRGB: the row sums of the matrix below (XYZ with
 * Y = 1). */
static const double white[3] = { 23359437.0 / 24577794.0, 1.0, 80288307.0 / 73733382.0 };

/* Rows a task. */
#define BLOCK_ROWS 16

double
rf_flip_ppd(double distance, double width, double resolution)
{
	return distance * (resolution / width) * (M_PI / 180.0);
}

int
rf__flip_spatial_radius(double ppd)
{
	/* three standard deviations of the widest Gaussian: exp(-pi^2 x^2
	 * / b) has sigma^2 = b / (2 pi^2) */
	return (int)ceil(3.0 * sqrt(0.04 / (2.0 * M_PI * M_PI)) * ppd);
}

int
rf__flip_feature_radius(double ppd)
{
	return (int)ceil(3.0 * 0.5 * FLIP_W * ppd);
}

void
rf__flip_spatial_filters(double ppd, float *y, float *cx, float *cz1, float *cz2)
{
	const int r = rf__flip_spatial_radius(ppd), n = 2 * r + 1;
	double sum[4] = { 0, 0, 0, 0 }, norm;
	float *f[4] = { y, cx, cz1, cz2 };
	int k, c;

	for (c = 0; c < 4; c++)
		for (k = 0; k < n; k++) {
			const double x = (k - r) / ppd;
			const double g = exp(-M_PI * M_PI * x * x / csf_b[c]);
			/* the blue-yellow pair: each 2D Gaussian is the outer
			 * product of the square root of its amplitude times its
			 * 1D shape */
			const double v = c < 2 ? g : sqrt(csf_a[c] * sqrt(M_PI / csf_b[c])) * g;

			sum[c] += v;
			f[c][k] = (float)v;
		}
	norm = 1.0 / sqrt(sum[2] * sum[2] + sum[3] * sum[3]);
	for (k = 0; k < n; k++) {
		y[k] = (float)(y[k] / sum[0]);
		cx[k] = (float)(cx[k] / sum[1]);
		cz1[k] = (float)(cz1[k] * norm);
		cz2[k] = (float)(cz2[k] * norm);
	}
}

void
rf__flip_feature_filters(double ppd, float *g, float *dg, float *ddg)
{
	const double sd = 0.5 * FLIP_W * ppd;
	const int r = rf__flip_feature_radius(ppd), n = 2 * r + 1;
	double sg = 0, dpos = 0, dneg = 0, ddpos = 0, ddneg = 0;
	double *v = malloc(3 * (size_t)n * sizeof(double));
	int k;

	if (!v) { /* small; a failure leaves zero filters, never garbage */
		memset(g, 0, (size_t)n * sizeof(float));
		memset(dg, 0, (size_t)n * sizeof(float));
		memset(ddg, 0, (size_t)n * sizeof(float));
		return;
	}
	for (k = 0; k < n; k++) {
		const double x = k - r, e = exp(-x * x / (2.0 * sd * sd));

		v[3 * k] = e;
		v[3 * k + 1] = -x * e;
		v[3 * k + 2] = (x * x / (sd * sd) - 1.0) * e;
		sg += e;
		if (v[3 * k + 1] > 0)
			dpos += v[3 * k + 1];
		else
			dneg -= v[3 * k + 1];
		if (v[3 * k + 2] > 0)
			ddpos += v[3 * k + 2];
		else
			ddneg -= v[3 * k + 2];
	}
	for (k = 0; k < n; k++) {
		g[k] = (float)(v[3 * k] / sg);
		dg[k] = (float)(v[3 * k + 1] / (v[3 * k + 1] > 0 ? dpos : dneg));
		ddg[k] = (float)(v[3 * k + 2] / (v[3 * k + 2] > 0 ? ddpos : ddneg));
	}
	free(v);
}

/* Linear sRGB to XYZ (D65), the matrix of the sRGB primaries and white
 * as exact fractions, and its inverse, so that the trip there and back
 * leaves a colour as it was. */
static void
rgb_to_xyz(const float c[3], float xyz[3])
{
	static const float m[9] = {
		(float)(10135552.0 / 24577794.0), (float)(8788810.0 / 24577794.0),
		(float)(4435075.0 / 24577794.0),  (float)(2613072.0 / 12288897.0),
		(float)(8788810.0 / 12288897.0),  (float)(887015.0 / 12288897.0),
		(float)(1425312.0 / 73733382.0),  (float)(8788810.0 / 73733382.0),
		(float)(70074185.0 / 73733382.0),
	};

	xyz[0] = m[0] * c[0] + m[1] * c[1] + m[2] * c[2];
	xyz[1] = m[3] * c[0] + m[4] * c[1] + m[5] * c[2];
	xyz[2] = m[6] * c[0] + m[7] * c[1] + m[8] * c[2];
}

static void
xyz_to_rgb(const float xyz[3], float c[3])
{
	c[0] = 3.2410032330f * xyz[0] - 1.5373989695f * xyz[1] - 0.4986158820f * xyz[2];
	c[1] = -0.9692242522f * xyz[0] + 1.8759299837f * xyz[1] + 0.0415542263f * xyz[2];
	c[2] = 0.0556394199f * xyz[0] - 0.2040112061f * xyz[1] + 1.0571489772f * xyz[2];
}

void
rf__flip_rgb_to_ycxcz(const float rgb[3], float ycc[3])
{
	float xyz[3], x, y, z;

	rgb_to_xyz(rgb, xyz);
	x = xyz[0] / (float)white[0];
	y = xyz[1];
	z = xyz[2] / (float)white[2];
	ycc[0] = 116.0f * y - 16.0f;
	ycc[1] = 500.0f * (x - y);
	ycc[2] = 200.0f * (y - z);
}

void
rf__flip_ycxcz_to_rgb(const float ycc[3], float rgb[3])
{
	const float y = (ycc[0] + 16.0f) / 116.0f;
	float xyz[3];

	xyz[0] = (y + ycc[1] / 500.0f) * (float)white[0];
	xyz[1] = y;
	xyz[2] = (y - ycc[2] / 200.0f) * (float)white[2];
	xyz_to_rgb(xyz, rgb);
}

/* CIELAB's f(t): a cube root above (6/29)^3, a line below. */
static float
lab_f(float t)
{
	const float d = 6.0f / 29.0f;

	return t > d * d * d ? cbrtf(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
}

void
rf__flip_rgb_to_lab_hunt(const float rgb[3], float lab[3])
{
	float xyz[3], fx, fy, fz;

	rgb_to_xyz(rgb, xyz);
	fx = lab_f(xyz[0] / (float)white[0]);
	fy = lab_f(xyz[1]);
	fz = lab_f(xyz[2] / (float)white[2]);
	lab[0] = 116.0f * fy - 16.0f;
	lab[1] = 0.01f * lab[0] * 500.0f * (fx - fy);
	lab[2] = 0.01f * lab[0] * 200.0f * (fy - fz);
}

static float
hyab(const float p[3], const float q[3])
{
	const float da = p[1] - q[1], db = p[2] - q[2];

	return fabsf(p[0] - q[0]) + sqrtf(da * da + db * db);
}

float
rf__flip_cmax(void)
{
	static const float green[3] = { 0, 1, 0 }, blue[3] = { 0, 0, 1 };
	float g[3], b[3];

	rf__flip_rgb_to_lab_hunt(green, g);
	rf__flip_rgb_to_lab_hunt(blue, b);
	return powf(hyab(g, b), (float)FLIP_QC);
}

float
rf__flip_color_error(const float lab_a[3], const float lab_b[3], float cmax)
{
	const float e = powf(hyab(lab_a, lab_b), (float)FLIP_QC);
	const float knee = (float)FLIP_PC * cmax;

	/* small errors spread over [0, pt], the rest compressed into (pt, 1] */
	if (e < knee)
		return e * (float)FLIP_PT / knee;
	return (float)FLIP_PT + (e - knee) / (cmax - knee) * (1.0f - (float)FLIP_PT);
}

/* The ACES fit HDR-FLIP uses, (a x^2 + b x) / (c x^2 + d x + e), with its
 * 0.6 pre-exposure folded in. */
static const double aces[5] = { 0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.6 * 0.6 * 2.43, 0.6 * 0.59,
                                0.14 };

float
rf__flip_aces(float x)
{
	return (x * x * (float)aces[0] + x * (float)aces[1]) /
	       (x * x * (float)aces[2] + x * (float)aces[3] + (float)aces[4]);
}

double
rf__flip_aces_inverse_085(void)
{
	/* (a - t c) x^2 + (b - t d) x - t e = 0: the larger root */
	const double t = 0.85, qa = aces[0] - t * aces[2], qb = aces[1] - t * aces[3];
	const double qc = -t * aces[4], h = -0.5 * qb / qa;

	return h + sqrt(h * h - qc / qa);
}

float
rf__flip_srgb_decode(float v)
{
	return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

static float
clamp01(float v)
{
	return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
}

/* Luminance of linear sRGB. */
static double
luminance(const float *c)
{
	return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

static int
cmp_double(const void *p, const void *q)
{
	const double a = *(const double *)p, b = *(const double *)q;

	return (a > b) - (a < b);
}

int
rf_flip_exposures(const struct rf_compare_input *in, double *start, double *stop, int *count)
{
	const size_t n = in->width * in->height;
	const double top = rf__flip_aces_inverse_085();
	double *lum, ymax = -INFINITY, ymed;
	size_t p;

	if (!n || in->nch != 3)
		return RF_EINVAL;
	if (!(lum = malloc(n * sizeof(double))))
		return RF_ENOMEM;
	for (p = 0; p < n; p++) {
		const float *b = in->b + p * in->b_stride;
		const float c[3] = { b[in->b_col[0]], b[in->b_col[1]], b[in->b_col[2]] };

		lum[p] = luminance(c);
		if (lum[p] > ymax)
			ymax = lum[p];
	}
	/* the median is the middle value, the upper one of an even count */
	qsort(lum, n, sizeof(double), cmp_double);
	ymed = lum[n / 2];
	free(lum);
	if (!(ymax > 0.0) || !(ymed > 0.0) || !isfinite(ymax))
		return RF_EINVAL;
	*start = log2(top / ymax);
	*stop = log2(top / ymed);
	*count = (int)fmax(2.0, ceil(*stop - *start));
	return 0;
}

/* One comparison's state: the filters and, for the pass under way, the
 * horizontal sums of both pictures (8 spatial and 6 feature floats a
 * pixel: A's then B's). */
struct flip {
	const struct rf_compare_input *in;
	const struct rf_flip_options *o;
	float scale; /* HDR-FLIP: 2^exposure */
	int rs, rf;
	float *fs[4], *fg, *fdg, *fddg;
	float *hs, *hf;
	float *row[RF__THREADS_MAX]; /* a thread's padded rows of YCxCz */
	float *acc[RF__THREADS_MAX]; /* a thread's vertical sums of one row */
	float cmax;
	float *error;
	int first; /* HDR-FLIP: the first exposure writes, the others keep the largest */
};

/* A pixel's colour as the filters take it: linear, clamped to [0, 1]
 * (LDR) or exposed, tone-mapped and clamped (HDR), in YCxCz. */
static void
to_ycxcz(const struct flip *f, const float *px, const int *col, int srgb, float ycc[3])
{
	float c[3];
	int k;

	for (k = 0; k < 3; k++) {
		float v = px[col[k]];

		if (f->o->hdr)
			v = rf__flip_aces(v * f->scale);
		else if (srgb)
			v = rf__flip_srgb_decode(clamp01(v));
		c[k] = clamp01(v);
	}
	rf__flip_rgb_to_ycxcz(c, ycc);
}

/* The horizontal sums of rows [task BLOCK_ROWS, +BLOCK_ROWS). */
static void
horizontal(void *arg, size_t task, int thread)
{
	struct flip *f = arg;
	const struct rf_compare_input *in = f->in;
	const size_t w = in->width, pad = (size_t)(f->rs > f->rf ? f->rs : f->rf);
	const size_t y0 = task * BLOCK_ROWS;
	const size_t y1 = y0 + BLOCK_ROWS < in->height ? y0 + BLOCK_ROWS : in->height;
	float *row = f->row[thread];
	size_t x, y;
	int s, k;

	for (y = y0; y < y1; y++) {
		/* both pictures' YCxCz, A's then B's rows, each padded by its
		 * edge pixels repeated */
		for (s = 0; s < 2; s++) {
			const float *src = s ? in->b : in->a;
			const size_t stride = s ? in->b_stride : in->a_stride;
			const int *col = s ? in->b_col : in->a_col;
			const int srgb = s ? f->o->b_srgb : f->o->a_srgb;
			float *r = row + (size_t)s * (w + 2 * pad) * 3;

			for (x = 0; x < w; x++)
				to_ycxcz(f, src + (y * w + x) * stride, col, srgb, r + (pad + x) * 3);
			for (x = 0; x < pad; x++) {
				memcpy(r + x * 3, r + pad * 3, 3 * sizeof(float));
				memcpy(r + (pad + w + x) * 3, r + (pad + w - 1) * 3, 3 * sizeof(float));
			}
		}
		for (x = 0; x < w; x++) {
			float *hs = f->hs + (y * w + x) * 8, *hf = f->hf + (y * w + x) * 6;

			for (s = 0; s < 2; s++) {
				const float *r = row + (size_t)s * (w + 2 * pad) * 3 + (pad + x) * 3;
				float sy = 0, scx = 0, scz1 = 0, scz2 = 0, d = 0, dd = 0, g = 0;

				for (k = -f->rs; k <= f->rs; k++) {
					const float *p = r + k * 3;

					sy += f->fs[0][k + f->rs] * p[0];
					scx += f->fs[1][k + f->rs] * p[1];
					scz1 += f->fs[2][k + f->rs] * p[2];
					scz2 += f->fs[3][k + f->rs] * p[2];
				}
				for (k = -f->rf; k <= f->rf; k++) {
					/* luminance, 0 to 1, from Y */
					const float l = (r[k * 3] + 16.0f) / 116.0f;

					d += f->fdg[k + f->rf] * l;
					dd += f->fddg[k + f->rf] * l;
					g += f->fg[k + f->rf] * l;
				}
				hs[4 * s] = sy;
				hs[4 * s + 1] = scx;
				hs[4 * s + 2] = scz1;
				hs[4 * s + 3] = scz2;
				hf[3 * s] = d;
				hf[3 * s + 1] = dd;
				hf[3 * s + 2] = g;
			}
		}
	}
}

/* The vertical sums and FLIP of rows [task BLOCK_ROWS, +BLOCK_ROWS). */
static void
vertical(void *arg, size_t task, int thread)
{
	struct flip *f = arg;
	const size_t w = f->in->width, h = f->in->height;
	const size_t y0 = task * BLOCK_ROWS, y1 = y0 + BLOCK_ROWS < h ? y0 + BLOCK_ROWS : h;
	float *as = f->acc[thread], *af = as + w * 8;
	const float qf_norm = (float)(1.0 / sqrt(2.0));
	size_t x, y, i;
	int k, s;

	for (y = y0; y < y1; y++) {
		memset(as, 0, w * 20 * sizeof(float));
		for (k = -f->rs; k <= f->rs; k++) {
			const long yy = (long)y + k < 0 ? 0 : (long)y + k >= (long)h ? (long)h - 1
			                                                         : (long)y + k;
			const float *src = f->hs + (size_t)yy * w * 8;
			const float wt[4] = { f->fs[0][k + f->rs], f->fs[1][k + f->rs],
			                      f->fs[2][k + f->rs], f->fs[3][k + f->rs] };

			for (i = 0; i < w * 8; i++)
				as[i] += wt[i & 3] * src[i];
		}
		for (k = -f->rf; k <= f->rf; k++) {
			const long yy = (long)y + k < 0 ? 0 : (long)y + k >= (long)h ? (long)h - 1
			                                                         : (long)y + k;
			const float *src = f->hf + (size_t)yy * w * 6;
			const float g = f->fg[k + f->rf], dg = f->fdg[k + f->rf];
			const float ddg = f->fddg[k + f->rf];

			/* per picture: d/dx and d2/dx2 (taken across) smoothed
			 * down, and the across-smoothed luminance derived down */
			for (x = 0; x < w; x++)
				for (s = 0; s < 2; s++) {
					const float *p = src + x * 6 + 3 * s;
					float *q = af + x * 12 + 6 * s;

					q[0] += g * p[0];
					q[1] += g * p[1];
					q[2] += dg * p[2];
					q[3] += ddg * p[2];
				}
		}
		for (x = 0; x < w; x++) {
			float lab[2][3], edge[2], point[2], c, fe, e;

			for (s = 0; s < 2; s++) {
				const float *p = as + x * 8 + 4 * s, *q = af + x * 12 + 6 * s;
				const float ycc[3] = { p[0], p[1], p[2] + p[3] };
				float rgb[3];

				rf__flip_ycxcz_to_rgb(ycc, rgb);
				rgb[0] = clamp01(rgb[0]);
				rgb[1] = clamp01(rgb[1]);
				rgb[2] = clamp01(rgb[2]);
				rf__flip_rgb_to_lab_hunt(rgb, lab[s]);
				edge[s] = sqrtf(q[0] * q[0] + q[2] * q[2]);
				point[s] = sqrtf(q[1] * q[1] + q[3] * q[3]);
			}
			c = rf__flip_color_error(lab[0], lab[1], f->cmax);
			fe = fmaxf(fabsf(edge[0] - edge[1]), fabsf(point[0] - point[1]));
			fe = powf(qf_norm * fe, (float)FLIP_QF);
			e = powf(c, 1.0f - fe);
			if (f->first || e > f->error[y * w + x])
				f->error[y * w + x] = e;
		}
	}
}

static void
run(struct flip *f, struct rf__pool *pool, rf__pool_fn *fn)
{
	const size_t ntasks = (f->in->height + BLOCK_ROWS - 1) / BLOCK_ROWS;
	size_t t;

	if (pool) {
		rf__pool_run(pool, ntasks, fn, f);
		return;
	}
	for (t = 0; t < ntasks; t++)
		fn(f, t, 0);
}

int
rf_compare_flip(float *error, const struct rf_flip_options *o, const struct rf_compare_input *in)
{
	const size_t w = in->width, h = in->height;
	struct flip f;
	struct rf__pool *pool = NULL;
	int nthreads = 1, i, rc = RF_ENOMEM, nexp;
	size_t pad;

	if (in->nch != 3 || !(o->ppd > 0.0) || !isfinite(o->ppd) ||
	    (o->hdr && (!isfinite(o->start) || !isfinite(o->stop) || o->start > o->stop ||
	                o->nexposures < 1)))
		return RF_EINVAL;
	if (!w || !h)
		return 0;
	memset(&f, 0, sizeof(f));
	f.in = in;
	f.o = o;
	f.error = error;
	f.rs = rf__flip_spatial_radius(o->ppd);
	f.rf = rf__flip_feature_radius(o->ppd);
	f.cmax = rf__flip_cmax();
	pad = (size_t)(f.rs > f.rf ? f.rs : f.rf);
	if (o->nthreads > 1)
		rf__pool_create(&pool, o->nthreads > RF__THREADS_MAX ? RF__THREADS_MAX : o->nthreads);
	if (pool)
		nthreads = rf__pool_threads(pool);
	if (w > (size_t)-1 / h / 14 / sizeof(float))
		goto out;
	for (i = 0; i < 4; i++)
		if (!(f.fs[i] = malloc((2 * (size_t)f.rs + 1) * sizeof(float))))
			goto out;
	if (!(f.fg = malloc((2 * (size_t)f.rf + 1) * sizeof(float))) ||
	    !(f.fdg = malloc((2 * (size_t)f.rf + 1) * sizeof(float))) ||
	    !(f.fddg = malloc((2 * (size_t)f.rf + 1) * sizeof(float))) ||
	    !(f.hs = malloc(w * h * 8 * sizeof(float))) ||
	    !(f.hf = malloc(w * h * 6 * sizeof(float))))
		goto out;
	for (i = 0; i < nthreads; i++)
		if (!(f.row[i] = malloc(2 * (w + 2 * pad) * 3 * sizeof(float))) ||
		    !(f.acc[i] = malloc(w * 20 * sizeof(float))))
			goto out;
	rf__flip_spatial_filters(o->ppd, f.fs[0], f.fs[1], f.fs[2], f.fs[3]);
	rf__flip_feature_filters(o->ppd, f.fg, f.fdg, f.fddg);
	nexp = o->hdr ? o->nexposures : 1;
	for (i = 0; i < nexp; i++) {
		const double step = nexp > 1 ? (o->stop - o->start) / (nexp - 1) : 0.0;

		f.scale = o->hdr ? (float)exp2(o->start + i * step) : 1.0f;
		f.first = i == 0;
		run(&f, pool, horizontal);
		run(&f, pool, vertical);
	}
	rc = 0;
out:
	if (pool)
		rf__pool_destroy(pool);
	for (i = 0; i < 4; i++)
		free(f.fs[i]);
	free(f.fg);
	free(f.fdg);
	free(f.fddg);
	free(f.hs);
	free(f.hf);
	for (i = 0; i < RF__THREADS_MAX; i++) {
		free(f.row[i]);
		free(f.acc[i]);
	}
	return rc;
}

/* matplotlib's magma (Nathaniel J. Smith and Stefan van der Walt, CC0):
 * dark purple to pale yellow, even in lightness, and readable in grey. */
static const float magma[256][3] = {
	{ 0.001462f, 0.000466f, 0.013866f },
	{ 0.002258f, 0.001295f, 0.018331f },
	{ 0.003279f, 0.002305f, 0.023708f },
	{ 0.004512f, 0.003490f, 0.029965f },
	{ 0.005950f, 0.004843f, 0.037130f },
	{ 0.007588f, 0.006356f, 0.044973f },
	{ 0.009426f, 0.008022f, 0.052844f },
	{ 0.011465f, 0.009828f, 0.060750f },
	{ 0.013708f, 0.011771f, 0.068667f },
	{ 0.016156f, 0.013840f, 0.076603f },
	{ 0.018815f, 0.016026f, 0.084584f },
	{ 0.021692f, 0.018320f, 0.092610f },
	{ 0.024792f, 0.020715f, 0.100676f },
	{ 0.028123f, 0.023201f, 0.108787f },
	{ 0.031696f, 0.025765f, 0.116965f },
	{ 0.035520f, 0.028397f, 0.125209f },
	{ 0.039608f, 0.031090f, 0.133515f },
	{ 0.043830f, 0.033830f, 0.141886f },
	{ 0.048062f, 0.036607f, 0.150327f },
	{ 0.052320f, 0.039407f, 0.158841f },
	{ 0.056615f, 0.042160f, 0.167446f },
	{ 0.060949f, 0.044794f, 0.176129f },
	{ 0.065330f, 0.047318f, 0.184892f },
	{ 0.069764f, 0.049726f, 0.193735f },
	{ 0.074257f, 0.052017f, 0.202660f },
	{ 0.078815f, 0.054184f, 0.211667f },
	{ 0.083446f, 0.056225f, 0.220755f },
	{ 0.088155f, 0.058133f, 0.229922f },
	{ 0.092949f, 0.059904f, 0.239164f },
	{ 0.097833f, 0.061531f, 0.248477f },
	{ 0.102815f, 0.063010f, 0.257854f },
	{ 0.107899f, 0.064335f, 0.267289f },
	{ 0.113094f, 0.065492f, 0.276784f },
	{ 0.118405f, 0.066479f, 0.286321f },
	{ 0.123833f, 0.067295f, 0.295879f },
	{ 0.129380f, 0.067935f, 0.305443f },
	{ 0.135053f, 0.068391f, 0.315000f },
	{ 0.140858f, 0.068654f, 0.324538f },
	{ 0.146785f, 0.068738f, 0.334011f },
	{ 0.152839f, 0.068637f, 0.343404f },
	{ 0.159018f, 0.068354f, 0.352688f },
	{ 0.165308f, 0.067911f, 0.361816f },
	{ 0.171713f, 0.067305f, 0.370771f },
	{ 0.178212f, 0.066576f, 0.379497f },
	{ 0.184801f, 0.065732f, 0.387973f },
	{ 0.191460f, 0.064818f, 0.396152f },
	{ 0.198177f, 0.063862f, 0.404009f },
	{ 0.204935f, 0.062907f, 0.411514f },
	{ 0.211718f, 0.061992f, 0.418647f },
	{ 0.218512f, 0.061158f, 0.425392f },
	{ 0.225302f, 0.060445f, 0.431742f },
	{ 0.232077f, 0.059889f, 0.437695f },
	{ 0.238826f, 0.059517f, 0.443256f },
	{ 0.245543f, 0.059352f, 0.448436f },
	{ 0.252220f, 0.059415f, 0.453248f },
	{ 0.258857f, 0.059706f, 0.457710f },
	{ 0.265447f, 0.060237f, 0.461840f },
	{ 0.271994f, 0.060994f, 0.465660f },
	{ 0.278493f, 0.061978f, 0.469190f },
	{ 0.284951f, 0.063168f, 0.472451f },
	{ 0.291366f, 0.064553f, 0.475462f },
	{ 0.297740f, 0.066117f, 0.478243f },
	{ 0.304081f, 0.067835f, 0.480812f },
	{ 0.310382f, 0.069702f, 0.483186f },
	{ 0.316654f, 0.071690f, 0.485380f },
	{ 0.322899f, 0.073782f, 0.487408f },
	{ 0.329114f, 0.075972f, 0.489287f },
	{ 0.335308f, 0.078236f, 0.491024f },
	{ 0.341482f, 0.080564f, 0.492631f },
	{ 0.347636f, 0.082946f, 0.494121f },
	{ 0.353773f, 0.085373f, 0.495501f },
	{ 0.359898f, 0.087831f, 0.496778f },
	{ 0.366012f, 0.090314f, 0.497960f },
	{ 0.372116f, 0.092816f, 0.499053f },
	{ 0.378211f, 0.095332f, 0.500067f },
	{ 0.384299f, 0.097855f, 0.501002f },
	{ 0.390384f, 0.100379f, 0.501864f },
	{ 0.396467f, 0.102902f, 0.502658f },
	{ 0.402548f, 0.105420f, 0.503386f },
	{ 0.408629f, 0.107930f, 0.504052f },
	{ 0.414709f, 0.110431f, 0.504662f },
	{ 0.420791f, 0.112920f, 0.505215f },
	{ 0.426877f, 0.115395f, 0.505714f },
	{ 0.432967f, 0.117855f, 0.506160f },
	{ 0.439062f, 0.120298f, 0.506555f },
	{ 0.445163f, 0.122724f, 0.506901f },
	{ 0.451271f, 0.125132f, 0.507198f },
	{ 0.457386f, 0.127522f, 0.507448f },
	{ 0.463508f, 0.129893f, 0.507652f },
	{ 0.469640f, 0.132245f, 0.507809f },
	{ 0.475780f, 0.134577f, 0.507921f },
	{ 0.481929f, 0.136891f, 0.507989f },
	{ 0.488088f, 0.139186f, 0.508011f },
	{ 0.494258f, 0.141462f, 0.507988f },
	{ 0.500438f, 0.143719f, 0.507920f },
	{ 0.506629f, 0.145958f, 0.507806f },
	{ 0.512831f, 0.148179f, 0.507648f },
	{ 0.519045f, 0.150383f, 0.507443f },
	{ 0.525270f, 0.152569f, 0.507192f },
	{ 0.531507f, 0.154739f, 0.506895f },
	{ 0.537755f, 0.156894f, 0.506551f },
	{ 0.544015f, 0.159033f, 0.506159f },
	{ 0.550287f, 0.161158f, 0.505719f },
	{ 0.556571f, 0.163269f, 0.505230f },
	{ 0.562866f, 0.165368f, 0.504692f },
	{ 0.569172f, 0.167454f, 0.504105f },
	{ 0.575490f, 0.169530f, 0.503466f },
	{ 0.581819f, 0.171596f, 0.502777f },
	{ 0.588158f, 0.173652f, 0.502035f },
	{ 0.594508f, 0.175701f, 0.501241f },
	{ 0.600868f, 0.177743f, 0.500394f },
	{ 0.607238f, 0.179779f, 0.499492f },
	{ 0.613617f, 0.181811f, 0.498536f },
	{ 0.620005f, 0.183840f, 0.497524f },
	{ 0.626401f, 0.185867f, 0.496456f },
	{ 0.632805f, 0.187893f, 0.495332f },
	{ 0.639216f, 0.189921f, 0.494150f },
	{ 0.645633f, 0.191952f, 0.492910f },
	{ 0.652056f, 0.193986f, 0.491611f },
	{ 0.658483f, 0.196027f, 0.490253f },
	{ 0.664915f, 0.198075f, 0.488836f },
	{ 0.671349f, 0.200133f, 0.487358f },
	{ 0.677786f, 0.202203f, 0.485819f },
	{ 0.684224f, 0.204286f, 0.484219f },
	{ 0.690661f, 0.206384f, 0.482558f },
	{ 0.697098f, 0.208501f, 0.480835f },
	{ 0.703532f, 0.210638f, 0.479049f },
	{ 0.709962f, 0.212797f, 0.477201f },
	{ 0.716387f, 0.214982f, 0.475290f },
	{ 0.722805f, 0.217194f, 0.473316f },
	{ 0.729216f, 0.219437f, 0.471279f },
	{ 0.735616f, 0.221713f, 0.469180f },
	{ 0.742004f, 0.224025f, 0.467018f },
	{ 0.748378f, 0.226377f, 0.464794f },
	{ 0.754737f, 0.228772f, 0.462509f },
	{ 0.761077f, 0.231214f, 0.460162f },
	{ 0.767398f, 0.233705f, 0.457755f },
	{ 0.773695f, 0.236249f, 0.455289f },
	{ 0.779968f, 0.238851f, 0.452765f },
	{ 0.786212f, 0.241514f, 0.450184f },
	{ 0.792427f, 0.244242f, 0.447543f },
	{ 0.798608f, 0.247040f, 0.444848f },
	{ 0.804752f, 0.249911f, 0.442102f },
	{ 0.810855f, 0.252861f, 0.439305f },
	{ 0.816914f, 0.255895f, 0.436461f },
	{ 0.822926f, 0.259016f, 0.433573f },
	{ 0.828886f, 0.262229f, 0.430644f },
	{ 0.834791f, 0.265540f, 0.427671f },
	{ 0.840636f, 0.268953f, 0.424666f },
	{ 0.846416f, 0.272473f, 0.421631f },
	{ 0.852126f, 0.276106f, 0.418573f },
	{ 0.857763f, 0.279857f, 0.415496f },
	{ 0.863320f, 0.283729f, 0.412403f },
	{ 0.868793f, 0.287728f, 0.409303f },
	{ 0.874176f, 0.291859f, 0.406205f },
	{ 0.879464f, 0.296125f, 0.403118f },
	{ 0.884651f, 0.300530f, 0.400047f },
	{ 0.889731f, 0.305079f, 0.397002f },
	{ 0.894700f, 0.309773f, 0.393995f },
	{ 0.899552f, 0.314616f, 0.391037f },
	{ 0.904281f, 0.319610f, 0.388137f },
	{ 0.908884f, 0.324755f, 0.385308f },
	{ 0.913354f, 0.330052f, 0.382563f },
	{ 0.917689f, 0.335500f, 0.379915f },
	{ 0.921884f, 0.341098f, 0.377376f },
	{ 0.925937f, 0.346844f, 0.374959f },
	{ 0.929845f, 0.352734f, 0.372677f },
	{ 0.933606f, 0.358764f, 0.370541f },
	{ 0.937221f, 0.364929f, 0.368567f },
	{ 0.940687f, 0.371224f, 0.366762f },
	{ 0.944006f, 0.377643f, 0.365136f },
	{ 0.947180f, 0.384178f, 0.363701f },
	{ 0.950210f, 0.390820f, 0.362468f },
	{ 0.953099f, 0.397563f, 0.361438f },
	{ 0.955849f, 0.404400f, 0.360619f },
	{ 0.958464f, 0.411324f, 0.360014f },
	{ 0.960949f, 0.418323f, 0.359630f },
	{ 0.963310f, 0.425390f, 0.359469f },
	{ 0.965549f, 0.432519f, 0.359529f },
	{ 0.967671f, 0.439703f, 0.359810f },
	{ 0.969680f, 0.446936f, 0.360311f },
	{ 0.971582f, 0.454210f, 0.361030f },
	{ 0.973381f, 0.461520f, 0.361965f },
	{ 0.975082f, 0.468861f, 0.363111f },
	{ 0.976690f, 0.476226f, 0.364466f },
	{ 0.978210f, 0.483612f, 0.366025f },
	{ 0.979645f, 0.491014f, 0.367783f },
	{ 0.981000f, 0.498428f, 0.369734f },
	{ 0.982279f, 0.505851f, 0.371874f },
	{ 0.983485f, 0.513280f, 0.374198f },
	{ 0.984622f, 0.520713f, 0.376698f },
	{ 0.985693f, 0.528148f, 0.379371f },
	{ 0.986700f, 0.535582f, 0.382210f },
	{ 0.987646f, 0.543015f, 0.385210f },
	{ 0.988533f, 0.550446f, 0.388365f },
	{ 0.989363f, 0.557873f, 0.391671f },
	{ 0.990138f, 0.565296f, 0.395122f },
	{ 0.990871f, 0.572706f, 0.398714f },
	{ 0.991558f, 0.580107f, 0.402441f },
	{ 0.992196f, 0.587502f, 0.406299f },
	{ 0.992785f, 0.594891f, 0.410283f },
	{ 0.993326f, 0.602275f, 0.414390f },
	{ 0.993834f, 0.609644f, 0.418613f },
	{ 0.994309f, 0.616999f, 0.422950f },
	{ 0.994738f, 0.624350f, 0.427397f },
	{ 0.995122f, 0.631696f, 0.431951f },
	{ 0.995480f, 0.639027f, 0.436607f },
	{ 0.995810f, 0.646344f, 0.441361f },
	{ 0.996096f, 0.653659f, 0.446213f },
	{ 0.996341f, 0.660969f, 0.451160f },
	{ 0.996580f, 0.668256f, 0.456192f },
	{ 0.996775f, 0.675541f, 0.461314f },
	{ 0.996925f, 0.682828f, 0.466526f },
	{ 0.997077f, 0.690088f, 0.471811f },
	{ 0.997186f, 0.697349f, 0.477182f },
	{ 0.997254f, 0.704611f, 0.482635f },
	{ 0.997325f, 0.711848f, 0.488154f },
	{ 0.997351f, 0.719089f, 0.493755f },
	{ 0.997351f, 0.726324f, 0.499428f },
	{ 0.997341f, 0.733545f, 0.505167f },
	{ 0.997285f, 0.740772f, 0.510983f },
	{ 0.997228f, 0.747981f, 0.516859f },
	{ 0.997138f, 0.755190f, 0.522806f },
	{ 0.997019f, 0.762398f, 0.528821f },
	{ 0.996898f, 0.769591f, 0.534892f },
	{ 0.996727f, 0.776795f, 0.541039f },
	{ 0.996571f, 0.783977f, 0.547233f },
	{ 0.996369f, 0.791167f, 0.553499f },
	{ 0.996162f, 0.798348f, 0.559820f },
	{ 0.995932f, 0.805527f, 0.566202f },
	{ 0.995680f, 0.812706f, 0.572645f },
	{ 0.995424f, 0.819875f, 0.579140f },
	{ 0.995131f, 0.827052f, 0.585701f },
	{ 0.994851f, 0.834213f, 0.592307f },
	{ 0.994524f, 0.841387f, 0.598983f },
	{ 0.994222f, 0.848540f, 0.605696f },
	{ 0.993866f, 0.855711f, 0.612482f },
	{ 0.993545f, 0.862859f, 0.619299f },
	{ 0.993170f, 0.870024f, 0.626189f },
	{ 0.992831f, 0.877168f, 0.633109f },
	{ 0.992440f, 0.884330f, 0.640099f },
	{ 0.992089f, 0.891470f, 0.647116f },
	{ 0.991688f, 0.898627f, 0.654202f },
	{ 0.991332f, 0.905763f, 0.661309f },
	{ 0.990930f, 0.912915f, 0.668481f },
	{ 0.990570f, 0.920049f, 0.675675f },
	{ 0.990175f, 0.927196f, 0.682926f },
	{ 0.989815f, 0.934329f, 0.690198f },
	{ 0.989434f, 0.941470f, 0.697519f },
	{ 0.989077f, 0.948604f, 0.704863f },
	{ 0.988717f, 0.955742f, 0.712242f },
	{ 0.988367f, 0.962878f, 0.719649f },
	{ 0.988033f, 0.970012f, 0.727077f },
	{ 0.987691f, 0.977154f, 0.734536f },
	{ 0.987387f, 0.984288f, 0.742002f },
	{ 0.987053f, 0.991438f, 0.749504f },
};

void
rf_flip_magma(float error, float rgb[3])
{
	/* the nearest of the 256 steps */
	const float t = error > 0.0f ? (error < 1.0f ? error : 1.0f) : 0.0f;
	const int i = (int)(t * 255.0f + 0.5f);

	memcpy(rgb, magma[i], 3 * sizeof(float));
}

void
rf_flip_heatmap(float *rgb, const float *error, size_t width, size_t height,
                const unsigned char *keep)
{
	size_t p;

	for (p = 0; p < width * height; p++) {
		if (keep && !keep[p])
			rgb[3 * p] = rgb[3 * p + 1] = rgb[3 * p + 2] = 0.15f;
		else
			rf_flip_magma(error[p], rgb + 3 * p);
	}
}

void
rf_flip_stats(struct rf_flip_stats *st, const float *error, size_t width, size_t height,
              const unsigned char *keep, double threshold, double warn)
{
	double sum = 0.0;
	size_t x, y;

	memset(st, 0, sizeof(*st));
	for (y = 0; y < height; y++)
		for (x = 0; x < width; x++) {
			const float e = error[y * width + x];

			if (keep && !keep[y * width + x])
				continue;
			st->npixels++;
			sum += e;
			st->nover += e > threshold;
			st->nwarn += e > warn;
			if (e > st->max_error) {
				st->max_error = e;
				st->max_x = x;
				st->max_y = y;
			}
		}
	st->mean = st->npixels ? sum / (double)st->npixels : 0.0;
}
