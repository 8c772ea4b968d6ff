/* The embedded environment: the default room seen from its probe. */
#include <math.h>
#include <stdint.h>

#include "util/pool.h"
#include "reflect/envmap.h"

/* The default scene's room and probe; the G-buffer's default scene uses
 * the same numbers. */
static const float room_min[3] = { -3.0f, 0.0f, -2.0f };
static const float room_max[3] = { 3.0f, 3.0f, 2.0f };
static const float probe_centre[3] = { 0.0f, 1.5f, 0.0f };

struct window {
	int axis;       /* the wall's axis: 0 x, 1 y, 2 z */
	float side;     /* the wall's coordinate on that axis */
	float lo[2], hi[2]; /* extent on the two other axes, in order */
	float rgb[3];
};

/* Two HDR windows: a warm one on the +X wall, a cool one on the -Z wall. */
static const struct window windows[] = {
	{ 0, 3.0f, { 1.0f, -1.2f }, { 2.3f, 0.2f }, { 18.0f, 15.5f, 12.0f } },
	{ 2, -2.0f, { -1.8f, 1.1f }, { -0.4f, 2.5f }, { 10.0f, 11.5f, 14.0f } },
};

/* Base colour of each wall: +X -X +Y(ceiling) -Y(floor) +Z -Z. */
static const float wall_rgb[6][3] = {
	{ 0.80f, 0.25f, 0.20f }, /* +X red */
	{ 0.20f, 0.65f, 0.25f }, /* -X green */
	{ 0.85f, 0.85f, 0.80f }, /* ceiling off-white */
	{ 0.45f, 0.35f, 0.28f }, /* floor brown */
	{ 0.20f, 0.30f, 0.85f }, /* +Z blue */
	{ 0.85f, 0.75f, 0.20f }, /* -Z yellow */
};

#define GRID 0.5f       /* metres between grid lines */
#define LINE 0.025f     /* half width of a grid line */
#define LINE_GAIN 3.0f  /* grid lines are this much brighter than white */

static float
grid_distance(float x)
{
	float m = x / GRID - floorf(x / GRID);

	return GRID * (m < 1.0f - m ? m : 1.0f - m); /* fminf is a call */
}

void
rf_default_room_radiance(const float p[3], float rgb[3])
{
	float best = INFINITY;
	int wall = 0, axis, k, a, b;
	float checker, scale;

	/* The wall the point is on: the nearest face of the box. */
	for (axis = 0; axis < 3; axis++) {
		float dmax = fabsf(room_max[axis] - p[axis]);
		float dmin = fabsf(p[axis] - room_min[axis]);

		if (dmax < best)
			best = dmax, wall = 2 * axis;
		if (dmin < best)
			best = dmin, wall = 2 * axis + 1;
	}
	axis = wall / 2;
	a = (axis + 1) % 3;
	b = (axis + 2) % 3;
	for (k = 0; k < (int)(sizeof(windows) / sizeof(windows[0])); k++) {
		const struct window *w = &windows[k];
		float s = p[a < b ? a : b], t = p[a < b ? b : a];

		if (w->axis != axis || fabsf(p[axis] - w->side) > 1e-3f)
			continue;
		if (s >= w->lo[0] && s <= w->hi[0] && t >= w->lo[1] && t <= w->hi[1]) {
			/* Mullions split each window into four panes. */
			float ms = fabsf(s - 0.5f * (w->lo[0] + w->hi[0]));
			float mt = fabsf(t - 0.5f * (w->lo[1] + w->hi[1]));

			if (ms < 0.03f || mt < 0.03f) {
				rgb[0] = rgb[1] = rgb[2] = 0.05f;
				return;
			}
			rgb[0] = w->rgb[0];
			rgb[1] = w->rgb[1];
			rgb[2] = w->rgb[2];
			return;
		}
	}
	if (grid_distance(p[a]) < LINE || grid_distance(p[b]) < LINE) {
		rgb[0] = rgb[1] = rgb[2] = LINE_GAIN;
		return;
	}
	checker = ((int)floorf(p[a] / GRID) + (int)floorf(p[b] / GRID)) & 1 ? 1.0f : 0.7f;
	scale = 0.6f * checker;
	rgb[0] = scale * wall_rgb[wall][0];
	rgb[1] = scale * wall_rgb[wall][1];
	rgb[2] = scale * wall_rgb[wall][2];
}

void
rf_default_environment(const float dir[3], float rgb[3])
{
	float t = INFINITY, p[3];
	int i;

	for (i = 0; i < 3; i++) {
		float ti;

		if (dir[i] > 1e-12f)
			ti = (room_max[i] - probe_centre[i]) / dir[i];
		else if (dir[i] < -1e-12f)
			ti = (room_min[i] - probe_centre[i]) / dir[i];
		else
			continue;
		if (ti < t)
			t = ti;
	}
	if (!(t < INFINITY)) {
		rgb[0] = rgb[1] = rgb[2] = 0.0f;
		return;
	}
	for (i = 0; i < 3; i++)
		p[i] = probe_centre[i] + t * dir[i];
	rf_default_room_radiance(p, rgb);
}

/* Row `task` (face task / n, row task % n) of level 0. */
static void
render_row(void *arg, size_t task, int thread)
{
	enum { SUPER = 4 };
	rf_cubemap *c = arg;
	size_t n = rf_cubemap_level_size(c, 0), i, j = task % n;
	enum rf_face f = (enum rf_face)(task / n);
	int si, sj;

	(void)thread;
	for (i = 0; i < n; i++) {
		float *out = rf_cubemap_texel(c, 0, f, i, j);
		float acc[3] = { 0, 0, 0 };

		/* Supersampling keeps the grid lines from aliasing. */
		for (sj = 0; sj < SUPER; sj++)
			for (si = 0; si < SUPER; si++) {
				float d[3], rgb[3];

				rf_cube_direction(f, ((float)i + ((float)si + 0.5f) / SUPER) / (float)n,
				                  ((float)j + ((float)sj + 0.5f) / SUPER) / (float)n, d);
				rf_default_environment(d, rgb);
				acc[0] += rgb[0];
				acc[1] += rgb[1];
				acc[2] += rgb[2];
			}
		out[0] = acc[0] / (SUPER * SUPER);
		out[1] = acc[1] / (SUPER * SUPER);
		out[2] = acc[2] / (SUPER * SUPER);
	}
}

void
rf_default_environment_cube_threads(rf_cubemap *c, int nthreads)
{
	size_t n = rf_cubemap_level_size(c, 0), row;
	struct rf__pool *pool = NULL;

	/* Each texel is its own sum, so any thread count gives the same
	 * bytes; without threads to be had, the caller renders it all. */
	if (nthreads > 1 && rf__pool_create(&pool, nthreads) == 0) {
		rf__pool_run(pool, 6 * n, render_row, c);
		rf__pool_destroy(pool);
	} else {
		for (row = 0; row < 6 * n; row++)
			render_row(c, row, 0);
	}
	rf_cubemap_seal_level(c, 0);
}

void
rf_default_environment_cube(rf_cubemap *c)
{
	rf_default_environment_cube_threads(c, 1);
}
