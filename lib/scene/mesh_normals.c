/*
 * A mesh's normals and tangents where its file has none (mesh.c reads
 * the file; this is geometry alone, in world space).
 */
#include <math.h>
#include <stdlib.h>

#include "scene/mesh-load.h"

static void
vget(const float *a, uint32_t i, double v[3])
{
	v[0] = a[3 * i];
	v[1] = a[3 * i + 1];
	v[2] = a[3 * i + 2];
}

/* The angle at corner a of the triangle (a, b, c), between unit edges. */
static double
corner_angle(const double e1[3], const double e2[3])
{
	double d = rf__dot(e1, e2);

	return acos(d > 1 ? 1 : d < -1 ? -1 : d);
}

/*
 * Normals where the file has none: each vertex's is the average of its
 * triangles' normals weighted by the triangle's angle at the vertex
 * (Thürmer and Wüthrich's), so that splitting a face into more triangles
 * does not tilt it.  (glTF files without normals reach here unwelded, one
 * triangle a vertex: flat, as glTF asks.)
 */
int
rf__mesh_normals(struct rf__mesh *m, const unsigned char *gen)
{
	double *acc = calloc(3 * (m->nvertices ? m->nvertices : 1), sizeof(*acc));
	size_t t, v;

	if (!acc)
		return RF_ENOMEM;
	for (t = 0; t < m->ntriangles; t++) {
		const uint32_t *tri = &m->indices[3 * t];
		double p[3][3], n[3], e1[3], e2[3];
		int c, i;

		if (!gen[tri[0]] && !gen[tri[1]] && !gen[tri[2]])
			continue;
		for (c = 0; c < 3; c++)
			vget(m->positions, tri[c], p[c]);
		for (i = 0; i < 3; i++) {
			e1[i] = p[1][i] - p[0][i];
			e2[i] = p[2][i] - p[0][i];
		}
		rf__cross(e1, e2, n);
		if (!(rf__normalize(n) > 0))
			continue;
		for (c = 0; c < 3; c++) {
			double a;

			if (!gen[tri[c]])
				continue;
			for (i = 0; i < 3; i++) {
				e1[i] = p[(c + 1) % 3][i] - p[c][i];
				e2[i] = p[(c + 2) % 3][i] - p[c][i];
			}
			rf__normalize(e1);
			rf__normalize(e2);
			a = corner_angle(e1, e2);
			for (i = 0; i < 3; i++)
				acc[3 * tri[c] + i] += a * n[i];
		}
	}
	for (v = 0; v < m->nvertices; v++) {
		double *n = &acc[3 * v];

		if (!gen[v])
			continue;
		if (!(rf__normalize(n) > 0)) {
			/* only in degenerate triangles: any unit vector will do */
			n[0] = 0;
			n[1] = 1;
			n[2] = 0;
		}
		for (int i = 0; i < 3; i++)
			m->normals[3 * v + i] = (float)n[i];
	}
	free(acc);
	return 0;
}

/*
 * Tangents where the file has none, MikkTSpace's way for what it shares
 * with it: for each corner, the direction of increasing u (dP/du) of its
 * triangle projected into the vertex's tangent plane and normalised,
 * weighted by the corner's angle there, summed per vertex, the sum
 * projected again and normalised; w, the bitangent's side, is the sign of
 * the triangle's area in (u, v) with v up (the convention Blender runs
 * MikkTSpace in and exports glTF tangents from, so that cross(N, T) w
 * points up the image).  What MikkTSpace does and this does not: it
 * splits a vertex whose triangles disagree in w (a mirrored uv seam that
 * shares vertices) or whose tangents differ by more than its angle
 * threshold, and gives degenerate triangles their neighbours' tangents;
 * here such a vertex gets the one average, and a triangle without uv
 * area gives none.  Where exporters split vertices at uv seams, as they
 * do, the two agree to rounding.  Computed in world space, after the
 * transforms.  uv set 0.
 */
int
rf__mesh_tangents(struct rf__mesh *m, const unsigned char *gen)
{
	double *acc = calloc(4 * (m->nvertices ? m->nvertices : 1), sizeof(*acc));
	size_t t, v;

	if (!acc)
		return RF_ENOMEM;
	for (t = 0; t < m->ntriangles; t++) {
		const uint32_t *tri = &m->indices[3 * t];
		double p[3][3], uv[3][2], area;
		int c, i;

		if (!gen[tri[0]] && !gen[tri[1]] && !gen[tri[2]])
			continue;
		for (c = 0; c < 3; c++) {
			vget(m->positions, tri[c], p[c]);
			uv[c][0] = m->uv[0][2 * tri[c]];
			uv[c][1] = 1.0 - m->uv[0][2 * tri[c] + 1]; /* v up */
		}
		area = (uv[1][0] - uv[0][0]) * (uv[2][1] - uv[0][1]) -
		       (uv[2][0] - uv[0][0]) * (uv[1][1] - uv[0][1]);
		if (!(area != 0) || !isfinite(area))
			continue;
		for (c = 0; c < 3; c++) {
			int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
			double e1[3], e2[3], s[3], n[3], dv1 = uv[c1][1] - uv[c][1],
			                                 dv2 = uv[c2][1] - uv[c][1], a, d;

			if (!gen[tri[c]])
				continue;
			vget(m->normals, tri[c], n);
			for (i = 0; i < 3; i++) {
				e1[i] = p[c1][i] - p[c][i];
				e2[i] = p[c2][i] - p[c][i];
				/* dP/du times the area: its sign gives the direction */
				s[i] = (dv2 * e1[i] - dv1 * e2[i]) * (area > 0 ? 1 : -1);
			}
			d = rf__dot(s, n);
			for (i = 0; i < 3; i++)
				s[i] -= d * n[i];
			if (!(rf__normalize(s) > 0))
				continue;
			/* the corner's angle in the tangent plane */
			d = rf__dot(e1, n);
			for (i = 0; i < 3; i++)
				e1[i] -= d * n[i];
			d = rf__dot(e2, n);
			for (i = 0; i < 3; i++)
				e2[i] -= d * n[i];
			if (!(rf__normalize(e1) > 0) || !(rf__normalize(e2) > 0))
				continue;
			a = corner_angle(e1, e2);
			for (i = 0; i < 3; i++)
				acc[4 * tri[c] + i] += a * s[i];
			acc[4 * tri[c] + 3] += area > 0 ? a : -a;
		}
	}
	for (v = 0; v < m->nvertices; v++) {
		double *s = &acc[4 * v], n[3], d;

		if (!gen[v])
			continue;
		vget(m->normals, (uint32_t)v, n);
		d = rf__dot(s, n);
		for (int i = 0; i < 3; i++)
			s[i] -= d * n[i];
		if (!(rf__normalize(s) > 0))
			rf__plane_tangent(n, s); /* no uv: any tangent */
		for (int i = 0; i < 3; i++)
			m->tangents[4 * v + i] = (float)s[i];
		m->tangents[4 * v + 3] = s[3] < 0 ? -1.0f : 1.0f;
	}
	free(acc);
	return 0;
}
