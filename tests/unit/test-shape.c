/*
 * Probe shapes: the sphere's exit against the analytic root in double
 * precision, an oriented box against the axis-aligned box turned with
 * the ray, the host's Jacobian against the solid angles it maps, the
 * blend weights inside turned boxes and spheres, the header keys both
 * ways, and every refusal.  Rotations here are built from an axis and
 * an angle (Rodrigues), not from the library's Euler angles, except
 * where those are the subject.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "reflect/host.h"
#include "reflect/probe.h"
#include "reflect/reflect.h"
#include "probe/shape.h"
#include "tap.h"

static char msg[512];

/* A fixed stream of numbers in [0, 1). */
static uint64_t rng = 0x9E3779B97F4A7C15ull;

static double
uniform(void)
{
	rng = rng * 6364136223846793005ull + 1442695040888963407ull;
	return (double)(rng >> 11) / 9007199254740992.0;
}

static void
random_unit(float d[3])
{
	double z = 2.0 * uniform() - 1.0, phi = 2.0 * M_PI * uniform(), s = sqrt(1.0 - z * z);

	d[0] = (float)(s * cos(phi));
	d[1] = (float)(s * sin(phi));
	d[2] = (float)z;
}

/* Rotation by angle (degrees) about a unit axis, row-major. */
static void
axis_angle(const double axis[3], double deg, double m[9])
{
	double a = deg * M_PI / 180.0, c = cos(a), s = sin(a), t = 1.0 - c;
	double x = axis[0], y = axis[1], z = axis[2];

	m[0] = t * x * x + c, m[1] = t * x * y - s * z, m[2] = t * x * z + s * y;
	m[3] = t * x * y + s * z, m[4] = t * y * y + c, m[5] = t * y * z - s * x;
	m[6] = t * x * z - s * y, m[7] = t * y * z + s * x, m[8] = t * z * z + c;
}

static void
turn(const double m[9], const double c[3], const float p[3], float out[3], int point)
{
	double v[3] = { p[0] - (point ? c[0] : 0.0), p[1] - (point ? c[1] : 0.0),
		        p[2] - (point ? c[2] : 0.0) };
	int i;

	for (i = 0; i < 3; i++)
		out[i] = (float)(m[3 * i] * v[0] + m[3 * i + 1] * v[1] + m[3 * i + 2] * v[2] +
		                 (point ? c[i] : 0.0));
}

static void
box_probe(struct rf_probe *p, float x0, float y0, float z0, float x1, float y1, float z1)
{
	memset(p, 0, sizeof(*p));
	p->box_min[0] = x0, p->box_min[1] = y0, p->box_min[2] = z0;
	p->box_max[0] = x1, p->box_max[1] = y1, p->box_max[2] = z1;
	p->center[0] = 0.5f * (x0 + x1), p->center[1] = 0.5f * (y0 + y1);
	p->center[2] = 0.5f * (z0 + z1);
	p->box_projection = 1;
	p->shape = RF_SHAPE_BOX;
}

/* 2000 rays from inside a sphere: the exit within 2e-6 of the radius of
 * the root found in double precision. */
TEST(sphere_exit_is_the_analytic_root)
{
	struct rf_probe probe;
	struct rf__proxy x;
	double worst = 0.0;
	int i;

	box_probe(&probe, -1.0f, 0.5f, 2.0f, 3.0f, 4.5f, 6.0f); /* radius 2 at (1, 2.5, 4) */
	probe.shape = RF_SHAPE_SPHERE;
	x = rf__proxy_of_probe(&probe);
	for (i = 0; i < 2000; i++) {
		float p[3], d[3], t;
		double o[3], b = 0.0, c = -4.0, ref, r = 2.0 * cbrt(uniform());
		int k;

		random_unit(p);
		random_unit(d);
		for (k = 0; k < 3; k++) {
			p[k] = (float)((double)x.sc[k] + r * p[k]);
			o[k] = (double)p[k] - x.sc[k];
			b += o[k] * d[k];
			c += o[k] * o[k];
		}
		/* d is unit to float rounding: take its length into a */
		{
			double a = (double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2];

			ref = (-b + sqrt(b * b - a * c)) / a;
		}
		ASSERT_EQ(rf__proxy_exit(&x, p, d, &t), 0);
		worst = fmax(worst, fabs(t - ref));
	}
	ASSERT(worst <= 2e-6 * 2.0);
	/* from the centre every exit is the radius; from outside, none */
	{
		float c[3] = { 1.0f, 2.5f, 4.0f }, d[3] = { 0.0f, 0.6f, -0.8f }, t;
		float out[3] = { 1.0f, 2.5f, 6.1f };

		ASSERT_EQ(rf__proxy_exit(&x, c, d, &t), 0);
		ASSERT_NEAR(t, 2.0, 1e-6);
		ASSERT_EQ(rf__proxy_exit(&x, out, d, &t), -1);
	}
}

