/* The split-sum environment BRDF of GGX: the DFG table. */
#include <math.h>
#include <pthread.h>
#include <stdint.h>

#include "util/pool.h"
#include "reflect/shading.h"

/*
 * Samples per entry.  Drawing the GGX distribution of *visible* normals
 * (Heitz 2018) rather than the plain normal distribution makes every
 * sample's weight G2/G1(v), bounded by 1: at grazing angles the plain
 * estimator needs some 50 times as many samples for the same error.
 * With 1024 Hammersley points and 64 x 64 entries, the bilinear lookup
 * is within 1e-3 of the integral for n.v >= 0.05 (tests/unit/test-dfg.c).
 */
#define DFG_SAMPLES 1024

static float table[RF_DFG_SIZE * RF_DFG_SIZE * 2];
static pthread_once_t table_once = PTHREAD_ONCE_INIT;

static double
radical_inverse(uint32_t i)
{
	i = (i << 16) | (i >> 16);
	i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
	i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
	i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
	i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
	return (double)i * 2.3283064365386963e-10;
}

/* Smith's Lambda for GGX at a direction of cosine c to the normal. */
static double
lambda(double a2, double c)
{
	double c2 = c * c;

	return 0.5 * (sqrt(1.0 + a2 * (1.0 - c2) / c2) - 1.0);
}

static double
pow5(double x)
{
	double x2 = x * x;

	return x2 * x2 * x;
}

/* Hammersley point i of n as (sqrt(u1), cos 2 pi u2, sin 2 pi u2): the
 * polar disc coordinates of the VNDF sampler. */
static void
disc_point(unsigned i, unsigned n, double p[3])
{
	double phi = 2.0 * M_PI * radical_inverse(i);

	p[0] = sqrt(((double)i + 0.5) / (double)n);
	p[1] = cos(phi);
	p[2] = sin(phi);
}

/* The integrals for one (n.v, roughness), from precomputed disc points;
 * the frame has n = +Z and v in the XZ plane. */
static void
integrate(double nv, double roughness, const double *disc, unsigned n, double *a,
          double *b)
{
	double alpha = roughness * roughness, a2 = alpha * alpha;
	double vx, vz = nv, hx, hz, len, lv, s, sum_a = 0.0, sum_b = 0.0;
	unsigned i;

	if (nv < 1e-4)
		vz = nv = 1e-4; /* the limit at grazing, without 0 / 0 */
	if (nv > 1.0)
		vz = nv = 1.0;
	if (alpha < 1e-7) {
		/* A mirror: h = n, l = reflect(v), G2 = 1. */
		*b = pow5(1.0 - nv);
		*a = 1.0 - *b;
		return;
	}
	vx = sqrt(1.0 - nv * nv);
	/* The view in the hemisphere configuration (stretched by alpha);
	 * its tangent frame is T1 = +Y, T2 = vh x T1. */
	hx = alpha * vx;
	hz = vz;
	len = sqrt(hx * hx + hz * hz);
	hx /= len;
	hz /= len;
	s = 0.5 * (1.0 + hz);
	lv = lambda(a2, nv);
	for (i = 0; i < n; i++) {
		const double *p = disc + 3 * i;
		double t1 = p[0] * p[1], t2 = p[0] * p[2], t3, mx, my, mz, vh, lz, w, fc;

		t2 = (1.0 - s) * sqrt(1.0 - t1 * t1) + s * t2;
		t3 = sqrt(fmax(0.0, 1.0 - t1 * t1 - t2 * t2));
		/* nh = t1 T1 + t2 (vh x T1) + t3 vh, with T1 = (0, 1, 0) and
		 * vh x T1 = (-hz, 0, hx); then unstretched. */
		mx = alpha * (-t2 * hz + t3 * hx);
		my = alpha * t1;
		mz = fmax(0.0, t2 * hx + t3 * hz);
		len = sqrt(mx * mx + my * my + mz * mz);
		if (!(len > 0.0))
			continue;
		mx /= len;
		mz /= len;
		vh = vx * mx + vz * mz;
		lz = 2.0 * vh * mz - vz;
		if (lz <= 0.0 || vh <= 0.0)
			continue;
		/* Visible-normal sampling leaves G2 / G1(v) as the weight. */
		w = (1.0 + lv) / (1.0 + lv + lambda(a2, lz));
		fc = pow5(1.0 - vh);
		sum_a += w * (1.0 - fc);
		sum_b += w * fc;
	}
	*a = sum_a / n;
	*b = sum_b / n;
}

