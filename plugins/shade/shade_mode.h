/* What the shade modes share (header-only: each plugin is one
 * self-contained shared object).  A shade mode reads the material's
 * perceptual roughness and whatever geometry its model needs, and writes
 * one channel, the effective perceptual roughness in [0, 1]; the host
 * turns it into a lod with the environment's one mapping and samples. */
#ifndef REFLECT_PLUGINS_SHADE_MODE_H
#define REFLECT_PLUGINS_SHADE_MODE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "reflect/plugin.h"

#define SHADE_PARAMS_MAX 4

/* An instance: the parameter values, nothing else. */
struct shade_mode {
	double p[SHADE_PARAMS_MAX];
};

/* clamp(x, 0, 1); NaN gives 0, so no NaN leaves a mode. */
static inline double
sat(double x)
{
	return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0;
}

/* hit.dist is +inf (the point is outside the box, or the projection is
 * infinite) or NaN: there is no hit to harden toward, and every model
 * must give exactly `none` (spec Part A #3). */
static inline int
no_hit(double d)
{
	return !(d < INFINITY);
}

static inline int
shade_mode_create(const struct rf_host *host, const double *values,
                  unsigned nparams, void **state, char *err, size_t errlen)
{
	struct shade_mode *m;
	unsigned i;

	(void)host;
	if (!(m = calloc(1, sizeof(*m)))) {
		snprintf(err, errlen, "out of memory");
		return -1;
	}
	for (i = 0; i < nparams && i < SHADE_PARAMS_MAX; i++)
		m->p[i] = values[i];
	*state = m;
	return 0;
}

static inline void
shade_mode_destroy(void *state)
{
	free(state);
}

#endif
