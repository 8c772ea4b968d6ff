/* GGX specular convolution of a cubemap into its mip levels. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "util/pool.h"
#include "envmap/envmap-internal.h"
#include "envmap/prefilter_bright.h"
#include "envmap/rgba_levels_simd.h"
#include "envmap/rgba_levels.h"
#include "reflect/envmap.h"

/* One precomputed GGX sample of a level: the direction of L in the frame
 * of N (= V) and where it reads the source (the levels its footprint
 * matches).  All samples weigh the same (see make_samples). */
struct lobe_sample {
	float l[3];
	struct rf__lod fetch;
};

struct job {
	const rf_cubemap *src; /* level 0 and its box chain */
	rf_cubemap *out;
	size_t level;
	float roughness;
	const struct lobe_sample *samples;
	size_t nsamples;
	/* The same samples as columns, for the vector kernel, when usable. */
	const struct rf__lobe_table *table;
	const struct rf__rgba_levels *levels;
	/* the source's bright texels, added exactly (NULL: none) */
	const struct rf__bright *bright;
	double lobe_integral;
	enum rf_prefilter_method method;
	/* brute force: integration points of the source */
	const float *src_dir;
	const float *src_omega;
	const float *src_radiance;
	size_t src_count;
};

void
rf_prefilter_defaults(struct rf_prefilter_options *o)
{
	memset(o, 0, sizeof(*o));
	o->mapping = RF_MAPPING_DEFAULT;
	o->samples = 64;
	o->method = RF_PREFILTER_FILTERED;
	o->nthreads = 1;
}

/* GGX normal distribution D(n.h) with alpha = a. */
static double
ggx_d(double a, double cos_h)
{
	double a2 = a * a, t = cos_h * cos_h * (a2 - 1.0) + 1.0;

	return a2 / (M_PI * t * t);
}

/*
 * Importance samples of the prefilter's lobe for V = N: L is drawn with a
 * density proportional to D(h) (n.l) itself, the whole weight, so every
 * sample counts the same and none is wasted below the horizon (drawing
 * h from D alone loses half the samples of a rough lobe there).  The
 * lobe is symmetric about N, so one table over the angle theta between N
 * and L, inverted at stratified points, gives theta; phi turns by the
 * golden angle from one sample to the next (a spherical Fibonacci set,
 * better spread than a Hammersley set for the same count).
 *
 * A sample stands for the solid angle 1 / (K p(L)); it reads the source
 * level whose texels cover that much: lod = log4(omega_s / omega_texel),
 * with omega_texel = 4 / n0^2, a level-0 texel at the centre of a face.
 * The lod is the same wherever the sample lands: texels near corners are
 * smaller, but reading a coarser level there than around it leaks the
 * energy of sources near corners (measured: -3% to -4% for a sun at a
 * corner), while one lod per sample keeps the chain's energy.
 */
#define LOBE_TABLE 4096

static size_t
make_samples(struct lobe_sample *s, size_t k, double alpha,
             const struct rf__rgba_levels *levels, float bias)
{
	size_t n0 = levels->size[0];
	static const double half_pi = M_PI / 2.0;
	double omega_texel = 4.0 / ((double)n0 * (double)n0);
	double *cdf = malloc((LOBE_TABLE + 1) * sizeof(double));
	double step = half_pi / LOBE_TABLE, total, prev;
	size_t i, t = 0;

	if (!cdf)
		return 0;
	/* cdf[t]: integral over theta in [0, t step] of D cos(theta) sin(theta) */
	cdf[0] = 0.0;
	prev = 0.0;
	for (i = 1; i <= LOBE_TABLE; i++) {
		double th = (double)i * step;
		double f = ggx_d(alpha, cos(th / 2.0)) * cos(th) * sin(th);

		cdf[i] = cdf[i - 1] + 0.5 * (prev + f) * step;
		prev = f;
	}
	total = cdf[LOBE_TABLE];
	for (i = 0; i < k; i++) {
		double target = ((double)i + 0.5) / (double)k * total;
		double frac, th, phi, st, density, omega_s;

		while (t + 1 < LOBE_TABLE && cdf[t + 1] < target)
			t++;
		frac = cdf[t + 1] > cdf[t] ? (target - cdf[t]) / (cdf[t + 1] - cdf[t]) : 0.0;
		th = ((double)t + frac) * step;
		phi = 2.0 * M_PI * fmod((double)i * 0.6180339887498949, 1.0);
		st = sin(th);
		/* p(L) per steradian: D (n.l) over its integral 2 pi total */
		density = ggx_d(alpha, cos(th / 2.0)) * cos(th) / (2.0 * M_PI * total);
		omega_s = density > 0.0 ? 1.0 / ((double)k * density) : 4.0 * M_PI;
		s[i].l[0] = (float)(st * cos(phi));
		s[i].l[1] = (float)(st * sin(phi));
		s[i].l[2] = (float)cos(th);
		s[i].fetch = rf__rgba_levels_lod(levels,
		                             (float)(0.5 * log2(omega_s / omega_texel) + bias));
	}
	free(cdf);
	return k;
}

