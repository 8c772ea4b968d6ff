/* A mesh's hit: the triangle's interpolated normal, tangent and texture
 * coordinates, its material through its textures (glTF 2.0's
 * metallic-roughness model, as lib/scene/mesh.h holds it). */
#include <math.h>
#include <stdint.h>

#include "scene/accel.h"

const struct rf__mesh_material *
rf__mesh_material_of(const struct rf__mesh *m, uint32_t prim)
{
	return &m->materials[m->material ? m->material[prim] : 0];
}

/* The texel index i of a row or column of n, wrapped (glTF's modes). */
static size_t
wrap(long long i, size_t n, enum rf__wrap mode)
{
	const long long ln = (long long)n;
	long long r;

	switch (mode) {
	case RF__WRAP_CLAMP:
		return i < 0 ? 0 : i >= ln ? n - 1 : (size_t)i;
	case RF__WRAP_MIRROR:
		/* period 2n: 0 .. n-1, then n-1 .. 0 */
		r = i % (2 * ln);
		if (r < 0)
			r += 2 * ln;
		return (size_t)(r < ln ? r : 2 * ln - 1 - r);
	case RF__WRAP_REPEAT:
	default:
		r = i % ln;
		return (size_t)(r < 0 ? r + ln : r);
	}
}

static void
texel(const struct rf__texture *tex, size_t x, size_t y, double v[4])
{
	const float *p = tex->pixels + (y * tex->width + x) * tex->nchannels;

	switch (tex->nchannels) {
	case 1:
	case 2:
		v[0] = v[1] = v[2] = p[0];
		v[3] = tex->nchannels == 2 ? p[1] : 1.0;
		break;
	case 3:
		v[0] = p[0], v[1] = p[1], v[2] = p[2], v[3] = 1.0;
		break;
	default:
		v[0] = p[0], v[1] = p[1], v[2] = p[2], v[3] = p[3];
		break;
	}
}

/* A texture coordinate in texels, its integer part bounded so that it
 * converts: a texture repeats long before. */
static double
texels(double c, size_t n)
{
	double x = c * (double)n - 0.5;

	return !isfinite(x) ? 0.0 : x < -1e15 ? -1e15 : x > 1e15 ? 1e15 : x;
}

void
rf__texture_sample(const struct rf__texture *tex, const double uv[2][2], float out[4])
{
	const double *st = uv[tex->texcoord == 1];
	const float *m = tex->transform;
	/* uv' = M (u, v, 1) (KHR_texture_transform); texel centres at
	 * (i + 1/2) / width, the first row at v = 0 (glTF's origin is the
	 * image's top left corner) */
	const double u = m[0] * st[0] + m[1] * st[1] + m[2];
	const double v = m[3] * st[0] + m[4] * st[1] + m[5];
	const double x = texels(u, tex->width), y = texels(v, tex->height);
	const double fx = floor(x), fy = floor(y), ax = x - fx, ay = y - fy;
	const size_t x0 = wrap((long long)fx, tex->width, tex->wrap[0]);
	const size_t x1 = wrap((long long)fx + 1, tex->width, tex->wrap[0]);
	const size_t y0 = wrap((long long)fy, tex->height, tex->wrap[1]);
	const size_t y1 = wrap((long long)fy + 1, tex->height, tex->wrap[1]);
	double a[4], b[4], c[4], d[4];
	int i;

	texel(tex, x0, y0, a);
	texel(tex, x1, y0, b);
	texel(tex, x0, y1, c);
	texel(tex, x1, y1, d);
	for (i = 0; i < 4; i++)
		out[i] = (float)((1.0 - ay) * ((1.0 - ax) * a[i] + ax * b[i]) +
		                 ay * ((1.0 - ax) * c[i] + ax * d[i]));
}

/* The weights of the three vertices, inside the triangle: double's
 * re-intersection may put an edge's hit a rounding error outside. */
static void
weights(double b1, double b2, double w[3])
{
	double sum;

	w[1] = b1 > 0.0 ? b1 : 0.0;
	w[2] = b2 > 0.0 ? b2 : 0.0;
	w[0] = 1.0 - b1 - b2;
	w[0] = w[0] > 0.0 ? w[0] : 0.0;
	sum = w[0] + w[1] + w[2];
	if (!(sum > 0.0)) {
		w[0] = 1.0, w[1] = w[2] = 0.0;
		return;
	}
	w[0] /= sum, w[1] /= sum, w[2] /= sum;
}

/* Vertex attribute a (n per vertex, component j of the first three)
 * interpolated over the triangle ix. */
static void
interpolate(const float *a, size_t n, const uint32_t *ix, const double w[3], double out[3])
{
	int j;

	for (j = 0; j < 3; j++)
		out[j] = w[0] * a[n * ix[0] + (size_t)j] + w[1] * a[n * ix[1] + (size_t)j] +
		         w[2] * a[n * ix[2] + (size_t)j];
}

