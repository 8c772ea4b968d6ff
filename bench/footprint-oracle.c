/*
 * footprint-oracle: what four taps could do at best, for
 * bench/footprint-rooms -o; a shade mode built by that script, never
 * installed.
 *
 * A cheap model reads a pixel in at most four taps of the prefilter's
 * round kernels, each standing for a share of the GGX lobe.  This mode
 * spends what such a model cannot, to learn where that family ends: it
 * draws rays= rays of the lobe at P (the visible normals, weighted
 * G2 / G1 as footprint-gen measures it), takes every one through the box
 * as reflect-shade would (the host's project_rays), and then
 *   - cuts the lobe into taps= shares of equal weight along its long
 *     axis at P (the order the box keeps: it maps the lobe's ends to the
 *     image's ends, so each share is one piece of the image at C);
 *   - reads each share at its weighted medians along and across the
 *     image's long axis at C, with the kernel whose width is the
 *     geometric mean of the share's half interquartile ranges there,
 *     times a factor that grows with roughness (SHARE_KERNEL below).
 * The axes come from the second moments of the lobe's core (the 70 %
 * of its weight nearest its mean direction): GGX's tails would turn the
 * full moments toward wherever the tail is longest.
 *
 * With 256 rays it is far too slow for any engine: it is a bound to
 * measure a cheap model against, not a model.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/plugin.h"

#include "maths/ggx.h"
#include "footprint-shape.h"
#include "footprint-table.h"
#include "footprint-kernel.h"

enum { RAYS, TAPS, NPARAMS };

static const struct rf_param params[NPARAMS] = {
	{ "rays", "rays of the lobe a pixel, traced through the box", 16, 1024, 256,
	  RF_PARAM_INTEGER, NULL },
	{ "taps", "shares of the lobe, one read each", 1, 4, 4, RF_PARAM_INTEGER, NULL },
};

static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", "roughness", NULL
};
static const char *const outputs[] = { RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B,
                                       NULL };

#define NINPUTS 10
#define RAYS_MAX 1024
#define TAPS_MAX 4
#define CORE 0.7 /* the share of the lobe's weight its axes are taken from */
/* A share's kernel against the geometric mean of its half interquartile
 * ranges at C: SHARE_KERNEL at roughness SHARE_KERNEL_AT, and relatively
 * SHARE_KERNEL_SLOPE more per unit of roughness.  Round kernels standing
 * for shares of a GGX lobe want more of their spread the rougher it is,
 * as footprint's do (binned by roughness on the rooms of seed 1, the best
 * constant goes from 0.85 at 0.1 to 0.3 to 1.15 and more at 0.5 to 0.7);
 * fitted on the rooms of seed 1 (0.1298, against 0.1457 with 1). */
#define SHARE_KERNEL 1.05
#define SHARE_KERNEL_AT 0.4
#define SHARE_KERNEL_SLOPE 1.0

struct oracle {
	const struct rf_host *host;
	unsigned rays, taps;
};

/* A ray's place in a share and along an axis, with its weight. */
struct ray {
	double u, w;
	unsigned k;
};

/* One pixel's rays and their places, on the heap: a thread's own. */
struct scratch {
	float dirs[3 * RAYS_MAX], look[3 * RAYS_MAX], dist[RAYS_MAX], jac[RAYS_MAX];
	double w[RAYS_MAX], px[RAYS_MAX], py[RAYS_MAX], cx[RAYS_MAX], cy[RAYS_MAX];
	double along[RAYS_MAX], across[RAYS_MAX], share_w[RAYS_MAX], radius[RAYS_MAX];
	struct ray order[RAYS_MAX], sorted[RAYS_MAX];
};

static double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int
unit(double v[3])
{
	double len = sqrt(dot(v, v));

	if (!(len > 0.0))
		return -1;
	v[0] /= len;
	v[1] /= len;
	v[2] /= len;
	return 0;
}