/* The box turned about its centre, with the ray turned the same way:
 * the same exit, 2000 times; and turned by nothing it is the box to the
 * bit. */
TEST(oriented_box_turns_with_the_ray)
{
	const double axis[3] = { 0.267261241912424, 0.534522483824849, 0.801783725737273 };
	const double c[3] = { 0.5, 1.5, 0.0 };
	struct rf_probe aligned, turned;
	struct rf__proxy a, b;
	double m[9], worst = 0.0;
	int i, k;

	box_probe(&aligned, -2.5f, 0.0f, -1.0f, 3.5f, 3.0f, 1.0f);
	turned = aligned;
	axis_angle(axis, 30.0, m);
	turned.rotated = 1;
	for (k = 0; k < 9; k++)
		turned.rotation[k] = (float)m[k];
	a = rf__proxy_of_probe(&aligned);
	b = rf__proxy_of_probe(&turned);
	for (i = 0; i < 2000; i++) {
		float p[3], d[3], tp[3], td[3], t0, t1;

		p[0] = (float)(-2.5 + 6.0 * uniform());
		p[1] = (float)(3.0 * uniform());
		p[2] = (float)(-1.0 + 2.0 * uniform());
		random_unit(d);
		turn(m, c, p, tp, 1);
		turn(m, c, d, td, 0);
		ASSERT_EQ(rf__proxy_exit(&a, p, d, &t0), 0);
		ASSERT_EQ(rf__proxy_exit(&b, tp, td, &t1), 0);
		worst = fmax(worst, fabs((double)t1 - t0) / fmax(1.0, t0));
	}
	ASSERT(worst <= 2e-5);
	/* a point inside the axis-aligned box but outside the turned one */
	{
		float p[3] = { 3.4f, 2.9f, 0.9f }, d[3] = { 1.0f, 0.0f, 0.0f }, t;

		ASSERT_EQ(rf__proxy_exit(&a, p, d, &t), 0);
		ASSERT_EQ(rf__proxy_exit(&b, p, d, &t), -1);
	}
}

static void
header_with_box(rf_header **h, const char *box)
{
	rf_header_create(h);
	rf_header_set_size(*h, 1, 1);
	rf_header_set_channels(*h, "P.X");
	rf_header_set(*h, RF_KEY_PROBE_BOX, box);
}

/* A rotation of nothing, as angles or as the identity, is no rotation:
 * the probe is the axis-aligned box, field for field. */
TEST(zero_rotation_is_the_box)
{
	static const char *const zero[] = { "0 0 0", "1 0 0 0 1 0 0 0 1", "0,0,0" };
	struct rf_probe plain, probe;
	rf_header *h;
	size_t i;

	header_with_box(&h, "-3 0 -2 3 3 2");
	ASSERT_EQ(rf_probe_resolve(&plain, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	for (i = 0; i < sizeof(zero) / sizeof(*zero); i++) {
		ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_ROTATION, zero[i]), 0);
		ASSERT_EQ(rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
		ASSERT_EQ(probe.rotated, 0);
		ASSERT_EQ(memcmp(&probe, &plain, offsetof(struct rf_probe, rotation)), 0);
	}
	rf_header_destroy(h);
}

/* Angles are Unity's order: y 90 takes +z to +x; x 90 takes +y to +z;
 * z 90 takes +x to +y; and (x 90, y 90) is y after x. */
TEST(euler_angles_by_hand)
{
	struct rf_probe probe;
	rf_header *h;

	header_with_box(&h, "-1 -1 -1 1 1 1");
	ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_ROTATION, "0 90 0"), 0);
	ASSERT_EQ(rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	/* column 2 (the image of +z) is (1, 0, 0) */
	ASSERT_NEAR(probe.rotation[2], 1, 1e-7);
	ASSERT_NEAR(probe.rotation[5], 0, 1e-7);
	ASSERT_NEAR(probe.rotation[8], 0, 1e-7);
	ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_ROTATION, "90 0 0"), 0);
	ASSERT_EQ(rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	ASSERT_NEAR(probe.rotation[7], 1, 1e-7); /* +y to +z */
	ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_ROTATION, "0 0 90"), 0);
	ASSERT_EQ(rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	ASSERT_NEAR(probe.rotation[3], 1, 1e-7); /* +x to +y */
	/* x then y: +y goes to +z, then to +x */
	ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_ROTATION, "90 90 0"), 0);
	ASSERT_EQ(rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	ASSERT_NEAR(probe.rotation[1], 1, 1e-7);
	rf_header_destroy(h);
}

