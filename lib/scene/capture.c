/*
 * Baking a probe: the scene as its capture point sees it, a cube of N x N
 * texels a face, each texel the mean of what its footprint holds.
 *
 * A texel's footprint on a wall is the quadrilateral its four corner
 * rays cut from the wall's plane.  Most texels of a room lie inside one
 * cell of its pattern: there the emission is constant, the centre ray's
 * value is the exact box filter, and one ray does what a path tracer
 * spends 256 on.  A texel whose footprint crosses an edge of the
 * emission (a grid line, a cell, a window, a mullion, two walls) takes
 * edge_samples x edge_samples rays at the centres of a grid, those of a
 * 256-sample box filter; one that may see an object (its square meets
 * the object's bounding box as projected on the face, clipped at the eye)
 * takes object_samples x object_samples full rays, each shaded.  At 256
 * texels a face the references' rooms take 1.6 rays a texel instead of
 * 256, and agree with their Cycles captures to 1e-6 inside the cells.
 *
 * Objects are shaded by the probe itself from the bounce before
 * (Unity's reflection bounces; the earlier bounces at bounce_size texels
 * a face with at most 4 x 4 and 2 x 2 samples, since they are only seen
 * blurred through the objects' lobes): the last bounce's capture, prefiltered,
 * read at the reflection box-projected from the hit as reflect-shade
 * -m none --final shades a pixel, plus the diffuse light from its
 * irradiance coefficients and the object's own emission.  Bounce 0 sees
 * objects black but for their emission.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "envmap/rgba_levels.h"
#include "probe/shape.h"
#include "surface/surface-internal.h"
#include "util/pool.h"
#include "scene/accel.h"
#include "reflect/plugin.h"

/* How a face's texel (a, b) in [-1, 1]^2 lines up with the world: the
 * direction is major + a axis_a + b axis_b (rf_cube_direction's table). */
struct face_frame {
	double major[3], axis_a[3], axis_b[3];
};

/* Where an object can be on a face, in (a, b). */
struct face_bounds {
	double a0, a1, b0, b1;
};

/* A corner ray: the wall it meets and where, in the wall's (u, v). */
struct corner {
	int face; /* -1: no wall */
	double uv[2];
};

struct capture {
	const rf_scene *s;
	const struct rf_scene_probe *probe;
	const struct rf_capture_options *o;
	double origin[3];
	double *k;           /* rf__trace_prepare for the origin */
	/* the boxes of what the capture sees: its objects, its meshes */
	struct object *visible;
	size_t nvisible;
	unsigned flags;      /* rf__trace's */
	/* lights and the sky shine on the walls too, and the sky is seen
	 * where no wall is: every texel takes full rays */
	int lit;
	struct face_frame frames[6];
	struct face_bounds *bounds; /* [face * nvisible + k]; a0 > a1: off the face */
	/* the bounce before, prefiltered, for shading objects; NULL: none;
	 * and its levels as the shading pass reads them */
	const rf_cubemap *env;
	struct rf__rgba_levels env_levels;
	enum rf_mapping mapping;
	float steps;
	float shq[3][9];
	/* a turned probe's rotation: its cube's reads of the bounce before */
	float turn[9];
	struct rf__proxy proxy; /* the probe's, its lookups in the bounces */
	size_t rows_done, rows_total; /* for the progress callback */
	size_t row_base; /* the face's first row, for capture_face_row */
	rf_cubemap *out;
	size_t n;
	size_t edge_samples, object_samples; /* of the bounce being rendered */
	struct corner *corners; /* per thread: two rows of n + 1 */
};

void
rf_capture_options_init(struct rf_capture_options *o)
{
	memset(o, 0, sizeof(*o));
	o->size = 256;
	o->bounces = 1;
	o->edge_samples = 16;
	o->object_samples = 4;
	o->bounce_size = 128;
	o->nthreads = 1;
}

/* The faces of a turned probe look along its box's axes: its cube is in
 * the box's frame, as the shading reads it. */