/* An orthonormal frame around unit n (Duff et al. 2017, branch-free). */
static void
frame(const float n[3], float t[3], float b[3])
{
	float sign = copysignf(1.0f, n[2]);
	float a = -1.0f / (sign + n[2]);
	float c = n[0] * n[1] * a;

	t[0] = 1.0f + sign * n[0] * n[0] * a;
	t[1] = sign * c;
	t[2] = -sign * n[0];
	b[0] = c;
	b[1] = sign + n[1] * n[1] * a;
	b[2] = -n[1];
}

static void
normalize3(float v[3])
{
	float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);

	v[0] /= len;
	v[1] /= len;
	v[2] /= len;
}

/* The samples' directions about n (frame t, b) summed in double: the
 * float sum of a texel's samples leaves the float range for radiance
 * within a few orders of it. */
static void
filtered_texel_wide(const struct job *jb, const float n[3], const float t[3],
                    const float b[3], float rgb[3])
{
	double acc[3] = { 0, 0, 0 };
	size_t i;
	int c;

	for (i = 0; i < jb->nsamples; i++) {
		const struct lobe_sample *s = &jb->samples[i];
		float d[3];
		rf__v4 v;

		d[0] = s->l[0] * t[0] + s->l[1] * b[0] + s->l[2] * n[0];
		d[1] = s->l[0] * t[1] + s->l[1] * b[1] + s->l[2] * n[1];
		d[2] = s->l[0] * t[2] + s->l[1] * b[2] + s->l[2] * n[2];
		v = rf__rgba_levels_fetch(d, &s->fetch);
		for (c = 0; c < 3; c++)
			acc[c] += v[c];
	}
	for (c = 0; c < 3; c++)
		rgb[c] = (float)(acc[c] / (double)jb->nsamples);
}

static void
filtered_texel(const struct job *jb, const float n[3], float rgb[3])
{
	float t[3], b[3];
	rf__v4 acc = { 0, 0, 0, 0 };
	size_t i = 0;

	frame(n, t, b);
	if (jb->table) {
		i = jb->nsamples & ~(size_t)7;
		acc = rf__lobe_sum8(jb->table, i, jb->levels, n, t, b);
	}
	for (; i < jb->nsamples; i++) {
		const struct lobe_sample *s = &jb->samples[i];
		float d[3];

		d[0] = s->l[0] * t[0] + s->l[1] * b[0] + s->l[2] * n[0];
		d[1] = s->l[0] * t[1] + s->l[1] * b[1] + s->l[2] * n[1];
		d[2] = s->l[0] * t[2] + s->l[1] * b[2] + s->l[2] * n[2];
		acc += rf__rgba_levels_fetch(d, &s->fetch);
	}
	if (!(isfinite(acc[0]) && isfinite(acc[1]) && isfinite(acc[2]))) {
		filtered_texel_wide(jb, n, t, b, rgb);
		return;
	}
	rgb[0] = acc[0] / (float)jb->nsamples;
	rgb[1] = acc[1] / (float)jb->nsamples;
	rgb[2] = acc[2] / (float)jb->nsamples;
}

/*
 * The integral of L(l) D(h) (n.l) over the sphere, over that of D (n.l),
 * with h the half vector of n and l: the same lobe the samples draw.  L
 * is the bilinear reconstruction of the source (what every sampler
 * reads), integrated on `sub` x `sub` points per source texel; the
 * tables hold their unit directions, solid angles and radiance.
 */
