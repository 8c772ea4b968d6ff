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
 *     the way from R to that median (fitted, see the page) where the
 *     box projects the lobe and place=axis reads it; without one (infinite
 *     projection, box projection off, P outside the box) D is the
 *     median itself, which reads the lobe best there.
 *
 * Through the box (place=shares, the default), then:
 *
 *  S. Shares.  The table's second part (footprint_shares) cuts that
 *     lobe into n = taps= shares of equal weight by in-plane angle and
 *     gives each its median angle and its half-widths in-plane and
 *     across.  Each tap is its share's median, box-projected from P;
 *     three more rays about it (its share's quartiles either way
 *     in-plane, and across to one side) say how wide the share is at
 *     C, and its kernel is that wide times a factor that grows with
 *     roughness.  The taps weigh alike, and go over to one kernel at
 *     their centre where the lobe looks round from C (at P = C head on,
 *     what none reads).  This is the bench's oracle (256 rays traced a
 *     pixel, cut the same way) with the shares' places and spreads
 *     known beforehand: as good on the rooms, and with 16 box
 *     projections, fewer than steps 2 to 4 take.
 *
 * Steps 2 to 4 are place=axis, and every pixel read without the box:
 *
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
 *  4. Taps.  n = taps=; the n taps sit at the n-quantiles of the
 *     lobe's (t-shaped) marginal along the major axis, each
 *     box-projected from P itself (the parallax inside the lobe), the
 *     inner taps weighing inner= times the outer ones.  A tap past the
 *     horizon (Ng, else N) slides back.  Without the box every tap
 *     reads the prefilter's kernel of width w = max(minor, major / n)
 *     (the lod of the roughness whose kernel is w wide), drawn in by
 *     sqrt(1 - (w / major)^2) for the width each adds.  Through the box
 *     each tap stands for its share of the lobe: three more rays about
 *     it, along and across, say how wide that share is at C, and its
 *     kernel is that wide times a factor that grows with roughness;
 *     the taps are drawn in by sqrt(1 - 1/n^2) and go over to one tap
 *     of width w as the footprint gets round.
 *
 * Limits: roughness 0 reads the box-projected mirror direction at lod 0;
 * no hit (P outside the box, or an infinite projection) with N = V, or
 * lobe=round, reads what `none` reads; the same room in other units
 * gives the same pixels (angles and ratios only).
 *
 * Speed: the eight width rays, their log map, the taps of a pixel and
 * their stencils (both places) go in lanes (footprint-lanes.h, the same bits at 4 and
 * 8), its angles by series rather than libm, and the taps of eight
 * pixels in one read of the environment; the model is the same to float
 * rounding.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/plugin.h"

#include "footprint-shape.h"
#include "footprint-table.h"
#include "footprint-kernel.h"

/* a pixel's rays, log map and taps in vectors of 4 lanes, and of 8
 * with AVX2 */
#include "maths/lanes.h"
#define RF__LANES_BODY "footprint-lanes.h"
#include "maths/lanes-widths.h"

enum { TAPS, LOBE, PLACE, BEND, INNER, NPARAMS };
enum { LOBE_MEASURED, LOBE_ROUND };
enum { PLACE_SHARES, PLACE_AXIS };