static void
make_frames(struct face_frame *fr, const struct rf_scene_probe *p)
{
	int f, k;

	for (f = 0; f < 6; f++) {
		float c[3], ua[3], vb[3];

		rf_cube_direction((enum rf_face)f, 0.5f, 0.5f, c);
		rf_cube_direction((enum rf_face)f, 1.0f, 0.5f, ua);
		rf_cube_direction((enum rf_face)f, 0.5f, 1.0f, vb);
		for (k = 0; k < 3; k++) {
			fr[f].major[k] = c[k];
			fr[f].axis_a[k] = ua[k] - c[k];
			fr[f].axis_b[k] = vb[k] - c[k];
		}
		if (p->rotated) {
			rf__mat3_mul(p->rotation, fr[f].major, fr[f].major);
			rf__mat3_mul(p->rotation, fr[f].axis_a, fr[f].axis_a);
			rf__mat3_mul(p->rotation, fr[f].axis_b, fr[f].axis_b);
		}
	}
}

/* Adds point r (relative to the eye, in front of the face) to the bounds. */
static void
grow(const struct face_frame *fr, const double r[3], struct face_bounds *fb)
{
	const double z = rf__dot(r, fr->major);
	const double a = rf__dot(r, fr->axis_a) / z, b = rf__dot(r, fr->axis_b) / z;

	fb->a0 = a < fb->a0 ? a : fb->a0;
	fb->a1 = a > fb->a1 ? a : fb->a1;
	fb->b0 = b < fb->b0 ? b : fb->b0;
	fb->b1 = b > fb->b1 ? b : fb->b1;
}

/* The projection on a face of an object's bounding box clipped to the
 * half-space in front of the eye: its corners there and where its edges
 * cross the clipping plane are the vertices of the clipped box. */
static void
object_face_bounds(const struct face_frame *fr, const struct object *ob, const double o[3],
                   struct face_bounds *fb)
{
	const double eps = 1e-9;
	double rel[8][3], z[8];
	int c, e, i, inside = 1;

	fb->a0 = fb->b0 = INFINITY;
	fb->a1 = fb->b1 = -INFINITY;
	for (i = 0; i < 3; i++)
		inside &= o[i] >= ob->min[i] && o[i] <= ob->max[i];
	if (inside) {
		/* the eye in the box: it may be seen anywhere */
		fb->a0 = fb->b0 = -INFINITY;
		fb->a1 = fb->b1 = INFINITY;
		return;
	}
	for (c = 0; c < 8; c++) {
		for (i = 0; i < 3; i++)
			rel[c][i] = ((c >> i) & 1 ? ob->max[i] : ob->min[i]) - o[i];
		z[c] = rf__dot(rel[c], fr->major);
		if (z[c] > eps)
			grow(fr, rel[c], fb);
	}
	for (c = 0; c < 8; c++)
		for (e = 0; e < 3; e++) {
			const int d = c | (1 << e);
			double t, p[3];

			if (d == c || (z[c] > eps) == (z[d] > eps))
				continue;
			/* the edge c-d crosses z = eps */
			t = (eps - z[c]) / (z[d] - z[c]);
			for (i = 0; i < 3; i++)
				p[i] = rel[c][i] + t * (rel[d][i] - rel[c][i]);
			/* just in front, against rounding */
			for (i = 0; i < 3; i++)
				p[i] += 2 * eps * fr->major[i];
			grow(fr, p, fb);
		}
}

/* The wall a ray from the eye leaves the room by, and where; -1 without
 * a room. */
static int
wall_hit(const struct capture *c, const double d[3], double uv[2])
{
	return rf__room_exit(c->s, c->origin, d, uv);
}

static void
texel_dir(const struct capture *c, enum rf_face f, size_t n, double i, double j, double d[3])
{
	float df[3];
	double len;

	rf_cube_direction(f, (float)(i / (double)n), (float)(j / (double)n), df);
	len = sqrt((double)df[0] * df[0] + (double)df[1] * df[1] + (double)df[2] * df[2]);
	d[0] = df[0] / len;
	d[1] = df[1] / len;
	d[2] = df[2] / len;
	if (c->probe->rotated)
		rf__mat3_mul(c->probe->rotation, d, d);
}

