/*
 * footprint: contact hardening from the geometry of the GGX lobe's
 * footprint: where the lobe lands on the box, how large it looks from
 * the capture point, and which of the prefilter's kernels covers that,
 * read in at most four taps along the direction in which it stretches.
 * reflect-mode-footprint(7) has the derivation; in short, per pixel:
 *
 *  1. The lobe at P.  footprint-table.h (made at build time from the
 *     GGX lobe itself, footprint-gen.c) gives, for the view's angle and
 *     the roughness, the lobe's in-plane median (bent from R toward the
 *     normal where the horizon cuts it), its in-plane widths toward the
 *     normal and toward the horizon, and its width across, as angles in
 *     units of the prefilter's own kernel.  The centre D goes bend= of
 *     the way from R to that median (the one fitted number, see the
 *     page).
 *  2. Its footprint seen from C.  Nine rays from P, the centre, the
 *     four width points and four at half the widths, go to where they
 *     leave the box (the host's project_rays, as reflect-project takes
 *     one ray); the directions from C to those exits span the footprint
 *     as the probe sees it: two vectors A (in-plane) and B (across) in
 *     the tangent plane of the centre's lookup, each the mean of its
 *     two secants (a secant whose end crosses a corner of the box bends
 *     the footprint; two of them halve the kink).  Near a wall they
 *     close in (contact hardening), on a wall seen at a slant from C
 *     they spread, and from P = C or at infinity they are the lobe's
 *     own widths.
 *  3. Its axes.  The singular values of [A B] are the footprint's
 *     major and minor widths at C; the right singular vector says which
 *     direction at P maps onto the major axis.
 *  4. Taps.  n = taps=; each tap reads the prefilter's kernel of width
 *     w = max(minor, major / n), so the lod is that of the roughness
 *     whose kernel is w wide; the n taps sit at the n-quantiles of the
 *     lobe's (t-shaped) marginal along the major axis, drawn in by
 *     sqrt(1 - (w / major)^2) for the width each tap adds, each
 *     box-projected from P itself (the parallax inside the lobe), equal
 *     weights, each kernel scaled by its own exit's Jacobian against the
 *     centre's.  A tap past the horizon (Ng, else N) slides back.
 *
 * Limits: roughness 0 reads the box-projected mirror direction at lod 0;
 * no hit (P outside the box, or an infinite projection) with N = V, or
 * lobe=round, reads what `none` reads; the same room in other units
 * gives the same pixels (angles and ratios only).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/plugin.h"

#include "footprint-shape.h"
#include "footprint-table.h"

enum { TAPS, LOBE, BEND, NPARAMS };
enum { LOBE_MEASURED, LOBE_ROUND };

static const struct rf_param params[NPARAMS] = {
	{ "taps", "cubemap reads a pixel at most, along the footprint's long axis",
	  1, 4, 4, RF_PARAM_INTEGER, NULL },
	{ "lobe", "measured: the lobe as GGX makes it at this view (bent, stretched); "
	  "round: the prefilter's kernel about R, parallax and contact only",
	  0, 1, LOBE_MEASURED, RF_PARAM_CHOICE, "measured|round" },
	{ "bend", "how far the centre moves from R toward the lobe's median (0: R, "
	  "1: the median); the default is fitted on the rooms of reflect-mode-footprint(7)",
	  0, 1.5, 0.55, 0, NULL },
};

static const char *const inputs[] = {
	"P.X", "P.Y", "P.Z", "N.X", "N.Y", "N.Z", "V.X", "V.Y", "V.Z", "roughness", NULL
};
static const char *const optional_inputs[] = { "Ng.X", "Ng.Y", "Ng.Z", NULL };
static const char *const outputs[] = { RF_SHADE_SPEC_R, RF_SHADE_SPEC_G, RF_SHADE_SPEC_B,
                                       NULL };

#define NINPUTS 13
#define RAYS 9 /* the footprint's centre, its four width points and four
                  at half their widths */
#define TAPS_MAX FOOTPRINT_TAPS_MAX

struct footprint {
	const struct rf_host *host;
	unsigned taps;
	int round;
	double bend;
};