static const struct rf_param params[NPARAMS] = {
	{ "taps", "cubemap reads a pixel at most, along the footprint's long axis",
	  1, 4, 4, RF_PARAM_INTEGER, NULL },
	{ "lobe", "measured: the lobe as GGX makes it at this view (bent, stretched); "
	  "round: the prefilter's kernel about R, parallax and contact only",
	  0, 1, LOBE_MEASURED, RF_PARAM_CHOICE, "measured|round" },
	{ "place", "where the taps go through the box: shares: each at the median of its "
	  "share of the lobe (cut by in-plane angle), its kernel that share's width at C; "
	  "axis: along the footprint's long axis at C, with bend= and inner=",
	  0, 1, PLACE_SHARES, RF_PARAM_CHOICE, "shares|axis" },
	{ "bend", "how far the centre moves from R toward the lobe's median (0: R, "
	  "1: the median) where the lobe is read through the box (without one, 1); "
	  "the default is fitted on the rooms of reflect-mode-footprint(7)",
	  0, 1.5, 0.55, 0, NULL },
	{ "inner", "how much more an inner tap weighs than an outer one (1: alike); "
	  "the default is fitted on the rooms of reflect-mode-footprint(7)",
	  0.25, 4, 1.5, 0, NULL },
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
#define CHUNK 8 /* pixels a read of the environment */
#define STENCIL 3 /* rays a tap's share is measured by, through the box */
/* Half a share's extent along the long axis, in width units, where its
 * stencil's rays go: for the two end shares, which reach into the
 * lobe's tails, and for the others, which lie between its quartiles.
 * The t marginal's own (half the distance between a share's quartiles)
 * are 0.87 and 0.24 at four taps; these and SHARE_KERNEL are fitted on
 * the rooms (see the page). */
#define SHARE_OUTER 0.6
#define SHARE_INNER 0.3
/* A share's kernel against the mean (geometric) of its two half-widths
 * at C: SHARE_KERNEL at roughness SHARE_KERNEL_AT, and relatively
 * SHARE_KERNEL_SLOPE more per unit of roughness.  Each room's own best
 * factor grows with its floor's roughness, from about 1.0 at 0.2 to 1.4
 * at 0.7 (log-linear, the same in rooms with and without spheres),
 * which one constant cannot follow; fitted on the rooms (see the
 * page). */
#define SHARE_KERNEL 1.15
#define SHARE_KERNEL_AT 0.4
#define SHARE_KERNEL_SLOPE 0.6
/* The same for place=shares, whose stencils span their share's
 * quartiles: fitted on the rooms of seed 1 (1.0 to 1.1 and slopes 0.8
 * to 1.2 are within 0.0006 of the best), the same numbers as the bench's
 * oracle took on those rooms. */
#define SHARES_KERNEL 1.05
#define SHARES_KERNEL_SLOPE 1.0
/* From this roundness (shares_roundness()) on, place=shares goes over
 * to one kernel about the lobe's centre, to be none's read at P = C
 * head on.  A line of round kernels is a poor round lobe (too narrow
 * across), yet on the rooms one kernel did worse still even where the
 * footprint was all but round (0.97: 0.1307 on seed 1, against 0.1272
 * without the go-over), so it is kept to the first 8 degrees of view
 * (0.99: 0.1284). */
#define SHARES_ROUND 0.99
/* From this ratio of the footprint's minor axis to its major one, the
 * taps close in and their kernels go over to the footprint's own, to
 * be one tap and one kernel where it is round (at P = C head on, what
 * none reads); fitted on the rooms (see the page). */
#define ROUND_FROM 0.6

struct footprint {
	const struct rf_host *host;
	unsigned taps;
	int round;
	int axis; /* place=axis */
	double bend;
	float inner; /* an inner tap's weight, an outer one's being 1 */
	const struct lanes *lanes; /* eight wide with AVX2, else four */
};

/* The lane code of one width, picked once at create. */
struct lanes {
	void (*rays)(const float *ca, const float *sa, const float *tb, const float d[3],
	             const float par[3], const float across[3], float *out);
	void (*taps)(const float *ia, const float *ib, const float d[3], const float par[3],
	             const float across[3], float *out);
	void (*log)(const float *look, const float c[3], const float t1[3], const float t2[3],
	            float *gx, float *gy);
};

static const struct lanes lanes_4 = { fp_rays_4, fp_taps_4, fp_log_4 };
#if defined(RF__LANES_WIDE)
static const struct lanes lanes_8 = { fp_rays_8, fp_taps_8, fp_log_8 };
#endif

/* n taps' places along the footprint's long axis, in units of its
 * width, for kernels q times as wide as that axis: the n-quantiles of
 * the lobe's marginal there, which is the marginal of GGX's slopes
 * (Student's t of two degrees of freedom, t(p) = (2p - 1) / sqrt(2 p
 * (1 - p)), in units of its quartile t(3/4) = sqrt(2/3)), drawn in by
 * sqrt(1 - q^2) for the width each tap's kernel adds.  Each tap stands
 * for the same share of the lobe, but the outer taps' kernels carry
 * their share past the lobe's flanks into its tails, while the peak
 * between the inner taps is left short; so the inner taps weigh more
 * (inner=, tap_weight()). */
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

/* Whether tap i of n is one of the two ends, whose share reaches into
 * the lobe's tails. */
static inline int
end_tap(unsigned i, unsigned n)
{
	return i == 0 || i + 1 == n;
}

/* Tap i of n's weight: the ones between the two ends weigh inner, the
 * ends 1.  Fitting only the weights of four kernels at tap_layout()'s
 * places to the t marginal, by least squares, gives the inner ones 1.2
 * to 1.3 times the outer ones' weight if it matches the cumulatives,
 * 1.8 to 2 if it matches the densities (q = 0.25 to 0.5); inner= is
 * 1.5, fitted on the rooms, between the two. */
static inline float
tap_weight(const struct footprint *fp, unsigned i, unsigned n)
{
	return end_tap(i, n) ? 1.0f : fp->inner;
}

/* Half tap i of n's share's extent along the long axis, in widths. */
static inline double
share_half(unsigned i, unsigned n)
{
	return end_tap(i, n) ? SHARE_OUTER : SHARE_INNER;
}

static inline double
dot(const double a[3], const double b[3])
{
	return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline int
unit(double v[3])
{
	double len = sqrt(dot(v, v)), inv;

	if (!(len > 0.0) || !(len < INFINITY))
		return -1;
	inv = 1.0 / len;
	v[0] *= inv;
	v[1] *= inv;
	v[2] *= inv;
	return 0;
}

static inline void
cross(const double a[3], const double b[3], double c[3])
{
	c[0] = a[1] * b[2] - a[2] * b[1];
	c[1] = a[2] * b[0] - a[0] * b[2];
	c[2] = a[0] * b[1] - a[1] * b[0];
}

/* The angles, without libm: a pixel takes some thirty sines, cosines,
 * tangents and arctangents, which libm's correctly rounded routines made
 * a third of the mode's time.  These series are good to ~1e-12 over the
 * ranges the mode gives them, far below the float the pixel ends in. */
#define PI_2_HI 1.5707963267341256   /* pi / 2 in two parts, so that   */
#define PI_2_LO 6.077100506506192e-11 /* x - k pi / 2 stays exact      */

/* fmax and fmin, NaN giving the other as theirs do, without the call
 * libm makes of them */
static inline double
fp_max(double a, double b)
{
	return a > b || b != b ? a : b;
}

static inline double
fp_min(double a, double b)
{
	return a < b || b != b ? a : b;
}

/* sin and cos of x: x less the nearest multiple of pi / 2, then Taylor
 * to the 14th power on [-pi / 4, pi / 4] (error below 3e-14). */
static inline void
fp_sincos(double x, double *s, double *c)
{
	double k = nearbyint(x * (2.0 / M_PI)), r, r2, sr, cr;
	long q = (long)k;

	r = (x - k * PI_2_HI) - k * PI_2_LO;
	r2 = r * r;
	sr = r + r * r2 * (-1.0 / 6 + r2 * (1.0 / 120 + r2 * (-1.0 / 5040 + r2 *
	     (1.0 / 362880 + r2 * (-1.0 / 39916800 + r2 * (1.0 / 6227020800.0))))));
	cr = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24 + r2 * (-1.0 / 720 + r2 * (1.0 / 40320 +
	     r2 * (-1.0 / 3628800 + r2 * (1.0 / 479001600.0 + r2 *
	     (-1.0 / 87178291200.0)))))));
	switch (q & 3) {
	case 0: *s = sr; *c = cr; break;
	case 1: *s = cr; *c = -sr; break;
	case 2: *s = -sr; *c = -cr; break;
	default: *s = -cr; *c = sr; break;
	}
}