/* Written and read back: the same probe to the bit. */
TEST(keys_round_trip)
{
	const double axis[3] = { 0.0, 0.6, 0.8 };
	struct rf_probe probe, back;
	rf_header *h;
	double m[9];
	int k;

	box_probe(&probe, -2.0f, 0.0f, -2.0f, 2.0f, 4.0f, 2.0f);
	probe.shape = RF_SHAPE_SPHERE;
	probe.center[1] = 1.25f;
	probe.proxy_shape = RF_SHAPE_BOX;
	probe.proxy_min[0] = -3.0f, probe.proxy_min[1] = 0.0f, probe.proxy_min[2] = -2.5f;
	probe.proxy_max[0] = 3.0f, probe.proxy_max[1] = 3.0f, probe.proxy_max[2] = 2.5f;
	axis_angle(axis, 17.0, m);
	probe.proxy_rotated = 1;
	for (k = 0; k < 9; k++)
		probe.proxy_rotation[k] = (float)m[k];
	ASSERT_EQ(rf_header_create(&h), 0);
	ASSERT_EQ(rf_probe_to_header(&probe, h), 0);
	ASSERT_STR_EQ(rf_header_get(h, RF_KEY_PROBE_SHAPE), "sphere");
	ASSERT_STR_EQ(rf_header_get(h, RF_KEY_PROBE_PROXY), "box");
	ASSERT(rf_header_get(h, RF_KEY_PROBE_ROTATION) == NULL);
	ASSERT_EQ(rf_probe_resolve(&back, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	ASSERT_EQ(memcmp(&back, &probe, sizeof(probe)), 0);
	/* the other way: a turned box projected onto nothing */
	memset(&probe.proxy_min, 0, sizeof(float) * 6);
	memset(&probe.proxy_rotation, 0, sizeof(probe.proxy_rotation));
	probe.proxy_rotated = 0;
	probe.proxy_shape = RF_SHAPE_INFINITE;
	probe.shape = RF_SHAPE_BOX;
	probe.rotated = 1;
	for (k = 0; k < 9; k++)
		probe.rotation[k] = (float)m[k];
	ASSERT_EQ(rf_probe_to_header(&probe, h), 0);
	ASSERT(rf_header_get(h, RF_KEY_PROBE_SHAPE) == NULL);
	ASSERT(rf_header_get(h, RF_KEY_PROBE_PROXY_BOX) == NULL);
	ASSERT_STR_EQ(rf_header_get(h, RF_KEY_PROBE_PROXY), "infinite");
	ASSERT_EQ(rf_probe_resolve(&back, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	ASSERT_EQ(memcmp(&back, &probe, sizeof(probe)), 0);
	rf_header_destroy(h);
}

static int
refused(const char *box, const char *key, const char *value, const char *key2,
        const char *value2, const char *want)
{
	struct rf_probe probe;
	rf_header *h;
	int ok;

	header_with_box(&h, box);
	rf_header_set(h, key, value);
	if (key2)
		rf_header_set(h, key2, value2);
	msg[0] = '\0';
	ok = rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)) == RF_EINVAL &&
	     strstr(msg, want) != NULL;
	if (!ok)
		printf("# for %s=%s: '%s'\n", key, value, msg);
	rf_header_destroy(h);
	return ok;
}

TEST(bad_keys_are_refused_by_name)
{
	const char *cube = "-1 -1 -1 1 1 1";

	ASSERT(refused(cube, RF_KEY_PROBE_ROTATION, "1 0 0 0 1 0 0 0 0", NULL, NULL,
	               "PROBE_ROTATION: '1 0 0 0 1 0 0 0 0' is not a rotation"));
	ASSERT(refused(cube, RF_KEY_PROBE_ROTATION, "2 0 0 0 2 0 0 0 2", NULL, NULL,
	               "is not a rotation"));
	ASSERT(refused(cube, RF_KEY_PROBE_ROTATION, "-1 0 0 0 1 0 0 0 1", NULL, NULL,
	               "is a reflection"));
	ASSERT(refused(cube, RF_KEY_PROBE_ROTATION, "10 20", NULL, NULL,
	               "needs 9 numbers (a row-major matrix) or 3 angles in degrees"));
	ASSERT(refused(cube, RF_KEY_PROBE_ROTATION, "nan 0 0", NULL, NULL, "needs 9 numbers"));
	ASSERT(refused(cube, RF_KEY_PROBE_SHAPE, "cone", NULL, NULL,
	               "PROBE_SHAPE: 'cone' is not a shape: box or sphere"));
	ASSERT(refused("-1 -1 -1 1 1 2", RF_KEY_PROBE_SHAPE, "sphere", NULL, NULL,
	               "bounding cube"));
	ASSERT(refused(cube, RF_KEY_PROBE_SHAPE, "sphere", RF_KEY_PROBE_ROTATION, "0 30 0",
	               "a sphere has no rotation"));
	ASSERT(refused(cube, RF_KEY_PROBE_PROXY, "box", NULL, NULL,
	               "PROBE_PROXY_BOX is missing"));
	ASSERT(refused(cube, RF_KEY_PROBE_PROXY, "sphere", RF_KEY_PROBE_PROXY_BOX,
	               "0 0 0 -1 1 1", "the box is empty on axis X"));
	ASSERT(refused(cube, RF_KEY_PROBE_PROXY, "torus", NULL, NULL,
	               "is not a proxy: box, sphere or infinite"));
	ASSERT(refused(cube, RF_KEY_PROBE_PROXY_BOX, "-2 -2 -2 2 2 2", NULL, NULL,
	               "no proxy of its own"));
	ASSERT(refused(cube, RF_KEY_PROBE_PROXY, "infinite", RF_KEY_PROBE_PROXY_ROTATION,
	               "0 10 0", "only a proxy box turns"));
	ASSERT(refused(cube, RF_KEY_PROBE_SHAPE, "sphere", RF_KEY_PROBE_BEVEL, "0.25",
	               "its proxy is no box"));
}

/* The host's Jacobian, dw at the capture point per dw at p, against the
 * areas of two small triangles of directions: the rays' and the
 * lookups' (a brute-force solid angle ratio). */
static double
jacobian_error(const struct rf_probe *probe, int n, int *used)
{
	rf_plugin_host *host;
	const struct rf_host *t;
	double worst = 0.0;
	int i;

	*used = 0;
	rf_plugin_host_create(&host);
	rf_plugin_host_set_probe(host, probe);
	t = rf_plugin_host_table(host);
	for (i = 0; i < n; i++) {
		float p[3], dirs[9], look[9], dist[3], jac[3], u[3], v[3], e = 1e-3f;
		double a0[3], a1[3], c0[3], c1[3], area_p, area_c;
		int k;

		for (k = 0; k < 3; k++)
			p[k] = probe->center[k] + (float)(0.6 * (uniform() - 0.5)) *
			                              (probe->box_max[k] - probe->box_min[k]);
		random_unit(dirs);
		/* two directions a small step off it */
		u[0] = -dirs[1], u[1] = dirs[0], u[2] = 0.0f;
		v[0] = dirs[1] * u[2] - dirs[2] * u[1];
		v[1] = dirs[2] * u[0] - dirs[0] * u[2];
		v[2] = dirs[0] * u[1] - dirs[1] * u[0];
		for (k = 0; k < 3; k++) {
			dirs[3 + k] = dirs[k] + e * u[k];
			dirs[6 + k] = dirs[k] + e * v[k];
		}
		for (k = 3; k < 9; k += 3) {
			float l = sqrtf(dirs[k] * dirs[k] + dirs[k + 1] * dirs[k + 1] +
			                dirs[k + 2] * dirs[k + 2]);

			dirs[k] /= l, dirs[k + 1] /= l, dirs[k + 2] /= l;
		}
		t->project_rays(t->ctx, 3, p, dirs, look, dist, jac);
		if (!(dist[0] < INFINITY))
			continue;
		for (k = 0; k < 3; k++) {
			a0[k] = dirs[3 + k] - dirs[k], a1[k] = dirs[6 + k] - dirs[k];
			c0[k] = look[3 + k] - look[k], c1[k] = look[6 + k] - look[k];
		}
		area_p = sqrt(pow(a0[1] * a1[2] - a0[2] * a1[1], 2) +
		              pow(a0[2] * a1[0] - a0[0] * a1[2], 2) +
		              pow(a0[0] * a1[1] - a0[1] * a1[0], 2));
		area_c = sqrt(pow(c0[1] * c1[2] - c0[2] * c1[1], 2) +
		              pow(c0[2] * c1[0] - c0[0] * c1[2], 2) +
		              pow(c0[0] * c1[1] - c0[1] * c1[0], 2));
		/* the three rays must leave by one face for a plain ratio */
		if (area_c / area_p > 50.0 || area_c / area_p < 0.02)
			continue;
		worst = fmax(worst, fabs(area_c / area_p - jac[0]) / jac[0]);
		++*used;
	}
	rf_plugin_host_destroy(host);
	return worst;
}

TEST(jacobian_is_the_solid_angle_ratio)
{
	const double axis[3] = { 0.6, 0.0, 0.8 };
	struct rf_probe probe;
	double m[9];
	int k, used;

	box_probe(&probe, -2.0f, -2.0f, -2.0f, 2.0f, 2.0f, 2.0f);
	probe.center[0] = 0.5f;
	probe.shape = RF_SHAPE_SPHERE;
	ASSERT(jacobian_error(&probe, 300, &used) < 0.02);
	ASSERT(used > 250);
	box_probe(&probe, -3.0f, 0.0f, -2.0f, 3.0f, 3.0f, 2.0f);
	probe.center[1] = 1.0f;
	axis_angle(axis, 25.0, m);
	probe.rotated = 1;
	for (k = 0; k < 9; k++)
		probe.rotation[k] = (float)m[k];
	ASSERT(jacobian_error(&probe, 300, &used) < 0.02);
	ASSERT(used > 150);
}

/* A proxy unlike the influence moves the lookups and not the weights;
 * an influence unlike the proxy moves the weights and not the lookups. */
TEST(proxy_and_influence_apart)
{
	struct rf_probe a, b;
	struct rf_blend blend_a, blend_b;
	rf_plugin_host *ha, *hb;
	const float p[3] = { 1.9f, 1.0f, 0.3f }, dir[3] = { 0.6f, 0.0f, 0.8f };
	float la[3], lb[3], da, db, ja, jb, wa, wb;

	box_probe(&a, -2.0f, 0.0f, -2.0f, 2.0f, 3.0f, 2.0f);
	b = a;
	b.proxy_shape = RF_SHAPE_SPHERE;
	b.proxy_min[0] = -3.0f, b.proxy_min[1] = -1.5f, b.proxy_min[2] = -3.0f;
	b.proxy_max[0] = 3.0f, b.proxy_max[1] = 4.5f, b.proxy_max[2] = 3.0f;
	memset(&blend_a, 0, sizeof(blend_a));
	blend_a.nprobes = 1;
	blend_a.face_blend[0][0] = 0.5f;
	blend_b = blend_a;
	blend_a.probes[0] = a;
	blend_b.probes[0] = b;
	rf_blend_order(&blend_a);
	rf_blend_order(&blend_b);
	rf_blend_weights(&blend_a, p, NULL, &wa);
	rf_blend_weights(&blend_b, p, NULL, &wb);
	ASSERT_NEAR(wa, 0.104, 1e-6); /* sat(0.1 / 0.5) = 0.2, smoothstepped */
	ASSERT(wa == wb);
	rf_plugin_host_create(&ha);
	rf_plugin_host_create(&hb);
	rf_plugin_host_set_probe(ha, &a);
	rf_plugin_host_set_probe(hb, &b);
	rf_plugin_host_table(ha)->project_rays(ha, 1, p, dir, la, &da, &ja);
	rf_plugin_host_table(hb)->project_rays(hb, 1, p, dir, lb, &db, &jb);
	ASSERT(fabsf(da - db) > 0.1f);
	/* the other way: the influence a sphere, the proxy the same box */
	b = a;
	b.shape = RF_SHAPE_SPHERE;
	b.box_min[1] = -0.5f, b.box_max[1] = 3.5f;
	b.proxy_shape = RF_SHAPE_BOX;
	memcpy(b.proxy_min, a.box_min, sizeof(a.box_min));
	memcpy(b.proxy_max, a.box_max, sizeof(a.box_max));
	rf_plugin_host_set_probe(hb, &b);
	rf_plugin_host_table(hb)->project_rays(hb, 1, p, dir, lb, &db, &jb);
	ASSERT(da == db && la[0] == lb[0] && la[1] == lb[1] && la[2] == lb[2]);
	blend_b.probes[0] = b;
	rf_blend_weights(&blend_b, p, NULL, &wb);
	/* (1.9, 1, 0.3) is 1.98746 from the sphere's centre (0, 1.5, 0):
	 * 0.0125 inside, over the widest blend distance 0.5 */
	{
		double x = (2.0 - sqrt(1.9 * 1.9 + 0.25 + 0.09)) / 0.5;

		ASSERT_NEAR(wb, x * x * (3.0 - 2.0 * x), 1e-6);
		ASSERT(fabs(wb - wa) > 0.1);
	}
	rf_plugin_host_destroy(ha);
	rf_plugin_host_destroy(hb);
}

/* Weights inside a box turned 45 degrees about y, and inside a sphere. */
TEST(weights_follow_the_shape)
{
	struct rf_blend b;
	float w;
	/* inside the box unturned, 1.98 along the turned box's local z */
	const float corner[3] = { 1.9f, 1.0f, 0.9f };
	const float on_axis[3] = { 1.3f, 1.0f, -1.3f }; /* 1.838 along its local x */
	const float s = (float)M_SQRT1_2;
	int f;

	memset(&b, 0, sizeof(b));
	b.nprobes = 1;
	box_probe(&b.probes[0], -2.0f, 0.0f, -1.0f, 2.0f, 2.0f, 1.0f);
	b.probes[0].rotated = 1;
	/* y 45: local x goes to (s, 0, -s), local z to (s, 0, s) */
	b.probes[0].rotation[0] = s, b.probes[0].rotation[2] = s;
	b.probes[0].rotation[4] = 1.0f;
	b.probes[0].rotation[6] = -s, b.probes[0].rotation[8] = s;
	for (f = 0; f < 6; f++)
		b.face_blend[0][f] = 0.5f;
	rf_blend_order(&b);
	rf_blend_weights(&b, corner, NULL, &w);
	ASSERT(w == 0.0f);
	rf_blend_weights(&b, on_axis, NULL, &w);
	/* local (1.838, 0, 0) from the centre: 0.162 from the +x face,
	 * sat(0.162 / 0.5) smoothstepped; an unturned box would give 0 */
	{
		double x = (2.0 - 1.3 * sqrt(2.0)) / 0.5;

		ASSERT_NEAR(w, x * x * (3.0 - 2.0 * x), 2e-5);
	}
	/* a sphere of radius 2 with blend 0.5: 1 at its centre, 0.5 at 1.75 */
	box_probe(&b.probes[0], -2.0f, -2.0f, -2.0f, 2.0f, 2.0f, 2.0f);
	b.probes[0].shape = RF_SHAPE_SPHERE;
	{
		const float c[3] = { 0.0f, 0.0f, 0.0f }, half[3] = { 0.0f, 1.75f, 0.0f };
		const float out[3] = { 1.5f, 1.5f, 0.0f };

		rf_blend_weights(&b, c, NULL, &w);
		ASSERT_NEAR(w, 1.0, 0);
		rf_blend_weights(&b, half, NULL, &w);
		ASSERT_NEAR(w, 0.5, 1e-6);
		rf_blend_weights(&b, out, NULL, &w); /* inside the cube, not the sphere */
		ASSERT(w == 0.0f);
	}
}

int
main(void)
{
	RUN(sphere_exit_is_the_analytic_root);
	RUN(oriented_box_turns_with_the_ray);
	RUN(zero_rotation_is_the_box);
	RUN(euler_angles_by_hand);
	RUN(keys_round_trip);
	RUN(bad_keys_are_refused_by_name);
	RUN(jacobian_is_the_solid_angle_ratio);
	RUN(proxy_and_influence_apart);
	RUN(weights_follow_the_shape);
	TAP_DONE();
}