/* The mean of ns x ns samples of texel (i, j) of face f, all on wall
 * `wall`: each sample's point on the wall's plane straight from the
 * face's (a, b), without a unit direction or a slab test. */
/* The walls' chunk for the first n of us, vs (the rest zeroed: every
 * entry is read), summed into acc in order. */
static void
wall_chunk(const rf_scene *s, int wall, float *us, float *vs, size_t n,
           float rgb[][3], double acc[3])
{
	size_t q;
	int x;

	for (q = n; q < RF__EMIT_CHUNK; q++)
		us[q] = vs[q] = 0.0f;
	rf__wall_emission_chunk(s, wall, us, vs, n, rgb);
	for (q = 0; q < n; q++)
		for (x = 0; x < 3; x++)
			acc[x] += rgb[q][x];
}

static void
wall_samples(const struct capture *c, int f, size_t i, size_t j, int wall, size_t ns,
             float out[3])
{
	const struct face_frame *fr = &c->frames[f];
	const struct rf_scene_probe *room = &c->s->probes[0];
	const int k = wall / 2;
	double major[3], axis_a[3], axis_b[3], origin[3];
	double plane;
	const double step = 2.0 / ((double)c->n * (double)ns);
	const double a0 = 2.0 * (double)i / (double)c->n - 1.0 + 0.5 * step;
	const double b0 = 2.0 * (double)j / (double)c->n - 1.0 + 0.5 * step;
	/* the wall's (u, v) are two of the point's axes: (z, y), (x, z) or
	 * (x, y), as rf__wall_uv has them */
	const int ku = k == 0 ? 2 : 0, kv = k == 1 ? 2 : 1;
	float us[RF__EMIT_CHUNK], vs[RF__EMIT_CHUNK], rgb[RF__EMIT_CHUNK][3];
	double acc[3] = { 0, 0, 0 };
	size_t sa, sb, q = 0;
	int x;

	/* the face's grid in the room's frame, where the wall is a plane of
	 * one axis */
	for (x = 0; x < 3; x++) {
		major[x] = fr->major[x];
		axis_a[x] = fr->axis_a[x];
		axis_b[x] = fr->axis_b[x];
		origin[x] = c->origin[x];
	}
	if (c->s->room_turned) {
		rf__room_dir_in(c->s, major, major);
		rf__room_dir_in(c->s, axis_a, axis_a);
		rf__room_dir_in(c->s, axis_b, axis_b);
		rf__room_point_in(c->s, origin, origin);
	}
	plane = (wall & 1 ? room->box_min[k] : room->box_max[k]) - origin[k];
	/* the grid's points row after row, read by the walls' vector code a
	 * chunk at a time (and the last, part full) */
	for (sb = 0; sb < ns; sb++) {
		const double b = b0 + (double)sb * step;

		for (sa = 0; sa < ns; sa++) {
			const double a = a0 + (double)sa * step;
			double d[3], t;

			for (x = 0; x < 3; x++)
				d[x] = major[x] + a * axis_a[x] + b * axis_b[x];
			t = plane / d[k];
			us[q] = (float)(origin[ku] + t * d[ku]);
			vs[q] = (float)(origin[kv] + t * d[kv]);
			if (++q == RF__EMIT_CHUNK || (sb == ns - 1 && sa == ns - 1)) {
				wall_chunk(c->s, wall, us, vs, q, rgb, acc);
				q = 0;
			}
		}
	}
	for (x = 0; x < 3; x++)
		out[x] = (float)(acc[x] / (double)(ns * ns));
}