static void
cross(const double a[3], const double b[3], double c[3])
{
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

/* t1, t2: a frame of the plane at right angles to unit n */
static void
tangents(const double n[3], double t1[3], double t2[3])
{
	const double a[3] = { fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0 };

	cross(n, a, t1);
	unit(t1);
	cross(n, t1, t2);
}

static int
by_u(const void *a, const void *b)
{
	double x = ((const struct ray *)a)->u, y = ((const struct ray *)b)->u;

	return (x > y) - (x < y);
}

/* Values v (n of them, with weights w) sorted into tmp; their total
 * weight. */
static double
sort_weighted(struct ray *tmp, const double *v, const double *w, unsigned n)
{
	double total = 0.0;
	unsigned i;

	for (i = 0; i < n; i++) {
		tmp[i].u = v[i];
		tmp[i].w = w[i];
		total += w[i];
	}
	qsort(tmp, n, sizeof(*tmp), by_u);
	return total;
}

/* The value at which n sorted values reach share q of their total
 * weight. */
static double
share_point(const struct ray *sorted, unsigned n, double total, double q)
{
	double sum = 0.0;
	unsigned i;

	for (i = 0; i < n; i++)
		if ((sum += sorted[i].w) >= q * total)
			return sorted[i].u;
	return n ? sorted[n - 1].u : 0.0;
}

/* The weighted median of n values and half the distance between their
 * quartiles, from one sort. */
static void
median_spread(struct ray *tmp, const double *v, const double *w, unsigned n, double *median,
              double *half_iqr)
{
	double total = sort_weighted(tmp, v, w, n);

	*median = share_point(tmp, n, total, 0.5);
	*half_iqr = 0.5 * (share_point(tmp, n, total, 0.75) - share_point(tmp, n, total, 0.25));
}

/* Directions dir (n, unit) about their weighted mean m: their places in
 * m's tangent plane (the logarithmic map) and the unit axis (ax, ay) along
 * which the core of them stretches most. */
static void
log_map(struct scratch *s, const float *dir, unsigned n, double m[3], double t1[3],
        double t2[3], double *gx, double *gy, double axis[2])
{
	double cxx = 0.0, cxy = 0.0, cyy = 0.0, *r = s->radius, core, tr, det, big;
	unsigned k, j;

	m[0] = m[1] = m[2] = 0.0;
	for (k = 0; k < n; k++)
		for (j = 0; j < 3; j++)
			m[j] += s->w[k] * dir[3 * k + j];
	if (unit(m) < 0) {
		m[0] = dir[0], m[1] = dir[1], m[2] = dir[2];
	}
	tangents(m, t1, t2);
	for (k = 0; k < n; k++) {
		double l[3] = { dir[3 * k], dir[3 * k + 1], dir[3 * k + 2] }, c, q[3], len;

		c = dot(l, m);
		c = c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c;
		for (j = 0; j < 3; j++)
			q[j] = l[j] - c * m[j];
		len = sqrt(dot(q, q));
		gx[k] = len > 1e-12 ? acos(c) * dot(q, t1) / len : 0.0;
		gy[k] = len > 1e-12 ? acos(c) * dot(q, t2) / len : 0.0;
		r[k] = sqrt(gx[k] * gx[k] + gy[k] * gy[k]);
	}
	core = share_point(s->sorted, n, sort_weighted(s->sorted, r, s->w, n), CORE);
	for (k = 0; k < n; k++)
		if (r[k] <= core) {
			cxx += s->w[k] * gx[k] * gx[k];
			cxy += s->w[k] * gx[k] * gy[k];
			cyy += s->w[k] * gy[k] * gy[k];
		}
	tr = cxx + cyy;
	det = cxx * cyy - cxy * cxy;
	big = 0.5 * tr + sqrt(fmax(0.0, 0.25 * tr * tr - det));
	if (fabs(cxy) > 1e-30) {
		axis[0] = big - cyy;
		axis[1] = cxy;
	} else {
		axis[0] = cxx >= cyy ? 1.0 : 0.0;
		axis[1] = cxx >= cyy ? 0.0 : 1.0;
	}
	big = sqrt(axis[0] * axis[0] + axis[1] * axis[1]);
	axis[0] /= big;
	axis[1] /= big;
}

/* The pixel's taps (directions, lods, weights); their number. */
static unsigned
shade_pixel(const struct oracle *o, struct scratch *s, const float *in, float *sx, float *sy,
            float *sz, float *sl, float *sw)
{
	const struct rf_host *host = o->host;
	double n[3] = { in[3], in[4], in[5] }, v[3] = { in[6], in[7], in[8] };
	double pr = in[9] < 1.0f ? in[9] : 1.0, alpha, a2, mu, x[3], y[3], lv, vl[3];
	double mp[3], mc[3], t1[3], t2[3], u1[3], u2[3], paxis[2], caxis[2], total = 0.0;
	unsigned kept = 0;
	const float p[3] = { in[0], in[1], in[2] };
	struct rf__ggx_vndf g;
	unsigned k, j, cnt = 0, t, start;
	double kernel = SHARE_KERNEL * (1.0 + SHARE_KERNEL_SLOPE * (pr - SHARE_KERNEL_AT));

	if (unit(n) < 0 || unit(v) < 0 || !(pr >= 0.0) || !((mu = dot(n, v)) > 0.0))
		return 0;
	mu = mu < 1.0 ? mu : 1.0;
	for (k = 0; k < 3; k++)
		x[k] = v[k] - mu * n[k];
	if (unit(x) < 0)
		tangents(n, x, y);
	cross(n, x, y);
	alpha = pr * pr > 1e-4 ? pr * pr : 1e-4;
	a2 = alpha * alpha;
	vl[0] = sqrt((1.0 - mu) * (1.0 + mu));
	vl[1] = 0.0;
	vl[2] = mu > 1e-3 ? mu : 1e-3;
	lv = rf__ggx_lambda(a2, vl[2]);
	rf__ggx_vndf_init(&g, vl, alpha);
	for (k = 0; k < o->rays; k++) {
		double h[3], vdh, l[3];

		rf__ggx_vndf_normal(&g, (k + 0.5) / o->rays, rf__ggx_radical_inverse(k), h);
		vdh = dot(vl, h);
		for (j = 0; j < 3; j++)
			l[j] = 2.0 * vdh * h[j] - vl[j];
		if (!(l[2] > 1e-4))
			continue; /* below the surface: no light */
		s->w[cnt] = (1.0 + lv) / (1.0 + lv + rf__ggx_lambda(a2, l[2]));
		for (j = 0; j < 3; j++)
			s->dirs[3 * cnt + j] = (float)(l[0] * x[j] + l[1] * y[j] + l[2] * n[j]);
		total += s->w[cnt++];
	}
	if (!cnt)
		return 0;
	if (host->project_rays)
		host->project_rays(host->ctx, cnt, p, s->dirs, s->look, s->dist, s->jac);
	else
		memcpy(s->look, s->dirs, 3 * cnt * sizeof(float));
	for (k = 0; k < cnt; k++) {
		double l[3] = { s->look[3 * k], s->look[3 * k + 1], s->look[3 * k + 2] };

		unit(l);
		for (j = 0; j < 3; j++)
			s->look[3 * k + j] = (float)l[j];
	}
	log_map(s, s->dirs, cnt, mp, u1, u2, s->px, s->py, paxis);
	log_map(s, s->look, cnt, mc, t1, t2, s->cx, s->cy, caxis);
	for (k = 0; k < cnt; k++) {
		s->order[k].u = s->px[k] * paxis[0] + s->py[k] * paxis[1];
		s->order[k].w = s->w[k];
		s->order[k].k = k;
	}
	qsort(s->order, cnt, sizeof(*s->order), by_u);
	/* equal shares in the order along the lobe's axis at P */
	for (t = start = 0; t < o->taps; t++) {
		double want = total * (t + 1) / o->taps, sum = 0.0, a, b, wa, wb, gl, g2[2], m[3];
		unsigned end = start, nn;

		for (k = 0; k < start; k++)
			sum += s->order[k].w;
		while (end < cnt && (t + 1 == o->taps || sum + s->order[end].w <= want))
			sum += s->order[end++].w;
		if (end == start && end < cnt)
			sum += s->order[end++].w;
		if (!(nn = end - start))
			continue;
		for (k = 0; k < nn; k++) {
			unsigned r = s->order[start + k].k;

			s->along[k] = s->cx[r] * caxis[0] + s->cy[r] * caxis[1];
			s->across[k] = -s->cx[r] * caxis[1] + s->cy[r] * caxis[0];
			s->share_w[k] = s->w[r];
		}
		median_spread(s->sorted, s->along, s->share_w, nn, &a, &wa);
		median_spread(s->sorted, s->across, s->share_w, nn, &b, &wb);
		/* the medians' place back on the sphere (the exponential map) */
		g2[0] = a * caxis[0] - b * caxis[1];
		g2[1] = a * caxis[1] + b * caxis[0];
		gl = sqrt(g2[0] * g2[0] + g2[1] * g2[1]);
		for (j = 0; j < 3; j++)
			m[j] = cos(gl) * mc[j] +
			       (gl > 1e-12 ? sin(gl) * (g2[0] * t1[j] + g2[1] * t2[j]) / gl : 0.0);
		sx[kept] = (float)m[0];
		sy[kept] = (float)m[1];
		sz[kept] = (float)m[2];
		sl[kept] = host->roughness_to_lod(
			host->ctx, (float)footprint_kernel_roughness(kernel * sqrt(wa * wb)));
		sw[kept] = 0.0f;
		for (k = 0; k < nn; k++)
			sw[kept] += (float)s->share_w[k];
		kept++;
		start = end;
	}
	return kept;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct oracle *o = state;
	struct scratch *s = malloc(sizeof(*s));
	uint32_t i, k;

	if (!s) {
		o->host->fail(o->host->ctx, "out of memory");
		return;
	}
	for (i = 0; i < span->npix; i++) {
		float sx[TAPS_MAX], sy[TAPS_MAX], sz[TAPS_MAX], sl[TAPS_MAX], sw[TAPS_MAX],
		      rgba[4 * TAPS_MAX], *out = span->out + 3 * (size_t)i, sum = 0.0f;
		unsigned nt = shade_pixel(o, s, span->in + (size_t)i * NINPUTS, sx, sy, sz, sl, sw);

		out[0] = out[1] = out[2] = 0.0f;
		if (!nt)
			continue;
		o->host->sample_many(o->host->ctx, nt, sx, sy, sz, sl, rgba);
		for (k = 0; k < nt; k++) {
			out[0] += sw[k] * rgba[4 * k];
			out[1] += sw[k] * rgba[4 * k + 1];
			out[2] += sw[k] * rgba[4 * k + 2];
			sum += sw[k];
		}
		if (sum > 0.0f) {
			out[0] /= sum;
			out[1] /= sum;
			out[2] /= sum;
		}
	}
	free(s);
}

static void
destroy(void *state)
{
	free(state);
}

static int
create(const struct rf_host *host, const double *values, void **state, char *err,
       size_t errlen)
{
	struct oracle *o;

	if (host->size < offsetof(struct rf_host, sample_many) + sizeof(host->sample_many) ||
	    !host->sample_many || !host->roughness_to_lod) {
		snprintf(err, errlen, "this host offers no prefiltered environment to read "
		         "(it needs reflect-shade with --env)");
		return -1;
	}
	if (!(o = calloc(1, sizeof(*o)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	o->host = host;
	o->rays = (unsigned)values[RAYS];
	o->taps = (unsigned)values[TAPS];
	*state = o;
	return 0;
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.flags = RF_PLUGIN_RADIANCE | RF_PLUGIN_PREFILTERED,
	.name = "footprint_oracle",
	.summary = "the lobe traced through the box, read in four taps: a bound for "
	           "cheap models (bench only)",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
