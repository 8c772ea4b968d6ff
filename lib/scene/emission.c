/*
 * What the scene's surfaces emit: a colour, an image on a wall, or the
 * walls' procedural pattern (the path-traced references' checker with
 * grid lines), with windows over any of them.  The pattern is defined in
 * world units on each wall's plane, so a wall's radiance at a point does
 * not depend on how the wall is seen: the G-buffer, reflect-capture and
 * a path tracer agree on it.
 */
#include <math.h>

#include "scene/accel.h"

void
rf__pattern_default(struct pattern *pt)
{
	pt->cell = 1.0;
	pt->inv_cell = 1.0;
	pt->line_width = 0.08;
	pt->base = 0.3;
	pt->checker = 0.25;
	pt->line = 1.0;
	pt->line_white = 0.5;
}

int
rf__wall_face(int objid)
{
	return objid <= RF_WALL_XMAX && objid >= RF_WALL_ZMIN ? -1 - objid : -1;
}

void
rf__wall_uv(int face, const double p[3], double uv[2])
{
	switch (face / 2) {
	case 0: uv[0] = p[2]; uv[1] = p[1]; break;
	case 1: uv[0] = p[0]; uv[1] = p[2]; break;
	default: uv[0] = p[0]; uv[1] = p[1]; break;
	}
}

int
rf__room_exit(const rf_scene *s, const double o[3], const double d[3], double uv[2])
{
	const struct rf_scene_probe *room = s->nprobes ? &s->probes[0] : NULL;
	double t = INFINITY, p[3], ol[3], dl[3];
	int face = -1, i;

	if (!s->room || !room)
		return -1;
	if (s->room_turned) {
		rf__room_point_in(s, o, ol);
		rf__room_dir_in(s, d, dl);
		o = ol;
		d = dl;
	}
	for (i = 0; i < 3; i++) {
		double ti;

		if (d[i] > 0)
			ti = (room->box_max[i] - o[i]) / d[i];
		else if (d[i] < 0)
			ti = (room->box_min[i] - o[i]) / d[i];
		else
			continue;
		if (ti < t) {
			t = ti;
			face = 2 * i + (d[i] < 0);
		}
	}
	if (face < 0 || !(t >= 0.0))
		return -1;
	/* the wall's own axis is not read: the point lies on it */
	for (i = 0; i < 3; i++)
		p[i] = o[i] + t * d[i];
	rf__wall_uv(face, p, uv);
	return face;
}

const struct emission *
rf__wall_emission_of(const rf_scene *s, int face)
{
	return s->wall_em[face].kind != EMIT_NONE ? &s->wall_em[face] : &s->room_mat.em;
}

static void
set_rgb(float rgb[3], const float v[3], float k)
{
	rgb[0] = k * v[0];
	rgb[1] = k * v[1];
	rgb[2] = k * v[2];
}

/* floor of a number well inside long's range, without a libm call (the
 * tracer asks millions of times a second) */
static inline double
fast_floor(double x)
{
	double t = (double)(long)x;

	return t > x ? t - 1.0 : t;
}

/* The pattern at (u, v) with face colour c: lines over cells. */
static void
pattern_at(const struct pattern *pt, const float c[3], const double uv[2], float rgb[3])
{
	const double su = uv[0] * pt->inv_cell, sv = uv[1] * pt->inv_cell;
	const double du = fabs(su + 0.5 - fast_floor(su + 0.5) - 0.5) * pt->cell;
	const double dv = fabs(sv + 0.5 - fast_floor(sv + 0.5) - 0.5) * pt->cell;
	int k;

	if (du < 0.5 * pt->line_width || dv < 0.5 * pt->line_width) {
		for (k = 0; k < 3; k++)
			rgb[k] = (float)(pt->line * ((1.0 - pt->line_white) * c[k] + pt->line_white));
	} else {
		/* (floor(su) + floor(sv)) mod 2, for negative cells too */
		const long parity = ((long)fast_floor(su) + (long)fast_floor(sv)) & 1;
		const double level = pt->base + (parity ? pt->checker : 0.0);

		for (k = 0; k < 3; k++)
			rgb[k] = (float)(c[k] * level);
	}
}