/* Does anything the wall emits change inside [u0, u1] x [v0, v1]? */
static int
wall_varies(const rf_scene *s, int face, const double lo[2], const double hi[2])
{
	const struct emission *e = rf__wall_emission_of(s, face);
	size_t i;
	int k;

	for (i = 0; i < s->nwindows; i++) {
		const struct window *w = &s->windows[i];
		int overlaps = 1, within = 1;

		if (w->face != face)
			continue;
		for (k = 0; k < 2; k++) {
			overlaps &= lo[k] < w->max[k] && hi[k] > w->min[k];
			within &= lo[k] > w->min[k] && hi[k] < w->max[k];
		}
		if (overlaps && !within)
			return 1;
		if (within) {
			/* inside the window: only its mullions vary */
			for (k = 0; k < 2 && w->mullion > 0; k++) {
				const double m = 0.5 * (w->min[k] + w->max[k]);

				if (lo[k] < m + 0.5 * w->mullion && hi[k] > m - 0.5 * w->mullion)
					return 1;
			}
			return 0;
		}
	}
	if (e->kind == EMIT_IMAGE)
		return 1;
	if (e->kind != EMIT_PATTERN)
		return 0;
	for (k = 0; k < 2; k++) {
		const struct pattern *pt = &s->pattern;
		/* edges at k c +- w/2 (lines), or at k c without lines */
		const double offs[2] = { 0.5 * pt->line_width, -0.5 * pt->line_width };
		int m;

		for (m = 0; m < (pt->line_width > 0 ? 2 : 1); m++) {
			double first = ceil((lo[k] - offs[m]) / pt->cell) * pt->cell + offs[m];

			if (first <= hi[k])
				return 1;
		}
	}
	return 0;
}

/* An object's hit as the probe sees it, from the bounce before. */
static void
shade_object(const struct capture *c, const struct rf_hit *h, const double d[3],
             float rgb[3])
{
	float n[3], v[3], r[3], dir[3], p[3], spec[3], f0[3], w[3], e[3], t, reach, lod, nv;
	const float metal = h->metallic;
	int k;

	for (k = 0; k < 3; k++) {
		n[k] = (float)h->N[k];
		v[k] = (float)-d[k];
		p[k] = (float)h->P[k];
	}
	nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
	for (k = 0; k < 3; k++)
		dir[k] = r[k] = 2.0f * nv * n[k] - v[k];
	if (c->probe->box_projection && rf__proxy_exit(&c->proxy, p, r, &t) == 0)
		rf__lookup_from_hit(&c->proxy.box, p, r, t, dir, &reach);
	lod = rf_roughness_to_lod(c->mapping, c->steps, h->roughness);
	{
		/* the shading pass's own read of the levels (reflect-shade -m
		 * none): twice as fast as rf_cubemap_sample */
		const struct rf__lod l = rf__rgba_levels_lod(&c->env_levels, lod);
		rf__v4 q;

		if (c->probe->rotated)
			rf__turn_in(c->turn, dir[0], dir[1], dir[2], dir);
		q = rf__rgba_levels_fetch(dir, &l);

		spec[0] = q[0];
		spec[1] = q[1];
		spec[2] = q[2];
	}
	rf__surface_f0(h->albedo, metal, f0);
	rf__surface_split_sum(f0, nv, h->roughness, 0, w);
	if (c->probe->rotated)
		rf__turn_in(c->turn, n[0], n[1], n[2], n);
	rf__surface_diffuse(c->shq, n, h->albedo, metal, e);
	for (k = 0; k < 3; k++)
		rgb[k] = spec[k] * w[k] + e[k];
}

/* What a full ray that met h along d brings back: its emission, and an
 * object's shading. */
static void
full_ray_colour(const struct capture *c, const struct rf_hit *h, const double d[3],
                float rgb[3])
{
	float em[3];
	int k;

	rf__radiance(c->s, h, em);
	if (h->objid >= 1 && c->env) {
		shade_object(c, h, d, rgb);
		for (k = 0; k < 3; k++)
			rgb[k] += em[k];
	} else {
		for (k = 0; k < 3; k++)
			rgb[k] = em[k];
	}
}

/* A texel that may see an object: no x no full rays, eight at a time
 * through rf__trace8 (the hits of one by one), summed in their order. */