/* n taps' places along the footprint's long axis, in units of its
 * width, for kernels q times as wide: the n-quantiles of
 * the lobe's marginal there, which is the marginal of GGX's slopes
 * (Student's t of two degrees of freedom, t(p) = (2p - 1) / sqrt(2 p
 * (1 - p)), in units of its quartile t(3/4) = sqrt(2/3)), drawn in by
 * sqrt(1 - q^2) for the width each tap's kernel adds.  Each tap stands
 * for the same share of the lobe: the taps weigh the same. */
static void
tap_layout(unsigned n, double q, double pos[TAPS_MAX])
{
	static const double at[TAPS_MAX][TAPS_MAX] = {
		{ 0 },
		{ -1.0, 1.0 },
		{ -1.5491933384829668, 0.0, 1.5491933384829668 },
		{ -1.9639610121239315, -0.4472135954999579, 0.4472135954999579,
		  1.9639610121239315 },
	};
	double shrink = sqrt(q < 1.0 ? 1.0 - q * q : 0.0);
	unsigned i;

	for (i = 0; i < n; i++)
		pos[i] = at[n - 1][i] * shrink;
}

static inline double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline int
unit(double v[3])
{
	double len = sqrt(dot(v, v));

	if (!(len > 0.0) || !(len < INFINITY))
		return -1;
	v[0] /= len;
	v[1] /= len;
	v[2] /= len;
	return 0;
}