static void
brute_texel(const float *dirs, const float *omega, const float *radiance,
            size_t count, const float n[3], double alpha, float rgb[3])
{
	double acc[3] = { 0, 0, 0 }, wsum = 0.0;
	size_t k;

	for (k = 0; k < count; k++) {
		const float *l = dirs + 3 * k;
		double nol = (double)n[0] * l[0] + (double)n[1] * l[1] + (double)n[2] * l[2];
		double noh, w;

		if (nol <= 0.0)
			continue;
		/* |n + l|^2 = 2 + 2 n.l and n.h = (1 + n.l) / |n + l|. */
		noh = (1.0 + nol) / sqrt(2.0 + 2.0 * nol);
		w = ggx_d(alpha, noh) * nol * omega[k];
		acc[0] += w * radiance[3 * k];
		acc[1] += w * radiance[3 * k + 1];
		acc[2] += w * radiance[3 * k + 2];
		wsum += w;
	}
	for (k = 0; k < 3; k++)
		rgb[k] = wsum > 0.0 ? (float)(acc[k] / wsum) : 0.0f;
}

/* Integration points per source texel side: enough that a lobe narrower
 * than a texel still sees the reconstruction's shape. */
static size_t
brute_subdivision(size_t n0, double alpha)
{
	double texel = M_PI / 2.0 / (double)n0; /* angle across a face texel */
	double s = ceil(2.0 * texel / (alpha > 1e-6 ? alpha : 1e-6));

	return s < 1.0 ? 1 : s > 4.0 ? 4 : (size_t)s;
}

static int
source_tables(const rf_cubemap *src, size_t sub, float **dirs, float **omega,
              float **radiance, size_t *count)
{
	size_t n0 = rf_cubemap_level_size(src, 0), m = n0 * sub, i, j, k = 0;
	int f;

	*count = 6 * m * m;
	*dirs = malloc(*count * 3 * sizeof(float));
	*omega = malloc(*count * sizeof(float));
	*radiance = malloc(*count * 3 * sizeof(float));
	if (!*dirs || !*omega || !*radiance) {
		free(*dirs);
		free(*omega);
		free(*radiance);
		return RF_ENOMEM;
	}
	for (f = 0; f < 6; f++)
		for (j = 0; j < m; j++)
			for (i = 0; i < m; i++, k++) {
				float *d = *dirs + 3 * k;

				rf_cube_direction((enum rf_face)f, ((float)i + 0.5f) / (float)m,
				                  ((float)j + 0.5f) / (float)m, d);
				normalize3(d);
				(*omega)[k] = (float)rf_cube_texel_solid_angle(m, i, j);
				rf_cubemap_sample_level(src, 0, d, *radiance + 3 * k);
			}
	return 0;
}

int
rf__prefilter_brute_texels(const rf_cubemap *src, const float *dirs, size_t count,
                          float roughness, float *rgb)
{
	float *pts, *omega, *radiance;
	double alpha = (double)roughness * roughness;
	size_t npts, k;
	int rc;

	if ((rc = source_tables(src, brute_subdivision(rf_cubemap_size(src), alpha), &pts,
	                        &omega, &radiance, &npts)) < 0)
		return rc;
	for (k = 0; k < count; k++) {
		float n[3] = { dirs[3 * k], dirs[3 * k + 1], dirs[3 * k + 2] };

		normalize3(n);
		brute_texel(pts, omega, radiance, npts, n, alpha, rgb + 3 * k);
	}
	free(pts);
	free(omega);
	free(radiance);
	return 0;
}

void
rf__prefilter_brute_texel(const rf_cubemap *src, const float n[3], float roughness,
                         float rgb[3])
{
	if (rf__prefilter_brute_texels(src, n, 1, roughness, rgb) < 0)
		rgb[0] = rgb[1] = rgb[2] = NAN;
}

/* Row `task` (face task / n, row task % n) of the job's level. */
static void
filter_row(void *arg, size_t task, int thread)
{
	const struct job *jb = arg;
	size_t n = rf_cubemap_level_size(jb->out, jb->level), i, j = task % n;
	enum rf_face f = (enum rf_face)(task / n);
	double alpha = (double)jb->roughness * jb->roughness;

	(void)thread;
	for (i = 0; i < n; i++) {
		float d[3], *out = rf_cubemap_texel(jb->out, jb->level, f, i, j);

		rf_cube_direction(f, ((float)i + 0.5f) / (float)n,
		                  ((float)j + 0.5f) / (float)n, d);
		normalize3(d);
		if (jb->method == RF_PREFILTER_BRUTE)
			brute_texel(jb->src_dir, jb->src_omega, jb->src_radiance,
			            jb->src_count, d, alpha, out);
		else {
			filtered_texel(jb, d, out);
			if (jb->bright)
				rf__bright_add(jb->bright, d, alpha, jb->lobe_integral, out);
		}
	}
}