static void
object_texel(const struct capture *c, enum rf_face f, size_t i, size_t j, size_t no,
             float out[3])
{
	const size_t total = no * no;
	double acc[3] = { 0, 0, 0 }, dirs[8][3], invs[8][3];
	const double *d[8], *inv[8];
	unsigned flags[8];
	struct rf_hit h[8];
	size_t s0, sa, sb;
	int k, m, n;

	for (s0 = 0; s0 < total; s0 += 8) {
		n = total - s0 < 8 ? (int)(total - s0) : 8;
		for (m = 0; m < n; m++) {
			sa = (s0 + (size_t)m) % no;
			sb = (s0 + (size_t)m) / no;
			texel_dir(c, f, c->n, (double)i + ((double)sa + 0.5) / (double)no,
			          (double)j + ((double)sb + 0.5) / (double)no, dirs[m]);
			for (k = 0; k < 3; k++)
				invs[m][k] = 1.0 / dirs[m][k];
			d[m] = dirs[m];
			inv[m] = invs[m];
			flags[m] = c->flags;
		}
		rf__trace8(c->s, c->origin, c->k, n, d, inv, flags, h);
		for (m = 0; m < n; m++) {
			float rgb[3];

			full_ray_colour(c, &h[m], d[m], rgb);
			for (k = 0; k < 3; k++)
				acc[k] += rgb[k];
		}
	}
	for (k = 0; k < 3; k++)
		out[k] = (float)(acc[k] / (double)(no * no));
}

static int
texel_meets_object(const struct capture *c, int f, double a0, double a1, double b0,
                   double b1)
{
	const struct face_bounds *fb = c->bounds + (size_t)f * c->nvisible;
	size_t k;

	for (k = 0; k < c->nvisible; k++)
		if (fb[k].a0 <= a1 && fb[k].a1 >= a0 && fb[k].b0 <= b1 && fb[k].b1 >= b0)
			return 1;
	return 0;
}

/* Row j of face f: task f n + j. */
static void
capture_row(void *arg, size_t task, int thread)
{
	const struct capture *c = arg;
	const size_t n = c->n, j = task % n;
	const enum rf_face f = (enum rf_face)(task / n);
	struct corner *top = c->corners + (size_t)thread * 2 * (n + 1), *bottom = top + n + 1;
	size_t i, r, sa, sb, ne = c->edge_samples, no = c->object_samples;
	double d[3];

	for (r = 0; r < 2; r++)
		for (i = 0; i <= n; i++) {
			struct corner *cn = (r ? bottom : top) + i;

			texel_dir(c, f, n, (double)i, (double)(j + r), d);
			cn->face = wall_hit(c, d, cn->uv);
		}
	for (i = 0; i < n; i++) {
		const double a0 = 2.0 * (double)i / (double)n - 1.0, a1 = 2.0 * (double)(i + 1) / (double)n - 1.0;
		const double b0 = 2.0 * (double)j / (double)n - 1.0, b1 = 2.0 * (double)(j + 1) / (double)n - 1.0;
		const struct corner *q[4] = { &top[i], &top[i + 1], &bottom[i], &bottom[i + 1] };
		float *out = rf_cubemap_texel(c->out, 0, f, i, j), rgb[3];
		double acc[3] = { 0, 0, 0 }, lo[2], hi[2], uv[2];
		size_t m;
		int k, face = q[0]->face, same = face >= 0;

		if (c->lit || texel_meets_object(c, (int)f, a0, a1, b0, b1)) {
			object_texel(c, f, i, j, no, out);
			continue;
		}
		for (m = 1; m < 4; m++)
			same &= q[m]->face == face;
		if (same) {
			for (k = 0; k < 2; k++) {
				lo[k] = hi[k] = q[0]->uv[k];
				for (m = 1; m < 4; m++) {
					lo[k] = q[m]->uv[k] < lo[k] ? q[m]->uv[k] : lo[k];
					hi[k] = q[m]->uv[k] > hi[k] ? q[m]->uv[k] : hi[k];
				}
			}
			if (!wall_varies(c->s, face, lo, hi)) {
				/* one value over the whole footprint */
				texel_dir(c, f, n, (double)i + 0.5, (double)j + 0.5, d);
				if (wall_hit(c, d, uv) == face) {
					rf__wall_emission(c->s, face, uv, out);
					continue;
				}
			}
			/* the footprint lies on the wall: every sample does */
			wall_samples(c, (int)f, i, j, face, ne, out);
			continue;
		} else if (face < 0 && q[1]->face < 0 && q[2]->face < 0 && q[3]->face < 0) {
			out[0] = out[1] = out[2] = 0.0f;
			continue;
		}
		for (sb = 0; sb < ne; sb++)
			for (sa = 0; sa < ne; sa++) {
				int g;

				texel_dir(c, f, n, (double)i + ((double)sa + 0.5) / (double)ne,
				          (double)j + ((double)sb + 0.5) / (double)ne, d);
				if ((g = wall_hit(c, d, uv)) < 0)
					continue;
				rf__wall_emission(c->s, g, uv, rgb);
				for (k = 0; k < 3; k++)
					acc[k] += rgb[k];
			}
		for (k = 0; k < 3; k++)
			out[k] = (float)(acc[k] / (double)(ne * ne));
	}
}

