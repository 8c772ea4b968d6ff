/* Unit tests of the host services every tool gives its plugins. */
#include "reflect/host.h"
#include "maths/sequences.h"
#include "tap.h"

TEST(table_follows_the_settings)
{
	rf_plugin_host *h;
	const struct rf_host *t;
	struct rf_probe probe = { { 1, 2, 3 }, { -1, -2, -3 }, { 4, 5, 6 }, 0, 0.0f, 0 };
	rf_header *frame;
	rf_cubemap *c;
	float dir[3] = { 0.3f, -0.2f, 0.9f }, got[3], want[3];

	ASSERT_EQ(rf_header_create(&frame), 0);
	ASSERT_EQ(rf_header_set(frame, "SCENE", "room"), 0);
	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT_EQ(t->size, sizeof(struct rf_host));
	ASSERT_EQ(t->abi_major, RF_PLUGIN_ABI_MAJOR);
	ASSERT_EQ(t->abi_minor, RF_PLUGIN_ABI_MINOR);
	/* Nothing set: keys absent, no probe, no sampling. */
	ASSERT(t->header_get(t->ctx, "SCENE") == NULL);
	ASSERT(t->probe == NULL);
	ASSERT(t->sample == NULL && t->roughness_to_lod == NULL &&
	       t->lod_to_roughness == NULL);
	ASSERT(t->lod_steps == 0.0f && t->seed == 0);

	rf_plugin_host_set_frame(h, frame);
	ASSERT_STR_EQ(t->header_get(t->ctx, "SCENE"), "room");
	ASSERT(t->header_get(t->ctx, "CAMERA") == NULL);
	/* The probe is a copy: the caller's may go. */
	rf_plugin_host_set_probe(h, &probe);
	probe.center[0] = 99;
	ASSERT(t->probe && t->probe->center[0] == 1 && t->probe->box_max[2] == 6 &&
	       t->probe->box_projection == 0);
	rf_plugin_host_set_probe(h, NULL);
	ASSERT(t->probe == NULL);

	/* Sampling is rf_cubemap_sample, the mapping rf_roughness_to_lod. */
	ASSERT_EQ(rf_cubemap_create(&c, 8, 4), 0);
	rf_default_environment_cube(c);
	rf_cubemap_box_chain(c, 1);
	rf_plugin_host_set_environment(h, c, RF_MAPPING_EXACT, 3);
	rf_plugin_host_set_seed(h, 7);
	ASSERT(t->sample && t->roughness_to_lod && t->lod_to_roughness);
	ASSERT(t->lod_steps == 3.0f && t->seed == 7);
	t->sample(t->ctx, dir, 1.25f, got);
	rf_cubemap_sample(c, dir, 1.25f, want);
	ASSERT(!memcmp(got, want, sizeof(got)));
	ASSERT(t->roughness_to_lod(t->ctx, 0.4f) ==
	       rf_roughness_to_lod(RF_MAPPING_EXACT, 3, 0.4f));
	ASSERT(t->lod_to_roughness(t->ctx, 2.0f) ==
	       rf_lod_to_roughness(RF_MAPPING_EXACT, 3, 2.0f));
	rf_plugin_host_set_environment(h, NULL, RF_MAPPING_EXACT, 3);
	ASSERT(t->sample == NULL && t->lod_steps == 0.0f);

	rf_plugin_host_destroy(h);
	rf_cubemap_destroy(c);
	rf_header_destroy(frame);
}