static float
srgb_to_linear(float v)
{
	return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

/* Texel (x, y) of a repeating image, colour channels 0..2 (grey: 0). */
static void
image_texel(const struct emission *e, long x, long y, float rgb[3])
{
	const long w = (long)e->width, h = (long)e->height;
	const float *t;
	int k;

	x %= w;
	y %= h;
	if (x < 0)
		x += w;
	if (y < 0)
		y += h;
	t = e->pixels + ((size_t)y * e->width + (size_t)x) * e->nchannels;
	for (k = 0; k < 3; k++) {
		float v = t[e->nchannels >= 3 ? k : 0];

		rgb[k] = e->srgb ? srgb_to_linear(v) : v;
	}
}

/* The image at (u, v), bilinear between texel centres; its top row is at
 * the top of the wall's v. */
static void
image_at(const struct emission *e, const double uv[2], float rgb[3])
{
	const double fx = (uv[0] - e->origin[0]) / e->size[0] * (double)e->width - 0.5;
	const double fy = (1.0 - (uv[1] - e->origin[1]) / e->size[1]) * (double)e->height - 0.5;
	const double x0 = floor(fx), y0 = floor(fy);
	const float ax = (float)(fx - x0), ay = (float)(fy - y0);
	float a[3], b[3], c[3], d[3];
	int k;

	image_texel(e, (long)x0, (long)y0, a);
	image_texel(e, (long)x0 + 1, (long)y0, b);
	image_texel(e, (long)x0, (long)y0 + 1, c);
	image_texel(e, (long)x0 + 1, (long)y0 + 1, d);
	for (k = 0; k < 3; k++) {
		float top = a[k] + ax * (b[k] - a[k]), bottom = c[k] + ax * (d[k] - c[k]);

		rgb[k] = e->rgb[k] * (top + ay * (bottom - top));
	}
}

void
rf__wall_emission(const rf_scene *s, int face, const double uv[2], float rgb[3])
{
	const struct emission *e = rf__wall_emission_of(s, face);
	size_t i;

	/* Windows win over what the wall emits. */
	for (i = 0; i < s->nwindows; i++) {
		const struct window *w = &s->windows[i];

		if (w->face != face || !(uv[0] > w->min[0] && uv[0] < w->max[0] &&
		                         uv[1] > w->min[1] && uv[1] < w->max[1]))
			continue;
		if (w->mullion > 0.0 &&
		    (fabs(uv[0] - 0.5 * (w->min[0] + w->max[0])) < 0.5 * w->mullion ||
		     fabs(uv[1] - 0.5 * (w->min[1] + w->max[1])) < 0.5 * w->mullion))
			set_rgb(rgb, w->mullion_rgb, 1.0f);
		else
			set_rgb(rgb, w->rgb, 1.0f);
		return;
	}
	switch (e->kind) {
	case EMIT_COLOUR: set_rgb(rgb, e->rgb, 1.0f); break;
	case EMIT_PATTERN: pattern_at(&s->pattern, e->rgb, uv, rgb); break;
	case EMIT_IMAGE: image_at(e, uv, rgb); break;
	default: rgb[0] = rgb[1] = rgb[2] = 0.0f; break;
	}
}

/*
 * rf__wall_emission for a chunk of rays leaving the room from one point:
 * the tracer's inner loop (reflect-trace reads the walls millions of
 * times a second).  One pass without branches finds each ray's exit face
 * and (u, v) and sorts it into grid line, even or odd cell, which the
 * compiler makes vector code; the colours of those three classes are the
 * pattern's per face, made once by pattern_at's own arithmetic, so every
 * value is the bits rf__room_exit and rf__wall_emission give.  Rays in a
 * window or on a wall that is not the pattern take the scalar path.
 */
/* fast_floor by int, inside whose range the clamp keeps x (and where a
 * NaN goes) */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-trapping-math"), always_inline))
#endif
static inline float
floor_clamped(float x)
{
	float f;

	x = x < 1e9f ? x : 1e9f;
	x = x > -1e9f ? x : -1e9f;
	f = (float)(int)x;
	return f > x ? f - 1.0f : f;
}

/* rf__room_exit's slab along one axis (number i), its branches as
 * selects: the wall at lo or hi that o + t d meets first so far. */
#if defined(__GNUC__) && !defined(__clang__)
/* as the caller's: GCC inlines no function built with other flags */
__attribute__((optimize("no-trapping-math"), always_inline))
#endif
static inline void
exit_slab(float lo, float hi, float o, float d, int i, float *t, int *face)
{
	const float bound = d > 0 ? hi : lo;
	float ti = (bound - o) / d;

	ti = d != 0 ? ti : INFINITY;
	*face = ti < *t ? 2 * i + (d < 0) : *face;
	*t = ti < *t ? ti : *t;
}

void
rf__wall_classes(rf_scene *s)
{
	const struct pattern *pt = &s->pattern;
	int f, k;

	for (f = 0; f <= RF__FACES; f++) {
		const struct emission *e = f < RF__FACES ? rf__wall_emission_of(s, f) : NULL;

		s->wall_pattern[f] = e && e->kind == EMIT_PATTERN;
		for (k = 0; k < 3; k++) {
			const float c = e ? e->rgb[k] : 0.0f;

			s->wall_class_rgb[f][0][k] = e ? (float)(pt->line * ((1.0 - pt->line_white) * c +
			                                                     pt->line_white))
			                               : 0.0f;
			s->wall_class_rgb[f][1][k] = (float)(c * (pt->base + 0.0));
			s->wall_class_rgb[f][2][k] = (float)(c * (pt->base + pt->checker));
		}
	}
}

/* What the rays of a chunk that meet face[j] (-1: none) at (us, vs)
 * see: one loop without branches sorts them into grid line, even cell
 * or odd cell, a second finds those in a window; rays in a window or on
 * a wall that is not the pattern take rf__wall_emission. */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-trapping-math"), always_inline))
#endif
static inline void
wall_colours(const rf_scene *s, const int *face, const float *us, const float *vs,
             const int *use, size_t n, float rgb[][3])
{
	const struct pattern *pt = &s->pattern;
	const float inv_cell = (float)pt->inv_cell, cell = (float)pt->cell;
	const float half_line = (float)(0.5 * pt->line_width);
	int cls[RF__EMIT_CHUNK], win[RF__EMIT_CHUNK];
	size_t j, w;
	int k;

	/* a fixed trip count: no scalar epilogue, and -O2 vectorizes it;
	 * lanes past n are computed and never read */
	for (j = 0; j < RF__EMIT_CHUNK; j++) {
		/* pattern_at's tests */
		const float su = us[j] * inv_cell, sv = vs[j] * inv_cell;
		const float du = fabsf(su + 0.5f - floor_clamped(su + 0.5f) - 0.5f) * cell;
		const float dv = fabsf(sv + 0.5f - floor_clamped(sv + 0.5f) - 0.5f) * cell;
		const int line = (du < half_line) | (dv < half_line);
		/* floor(su) + floor(sv) = floor(su + 0.5) + floor(sv + 0.5)
		 * would not hold: take su's own */
		const int parity = ((int)floor_clamped(su) + (int)floor_clamped(sv)) & 1;

		cls[j] = line ? 0 : 1 + parity;
		win[j] = 0;
	}
	/* the first window a ray is in wins */
	for (w = 0; w < s->nwindows; w++) {
		const struct window *wd = &s->windows[w];

		for (j = 0; j < RF__EMIT_CHUNK; j++)
			win[j] |= (face[j] == wd->face) & (us[j] > wd->min[0]) &
			          (us[j] < wd->max[0]) & (vs[j] > wd->min[1]) & (vs[j] < wd->max[1]);
	}
	for (j = 0; j < n; j++) {
		const int fc = face[j] < 0 ? RF__FACES : face[j];

		if (use[j] && face[j] >= 0 && (win[j] || !s->wall_pattern[fc])) {
			const double uv[2] = { us[j], vs[j] };

			rf__wall_emission(s, face[j], uv, rgb[j]);
			continue;
		}
		for (k = 0; k < 3; k++)
			rgb[j][k] = s->wall_class_rgb[fc][cls[j]][k];
	}
}

#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-trapping-math"), always_inline))
#endif
static inline void
room_emission_chunk(const rf_scene *s, const double o[3], const float *dx,
                    const float *dy, const float *dz, const int *use, size_t n,
                    float rgb[][3])
{
	const struct rf_scene_probe *room = s->nprobes ? &s->probes[0] : NULL;
	int face[RF__EMIT_CHUNK];
	float us[RF__EMIT_CHUNK], vs[RF__EMIT_CHUNK];
	float lx[RF__EMIT_CHUNK], ly[RF__EMIT_CHUNK], lz[RF__EMIT_CHUNK];
	double ol[3];
	float lo0, lo1, lo2, hi0, hi1, hi2, o0, o1, o2;
	size_t j;

	if (!s->room || !room) {
		for (j = 0; j < n; j++)
			rgb[j][0] = rgb[j][1] = rgb[j][2] = 0.0f;
		return;
	}
	if (s->room_turned) {
		/* the rays in the room's frame, where its walls are slabs */
		const double *r = s->room_rotation;

		rf__room_point_in(s, o, ol);
		o = ol;
		for (j = 0; j < RF__EMIT_CHUNK; j++) {
			const float x = dx[j], y = dy[j], z = dz[j];

			lx[j] = (float)r[0] * x + (float)r[3] * y + (float)r[6] * z;
			ly[j] = (float)r[1] * x + (float)r[4] * y + (float)r[7] * z;
			lz[j] = (float)r[2] * x + (float)r[5] * y + (float)r[8] * z;
		}
		dx = lx;
		dy = ly;
		dz = lz;
	}
	lo0 = room->box_min[0], lo1 = room->box_min[1], lo2 = room->box_min[2];
	hi0 = room->box_max[0], hi1 = room->box_max[1], hi2 = room->box_max[2];
	o0 = o[0], o1 = o[1], o2 = o[2];
	for (j = 0; j < RF__EMIT_CHUNK; j++) {
		const float d0 = dx[j], d1 = dy[j], d2 = dz[j];
		float t = INFINITY, p0, p1, p2;
		int fc = -1;

		/* written out in scalars: the vectorizer takes no inner loop
		 * and no load under a condition */
		exit_slab(lo0, hi0, o0, d0, 0, &t, &fc);
		exit_slab(lo1, hi1, o1, d1, 1, &t, &fc);
		exit_slab(lo2, hi2, o2, d2, 2, &t, &fc);
		fc = t >= 0.0f ? fc : -1;
		p0 = o0 + t * d0;
		p1 = o1 + t * d1;
		p2 = o2 + t * d2;
		us[j] = fc / 2 == 0 ? p2 : p0;
		vs[j] = fc / 2 == 1 ? p2 : p1;
		face[j] = fc;
	}
	wall_colours(s, face, us, vs, use, n, rgb);
}

#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-trapping-math")))
#endif
void
rf__wall_emission_chunk(const rf_scene *s, int wall, const float *us, const float *vs,
                        size_t n, float rgb[][3])
{
	int face[RF__EMIT_CHUNK], use[RF__EMIT_CHUNK];
	size_t j;

	for (j = 0; j < RF__EMIT_CHUNK; j++) {
		face[j] = wall;
		use[j] = 1;
	}
	wall_colours(s, face, us, vs, use, n, rgb);
}

#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("no-trapping-math")))
#endif
void
rf__room_emission_chunk(const rf_scene *s, const double o[3], const float *dx,
                        const float *dy, const float *dz, const int *use, size_t n,
                        float rgb[][3])
{
	room_emission_chunk(s, o, dx, dy, dz, use, n, rgb);
}

void
rf__emission(const rf_scene *s, const struct rf_hit *hit, float rgb[3])
{
	int face = rf__wall_face(hit->objid);

	if (face >= 0) {
		double uv[2], pl[3];

		if (s->room_turned) {
			rf__room_point_in(s, hit->P, pl);
			rf__wall_uv(face, pl, uv);
		} else
			rf__wall_uv(face, hit->P, uv);
		rf__wall_emission(s, face, uv, rgb);
	} else if (hit->objid >= 1 && (size_t)hit->objid <= s->nobjects &&
	           s->objects[hit->objid - 1].mat.em.kind == EMIT_COLOUR) {
		set_rgb(rgb, s->objects[hit->objid - 1].mat.em.rgb, 1.0f);
	} else if (hit->objid >= 1 && (size_t)hit->objid <= s->nobjects &&
	           s->objects[hit->objid - 1].mat.em.kind == EMIT_PATTERN) {
		/* on the plane the surface faces along, as on a wall: for the
		 * walls of rooms built of boxes and rectangles */
		const double *n = hit->Ng;
		const int axis = fabs(n[0]) >= fabs(n[1]) && fabs(n[0]) >= fabs(n[2]) ? 0
		                 : fabs(n[1]) >= fabs(n[2]) ? 1 : 2;
		double uv[2];

		rf__wall_uv(2 * axis, hit->P, uv);
		pattern_at(&s->pattern, s->objects[hit->objid - 1].mat.em.rgb, uv, rgb);
	} else if ((size_t)hit->objid > s->nobjects && hit->objid > 0 &&
	           (size_t)hit->objid <= s->nobjects + s->nmeshes) {
		/* a mesh's: its material's factor times its texture */
		const struct rf__mesh *m = &s->meshes[(size_t)hit->objid - 1 - s->nobjects];
		const struct rf__mesh_material *mat = rf__mesh_material_of(m, hit->prim);
		int c;

		for (c = 0; c < 3; c++)
			rgb[c] = mat->emission[c];
		if (mat->emission_tex && (rgb[0] != 0.0f || rgb[1] != 0.0f || rgb[2] != 0.0f)) {
			double uv[2][2];
			float tex[4];

			rf__mesh_uv(m, hit->prim, hit->bary[0], hit->bary[1], uv);
			rf__texture_sample(mat->emission_tex, uv, tex);
			for (c = 0; c < 3; c++)
				rgb[c] *= tex[c];
		}
	} else {
		rgb[0] = rgb[1] = rgb[2] = 0.0f;
	}
}