/* Row task of the face that render() runs now. */
static void
capture_face_row(void *arg, size_t task, int thread)
{
	const struct capture *c = arg;

	capture_row(arg, c->row_base + task, thread);
}

/* One bounce at face size n, objects shaded from env (NULL: black). */
static int
render(struct capture *c, size_t n, struct rf__pool *pool, rf_cubemap **cube)
{
	size_t t, f;
	int rc;

	if ((rc = rf_cubemap_create(cube, n, 1)) < 0)
		return rc;
	c->out = *cube;
	c->n = n;
	c->corners = malloc((size_t)c->o->nthreads * 2 * (n + 1) * sizeof(*c->corners));
	if (!c->corners) {
		rf_cubemap_destroy(*cube);
		*cube = NULL;
		return RF_ENOMEM;
	}
	/* a face at a time, so that progress is told between them (the rows
	 * do not depend on how they are batched) */
	for (f = 0; f < 6; f++) {
		c->row_base = f * n;
		if (pool)
			rf__pool_run(pool, n, capture_face_row, c);
		else
			for (t = f * n; t < (f + 1) * n; t++)
				capture_row(c, t, 0);
		c->rows_done += n;
		if (c->o->progress)
			c->o->progress(c->o->progress_arg, c->rows_done, c->rows_total);
	}
	free(c->corners);
	c->corners = NULL;
	rf_cubemap_seal_level(*cube, 0);
	return 0;
}

/* The bounce's capture prefiltered, and its irradiance, for the next. */
static int
light_from(struct capture *c, const rf_cubemap *cube, rf_cubemap **chain, char *err,
           size_t errlen)
{
	struct rf_prefilter_options po;
	float sh[27];
	int rc;

	if ((rc = rf_cubemap_create(chain, rf_cubemap_size(cube), 0)) < 0)
		return rc;
	rf_prefilter_defaults(&po);
	po.nthreads = c->o->nthreads;
	if ((rc = rf_prefilter(cube, *chain, &po, err, errlen)) < 0)
		return rc;
	rf__rgba_levels_destroy(&c->env_levels);
	if ((rc = rf__rgba_levels_from_cube(&c->env_levels, *chain)) < 0)
		return rc;
	c->env = *chain;
	c->mapping = po.mapping;
	c->steps = (float)(rf_cubemap_levels(*chain) - 1);
	rf_cubemap_sh9(cube, 0, sh);
	rf__sh9_quadratic(sh, c->shq);
	return 0;
}