/* Hand-derived exits from the box [-3,0,-2]..[3,3,2], centre (0,1.5,0). */
TEST(rays_leave_the_box)
{
	struct rf_probe probe = { { 0, 1.5f, 0 }, { -3, 0, -2 }, { 3, 3, 2 }, 1, 0.0f, 0 };
	rf_plugin_host *h;
	const struct rf_host *t;
	const float at_c[3] = { 0, 1.5f, 0 }, off[3] = { 1, 1.5f, 0 }, low[3] = { 0, 0.5f, 0 };
	const float outside[3] = { 9, 1, 0 };
	float diag[3] = { 0.48f, 0.6f, 0.64f }, dirs[6] = { 1, 0, 0, 0, 1, 0 };
	float look[6], dist[2], jac[2];

	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT(t->project_rays == NULL);
	rf_plugin_host_set_probe(h, &probe);
	ASSERT(t->project_rays != NULL);
	/* From the centre: the direction itself, Jacobian 1, whatever the ray. */
	t->project_rays(t->ctx, 1, at_c, diag, look, dist, jac);
	ASSERT_NEAR(look[0], 0.48, 1e-6);
	ASSERT_NEAR(look[1], 0.6, 1e-6);
	ASSERT_NEAR(look[2], 0.64, 1e-6);
	ASSERT_NEAR(dist[0], 2.5, 1e-6); /* the ceiling first: 1.5 / 0.6 */
	ASSERT_NEAR(jac[0], 1, 1e-6);
	/* 1 m off the centre, along +X: the wall at 2 m, 3 m from C, so
	 * dw_C / dw_P = 2^2 / 3^2.  Then straight up from 1 m below C: the
	 * ceiling at 2.5 m, 1.5 m from C: 2.5^2 / 1.5^2. */
	t->project_rays(t->ctx, 1, off, dirs, look, dist, jac);
	ASSERT_NEAR(look[0], 1, 1e-6);
	ASSERT_NEAR(dist[0], 2, 1e-6);
	ASSERT_NEAR(jac[0], 4.0 / 9.0, 1e-6);
	t->project_rays(t->ctx, 1, low, dirs + 3, look, dist, jac);
	ASSERT_NEAR(look[1], 1, 1e-6);
	ASSERT_NEAR(dist[0], 2.5, 1e-6);
	ASSERT_NEAR(jac[0], 6.25 / 2.25, 1e-5);
	/* Outside the box, or with box projection off: the ray as it is. */
	t->project_rays(t->ctx, 2, outside, dirs, look, dist, jac);
	ASSERT(look[0] == 1 && look[4] == 1 && !(dist[0] < INFINITY) && jac[1] == 1);
	probe.box_projection = 0;
	rf_plugin_host_set_probe(h, &probe);
	t->project_rays(t->ctx, 1, off, dirs, look, dist, jac);
	ASSERT(look[0] == 1 && !(dist[0] < INFINITY) && jac[0] == 1);
	rf_plugin_host_destroy(h);
}