static inline void
cross(const double a[3], const double b[3], double c[3])
{
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

/* Any unit vector perpendicular to unit n. */
static void
perpendicular(const double n[3], double t[3])
{
	double a[3] = { 0, 0, 0 };

	a[fabs(n[0]) < 0.6 ? 0 : fabs(n[1]) < 0.6 ? 1 : 2] = 1.0;
	cross(n, a, t);
	unit(t);
}

/* The table at view angle theta_v and roughness pr, bilinearly. */
static void
lobe_at(double theta_v, double pr, double e[4])
{
	double x = theta_v / footprint_view_angle(FOOTPRINT_VIEWS - 1) * (FOOTPRINT_VIEWS - 1);
	double y = pr * (FOOTPRINT_ROUGHNESSES - 1), fx, fy;
	unsigned i, j, k;

	x = x < 0.0 ? 0.0 : x > FOOTPRINT_VIEWS - 1 ? FOOTPRINT_VIEWS - 1 : x;
	y = y < 0.0 ? 0.0 : y > FOOTPRINT_ROUGHNESSES - 1 ? FOOTPRINT_ROUGHNESSES - 1 : y;
	i = (unsigned)x < FOOTPRINT_VIEWS - 1 ? (unsigned)x : FOOTPRINT_VIEWS - 2;
	j = (unsigned)y < FOOTPRINT_ROUGHNESSES - 1 ? (unsigned)y : FOOTPRINT_ROUGHNESSES - 2;
	fx = x - i;
	fy = y - j;
	for (k = 0; k < 4; k++)
		e[k] = (1.0 - fx) * ((1.0 - fy) * footprint_table[i][j][k] +
		                     fy * footprint_table[i][j + 1][k]) +
		       fx * ((1.0 - fy) * footprint_table[i + 1][j][k] +
		             fy * footprint_table[i + 1][j + 1][k]);
}

/* The perceptual roughness whose prefilter kernel is w wide: the row
 * theta_v = 0, piecewise linear in roughness, inverted. */
static double
kernel_roughness(double w)
{
	unsigned j;

	if (!(w > 0.0))
		return 0.0;
	for (j = 1; j < FOOTPRINT_ROUGHNESSES; j++) {
		double lo = footprint_table[0][j - 1][3], hi = footprint_table[0][j][3];

		if (w <= hi)
			return ((double)(j - 1) + (w - lo) / (hi - lo)) /
			       (FOOTPRINT_ROUGHNESSES - 1);
	}
	return 1.0;
}

/* u's place in the tangent plane at unit c, t1 t2 (the logarithmic
 * map: the angle from c, along the great circle's direction). */
static void
log_map(const double c[3], const double t1[3], const double t2[3], const float u[3],
        double g[2])
{
	double v[3] = { u[0], u[1], u[2] }, x, y, s, ang;

	unit(v);
	x = dot(v, t1);
	y = dot(v, t2);
	s = sqrt(x * x + y * y);
	ang = atan2(s, dot(v, c));
	if (s > 0.0) {
		g[0] = ang * x / s;
		g[1] = ang * y / s;
	} else {
		g[0] = g[1] = 0.0;
	}
}

/* The direction at in-plane angle a from d (toward par) and across
 * angle b (toward across), as the table measures them, given cos a,
 * sin a and tan b. */
static void
lobe_direction_trig(const double d[3], const double par[3], const double across[3],
                    double ca, double sa, double tb, float out[3])
{
	double r[3];
	unsigned k;

	for (k = 0; k < 3; k++)
		r[k] = ca * d[k] + sa * par[k] + tb * across[k];
	unit(r);
	for (k = 0; k < 3; k++)
		out[k] = (float)r[k];
}

static void
lobe_direction(const double d[3], const double par[3], const double across[3], double a,
               double b, float out[3])
{
	lobe_direction_trig(d, par, across, cos(a), sin(a), tan(b), out);
}

/* Just above the surface: a tap no lower than this (a cosine) reads. */
#define HORIZON 1e-4

static int
above(const float l[3], const double below[3])
{
	return l[0] * below[0] + l[1] * below[1] + l[2] * below[2] > HORIZON;
}

static void
shade_pixel(const struct footprint *fp, const float *in, float out[3])
{
	const struct rf_host *host = fp->host;
	double n[3] = { in[3], in[4], in[5] };
	double v[3] = { in[6], in[7], in[8] }, ng[3] = { in[10], in[11], in[12] }, pr = in[9];
	double mu, theta_v, e[4], x[3], y[3], d[3], par[3], c[3], t1[3], t2[3], g[RAYS][2];
	double a[2], b[2], m11, m12, m22, tr, det, disc, smaj, smin, phi, w, ca, sa;
	double lod;
	float pf[3] = { in[0], in[1], in[2] }, dirs[3 * RAYS], look[3 * RAYS], dist[RAYS],
	      jac[RAYS], tdir[3 * TAPS_MAX], tlook[3 * TAPS_MAX], tdist[TAPS_MAX],
	      tjac[TAPS_MAX], sx[TAPS_MAX], sy[TAPS_MAX], sz[TAPS_MAX], sl[TAPS_MAX],
	      rgba[4 * TAPS_MAX];
	const double *below;
	double centre_dot;
	int centre_above;
	unsigned k, i, ntap, kept;

	out[0] = out[1] = out[2] = 0.0f;
	if (unit(n) < 0 || unit(v) < 0 || !(pr >= 0.0))
		return;
	pr = pr < 1.0 ? pr : 1.0;
	mu = dot(n, v);
	if (!(mu > 0.0))
		return; /* seen from below its surface: no light, as in Cycles */
	below = unit(ng) == 0 ? ng : n;
	theta_v = acos(mu < 1.0 ? mu : 1.0);
	lobe_at(fp->round ? 0.0 : theta_v, pr, e);
	/* The incidence plane: x toward V along the surface, y across. */
	for (k = 0; k < 3; k++)
		x[k] = v[k] - mu * n[k];
	if (!(sqrt(dot(x, x)) > 1e-6)) {
		perpendicular(n, x); /* head on: any direction along the surface */
	} else {
		double xn = dot(x, n);

		for (k = 0; k < 3; k++)
			x[k] -= xn * n[k]; /* what rounding left along n */
		unit(x);
	}
	cross(n, x, y);
	{
		/* the centre, theta_v + bend from N toward -x: R itself for
		 * lobe=round, whose row has no bend */
		double th = theta_v + fp->bend * e[0], st = sin(th), ct = cos(th);

		for (k = 0; k < 3; k++) {
			d[k] = -st * x[k] + ct * n[k];
			par[k] = -ct * x[k] - st * n[k];
		}
	}
	/* Toward the horizon the lobe ends at the surface: a width point
	 * past it would leave the box through the surface's own wall, right
	 * beside P, and take the footprint with it.  (lobe=round is the
	 * prefilter's kernel about R, as none reads it: horizon and all.) */
	if (!fp->round) {
		double el = asin(fmax(-1.0, fmin(1.0, dot(d, below))));

		if (e[2] > el - 1e-3)
			e[2] = fmax(0.0, el - 1e-3);
	}
	/* The footprint's centre and width points, at the widths and at
	 * half of them, taken through the box. */
	{
		/* Each ray turns one way only: of its cos, sin and tan, two are
		 * those of 0 (1, 0, 0 exactly), and only four angles each way
		 * are left to take; the bytes are those of lobe_direction. */
		const double in_plane[4] = { e[2], -e[1], 0.5 * e[2], -0.5 * e[1] };
		const double across[4] = { e[3], -e[3], 0.5 * e[3], -0.5 * e[3] };
		double cos_in[4], sin_in[4], tan_across[4];

		for (i = 0; i < 4; i++) {
			cos_in[i] = cos(in_plane[i]);
			sin_in[i] = sin(in_plane[i]);
			tan_across[i] = tan(across[i]);
		}
		lobe_direction_trig(d, par, y, 1.0, 0.0, 0.0, dirs);
		lobe_direction_trig(d, par, y, cos_in[0], sin_in[0], 0.0, dirs + 3);
		lobe_direction_trig(d, par, y, cos_in[1], sin_in[1], 0.0, dirs + 6);
		lobe_direction_trig(d, par, y, 1.0, 0.0, tan_across[0], dirs + 9);
		lobe_direction_trig(d, par, y, 1.0, 0.0, tan_across[1], dirs + 12);
		lobe_direction_trig(d, par, y, cos_in[2], sin_in[2], 0.0, dirs + 15);
		lobe_direction_trig(d, par, y, cos_in[3], sin_in[3], 0.0, dirs + 18);
		lobe_direction_trig(d, par, y, 1.0, 0.0, tan_across[2], dirs + 21);
		lobe_direction_trig(d, par, y, 1.0, 0.0, tan_across[3], dirs + 24);
	}
	if (host->project_rays) {
		host->project_rays(host->ctx, RAYS, pf, dirs, look, dist, jac);
	} else {
		memcpy(look, dirs, sizeof(look));
	}
	centre_dot = dirs[0] * below[0] + dirs[1] * below[1] + dirs[2] * below[2];
	centre_above = centre_dot > HORIZON;
	for (k = 0; k < 3; k++)
		c[k] = look[k];
	unit(c);
	perpendicular(c, t1);
	cross(c, t1, t2);
	for (i = 1; i < RAYS; i++) /* the centre's own is 0 */
		log_map(c, t1, t2, look + 3 * i, g[i]);
	a[0] = 0.25 * (g[1][0] - g[2][0]) + 0.5 * (g[5][0] - g[6][0]);
	a[1] = 0.25 * (g[1][1] - g[2][1]) + 0.5 * (g[5][1] - g[6][1]);
	b[0] = 0.25 * (g[3][0] - g[4][0]) + 0.5 * (g[7][0] - g[8][0]);
	b[1] = 0.25 * (g[3][1] - g[4][1]) + 0.5 * (g[7][1] - g[8][1]);
	/* [A B]^T [A B]: its eigenvalues are the squared widths at C, its
	 * eigenvectors the directions at P (in width units) that map onto
	 * them. */
	m11 = a[0] * a[0] + a[1] * a[1];
	m22 = b[0] * b[0] + b[1] * b[1];
	m12 = a[0] * b[0] + a[1] * b[1];
	tr = m11 + m22;
	det = m11 * m22 - m12 * m12;
	disc = sqrt(fmax(0.0, 0.25 * tr * tr - det));
	smaj = sqrt(fmax(0.0, 0.5 * tr + disc));
	smin = sqrt(fmax(0.0, 0.5 * tr - disc));
	phi = 0.5 * atan2(2.0 * m12, m11 - m22);
	/* All taps, unless the footprint is round (q = 1: one kernel is
	 * it); each kernel as wide as the minor axis, or a share of the
	 * major one, whichever is wider. */
	ntap = fp->taps;
	w = fmax(smin, smaj / ntap);
	if (!(smaj > 0.0) || w >= smaj || ntap == 1) {
		ntap = 1;
		w = smaj;
	}
	ca = cos(phi);
	sa = sin(phi);
	kept = 0;
	{
		double pos[TAPS_MAX];

		tap_layout(ntap, w / smaj, pos);

		for (i = 0; i < ntap; i++) {
			double ta = pos[i] * ca, tb = pos[i] * sa;
			double ia = ta * (ta > 0.0 ? e[2] : e[1]), ib = tb * e[3];

			/* in-plane: toward the horizon by its own width, toward
			 * the normal by the other */
			lobe_direction(d, par, y, ia, ib, tdir + 3 * kept);
			if (!above(tdir + 3 * kept, below)) {
				/* The t-shaped tail reaches past the horizon, which
				 * the measured lobe never does: the tap slides back
				 * toward the centre until it is just above (halving
				 * steps), so the picture stays continuous where a
				 * tap would cross it. */
				double f = 0.5, step = 0.25;
				unsigned it;

				if (!centre_above)
					continue;
				for (it = 0; it < 12; it++, step *= 0.5) {
					lobe_direction(d, par, y, f * ia, f * ib, tdir + 3 * kept);
					f += above(tdir + 3 * kept, below) ? step : -step;
				}
				lobe_direction(d, par, y, (f - 2.0 * step) * ia, (f - 2.0 * step) * ib,
				               tdir + 3 * kept);
				if (!above(tdir + 3 * kept, below))
					continue;
			}
			kept++;
		}
	}
	if (!kept) {
		/* every tap below the surface: the centre, if it is above */
		if (!(centre_dot > 0.0))
			return;
		ntap = 1;
		kept = 1;
	}
	if (ntap == 1) {
		memcpy(tlook, look, 3 * sizeof(float)); /* the centre, already projected */
		tjac[0] = jac[0];
	} else if (host->project_rays) {
		host->project_rays(host->ctx, kept, pf, tdir, tlook, tdist, tjac);
	} else {
		memcpy(tlook, tdir, 3 * kept * sizeof(float));
	}
	/* Each tap's kernel: w where the centre lands, scaled by how much
	 * more (or less) solid angle at C the tap's own exit takes per solid
	 * angle at P than the centre's does. */
	lod = host->roughness_to_lod(host->ctx, (float)kernel_roughness(w));
	for (i = 0; i < kept; i++) {
		sx[i] = tlook[3 * i];
		sy[i] = tlook[3 * i + 1];
		sz[i] = tlook[3 * i + 2];
		sl[i] = (float)lod;
		if (ntap > 1 && host->project_rays && jac[0] > 0.0f && tjac[i] > 0.0f &&
		    tjac[i] < INFINITY && tjac[i] != jac[0])
			sl[i] = host->roughness_to_lod(
				host->ctx, (float)kernel_roughness(w * sqrt(tjac[i] / jac[0])));
	}
	host->sample_many(host->ctx, kept, sx, sy, sz, sl, rgba);
	for (i = 0; i < kept; i++)
		for (k = 0; k < 3; k++)
			out[k] += rgba[4 * i + k];
	for (k = 0; k < 3; k++)
		out[k] /= (float)kept;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct footprint *fp = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i;

	for (i = 0; i < span->npix; i++, in += NINPUTS, out += 3)
		shade_pixel(fp, in, out);
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
	struct footprint *fp;

	if (host->size < offsetof(struct rf_host, sample_many) + sizeof(host->sample_many) ||
	    !host->sample_many || !host->roughness_to_lod) {
		snprintf(err, errlen, "this host offers no prefiltered environment to read "
		         "(it needs reflect-shade of plugin ABI 1.1 or later, with --env)");
		return -1;
	}
	if (!(fp = calloc(1, sizeof(*fp)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	fp->host = host;
	fp->taps = (unsigned)values[TAPS];
	fp->round = values[LOBE] == LOBE_ROUND;
	fp->bend = values[BEND];
	*state = fp;
	return 0;
}

static const struct rf_plugin descriptor = {
	.abi_major = RF_PLUGIN_ABI_MAJOR,
	.abi_minor = RF_PLUGIN_ABI_MINOR,
	.size = sizeof(struct rf_plugin),
	.kind = RF_KIND_SHADE,
	.flags = RF_PLUGIN_RADIANCE | RF_PLUGIN_PREFILTERED,
	.name = "footprint",
	.summary = "the GGX lobe's footprint on the box as the probe sees it, read in up "
	           "to four taps",
	.version = "1.0",
	.author = "reflect developers",
	.license = "MIT",
	.nparams = NPARAMS,
	.params = params,
	.inputs = inputs,
	.outputs = outputs,
	.optional_inputs = optional_inputs,
	.create = create,
	.run = run,
	.destroy = destroy,
};

RF_PLUGIN_DEFINE(descriptor)