/*
 * Samples for level k: the base count at level 1, three times as many at
 * each rougher level.  A rougher level has a wider lobe and 4 times fewer
 * texels; with a fixed count its texels land on a sample pattern coarse
 * against a small bright source, and the level's mean (its energy) drifts
 * by +-4% for a sun near a cube corner; doubling leaves +-3%, tripling
 * under 1%, for about twice the work of a fixed count.
 */
size_t
rf_prefilter_level_samples(unsigned base, size_t k)
{
	size_t n = base;

	while (k-- > 1 && n < ((size_t)base << 12))
		n *= 3;
	return n;
}

static int
source_finite(const rf_cubemap *src, char *err, size_t errlen)
{
	const size_t n = rf_cubemap_size(src);
	size_t i, j;
	int f, ch;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++) {
			const float *t = rf_cubemap_texel_const(src, 0, (enum rf_face)f, 0, j);

			for (i = 0; i < 3 * n; i++)
				if (!rf__texel_ok(t[i])) {
					struct rf__nonfinite nf = { 0 };
					char where[128];

					ch = (int)(i % 3);
					rf__nonfinite_note(&nf, 0, f, i / 3, j, ch, t[i]);
					rf__nonfinite_where(&nf, where, sizeof(where));
					rf__format(err, errlen, "the source's %s", where);
					return RF_EINVAL;
				}
		}
	return 0;
}

