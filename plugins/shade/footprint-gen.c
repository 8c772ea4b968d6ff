/*
 * footprint-gen: writes the lobe table of the footprint mode as a C
 * header, measured on the GGX lobe itself when reflect is built, so the
 * model carries no constant that was fitted to anything.
 *
 *	footprint-gen >footprint-table.h
 *
 * An entry is the reflected lobe of white GGX (the exact estimator's
 * weight G2 / G1(V), height-correlated, over the visible normals) for a
 * view at angle theta_v from the normal and a perceptual roughness, in
 * the frame where N is z and V lies in the xz plane toward +x, so the
 * mirror direction R is at in-plane angle theta_v on the -x side.  Of the
 * lobe's directions L it records, weighted:
 *   - the in-plane angle phi = atan2(-L.x, L.z) at its quartiles: the
 *     median gives the lobe's centre D (stored as phi50 - theta_v, the
 *     bend away from R), phi50 - phi25 and phi75 - phi50 its widths
 *     toward the normal and toward the horizon;
 *   - the median of |psi|, psi = atan2(L.y, L.D), the width across.
 * A second table, footprint_shares, cuts each of those lobes by phi into
 * n = 1 to 4 shares of equal weight, for the mode's place=shares: each
 * share's median phi, half the distance between its quartiles in phi,
 * and the median of its |psi'|, psi' = atan2(L.y, |L in the xz plane|)
 * (the across angle of the mode's lobe_direction()), in radians.
 * Quartiles and medians, not moments: GGX's tails leave the second
 * moment to the hemisphere's edge, the quartiles stay where the lobe is.
 * Widths are kept in the units of the prefilter's own kernel, L(l)
 * weighted by D(h) (n.l) about N = V = R (lib/envmap/prefilter.c): the
 * row theta_v = 0 is that kernel's width at each roughness (its
 * quartile, in-plane and across alike), and every other row is the
 * lobe's widths times kernel / lobe at theta_v = 0 for its roughness.
 * The two differ only by G(L) against n.l, a few per cent at r = 1; so
 * kept, the N = V lobe read through the box is exactly what the
 * prefilter made, and a lobe twice as wide as that reads where the
 * prefilter's kernel is twice as wide.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "maths/ggx.h"
#include "footprint-shape.h"

#define SAMPLES 4096


struct sample {
	double phi, w, l[3];
};

static int
by_phi(const void *a, const void *b)
{
	double x = ((const struct sample *)a)->phi, y = ((const struct sample *)b)->phi;

	return (x > y) - (x < y);
}

static int
by_psi(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;

	return (x > y) - (x < y);
}

/* The n samples sorted by angle, as the pairs (phi, w) quantile reads. */
static void
sort_by_phi(struct sample *s, size_t n, double *vw)
{
	size_t k;

	qsort(s, n, sizeof(*s), by_phi);
	for (k = 0; k < n; k++) {
		vw[2 * k] = s[k].phi;
		vw[2 * k + 1] = s[k].w;
	}
}

/* The value where the cumulative weight of the sorted values (their
 * weights alongside, pairs of doubles) reaches share of the total. */
static double
quantile(const double *vw, size_t n, double total, double share)
{
	double want = share * total, sum = 0.0;
	size_t k;

	for (k = 0; k < n; k++) {
		double next = sum + vw[2 * k + 1];

		if (next >= want) {
			double t = vw[2 * k + 1] > 0.0 ? (want - sum) / vw[2 * k + 1] : 0.0;
			double lo = k ? vw[2 * (k - 1)] : vw[0];

			return lo + t * (vw[2 * k] - lo);
		}
		sum = next;
	}
	return n ? vw[2 * (n - 1)] : 0.0;
}

/* The prefilter's kernel at perceptual roughness pr: microfacet normals
 * h of density D(h) (n.h), each l = 2 (n.h) h - n weighted by n.l; its
 * in-plane quartile (by symmetry, the across one too). */
static double
measure_kernel(double pr, struct sample *s, double *vw)
{
	double alpha = pr * pr, total = 0.0;
	size_t k, n = 0;

	for (k = 0; k < SAMPLES; k++) {
		double u0 = (k + 0.5) / SAMPLES, u1 = rf__ggx_radical_inverse((uint32_t)k);
		double t2 = alpha * alpha * u0 / (1.0 - u0), ch = 1.0 / sqrt(1.0 + t2);
		double sh = sqrt(1.0 - ch * ch), a = 2.0 * M_PI * u1, h[3], l[3];

		h[0] = sh * cos(a);
		h[1] = sh * sin(a);
		h[2] = ch;
		l[0] = 2.0 * ch * h[0];
		l[1] = 2.0 * ch * h[1];
		l[2] = 2.0 * ch * h[2] - 1.0;
		if (!(l[2] > 0.0))
			continue;
		s[n].w = l[2];
		s[n].phi = fabs(atan2(-l[0], l[2]));
		total += s[n].w;
		n++;
	}
	sort_by_phi(s, n, vw);
	return quantile(vw, n, total, 0.5);
}