/* atan of t in [0, 1]: past tan(pi / 12) by atan t = pi / 6 +
 * atan((sqrt(3) t - 1) / (t + sqrt(3))), then Taylor to the 17th power
 * on [0, tan(pi / 12)] (error below 1e-12). */
static inline double
fp_atan01(double t)
{
	double base = 0.0, u2;

	if (t > 0.2679491924311227) {
		t = (1.7320508075688772 * t - 1.0) / (t + 1.7320508075688772);
		base = M_PI / 6.0;
	}
	u2 = t * t;
	return base + t + t * u2 * (-1.0 / 3 + u2 * (1.0 / 5 + u2 * (-1.0 / 7 + u2 *
	       (1.0 / 9 + u2 * (-1.0 / 11 + u2 * (1.0 / 13 + u2 * (-1.0 / 15 + u2 *
	       (1.0 / 17))))))));
}

/* atan2 of finite y, x, as libm's (0 for 0, 0). */
static inline double
fp_atan2(double y, double x)
{
	double ay = fabs(y), ax = fabs(x), a;

	if (ay <= ax)
		a = ax > 0.0 ? fp_atan01(ay / ax) : 0.0;
	else
		a = M_PI_2 - fp_atan01(ax / ay);
	if (x < 0.0)
		a = M_PI - a;
	return copysign(a, y);
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

/* Where the tables are read at view angle theta_v and roughness pr,
 * bilinearly: the cell (i, j) and the weights (fx, fy) within it. */
static void
table_cell(double theta_v, double pr, unsigned *i, unsigned *j, double *fx, double *fy)
{
	double x = theta_v / footprint_view_angle(FOOTPRINT_VIEWS - 1) * (FOOTPRINT_VIEWS - 1);
	double y = pr * (FOOTPRINT_ROUGHNESSES - 1);

	x = x < 0.0 ? 0.0 : x > FOOTPRINT_VIEWS - 1 ? FOOTPRINT_VIEWS - 1 : x;
	y = y < 0.0 ? 0.0 : y > FOOTPRINT_ROUGHNESSES - 1 ? FOOTPRINT_ROUGHNESSES - 1 : y;
	*i = (unsigned)x < FOOTPRINT_VIEWS - 1 ? (unsigned)x : FOOTPRINT_VIEWS - 2;
	*j = (unsigned)y < FOOTPRINT_ROUGHNESSES - 1 ? (unsigned)y : FOOTPRINT_ROUGHNESSES - 2;
	*fx = x - *i;
	*fy = y - *j;
}

/* The table at view angle theta_v and roughness pr, bilinearly. */
static void
lobe_at(double theta_v, double pr, double e[4])
{
	double fx, fy;
	unsigned i, j, k;

	table_cell(theta_v, pr, &i, &j, &fx, &fy);
	for (k = 0; k < 4; k++)
		e[k] = (1.0 - fx) * ((1.0 - fy) * footprint_table[i][j][k] +
		                     fy * footprint_table[i][j + 1][k]) +
		       fx * ((1.0 - fy) * footprint_table[i + 1][j][k] +
		             fy * footprint_table[i + 1][j + 1][k]);
}

/* The box path's table at view angle theta_v and roughness pr, for n
 * taps, bilinearly: each share's median in-plane angle from the normal,
 * and its half-widths in-plane and across (footprint-gen.c). */
static void
shares_at(double theta_v, double pr, unsigned n, double sh[TAPS_MAX][3])
{
	double fx, fy;
	unsigned i, j, t, k, first = footprint_first_share(n);

	table_cell(theta_v, pr, &i, &j, &fx, &fy);
	for (t = 0; t < n; t++)
		for (k = 0; k < 3; k++)
			sh[t][k] = (1.0 - fx) * ((1.0 - fy) * footprint_shares[i][j][first + t][k] +
			                         fy * footprint_shares[i][j + 1][first + t][k]) +
			           fx * ((1.0 - fy) * footprint_shares[i + 1][j][first + t][k] +
			                 fy * footprint_shares[i + 1][j + 1][first + t][k]);
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
	double ca, sa, cb, sb;

	fp_sincos(a, &sa, &ca);
	fp_sincos(b, &sb, &cb);
	lobe_direction_trig(d, par, across, ca, sa, sb / cb, out);
}

/* Just above the surface: a tap no lower than this (a cosine) reads. */
#define HORIZON 1e-4

static int
above(const float l[3], const double below[3])
{
	return l[0] * below[0] + l[1] * below[1] + l[2] * below[2] > HORIZON;
}

/* A tap at angles (a1, b1) from d that is below the surface, slid back
 * toward (a0, b0), which is above, until it is just above (halving
 * steps), so that the picture stays continuous where a tap would cross
 * the horizon: its angles in *a, *b and its direction in out; 0 where
 * even that is below. */
static int
slide_above(const double d[3], const double par[3], const double across[3], double a0,
            double b0, double a1, double b1, const double below[3], double *a, double *b,
            float out[3])
{
	double f = 0.5, step = 0.25;
	unsigned it;

	for (it = 0; it < 12; it++, step *= 0.5) {
		lobe_direction(d, par, across, a0 + f * (a1 - a0), b0 + f * (b1 - b0), out);
		f += above(out, below) ? step : -step;
	}
	f -= 2.0 * step;
	*a = a0 + f * (a1 - a0);
	*b = b0 + f * (b1 - b0);
	lobe_direction(d, par, across, *a, *b, out);
	return above(out, below);
}

/* The stencil of a tap at angles (a, b) from d, as angles (ra, rb, 3
 * each): its share, half of it either way along the long axis (cos phi,
 * sin phi in width units; half widths, in-plane by the width of the
 * tap's side), and one width to one side across it, so that where the
 * box takes them says how wide the share is at C.  (The other side
 * across, a fourth ray, changed the rooms' error by under 0.001.) */
static void
stencil_angles(double a, double b, double half, const double e[4], double ca, double sa,
               float *ra, float *rb)
{
	double side = a > 0.0 ? e[2] : e[1];

	ra[0] = (float)(a + half * ca * side);
	rb[0] = (float)(b + half * sa * e[3]);
	ra[1] = (float)(a - half * ca * side);
	rb[1] = (float)(b - half * sa * e[3]);
	ra[2] = (float)(a - sa * side);
	rb[2] = (float)(b + ca * e[3]);
}

/* The kernel for a tap's share: factor times the geometric mean of its
 * half-widths at C, along and across: along, half the chord between
 * its stencil's two lookups that way, or the whole chord from the
 * tap's own lookup where one of the two rays is below the surface (its
 * exit would be the surface's own wall, beside P); across, the chord
 * from the tap's lookup to the third ray's.  w where neither way can be
 * measured. */
static double
share_kernel(const float tap[3], const float *dirs, const float *look, const double below[3],
             double w, double factor)
{
	double half[2][3], along, across, c[3]; /* along, across: squared */
	int up_plus = above(dirs, below), up_minus = above(dirs + 3, below);
	int up_side = above(dirs + 6, below);
	unsigned k;

	for (k = 0; k < 3; k++) {
		half[0][k] = up_plus && up_minus ? 0.5 * ((double)look[k] - look[3 + k])
		             : up_plus           ? (double)look[k] - tap[k]
		             : up_minus          ? (double)tap[k] - look[3 + k]
		                                 : 0.0;
		half[1][k] = up_side ? (double)look[6 + k] - tap[k] : 0.0;
	}
	along = dot(half[0], half[0]);
	across = dot(half[1], half[1]);
	if (along > 0.0 && across > 0.0) {
		cross(half[0], half[1], c);
		return factor * sqrt(sqrt(dot(c, c)));
	}
	if (along > 0.0 || across > 0.0)
		return factor * (sqrt(along) + sqrt(across));
	return w;
}

/* A share's stencil (ra, rb, 3 each) about its median at in-plane
 * angle a: half its in-plane width wa either way, and its width across
 * wb to one side (the other side is the mirror image in the lobe). */
static void
share_stencil(double a, double wa, double wb, float *ra, float *rb)
{
	ra[0] = (float)(a + wa);
	ra[1] = (float)(a - wa);
	ra[2] = (float)a;
	rb[0] = rb[1] = 0.0f;
	rb[2] = (float)wb;
}

static inline double
chord(const float a[3], const float b[3])
{
	double d[3] = { (double)a[0] - b[0], (double)a[1] - b[1], (double)a[2] - b[2] };

	return sqrt(dot(d, d));
}

/* How round the lobe looks from C, as a weight: 1 where its extents
 * in-plane and across stand as they do for a lobe seen head on (the
 * prefilter's kernel), where one kernel about its centre reads it best,
 * down to 0 at SHARES_ROUND of that.  The n taps and their stencils at P
 * (tdir) and at C (tlook), as shade_shares() lays them out; sh their
 * table rows.  Where it is not 0, centre gets the lobe's centre at C and
 * w the whole lobe's kernel there: its own width (lobe_at()) times how
 * much the box grows it. */
static double
shares_roundness(unsigned n, const float *tdir, const float *tlook, const double below[3],
                 double theta_v, double pr, const double sh[TAPS_MAX][3], double centre[3],
                 double *w)
{
	double at_p[2], at_c[2] = { 0.0, 0.0 }, head[TAPS_MAX][3], e[4];
	double across_p = 0.0, across_head = 0.0, q, rho;
	unsigned i, k;

	at_p[1] = 0.0;
	for (i = 0; i < n; i++) {
		const float *side = tdir + 3 * (n + STENCIL * i + 2);

		if (!above(side, below))
			return 0.0;
		at_p[1] += chord(side, tdir + 3 * i);
		at_c[1] += chord(tlook + 3 * (n + STENCIL * i + 2), tlook + 3 * i);
	}
	at_p[0] = chord(tdir, tdir + 3 * (n - 1));
	at_c[0] = chord(tlook, tlook + 3 * (n - 1));
	shares_at(0.0, pr, n, head);
	for (i = 0; i < n; i++) {
		across_p += sh[i][2];
		across_head += head[i][2];
	}
	/* C's ratio against P's (the box's doing), times the lobe's own
	 * against a head-on lobe's */
	q = at_c[0] * at_p[1] * (sh[n - 1][0] - sh[0][0]) * across_head /
	    (at_c[1] * at_p[0] * (head[n - 1][0] - head[0][0]) * across_p);
	if (!(q > 0.0) || !(q < INFINITY))
		return 0.0;
	q = q < 1.0 ? q : 1.0 / q;
	rho = (q - SHARES_ROUND) / (1.0 - SHARES_ROUND);
	if (!(rho > 0.0))
		return 0.0;
	centre[0] = centre[1] = centre[2] = 0.0;
	for (i = 0; i < n; i++)
		for (k = 0; k < 3; k++)
			centre[k] += tlook[3 * i + k];
	if (unit(centre) < 0)
		return 0.0;
	lobe_at(theta_v, pr, e);
	*w = sqrt(at_c[0] * at_c[1] / (at_p[0] * at_p[1]) * 0.5 * (e[1] + e[2]) * e[3]);
	return rho < 1.0 ? rho : 1.0;
}

/* place=shares, through the box: the lobe cut into n shares of equal
 * weight by in-plane angle (footprint_shares), each read at its median,
 * box-projected from P, with the kernel its stencil measures at C; the
 * taps weigh alike.  The pixel's taps as shade_pixel() gives them, or
 * -1 where P is outside the box or no share is above the surface (the
 * rest of shade_pixel() reads those). */
static int
shade_shares(const struct footprint *fp, const float pf[3], const double n[3],
             const double x[3], const double y[3], const double below[3], double theta_v,
             double pr, float *sx, float *sy, float *sz, float *sl, float *sw)
{
	const struct rf_host *host = fp->host;
	unsigned ntap = fp->taps, i, k, kept = 0, src[TAPS_MAX];
	double sh[TAPS_MAX][3], par[3], factor, rho = 0.0, centre[3], whole = 0.0;
	float ia16[2 * 8] = { 0 }, ib16[2 * 8] = { 0 }, dir16[3 * 2 * 8], nf[3], parf[3], yf[3];
	float tdir[3 * TAPS_MAX * (1 + STENCIL)], tlook[3 * TAPS_MAX * (1 + STENCIL)],
	      tdist[TAPS_MAX * (1 + STENCIL)], tjac[TAPS_MAX * (1 + STENCIL)];
	double lobe[TAPS_MAX][3]; /* the whole lobe as one share: its median */
	int lobe_above = -1; /* whether the lobe's median is: not yet known */

	shares_at(theta_v, pr, ntap, sh);
	for (k = 0; k < 3; k++) {
		par[k] = -x[k];
		nf[k] = (float)n[k];
		parf[k] = (float)par[k];
		yf[k] = (float)y[k];
	}
	for (i = 0; i < ntap; i++) {
		ia16[i] = (float)sh[i][0];
		share_stencil(sh[i][0], sh[i][1], sh[i][2], ia16 + TAPS_MAX + STENCIL * i,
		              ib16 + TAPS_MAX + STENCIL * i);
	}
	fp->lanes->taps(ia16, ib16, nf, parf, yf, dir16);
	fp->lanes->taps(ia16 + 8, ib16 + 8, nf, parf, yf, dir16 + 24);
	for (i = 0; i < ntap; i++) {
		memcpy(tdir + 3 * kept, dir16 + 3 * i, 3 * sizeof(float));
		if (!above(tdir + 3 * kept, below)) {
			/* below the geometric surface (N leans away from Ng): the
			 * tap slides toward the lobe's median, its stencil with
			 * it, as on the axis path; where the median is below too,
			 * the share gives no light */
			double a, b;
			float ra[STENCIL], rb[STENCIL];

			if (lobe_above < 0) {
				shares_at(theta_v, pr, 1, lobe);
				lobe_direction(n, par, y, lobe[0][0], 0.0, tdir + 3 * kept);
				lobe_above = above(tdir + 3 * kept, below);
			}
			if (!lobe_above || !slide_above(n, par, y, lobe[0][0], 0.0, sh[i][0], 0.0, below,
			                                &a, &b, tdir + 3 * kept))
				continue;
			share_stencil(a, sh[i][1], sh[i][2], ra, rb);
			for (k = 0; k < STENCIL; k++)
				lobe_direction(n, par, y, ra[k], rb[k],
				               dir16 + 3 * (TAPS_MAX + STENCIL * i + k));
		}
		src[kept++] = i;
	}
	if (!kept)
		return -1;
	for (i = 0; i < kept; i++)
		memcpy(tdir + 3 * (kept + STENCIL * i), dir16 + 3 * (TAPS_MAX + STENCIL * src[i]),
		       3 * STENCIL * sizeof(float));
	host->project_rays(host->ctx, kept * (1 + STENCIL), pf, tdir, tlook, tdist, tjac);
	if (!(tdist[0] < INFINITY))
		return -1;
	if (kept == ntap && ntap > 1)
		rho = shares_roundness(ntap, tdir, tlook, below, theta_v, pr, sh, centre, &whole);
	factor = SHARES_KERNEL * (1.0 + SHARES_KERNEL_SLOPE * (pr - SHARE_KERNEL_AT));
	for (i = 0; i < kept; i++) {
		const double *share = sh[src[i]];
		double w = share_kernel(tlook + 3 * i, tdir + 3 * (kept + STENCIL * i),
		                        tlook + 3 * (kept + STENCIL * i), below,
		                        factor * sqrt(share[1] * share[2]), factor);

		if (rho > 0.0) {
			/* toward one kernel about the centre, as the lobe
			 * gets round */
			double l[3];

			for (k = 0; k < 3; k++)
				l[k] = centre[k] + (1.0 - rho) * (tlook[3 * i + k] - centre[k]);
			unit(l);
			for (k = 0; k < 3; k++)
				tlook[3 * i + k] = (float)l[k];
			w = (1.0 - rho) * w + rho * whole;
		}
		sx[i] = tlook[3 * i];
		sy[i] = tlook[3 * i + 1];
		sz[i] = tlook[3 * i + 2];
		sl[i] = host->roughness_to_lod(host->ctx, (float)footprint_kernel_roughness(w));
		sw[i] = 1.0f;
	}
	return (int)kept;
}

/* The pixel's taps, appended to sx, sy, sz (directions), sl (lods) and
 * sw (weights); their number (0: black). */
static unsigned
shade_pixel(const struct footprint *fp, const float *in, float *sx, float *sy, float *sz,
            float *sl, float *sw)
{
	const struct rf_host *host = fp->host;
	double n[3] = { in[3], in[4], in[5] };
	double v[3] = { in[6], in[7], in[8] }, ng[3] = { in[10], in[11], in[12] }, pr = in[9];
	double mu, sv, theta_v, e[4], x[3], y[3], d[3], par[3], c[3], t1[3], t2[3];
	float df[3], parf[3], yf[3], cf[3], t1f[3], t2f[3], gx[8], gy[8];
	double a[2], b[2], m11, m12, m22, tr, det, disc, smaj, smin, w, ca, sa;
	double lod, bend, horizon_width, roundness, factor;
	/* the taps' directions, then their stencils' (see stencil_angles()) */
	float pf[3] = { in[0], in[1], in[2] }, dirs[3 * RAYS], look[3 * RAYS], dist[RAYS],
	      jac[RAYS], tdir[3 * TAPS_MAX * (1 + STENCIL)],
	      tlook[3 * TAPS_MAX * (1 + STENCIL)], tdist[TAPS_MAX * (1 + STENCIL)],
	      tjac[TAPS_MAX * (1 + STENCIL)];
	const double *below;
	double centre_dot;
	int centre_above, boxed, own;
	unsigned k, i, ntap, kept;

	if (unit(n) < 0 || unit(v) < 0 || !(pr >= 0.0))
		return 0;
	pr = pr < 1.0 ? pr : 1.0;
	mu = dot(n, v);
	if (!(mu > 0.0))
		return 0; /* seen from below its surface: no light, as in Cycles */
	below = unit(ng) == 0 ? ng : n;
	mu = mu < 1.0 ? mu : 1.0;
	sv = sqrt((1.0 - mu) * (1.0 + mu)); /* sin theta_v */
	theta_v = fp_atan2(sv, mu);
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
	if (!fp->axis && !fp->round && host->project_rays && host->probe &&
	    host->probe->box_projection) {
		int got = shade_shares(fp, pf, n, x, y, below, theta_v, pr, sx, sy, sz, sl, sw);

		if (got >= 0)
			return (unsigned)got;
	}
	lobe_at(fp->round ? 0.0 : theta_v, pr, e);
	/* Where the rays keep their directions (no box: infinite projection,
	 * box projection off) the lobe is read as it is, about its own
	 * median; bend= is for the box (see the page). */
	bend = host->project_rays && host->probe && host->probe->box_projection ? fp->bend : 1.0;
	horizon_width = e[2];
cast:
	e[2] = horizon_width;
	{
		/* the centre, theta_v + bend from N toward -x: R itself for
		 * lobe=round, whose row has no bend */
		double sb, cb, st, ct;

		fp_sincos(bend * e[0], &sb, &cb);
		st = sv * cb + mu * sb;
		ct = mu * cb - sv * sb;

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
		double h = fp_max(-1.0, fp_min(1.0, dot(d, below)));
		double el = fp_atan2(h, sqrt((1.0 - h) * (1.0 + h)));

		if (e[2] > el - 1e-3)
			e[2] = fp_max(0.0, el - 1e-3);
	}
	/* The footprint's centre and width points, at the widths and at
	 * half of them, taken through the box. */
	{
		/* Each ray turns one way only: of its cos, sin and tan, two are
		 * those of 0 (1, 0, 0 exactly), and only four angles each way
		 * are left to take.  The centre in double, the eight others in
		 * lanes (float, as they go to the host). */
		const double in_plane[4] = { e[2], -e[1], 0.5 * e[2], -0.5 * e[1] };
		const double across[2] = { e[3], 0.5 * e[3] };
		double sn, cs;
		float ca8[8], sa8[8], tb8[8];

		/* rays 1 2 5 6 turn in-plane, 3 4 7 8 across */
		for (i = 0; i < 4; i++) {
			unsigned r = i < 2 ? i : i + 2;

			fp_sincos(in_plane[i], &sn, &cs);
			ca8[r] = (float)cs;
			sa8[r] = (float)sn;
			tb8[r] = 0.0f;
		}
		for (i = 0; i < 2; i++) {
			fp_sincos(across[i], &sn, &cs);
			ca8[2 + 4 * i] = ca8[3 + 4 * i] = 1.0f;
			sa8[2 + 4 * i] = sa8[3 + 4 * i] = 0.0f;
			tb8[2 + 4 * i] = (float)(sn / cs);
			tb8[3 + 4 * i] = -tb8[2 + 4 * i];
		}
		for (k = 0; k < 3; k++) {
			df[k] = (float)d[k];
			parf[k] = (float)par[k];
			yf[k] = (float)y[k];
		}
		lobe_direction_trig(d, par, y, 1.0, 0.0, 0.0, dirs);
		fp->lanes->rays(ca8, sa8, tb8, df, parf, yf, dirs + 3);
	}
	if (host->project_rays) {
		host->project_rays(host->ctx, RAYS, pf, dirs, look, dist, jac);
		if (!(dist[0] < INFINITY) && bend != 1.0) {
			bend = 1.0; /* P outside the box: no box either */
			goto cast;
		}
	} else {
		memcpy(look, dirs, sizeof(look));
	}
	/* where the box projects the lobe, each tap's kernel is measured
	 * on its own share of it (below); elsewhere the footprint is the
	 * lobe's, and one kernel serves every tap */
	boxed = host->project_rays && host->probe && host->probe->box_projection &&
	        dist[0] < INFINITY;
	centre_dot = dirs[0] * below[0] + dirs[1] * below[1] + dirs[2] * below[2];
	centre_above = centre_dot > HORIZON;
	for (k = 0; k < 3; k++)
		c[k] = look[k];
	unit(c);
	perpendicular(c, t1);
	cross(c, t1, t2);
	/* u's place in the tangent plane at c (the logarithmic map: the
	 * angle from c, along the great circle's direction); the centre's
	 * own is 0 */
	for (k = 0; k < 3; k++) {
		cf[k] = (float)c[k];
		t1f[k] = (float)t1[k];
		t2f[k] = (float)t2[k];
	}
	fp->lanes->log(look + 3, cf, t1f, t2f, gx, gy);
	a[0] = 0.25 * ((double)gx[0] - gx[1]) + 0.5 * ((double)gx[4] - gx[5]);
	a[1] = 0.25 * ((double)gy[0] - gy[1]) + 0.5 * ((double)gy[4] - gy[5]);
	b[0] = 0.25 * ((double)gx[2] - gx[3]) + 0.5 * ((double)gx[6] - gx[7]);
	b[1] = 0.25 * ((double)gy[2] - gy[3]) + 0.5 * ((double)gy[6] - gy[7]);
	/* [A B]^T [A B]: its eigenvalues are the squared widths at C, its
	 * eigenvectors the directions at P (in width units) that map onto
	 * them. */
	m11 = a[0] * a[0] + a[1] * a[1];
	m22 = b[0] * b[0] + b[1] * b[1];
	m12 = a[0] * b[0] + a[1] * b[1];
	tr = m11 + m22;
	det = m11 * m22 - m12 * m12;
	disc = sqrt(fp_max(0.0, 0.25 * tr * tr - det));
	smaj = sqrt(fp_max(0.0, 0.5 * tr + disc));
	smin = sqrt(fp_max(0.0, 0.5 * tr - disc));
	{
		/* cos and sin of the major axis' angle phi from those of 2 phi
		 * (half angles, no arctangent): 2 phi is atan2(2 m12,
		 * m11 - m22), so phi is in (-pi/2, pi/2] and cos phi >= 0. */
		double r2 = sqrt(4.0 * m12 * m12 + (m11 - m22) * (m11 - m22)), c2, s2;

		if (!(r2 > 0.0)) {
			ca = 1.0;
			sa = 0.0;
		} else {
			c2 = (m11 - m22) / r2;
			s2 = 2.0 * m12 / r2;
			if (c2 >= 0.0) {
				ca = sqrt(0.5 * (1.0 + c2));
				sa = 0.5 * s2 / ca;
			} else {
				sa = copysign(sqrt(0.5 * (1.0 - c2)), m12);
				ca = 0.5 * fabs(s2) / fabs(sa);
			}
		}
	}
	/* All taps, unless the footprint is round (q = 1: one kernel is
	 * it); without the box each kernel as wide as the minor axis, or a
	 * share of the major one, whichever is wider (through the box each
	 * covers a share: q = 1 / n). */
	ntap = fp->taps;
	w = fp_max(smin, smaj / ntap);
	if (!(smaj > 0.0) || w >= smaj || ntap == 1) {
		ntap = 1;
		w = smaj;
	}
	kept = 0;
	roundness = fp_min(1.0, fp_max(0.0, (w / smaj - ROUND_FROM) / (1.0 - ROUND_FROM)));
	/* one kernel for every tap, unless each has its share's */
	own = ntap > 1 && boxed && roundness < 1.0;
	{
		/* the taps' angles in lanes 0 to 3, their stencils' (if
		 * measured) after them: two lane calls of eight directions */
		double pos[TAPS_MAX], tia[TAPS_MAX], tib[TAPS_MAX];
		float ia16[2 * 8] = { 0 }, ib16[2 * 8] = { 0 }, dir16[3 * 2 * 8];
		unsigned src[TAPS_MAX];

		tap_layout(ntap, boxed ? 1.0 / ntap + roundness * (1.0 - 1.0 / ntap) : w / smaj, pos);
		for (i = 0; i < ntap; i++) {
			double ta = pos[i] * ca, tb = pos[i] * sa;

			/* in-plane: toward the horizon by its own width, toward
			 * the normal by the other */
			tia[i] = ta * (ta > 0.0 ? e[2] : e[1]);
			tib[i] = tb * e[3];
			ia16[i] = (float)tia[i];
			ib16[i] = (float)tib[i];
			if (own)
				stencil_angles(tia[i], tib[i], share_half(i, ntap), e, ca, sa,
				               ia16 + TAPS_MAX + STENCIL * i,
				               ib16 + TAPS_MAX + STENCIL * i);
		}
		fp->lanes->taps(ia16, ib16, df, parf, yf, dir16);
		if (own)
			fp->lanes->taps(ia16 + 8, ib16 + 8, df, parf, yf, dir16 + 24);

		for (i = 0; i < ntap; i++) {
			double ia = tia[i], ib = tib[i];

			memcpy(tdir + 3 * kept, dir16 + 3 * i, 3 * sizeof(float));
			if (!above(tdir + 3 * kept, below)) {
				/* The t-shaped tail reaches past the horizon, which
				 * the measured lobe never does: the tap slides back
				 * toward the centre; its stencil goes with it. */
				float ra[STENCIL], rb[STENCIL];

				if (!centre_above ||
				    !slide_above(d, par, y, 0.0, 0.0, tia[i], tib[i], below, &ia, &ib,
				                 tdir + 3 * kept))
					continue;
				if (own) {
					stencil_angles(ia, ib, share_half(i, ntap), e, ca, sa, ra, rb);
					for (k = 0; k < STENCIL; k++)
						lobe_direction(d, par, y, ra[k], rb[k],
						               dir16 + 3 * (TAPS_MAX + STENCIL * i + k));
				}
			}
			src[kept] = i;
			sw[kept] = tap_weight(fp, i, ntap);
			kept++;
		}
		/* the kept taps' stencils after the kept taps */
		for (i = 0; own && i < kept; i++)
			memcpy(tdir + 3 * (kept + STENCIL * i),
			       dir16 + 3 * (TAPS_MAX + STENCIL * src[i]), 3 * STENCIL * sizeof(float));
	}
	if (!kept) {
		/* every tap below the surface: the centre, if it is above */
		if (!(centre_dot > 0.0))
			return 0;
		ntap = 1;
		kept = 1;
		own = 0;
	}
	if (ntap == 1) {
		memcpy(tlook, look, 3 * sizeof(float)); /* the centre, already projected */
		sw[0] = 1.0f;
	} else if (own) {
		host->project_rays(host->ctx, kept * (1 + STENCIL), pf, tdir, tlook, tdist, tjac);
	} else if (host->project_rays) {
		host->project_rays(host->ctx, kept, pf, tdir, tlook, tdist, tjac);
	} else {
		memcpy(tlook, tdir, 3 * kept * sizeof(float));
	}
	lod = own ? 0.0 : host->roughness_to_lod(host->ctx, (float)footprint_kernel_roughness(w));
	factor = SHARE_KERNEL * (1.0 + SHARE_KERNEL_SLOPE * (pr - SHARE_KERNEL_AT));
	for (i = 0; i < kept; i++) {
		sx[i] = tlook[3 * i];
		sy[i] = tlook[3 * i + 1];
		sz[i] = tlook[3 * i + 2];
		sl[i] = (float)lod;
		if (own) {
			double share = share_kernel(tlook + 3 * i, tdir + 3 * (kept + STENCIL * i),
			                            tlook + 3 * (kept + STENCIL * i), below, w,
			                            factor);

			sl[i] = host->roughness_to_lod(
				host->ctx,
				(float)footprint_kernel_roughness((1.0 - roundness) * share + roundness * w));
		}
	}
	return kept;
}

static void
run(void *state, const struct rf_span *span)
{
	const struct footprint *fp = state;
	const float *in = span->in;
	float *out = span->out;
	uint32_t i0, i, n, k, t;

	/* eight pixels' taps in one read of the environment: its vector
	 * path takes eight at a time */
	for (i0 = 0; i0 < span->npix; i0 += CHUNK) {
		float sx[CHUNK * TAPS_MAX], sy[CHUNK * TAPS_MAX], sz[CHUNK * TAPS_MAX],
		      sl[CHUNK * TAPS_MAX], sw[CHUNK * TAPS_MAX], rgba[4 * CHUNK * TAPS_MAX];
		unsigned kept[CHUNK];

		n = span->npix - i0 < CHUNK ? span->npix - i0 : CHUNK;
		for (i = t = 0; i < n; i++) {
			kept[i] = shade_pixel(fp, in + (size_t)(i0 + i) * NINPUTS, sx + t, sy + t,
			                      sz + t, sl + t, sw + t);
			t += kept[i];
		}
		if (t)
			fp->host->sample_many(fp->host->ctx, t, sx, sy, sz, sl, rgba);
		for (i = t = 0; i < n; i++) {
			float *o = out + 3 * (size_t)(i0 + i), sum = 0.0f;

			o[0] = o[1] = o[2] = 0.0f;
			for (k = 0; k < kept[i]; k++, t++) {
				o[0] += sw[t] * rgba[4 * t];
				o[1] += sw[t] * rgba[4 * t + 1];
				o[2] += sw[t] * rgba[4 * t + 2];
				sum += sw[t];
			}
			if (kept[i]) {
				o[0] /= sum;
				o[1] /= sum;
				o[2] /= sum;
			}
		}
	}
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
	fp->axis = values[PLACE] == PLACE_AXIS;
	fp->bend = values[BEND];
	fp->inner = (float)values[INNER];
	fp->lanes = &lanes_4;
#if defined(RF__LANES_WIDE)
	if (rf__lanes_wide())
		fp->lanes = &lanes_8;
#endif
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
	.version = "1.2",
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