int
rf_prefilter(const rf_cubemap *src, rf_cubemap *out,
             const struct rf_prefilter_options *o, char *err, size_t errlen)
{
	size_t n0 = rf_cubemap_level_size(src, 0), nout = rf_cubemap_size(out);
	size_t levels = rf_cubemap_levels(out), k, base, total = 0, done = 0;
	float steps = o->steps > 0.0f ? o->steps : (float)(levels - 1);
	struct lobe_sample *samples = NULL;
	struct rf__lobe_table table = { 0 };
	int vector = 0;
	rf_cubemap *chain = NULL;
	struct rf__rgba_levels rgba = { 0 };
	float *dirs = NULL, *omega = NULL, *radiance = NULL;
	size_t count = 0, sub = 0, nbright = 0;
	rf_cubemap *resid = NULL;
	struct rf__bright bright = { 0 };
	struct rf__pool *pool = NULL;
	int rc = 0;

	if (levels < 2) {
		rf__format(err, errlen, "a chain of one level has nothing to convolve "
		           "(ask for at least 2 levels)");
		return RF_EINVAL;
	}
	if (o->method == RF_PREFILTER_FILTERED && (o->samples < 1 || o->samples > (1u << 20))) {
		rf__format(err, errlen, "sample count %u is out of range [1, %u]",
		           o->samples, 1u << 20);
		return RF_EINVAL;
	}
	if (o->steps < 0.0f || !isfinite(o->steps)) {
		rf__format(err, errlen, "steps must be a positive number, not %g",
		           (double)o->steps);
		return RF_EINVAL;
	}
	if (nout > n0 || n0 % nout) {
		rf__format(err, errlen, "output size %zu does not divide the source "
		           "size %zu", nout, n0);
		return RF_EINVAL;
	}
	/* One NaN would spread over every lobe that reaches it, and an
	 * infinity over whole levels: the loaders refuse both (and texels
	 * past RF__TEXEL_MAX), and so does the prefilter for a cube made
	 * some other way. */
	if ((rc = source_finite(src, err, errlen)) < 0)
		return rc;
	/* The source as a full box chain, read by filtered samples. */
	if ((rc = rf_cubemap_create(&chain, n0, 0)) < 0)
		return rc;
	rf__cubemap_copy_level(chain, 0, src, 0);
	rf_cubemap_box_chain(chain, 0);
	for (base = 0; (n0 >> base) != nout; base++)
		;
	if (base >= rf_cubemap_levels(chain)) {
		rf__format(err, errlen, "output size %zu is not reachable from %zu by "
		           "halving", nout, n0);
		rc = RF_EINVAL;
		goto out;
	}
	rf__cubemap_copy_level(out, 0, chain, base);
	/* The samples read the source without its bright texels; those are
	 * added exactly (prefilter_bright.c). */
	if (o->method == RF_PREFILTER_FILTERED) {
		float r1 = rf_lod_to_roughness(o->mapping, steps, 1.0f);

		if ((rc = rf__bright_split(chain, brute_subdivision(n0, (double)r1 * r1), &resid,
		                           &nbright)) < 0)
			goto out;
		if (resid)
			rf_cubemap_box_chain(chain, 0);
		if ((rc = rf__rgba_levels_from_cube(&rgba, chain)) < 0)
			goto out;
	}
	if (o->method == RF_PREFILTER_FILTERED &&
	    !(samples = malloc(rf_prefilter_level_samples(o->samples, levels - 1) * sizeof(*samples)))) {
		rc = RF_ENOMEM;
		goto out;
	}
	if (o->method == RF_PREFILTER_FILTERED && rf__rgba_levels_simd_usable(&rgba)) {
		if ((rc = rf__lobe_table_alloc(&table, rf_prefilter_level_samples(o->samples,
		                                                                   levels - 1))) < 0)
			goto out;
		vector = 1;
	}
	for (k = 1; k < levels; k++)
		total += 6 * rf_cubemap_level_size(out, k);
	/* One pool for every level; without one, the caller filters alone. */
	if (o->nthreads > 1)
		rf__pool_create(&pool, o->nthreads > RF__THREADS_MAX ? RF__THREADS_MAX : o->nthreads);
	for (k = 1; k < levels; k++) {
		struct job jb;
		size_t n = rf_cubemap_level_size(out, k), row;

		memset(&jb, 0, sizeof(jb));
		jb.src = chain;
		jb.out = out;
		jb.level = k;
		jb.roughness = rf_lod_to_roughness(o->mapping, steps, (float)k);
		jb.method = o->method;
		if (o->method == RF_PREFILTER_BRUTE) {
			size_t want = brute_subdivision(n0, (double)jb.roughness * jb.roughness);

			if (want != sub) {
				free(dirs);
				free(omega);
				free(radiance);
				dirs = omega = radiance = NULL;
				if ((rc = source_tables(chain, want, &dirs, &omega, &radiance,
				                        &count)) < 0)
					goto out;
				sub = want;
			}
			jb.src_dir = dirs;
			jb.src_omega = omega;
			jb.src_radiance = radiance;
			jb.src_count = count;
		} else {
			jb.samples = samples;
			jb.nsamples = make_samples(samples, rf_prefilter_level_samples(o->samples, k),
			                           (double)jb.roughness * jb.roughness, &rgba,
			                           o->lod_bias);
			if (!jb.nsamples) {
				rc = RF_ENOMEM;
				goto out;
			}
			if (resid) {
				size_t want = brute_subdivision(n0, (double)jb.roughness * jb.roughness);

				if (want != bright.sub &&
				    (rc = rf__bright_points(&bright, resid, want)) < 0)
					goto out;
				jb.bright = &bright;
				jb.lobe_integral = rf__ggx_lobe_integral((double)jb.roughness *
				                                         jb.roughness);
			}
			if (vector) {
				size_t i;

				for (i = 0; i < jb.nsamples; i++)
					rf__lobe_table_set(&table, i, samples[i].l, &samples[i].fetch,
					                   &rgba);
				jb.table = &table;
				jb.levels = &rgba;
			}
		}
		/* A row is a task: each texel is its own sum, so the bytes do not
		 * depend on which thread takes it. */
		if (pool)
			rf__pool_run(pool, 6 * n, filter_row, &jb);
		else
			for (row = 0; row < 6 * n; row++)
				filter_row(&jb, row, 0);
		rf_cubemap_seal_level(out, k);
		done += 6 * n;
		if (o->progress)
			o->progress(o->progress_arg, (double)done, (double)total);
	}
out:
	rf__pool_destroy(pool);
	free(samples);
	rf__lobe_table_destroy(&table);
	free(dirs);
	free(omega);
	free(radiance);
	rf__rgba_levels_destroy(&rgba);
	rf_cubemap_destroy(chain);
	rf_cubemap_destroy(resid);
	rf__bright_destroy(&bright);
	return rc;
}
