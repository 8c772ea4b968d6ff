/* The split-sum environment BRDF of GGX: the DFG table. */
#include <math.h>
#include <stdint.h>

#include "surface/dfg-integrate.h"
#include "reflect/surface.h"

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

/* The table, integrated when reflect was built (dfg-gen.c): nothing to
 * compute at run time, where the first lookup once cost some 30 ms of
 * every process that used it. */
#include "surface/dfg-table.h"

const float *
rf_dfg_table(size_t *size)
{
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