void
rf__mesh_uv(const struct rf__mesh *m, uint32_t prim, double b1, double b2, double uv[2][2])
{
	const uint32_t *ix = m->indices + 3 * (size_t)prim;
	double w[3];
	int set, j;

	weights(b1, b2, w);
	for (set = 0; set < 2; set++) {
		const float *t = m->uv[set] ? m->uv[set] : m->uv[0];

		for (j = 0; j < 2; j++)
			uv[set][j] = t ? w[0] * t[2 * (size_t)ix[0] + (size_t)j] +
			                         w[1] * t[2 * (size_t)ix[1] + (size_t)j] +
			                         w[2] * t[2 * (size_t)ix[2] + (size_t)j]
			               : 0.0;
	}
}

void
rf__mesh_shade(const rf_scene *s, const struct rf__mesh_hit *mh, const double o[3],
               const double d[3], struct rf_hit *hit)
{
	const struct rf__mesh *m = &s->meshes[mh->mesh];
	const struct rf__mesh_material *mat = rf__mesh_material_of(m, mh->prim);
	const uint32_t *ix = m->indices + 3 * (size_t)mh->prim;
	double w[3], e1[3], e2[3], n[3], t[3], uv[2][2];
	float tex[4];
	int j, flip;

	weights(mh->b1, mh->b2, w);
	hit->t = mh->t;
	for (j = 0; j < 3; j++) {
		const double v0 = m->positions[3 * (size_t)ix[0] + (size_t)j];

		hit->P[j] = o[j] + mh->t * d[j];
		e1[j] = (double)m->positions[3 * (size_t)ix[1] + (size_t)j] - v0;
		e2[j] = (double)m->positions[3 * (size_t)ix[2] + (size_t)j] - v0;
	}
	rf__cross(e1, e2, hit->Ng);
	if (!(rf__normalize(hit->Ng) > 0.0))
		for (j = 0; j < 3; j++)
			hit->Ng[j] = -d[j];
	/* Seen from behind: both normals turn to the ray, as a path tracer
	 * shades a back face (after the normal map, which reads the front). */
	flip = rf__dot(hit->Ng, d) > 0.0;
	interpolate(m->normals, 3, ix, w, n);
	if (!(rf__normalize(n) > 0.0))
		for (j = 0; j < 3; j++)
			n[j] = hit->Ng[j];
	interpolate(m->tangents, 4, ix, w, t);
	rf__mesh_uv(m, mh->prim, mh->b1, mh->b2, uv);
	if (mat->normal_tex) {
		/* tangent space: x along T, y along B = sign (N x T), z along N */
		const double sign = m->tangents[4 * (size_t)ix[0] + 3] < 0.0f ? -1.0 : 1.0;
		double tt[3], b[3], nt[3], dn = rf__dot(t, n), out[3];

		for (j = 0; j < 3; j++)
			tt[j] = t[j] - dn * n[j];
		if (rf__normalize(tt) > 0.0) {
			rf__cross(n, tt, b);
			rf__texture_sample(mat->normal_tex, uv, tex);
			nt[0] = (2.0 * tex[0] - 1.0) * mat->normal_scale;
			nt[1] = (2.0 * tex[1] - 1.0) * mat->normal_scale;
			nt[2] = 2.0 * tex[2] - 1.0;
			for (j = 0; j < 3; j++)
				out[j] = nt[0] * tt[j] + sign * nt[1] * b[j] + nt[2] * n[j];
			if (rf__normalize(out) > 0.0)
				for (j = 0; j < 3; j++)
					n[j] = out[j];
		}
	}
	for (j = 0; j < 3; j++) {
		if (flip) {
			hit->Ng[j] = -hit->Ng[j];
			n[j] = -n[j];
		}
		hit->N[j] = n[j];
	}
	rf__hit_tangent(hit, t);
	hit->albedo[0] = mat->base_colour[0];
	hit->albedo[1] = mat->base_colour[1];
	hit->albedo[2] = mat->base_colour[2];
	hit->roughness = mat->roughness;
	hit->metallic = mat->metallic;
	if (mat->base_colour_tex) {
		rf__texture_sample(mat->base_colour_tex, uv, tex);
		for (j = 0; j < 3; j++)
			hit->albedo[j] *= tex[j];
	}
	if (mat->metallic_roughness_tex) {
		rf__texture_sample(mat->metallic_roughness_tex, uv, tex);
		hit->roughness *= tex[1];
		hit->metallic *= tex[2];
	}
	hit->mask = mat->mask;
	hit->objid = m->objid;
	hit->prim = mh->prim;
	hit->bary[0] = mh->b1;
	hit->bary[1] = mh->b2;
}