int
rf_scene_capture(const rf_scene *s, size_t probe, const struct rf_capture_options *o,
                 rf_cubemap **cube, char *err, size_t errlen)
{
	struct capture c;
	struct rf_probe pr;
	struct rf__pool *pool = NULL;
	rf_cubemap *prev = NULL, *chain = NULL, *cur = NULL;
	size_t i, f;
	int b, rc = 0;

	*cube = NULL;
	if (probe >= s->nprobes) {
		rf__format(err, errlen, "the scene has %zu probe%s, not %zu", s->nprobes,
		           s->nprobes == 1 ? "" : "s", probe + 1);
		return RF_EINVAL;
	}
	if (o->size < 1 || o->size > 8192 || o->bounces < 0 || o->bounces > 16 ||
	    o->edge_samples < 1 || o->edge_samples > 64 || o->object_samples < 1 ||
	    o->object_samples > 64 || o->bounce_size < 1 || o->nthreads < 1) {
		rf__format(err, errlen, "capture options out of range");
		return RF_EINVAL;
	}
	memset(&c, 0, sizeof(c));
	c.s = s;
	c.probe = &s->probes[probe];
	for (i = 0; i < 9; i++)
		c.turn[i] = (float)c.probe->rotation[i];
	c.o = o;
	for (i = 0; i < 3; i++)
		c.origin[i] = c.probe->center[i];
	rf__scene_probe_shape(c.probe, &pr);
	c.proxy = rf__proxy_of_probe(&pr);
	make_frames(c.frames, c.probe);
	c.k = calloc(s->nobjects + 1, RF__ORIGIN_STRIDE * sizeof(double));
	c.visible = calloc(s->nobjects + s->nmeshes + 1, sizeof(*c.visible));
	c.bounds = calloc(6 * (s->nobjects + s->nmeshes + 1), sizeof(*c.bounds));
	if (!c.k || !c.visible || !c.bounds) {
		rc = RF_ENOMEM;
		goto out;
	}
	if ((s->nobjects || s->nmeshes) && !rf__accel_get(s, err, errlen)) {
		rc = RF_ENOMEM;
		goto out;
	}
	rf__trace_prepare(s, c.origin, c.k);
	c.flags = o->hide_reflective ? RF__TRACE_SKIP_REFLECTIVE : 0;
	c.lit = s->nlights > 0 || s->sky;
	for (i = 0; i < s->nobjects; i++)
		if (!(o->hide_reflective && s->objects[i].mat.mask > 0.0f))
			c.visible[c.nvisible++] = s->objects[i];
	for (i = 0; i < s->nmeshes; i++) {
		/* a mesh is seen inside its box, a float's rounding wider */
		struct object *box = &c.visible[c.nvisible++];
		int j;

		for (j = 0; j < 3; j++) {
			const double pad = 1e-6 * (1.0 + fmax(fabs(s->meshes[i].bounds[j]),
			                                      fabs(s->meshes[i].bounds[j + 3])));

			box->min[j] = s->meshes[i].bounds[j] - pad;
			box->max[j] = s->meshes[i].bounds[j + 3] + pad;
		}
	}
	for (f = 0; f < 6; f++)
		for (i = 0; i < c.nvisible; i++)
			object_face_bounds(&c.frames[f], &c.visible[i], c.origin,
			                   &c.bounds[f * c.nvisible + i]);
	if (o->nthreads > 1)
		rf__pool_create(&pool, o->nthreads);
	/* Without objects to light, bounces change nothing. */
	for (b = c.nvisible ? 0 : o->bounces; b <= o->bounces; b++)
		c.rows_total += 6 * (b < o->bounces && o->bounce_size < o->size ? o->bounce_size
		                                                                 : o->size);
	if (o->progress)
		o->progress(o->progress_arg, 0, c.rows_total);
	for (b = c.nvisible ? 0 : o->bounces; b <= o->bounces; b++) {
		const size_t n = b < o->bounces && o->bounce_size < o->size ? o->bounce_size
		                                                            : o->size;

		/* An earlier bounce is seen only through the objects' lobes,
		 * prefiltered: a few samples a texel resolve it. */
		c.edge_samples = b < o->bounces && o->edge_samples > 4 ? 4 : o->edge_samples;
		c.object_samples = b < o->bounces && o->object_samples > 2 ? 2 : o->object_samples;

		if ((rc = render(&c, n, pool, &cur)) < 0)
			break;
		if (b == o->bounces)
			break;
		rf_cubemap_destroy(chain);
		chain = NULL;
		if ((rc = light_from(&c, cur, &chain, err, errlen)) < 0)
			break;
		rf_cubemap_destroy(prev);
		prev = cur;
		cur = NULL;
	}
	if (rc == 0) {
		*cube = cur;
		cur = NULL;
	}
out:
	rf__pool_destroy(pool);
	rf_cubemap_destroy(cur);
	rf_cubemap_destroy(prev);
	rf_cubemap_destroy(chain);
	rf__rgba_levels_destroy(&c.env_levels);
	free(c.k);
	free(c.visible);
	free(c.bounds);
	if (rc == RF_ENOMEM)
		rf__format(err, errlen, "%s", rf_strerror(rc));
	return rc;
}