/* The reflected lobe for a view at theta_v and perceptual roughness pr,
 * as samples sorted by in-plane angle (and as the pairs quantile reads,
 * in vw); their number, and their total weight in *total. */
static size_t
draw_lobe(double theta_v, double pr, struct sample *s, double *vw, double *total)
{
	double alpha = pr * pr, a2 = alpha * alpha, mu = cos(theta_v), v[3], lv;
	struct rf__ggx_vndf g;
	size_t k, n = 0;

	*total = 0.0;
	if (mu < 1e-3)
		mu = 1e-3;
	v[0] = sqrt(1.0 - mu * mu);
	v[1] = 0.0;
	v[2] = mu;
	lv = rf__ggx_lambda(a2, mu);
	rf__ggx_vndf_init(&g, v, alpha);
	for (k = 0; k < SAMPLES; k++) {
		double h[3], vdh, *l = s[n].l;

		rf__ggx_vndf_normal(&g, (k + 0.5) / SAMPLES, rf__ggx_radical_inverse((uint32_t)k), h);
		vdh = v[0] * h[0] + v[1] * h[1] + v[2] * h[2];
		l[0] = 2.0 * vdh * h[0] - v[0];
		l[1] = 2.0 * vdh * h[1] - v[1];
		l[2] = 2.0 * vdh * h[2] - v[2];
		if (!(l[2] > 0.0))
			continue; /* below the surface (or no normal): no light */
		s[n].w = (1.0 + lv) / (1.0 + lv + rf__ggx_lambda(a2, l[2]));
		s[n].phi = atan2(-l[0], l[2]);
		*total += s[n].w;
		n++;
	}
	sort_by_phi(s, n, vw);
	return n;
}

/* The lobe for a view at theta_v and perceptual roughness pr. */
static void
measure(double theta_v, double pr, struct sample *s, double *vw, double out[4])
{
	double total, phi25, phi50, phi75, d[3];
	size_t k, n;

	n = draw_lobe(theta_v, pr, s, vw, &total);
	phi25 = quantile(vw, n, total, 0.25);
	phi50 = quantile(vw, n, total, 0.5);
	phi75 = quantile(vw, n, total, 0.75);
	d[0] = -sin(phi50);
	d[1] = 0.0;
	d[2] = cos(phi50);
	for (k = 0; k < n; k++) {
		const double *l = s[k].l;

		vw[2 * k] = fabs(atan2(l[1], l[0] * d[0] + l[2] * d[2]));
		vw[2 * k + 1] = s[k].w;
	}
	qsort(vw, n, 2 * sizeof(double), by_psi);
	out[0] = phi50 - theta_v;
	out[1] = phi50 - phi25;
	out[2] = phi75 - phi50;
	out[3] = quantile(vw, n, total, 0.5);
}

/* The lobe for a view at theta_v and perceptual roughness pr cut into
 * n shares of equal weight by in-plane angle, as the taps of the mode's
 * box path read it: for share t, out[t] gets its median phi, half the
 * distance between its quartiles in phi, and the median of its |psi|,
 * psi = atan2(L.y, |L in the plane|) (the across angle of the mode's
 * lobe_direction(), whose in-plane angle is phi). */
static void
measure_shares(double theta_v, double pr, unsigned n, struct sample *s, double *vw,
               double *psi, double out[][3])
{
	double total;
	size_t k, m = draw_lobe(theta_v, pr, s, vw, &total), first = 0;
	unsigned t;

	for (t = 0; t < n; t++) {
		double q25 = quantile(vw, m, total, (t + 0.25) / n);
		double q75 = quantile(vw, m, total, (t + 0.75) / n);
		double end = (t + 1.0) / n * total, sum = 0.0, share = 0.0;
		size_t last, j = 0;

		/* the share: the samples whose weight so far is under its end */
		for (k = 0; k < first; k++)
			sum += s[k].w;
		for (last = first; last < m && (t + 1 == n || sum + 0.5 * s[last].w < end); last++)
			sum += s[last].w;
		for (k = first; k < last; k++, j++) {
			const double *l = s[k].l;

			psi[2 * j] = fabs(atan2(l[1], sqrt(l[0] * l[0] + l[2] * l[2])));
			psi[2 * j + 1] = s[k].w;
			share += s[k].w;
		}
		qsort(psi, j, 2 * sizeof(double), by_psi);
		out[t][0] = quantile(vw, m, total, (t + 0.5) / n);
		out[t][1] = 0.5 * (q75 - q25);
		out[t][2] = quantile(psi, j, share, 0.5);
		first = last;
	}
}