void
rf_dfg_integrate(double n_dot_v, double roughness, unsigned samples, double *a,
                 double *b)
{
	double one[3], sa = 0.0, sb = 0.0;
	unsigned i;

	if (samples < 1)
		samples = 1;
	if (!(roughness > 0.0))
		roughness = 0.0;
	if (roughness > 1.0)
		roughness = 1.0;
	if (!(n_dot_v > 0.0))
		n_dot_v = 0.0;
	/* One disc point at a time: no allocation for any sample count (a
	 * mirror returns before it reads its point). */
	for (i = 0; i < samples; i++) {
		double pa, pb;

		disc_point(i, samples, one);
		integrate(n_dot_v, roughness, one, 1, &pa, &pb);
		if (roughness * roughness * roughness * roughness < 1e-14) {
			*a = pa;
			*b = pb;
			return;
		}
		sa += pa;
		sb += pb;
	}
	*a = sa / samples;
	*b = sb / samples;
}

static double disc[3 * DFG_SAMPLES];

/* Row `task` of the table (roughness task / (size - 1)). */
static void
build_row(void *arg, size_t task, int thread)
{
	unsigned j = (unsigned)task, i;

	(void)arg;
	(void)thread;
	for (i = 0; i < RF_DFG_SIZE; i++) {
		double x = (double)i / (RF_DFG_SIZE - 1), a, b;

		integrate(x * x, (double)j / (RF_DFG_SIZE - 1), disc, DFG_SAMPLES,
		          &a, &b);
		table[2 * (j * RF_DFG_SIZE + i)] = (float)a;
		table[2 * (j * RF_DFG_SIZE + i) + 1] = (float)b;
	}
}

/* Four million samples: a tenth of a second on one core, so the rows are
 * shared among threads (the entries do not depend on how).  No -j
 * reaches here (the first lookup builds the table, from whichever thread
 * makes it), hence a fixed count. */
#define BUILD_THREADS 4

static void
build(void)
{
	struct rf__pool *pool = NULL;
	unsigned k;

	for (k = 0; k < DFG_SAMPLES; k++)
		disc_point(k, DFG_SAMPLES, disc + 3 * k);
	/* Without a pool, the caller integrates every row. */
	if (rf__pool_create(&pool, BUILD_THREADS) == 0) {
		rf__pool_run(pool, RF_DFG_SIZE, build_row, NULL);
		rf__pool_destroy(pool);
	} else {
		for (k = 0; k < RF_DFG_SIZE; k++)
			build_row(NULL, k, 0);
	}
}

const float *
rf_dfg_table(size_t *size)
{
	pthread_once(&table_once, build);
	if (size)
		*size = RF_DFG_SIZE;
	return table;
}

static float
clamp01(float x)
{
	return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f;
}

void
rf_dfg_lookup(float n_dot_v, float roughness, float *a, float *b)
{
	const float *t = rf_dfg_table(NULL);
	float x = sqrtf(clamp01(n_dot_v)) * (RF_DFG_SIZE - 1);
	float y = clamp01(roughness) * (RF_DFG_SIZE - 1);
	int i = (int)x, j = (int)y;
	float fx, fy;
	const float *p, *q;

	if (i > RF_DFG_SIZE - 2)
		i = RF_DFG_SIZE - 2;
	if (j > RF_DFG_SIZE - 2)
		j = RF_DFG_SIZE - 2;
	fx = x - (float)i;
	fy = y - (float)j;
	p = t + 2 * (j * RF_DFG_SIZE + i);
	q = p + 2 * RF_DFG_SIZE;
	*a = (1.0f - fy) * ((1.0f - fx) * p[0] + fx * p[2]) +
	     fy * ((1.0f - fx) * q[0] + fx * q[2]);
	*b = (1.0f - fy) * ((1.0f - fx) * p[1] + fx * p[3]) +
	     fy * ((1.0f - fx) * q[1] + fx * q[3]);
}