/* Half the cross product of a quadrilateral's diagonals: its area. */
static float
diagonal_area(float q[4][3])
{
	float u[3], v[3], c[3];
	int k;

	for (k = 0; k < 3; k++) {
		u[k] = q[3][k] - q[0][k];
		v[k] = q[2][k] - q[1][k];
	}
	c[0] = u[1] * v[2] - u[2] * v[1];
	c[1] = u[2] * v[0] - u[0] * v[2];
	c[2] = u[0] * v[1] - u[1] * v[0];
	return 0.5f * sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

/* A unit vector's two tangents. */
static void
tangents(const float d[3], float a[3], float b[3])
{
	float h[3] = { 0, 0, 1 }, l;

	if (fabsf(d[2]) > 0.9f) {
		h[0] = 1;
		h[2] = 0;
	}
	a[0] = d[1] * h[2] - d[2] * h[1];
	a[1] = d[2] * h[0] - d[0] * h[2];
	a[2] = d[0] * h[1] - d[1] * h[0];
	l = sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
	a[0] /= l;
	a[1] /= l;
	a[2] /= l;
	b[0] = d[1] * a[2] - d[2] * a[1];
	b[1] = d[2] * a[0] - d[0] * a[2];
	b[2] = d[0] * a[1] - d[1] * a[0];
}

/* With a bevel declared, the rays leave the rounded box: radius 1 with
 * the faces on the box, inner box (-2, 1, -1) .. (2, 2, 1).  From the
 * centre through the edge's point at 45 degrees, (2.70711, 2.70711, 0),
 * 2.96404 away; and the Jacobian at a face, a corner and an edge, against
 * the solid angle of a small square of directions from P mapped to the
 * capture point. */
TEST(rays_leave_the_rounded_box)
{
	struct rf_probe probe = { { 0.5f, 1.2f, 0.3f }, { -3, 0, -2 }, { 3, 3, 2 }, 1, 0.0f, 0 };
	rf_plugin_host *h;
	const struct rf_host *t;
	const float c[3] = { 0, 1.5f, 0 }, p[3] = { -1, 0.8f, 0.4f };
	float d[3] = { 2.70711f, 1.20711f, 0 }, look[3], dist, jac, l;
	int k, r;

	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT(t->declare_bevel != NULL);
	ASSERT(t->declare_bevel(t->ctx, 1.0f, 0) == -1); /* no probe yet */
	rf_plugin_host_set_probe(h, &probe);
	ASSERT(t->declare_bevel(t->ctx, 1.6f, 0) == -1); /* over 1.5 */
	ASSERT(t->declare_bevel(t->ctx, -0.1f, 0) == -1);
	ASSERT(t->declare_bevel(t->ctx, 1.0f, 0) == 0);
	ASSERT(rf_plugin_host_probe(h)->bevel == 1.0f);
	l = sqrtf(d[0] * d[0] + d[1] * d[1]);
	d[0] /= l;
	d[1] /= l;
	t->project_rays(t->ctx, 1, c, d, look, &dist, &jac);
	ASSERT_NEAR(dist, 2.96404, 2e-5);
	/* Jacobians at a face, an edge and a corner, from off the centre */
	for (r = 0; r < 3; r++) {
		float dir[3] = { 1, 0.1f, 0.05f }, a[3], b[3], sq[4][3], lk[4][3], e = 1e-3f;
		float area_c, area_p, dd[4], jj[4];

		if (r == 1) { /* to the corner sphere's point along (1, 1, 1) */
			dir[0] = 2 + 0.57735f - p[0];
			dir[1] = 2 + 0.57735f - p[1];
			dir[2] = 1 + 0.57735f - p[2];
		} else if (r == 2) { /* onto the edge along x at y = 2, z = 1 */
			dir[0] = 1.0f;
			dir[1] = 1.1f;
			dir[2] = 0.75f;
		}
		l = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
		for (k = 0; k < 3; k++)
			dir[k] /= l;
		tangents(dir, a, b);
		for (k = 0; k < 4; k++) {
			float sa = k & 1 ? e : -e, sb = k & 2 ? e : -e;
			int i;

			for (i = 0; i < 3; i++)
				sq[k][i] = dir[i] + sa * a[i] + sb * b[i];
			l = sqrtf(sq[k][0] * sq[k][0] + sq[k][1] * sq[k][1] + sq[k][2] * sq[k][2]);
			for (i = 0; i < 3; i++)
				sq[k][i] /= l;
		}
		t->project_rays(t->ctx, 4, p, sq[0], lk[0], dd, jj);
		t->project_rays(t->ctx, 1, p, dir, look, &dist, &jac);
		/* the squares' areas on the unit spheres at P and at C: half the
		 * cross product of their diagonals */
		area_p = diagonal_area(sq);
		area_c = diagonal_area(lk);
		{
			const float x = p[0] + dir[0] * dist, y = p[1] + dir[1] * dist;
			const float z = p[2] + dir[2] * dist;

			if (r == 0)
				ASSERT_NEAR(x, 3.0, 1e-5);
			else if (r == 1)
				ASSERT(fabsf(x - 2.57735f) < 1e-4f && fabsf(y - 2.57735f) < 1e-4f &&
				       fabsf(z - 1.57735f) < 1e-4f);
			else
				ASSERT(fabsf(x) < 2 && y > 2 && z > 1);
		}
		ASSERT_NEAR(jac, area_c / area_p, 1e-2 * jac);
	}
	rf_plugin_host_destroy(h);
}

/* face_size and texel_solid_angle: the chain's sizes, the solid angle at
 * a face's centre (2/S)^2 times 4 a lod, and the texels of a level that
 * sum to the whole sphere. */
TEST(environment_geometry)
{
	rf_plugin_host *h;
	const struct rf_host *t;
	rf_cubemap *c;
	const float centre[3] = { 0, 0, -3 };
	double sum = 0.0;
	int f, i, j;

	ASSERT_EQ(rf_cubemap_create(&c, 16, 5), 0);
	rf_default_environment_cube(c);
	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT(t->face_size == NULL && t->texel_solid_angle == NULL);
	ASSERT_EQ(rf_plugin_host_set_environment(h, c, RF_MAPPING_DEFAULT, 4), 0);
	ASSERT_EQ(t->face_size(t->ctx, 0), 16);
	ASSERT_EQ(t->face_size(t->ctx, 2), 4);
	ASSERT_EQ(t->face_size(t->ctx, 4), 1);
	ASSERT_EQ(t->face_size(t->ctx, 5), 0);
	ASSERT_NEAR(t->texel_solid_angle(t->ctx, centre, 0), 1.0 / 64, 1e-9);
	ASSERT_NEAR(t->texel_solid_angle(t->ctx, centre, 1.5), 8.0 / 64, 1e-7);
	/* every texel of level 0 at its centre: 4 pi to the midpoint rule's
	 * error, under 0.2 % at 16 texels a face */
	for (f = 0; f < 6; f++)
		for (j = 0; j < 16; j++)
			for (i = 0; i < 16; i++) {
				float u = (i + 0.5f) / 8 - 1, v = (j + 0.5f) / 8 - 1, d[3];

				d[f / 2] = f & 1 ? -1.0f : 1.0f;
				d[(f / 2 + 1) % 3] = u;
				d[(f / 2 + 2) % 3] = v;
				sum += t->texel_solid_angle(t->ctx, d, 0);
			}
	ASSERT_NEAR(sum, 4 * M_PI, 0.002 * 4 * M_PI);
	rf_plugin_host_destroy(h);
	rf_cubemap_destroy(c);
}

/* pixel_footprint: a camera at the origin looking down -z, 90 degrees,
 * 100 x 100 pixels, and the plane z = -1: neighbouring pixel centres are
 * 2 / 100 apart on it, right along +x, down along -y; in a tile of the
 * frame too. */
TEST(pixel_footprint_by_hand)
{
	rf_plugin_host *h;
	const struct rf_host *t;
	rf_header *frame;
	const float p[3] = { -0.01f, 0.01f, -1 }, n[3] = { 0, 0, 1 }, along[3] = { 0, 1, 0.01f };
	float dx[3], dy[3];

	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT_EQ(rf_header_create(&frame), 0);
	ASSERT_EQ(rf_header_set_size(frame, 100, 100), 0);
	rf_plugin_host_set_frame(h, frame);
	ASSERT(t->pixel_footprint(t->ctx, 49, 49, p, n, dx, dy) == -1);
	ASSERT(dx[0] == 0 && dy[1] == 0);
	ASSERT_EQ(rf_header_set(frame, RF_KEY_CAMERA, "0 0 0 0 0 -1 0 1 0 90"), 0);
	rf_plugin_host_set_frame(h, frame);
	ASSERT(t->pixel_footprint(t->ctx, 49, 49, p, n, dx, dy) == 0);
	ASSERT_NEAR(dx[0], 0.02, 1e-6);
	ASSERT_NEAR(dx[1], 0, 1e-6);
	ASSERT_NEAR(dx[2], 0, 1e-6);
	ASSERT_NEAR(dy[0], 0, 1e-6);
	ASSERT_NEAR(dy[1], -0.02, 1e-6);
	/* twice as far, twice as large.  The plane tilted 60 degrees about y,
	 * n = (sin 60, 0, cos 60) through p: the rays (-0.01, 0.01, -1) and
	 * (0.01, 0.01, -1) meet it at t = p.n / d.n = 1.000079 and 1.035332,
	 * (-0.010001, 0.010001, -1.000079) and (0.010353, 0.010353,
	 * -1.035332): 0.040705 apart in x and z (about 0.02 / cos 60, the
	 * perspective on top). */
	{
		const float far[3] = { -0.02f, 0.02f, -2 };
		const float tilted[3] = { 0.8660254f, 0, 0.5f };

		ASSERT(t->pixel_footprint(t->ctx, 49, 49, far, n, dx, dy) == 0);
		ASSERT_NEAR(dx[0], 0.04, 1e-6);
		ASSERT(t->pixel_footprint(t->ctx, 49, 49, p, tilted, dx, dy) == 0);
		ASSERT_NEAR(sqrt(dx[0] * dx[0] + dx[2] * dx[2]), 0.040705, 2e-6);
		/* the pixel's own ray, (-0.01, 0.01, -1), along the plane */
		ASSERT(t->pixel_footprint(t->ctx, 49, 49, p, along, dx, dy) == -1);
	}
	/* a tile of that frame, 50 x 25 from (25, 40): the full frame's rays
	 * (its pixel 49, 49 as above), not a 50 x 25 frame's */
	{
		const struct rf_region tile = { 25, 40, 100, 100 };

		ASSERT_EQ(rf_header_set_size(frame, 50, 25), 0);
		ASSERT_EQ(rf_header_set_region(frame, &tile), 0);
		rf_plugin_host_set_frame(h, frame);
		ASSERT(t->pixel_footprint(t->ctx, 49, 49, p, n, dx, dy) == 0);
		ASSERT_NEAR(dx[0], 0.02, 1e-6);
		ASSERT_NEAR(dy[1], -0.02, 1e-6);
	}
	rf_header_destroy(frame);
	rf_plugin_host_destroy(h);
}

/* random_pairs: the low-discrepancy set by hand, in pieces as whole, the
 * blue set a per-pixel shift of it, frames moved by the R2 step, white
 * noise that averages 1/2; and the raytraced mode's own numbers
 * (sequences.h, which it draws from) for the same keys. */
TEST(random_pairs_of_the_host)
{
	rf_plugin_host *h;
	const struct rf_host *t;
	float a[16], b[16], c[16], d[16], w0[4096], w1[4096], ham0[16], ham1[16];
	double mean = 0.0;
	int i;

	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	rf_plugin_host_set_seed(h, 7);
	t = rf_plugin_host_table(h);
	t->random_pairs(t->ctx, RF_SEQUENCE_LOW_DISCREPANCY, 3, 4, 0, 0, 16, 16, a, b);
	for (i = 0; i < 16; i++) {
		ASSERT(a[i] == (i + 0.5f) / 16);
		ham0[i] = a[i];
		ham1[i] = b[i];
	}
	ASSERT(b[0] == 0.0f && b[1] == 0.5f && b[2] == 0.25f && b[3] == 0.75f);
	t->random_pairs(t->ctx, RF_SEQUENCE_LOW_DISCREPANCY, 3, 4, 0, 4, 8, 16, c, d);
	for (i = 0; i < 8; i++)
		ASSERT(c[i] == a[4 + i] && d[i] == b[4 + i]);
	/* blue: the same set, every point moved by the pixel's one shift */
	t->random_pairs(t->ctx, RF_SEQUENCE_BLUE, 3, 4, 0, 0, 16, 16, c, d);
	for (i = 1; i < 16; i++) {
		float s0 = c[i] - a[i] - (c[0] - a[0]), s1 = d[i] - b[i] - (d[0] - b[0]);

		ASSERT(fabsf(s0 - roundf(s0)) < 1e-6f && fabsf(s1 - roundf(s1)) < 1e-6f);
	}
	/* frame 1: moved by one step of R2, 0.7548777 and 0.5698403 */
	t->random_pairs(t->ctx, RF_SEQUENCE_LOW_DISCREPANCY, 3, 4, 1, 0, 16, 16, c, d);
	for (i = 0; i < 16; i++) {
		float s0 = c[i] - a[i] - 0.7548776662f, s1 = d[i] - b[i] - 0.5698402910f;

		ASSERT(fabsf(s0 - roundf(s0)) < 1e-6f && fabsf(s1 - roundf(s1)) < 1e-6f);
	}
	/* the raytraced mode's numbers for the same pattern, seed and frame */
	for (i = 0; i < 3; i++) {
		static const int patterns[3] = { RF_SEQUENCE_WHITE, RF_SEQUENCE_BLUE,
		                                 RF_SEQUENCE_LOW_DISCREPANCY };
		int k;

		t->random_pairs(t->ctx, patterns[i], 10, 20, 5, 0, 16, 16, a, b);
		rf__sequence_pairs(patterns[i], 7, 5, 5, 10, 20, 0, 16, ham0, ham1, c, d);
		for (k = 0; k < 16; k++)
			ASSERT(a[k] == c[k] && b[k] == d[k]);
	}
	/* white: 4096 pairs average 1/2 (to 0.01, 3 sigma 0.0045), another
	 * frame draws others */
	t->random_pairs(t->ctx, RF_SEQUENCE_WHITE, 1, 2, 0, 0, 4096, 4096, w0, w1);
	for (i = 0; i < 4096; i++) {
		ASSERT(w0[i] >= 0.0f && w0[i] < 1.0f);
		mean += w0[i] + w1[i];
	}
	ASSERT_NEAR(mean / 8192, 0.5, 0.01);
	t->random_pairs(t->ctx, RF_SEQUENCE_WHITE, 1, 2, 1, 0, 16, 16, a, b);
	ASSERT(a[0] != w0[0] || a[1] != w0[1]);
	rf_plugin_host_destroy(h);
}

/* The probe list from the keys and HDRP's weights, by hand.  A: the box
 * 0..4 on every axis, blend 1 (volume 64); B: 3..8 x 0..4 x 0..4, blend 1
 * (volume 80), so A is taken first.
 *   (3.5, 2, 2): 0.5 from A's x = 4 and from B's x = 3: smoothstep(0.5)
 *   = 0.5 each; A 0.5, B min(0.5, 1 - 0.5) = 0.5, sky 0.
 *   (2, 2, 2): A 1 (2 from every face), B 0 (outside).
 *   (3.8, 0.2, 2): 0.2 from the floor in both: smoothstep(0.2) = 0.104
 *   each, sky 0.792.
 *   (9, 2, 2): outside both: sky 1. */
TEST(probe_list_and_weights)
{
	rf_plugin_host *h;
	const struct rf_host *t;
	rf_header *frame;
	static const float pts[4][3] = { { 3.5f, 2, 2 }, { 2, 2, 2 }, { 3.8f, 0.2f, 2 },
		                         { 9, 2, 2 } };
	static const float want[4][3] = { { 0.5f, 0.5f, 0 }, { 1, 0, 0 },
		                          { 0.104f, 0.104f, 0.792f }, { 0, 0, 1 } };
	struct rf_probe first;
	char err[256];
	float w[RF_PROBES_MAX], sky;
	int i;

	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT_EQ(t->nprobes, 0);
	ASSERT_EQ(rf_header_create(&frame), 0);
	ASSERT_EQ(rf_header_set_size(frame, 1, 1), 0);
	ASSERT_EQ(rf_header_set(frame, "PROBE_BOX", "0 0 0 4 4 4"), 0);
	ASSERT_EQ(rf_header_set(frame, "PROBE_BLEND", "1"), 0);
	ASSERT_EQ(rf_header_set(frame, "PROBE2_BOX", "3 0 0 8 4 4"), 0);
	ASSERT_EQ(rf_header_set(frame, "PROBE2_CENTER", "5 2 2"), 0);
	ASSERT_EQ(rf_header_set(frame, "PROBE2_BLEND", "1"), 0);
	ASSERT_EQ(rf_probe_resolve(&first, frame, NULL, NULL, NULL, err, sizeof(err)), 0);
	rf_plugin_host_set_frame(h, frame);
	rf_plugin_host_set_probe(h, &first);
	ASSERT_EQ(t->nprobes, 2);
	ASSERT(t->probes[1].center[0] == 5 && t->probes[1].box_min[0] == 3);
	ASSERT(t->probe_blend[0] == 1 && t->probe_blend[1] == 1);
	for (i = 0; i < 4; i++) {
		sky = t->probe_weights(t->ctx, pts[i], w);
		ASSERT_NEAR(w[0], want[i][0], 1e-6);
		ASSERT_NEAR(w[1], want[i][1], 1e-6);
		ASSERT_NEAR(sky, want[i][2], 1e-6);
	}
	/* without a blend distance, a probe is all or nothing */
	ASSERT_EQ(rf_header_unset(frame, "PROBE_BLEND"), 0);
	rf_plugin_host_set_frame(h, frame);
	rf_plugin_host_set_probe(h, &first);
	sky = t->probe_weights(t->ctx, pts[2], w);
	ASSERT(w[0] == 1 && w[1] == 0 && sky == 0);
	rf_header_destroy(frame);
	rf_plugin_host_destroy(h);
}

/* sample_radiance: the plain levels of the environment's level 0. */
TEST(radiance_reads_plain_levels)
{
	rf_plugin_host *h;
	const struct rf_host *t;
	rf_cubemap *c, *plain;
	float x[2] = { 0.3f, 0.3f }, y[2] = { -0.2f, -0.2f }, z[2] = { 0.9f, 0.9f };
	float lod[2] = { 0.0f, 2.5f }, rgba[8], dir[3] = { 0.3f, -0.2f, 0.9f }, want[3];
	int k;

	ASSERT_EQ(rf_cubemap_create(&c, 16, 3), 0);
	rf_default_environment_cube(c);
	rf_cubemap_box_chain(c, 0);
	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	t = rf_plugin_host_table(h);
	ASSERT(t->sample_radiance == NULL && t->env_size == 0);
	ASSERT_EQ(rf_plugin_host_set_radiance(h, c), 0);
	ASSERT(t->sample_radiance != NULL);
	ASSERT_EQ(t->env_size, 16);
	ASSERT_EQ(t->env_levels, 5); /* 16 8 4 2 1 */
	t->sample_radiance(t->ctx, 2, x, y, z, lod, rgba);
	/* The same plain chain read by the library's own sampler. */
	ASSERT_EQ(rf_cubemap_create(&plain, 16, 5), 0);
	rf_default_environment_cube(plain);
	rf_cubemap_box_chain(plain, 0);
	rf_cubemap_sample(plain, dir, 0.0f, want);
	for (k = 0; k < 3; k++)
		ASSERT_NEAR(rgba[k], want[k], 1e-4 * want[k] + 1e-6);
	rf_cubemap_sample(plain, dir, 2.5f, want);
	for (k = 0; k < 3; k++)
		ASSERT_NEAR(rgba[4 + k], want[k], 1e-4 * want[k] + 1e-6);
	ASSERT_EQ(rf_plugin_host_set_radiance(h, NULL), 0);
	ASSERT(t->sample_radiance == NULL && t->env_levels == 0);
	rf_plugin_host_destroy(h);
	rf_cubemap_destroy(c);
	rf_cubemap_destroy(plain);
}

/* A filter mode that declares one pass of radius 1. */
static int
one_pass_create(const struct rf_host *host, const double *values, void **state, char *err,
                size_t errlen)
{
	const uint32_t radius = 1;

	(void)values, (void)err, (void)errlen;
	*state = NULL;
	return host->filter_passes(host->ctx, 1, &radius);
}

static void
one_pass_run(void *state, const struct rf_span *span)
{
	(void)state, (void)span; /* never run: no frame is filtered here */
}

static void
one_pass_destroy(void *state)
{
	(void)state;
}

/* A filter's mode declares its passes to the host's own table: the
 * library refuses a table of the caller's (it would have taken them
 * where the filter cannot see, and crashed), and takes the host's. */
TEST(filter_needs_the_hosts_table)
{
	static const char *const none[] = { NULL };
	static const struct rf_plugin one_pass = {
		RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
		RF_KIND_FILTER, 0, "one_pass", "test: declares one pass", "1.0", "reflect tests",
		"MIT", 0, NULL, none, none, one_pass_create, one_pass_run, one_pass_destroy,
	};
	struct rf_host own;
	rf_plugin_host *h;
	rf_filter *f = NULL;
	char err[256] = "";

	memset(&own, 0, sizeof(own));
	own.size = sizeof(own);
	own.abi_major = RF_PLUGIN_ABI_MAJOR;
	own.abi_minor = RF_PLUGIN_ABI_MINOR;
	ASSERT_EQ(rf_filter_create(&f, &one_pass, NULL, &own, 1, NULL, err, sizeof(err)), RF_EINVAL);
	ASSERT(f == NULL);
	ASSERT(strstr(err, "rf_plugin_host_table") != NULL);
	ASSERT_EQ(rf_plugin_host_create(&h), 0);
	ASSERT_EQ(rf_filter_create(&f, &one_pass, NULL, rf_plugin_host_table(h), 2, NULL, err,
	                           sizeof(err)), 0);
	ASSERT_EQ(rf_filter_passes(f), 1);
	ASSERT_EQ(rf_filter_reach(f), 1);
	rf_filter_destroy(f);
	rf_plugin_host_destroy(h);
}

int
main(void)
{
	RUN(table_follows_the_settings);
	RUN(rays_leave_the_box);
	RUN(rays_leave_the_rounded_box);
	RUN(environment_geometry);
	RUN(pixel_footprint_by_hand);
	RUN(random_pairs_of_the_host);
	RUN(probe_list_and_weights);
	RUN(radiance_reads_plain_levels);
	RUN(filter_needs_the_hosts_table);
	TAP_DONE();
}