int
main(void)
{
	static struct sample s[SAMPLES];
	static double vw[2 * SAMPLES], psi[2 * SAMPLES];
	static double kernel[FOOTPRINT_ROUGHNESSES], scale[FOOTPRINT_ROUGHNESSES];
	unsigned i, j, k;

	for (j = 1; j < FOOTPRINT_ROUGHNESSES; j++) {
		double pr = (double)j / (FOOTPRINT_ROUGHNESSES - 1), e[4];

		kernel[j] = measure_kernel(pr, s, vw);
		measure(0.0, pr, s, vw, e);
		scale[j] = kernel[j] / ((e[1] + e[2] + e[3]) / 3.0);
		/* footprint_kernel_roughness() finds a kernel as wide as w by halves */
		if (!((float)kernel[j] > (j > 1 ? (float)kernel[j - 1] : 0.0f))) {
			fprintf(stderr, "footprint-gen: the prefilter's kernel at roughness %g is "
			        "no wider than at %g (%g, %g); footprint_kernel_roughness() "
			        "needs them to grow\n", pr, (double)(j - 1) / (FOOTPRINT_ROUGHNESSES - 1),
			        kernel[j], j > 1 ? kernel[j - 1] : 0.0);
			return 1;
		}
	}
	printf("/* Made by footprint-gen (%d x %d entries, %d visible normals each): "
	       "do not edit. */\n", FOOTPRINT_VIEWS, FOOTPRINT_ROUGHNESSES, SAMPLES);
	printf("static const float footprint_table[%d][%d][4] = {\n", FOOTPRINT_VIEWS,
	       FOOTPRINT_ROUGHNESSES);
	for (i = 0; i < FOOTPRINT_VIEWS; i++) {
		double theta_v = footprint_view_angle(i);

		printf("{\n");
		for (j = 0; j < FOOTPRINT_ROUGHNESSES; j++) {
			double pr = (double)j / (FOOTPRINT_ROUGHNESSES - 1), e[4] = { 0, 0, 0, 0 };

			if (j > 0 && i == 0) {
				e[1] = e[2] = e[3] = kernel[j]; /* round, no bend */
			} else if (j > 0) {
				measure(theta_v, pr, s, vw, e);
				for (k = 1; k < 4; k++)
					e[k] *= scale[j];
			}
			printf("\t{");
			for (k = 0; k < 4; k++)
				printf(" %af,", (double)(float)e[k]);
			printf(" },\n");
		}
		printf("},\n");
	}
	printf("};\n");
	printf("static const float footprint_shares[%d][%d][%d][3] = {\n", FOOTPRINT_VIEWS,
	       FOOTPRINT_ROUGHNESSES, FOOTPRINT_SHARES);
	for (i = 0; i < FOOTPRINT_VIEWS; i++) {
		double theta_v = footprint_view_angle(i);

		printf("{\n");
		for (j = 0; j < FOOTPRINT_ROUGHNESSES; j++) {
			double pr = (double)j / (FOOTPRINT_ROUGHNESSES - 1), sh[FOOTPRINT_SHARES][3];
			unsigned n, t;

			for (n = 1; n <= FOOTPRINT_TAPS_MAX; n++) {
				double *row = sh[footprint_first_share(n)];

				if (j == 0) {
					for (t = 0; t < n; t++) {
						row[3 * t] = theta_v; /* the mirror */
						row[3 * t + 1] = row[3 * t + 2] = 0.0;
					}
				} else {
					measure_shares(theta_v, pr, n, s, vw, psi,
					               (double (*)[3])row);
				}
				for (t = 0; i == 0 && t < n / 2; t++) {
					/* head on the lobe is round: its shares
					 * mirror each other, to the bit */
					double *a = row + 3 * t, *b = row + 3 * (n - 1 - t);
					double phi = 0.5 * (a[0] - b[0]);

					a[0] = phi;
					b[0] = -phi;
					a[1] = b[1] = 0.5 * (a[1] + b[1]);
					a[2] = b[2] = 0.5 * (a[2] + b[2]);
				}
				if (i == 0 && n % 2)
					row[3 * (n / 2)] = 0.0;
			}
			printf("\t{");
			for (k = 0; k < FOOTPRINT_SHARES; k++)
				printf(" { %af, %af, %af },", (double)(float)sh[k][0],
				       (double)(float)sh[k][1], (double)(float)sh[k][2]);
			printf(" },\n");
		}
		printf("},\n");
	}
	printf("};\n");
	return ferror(stdout) ? 1 : 0;
}
