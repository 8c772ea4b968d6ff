/* Unit tests of meshes through the scene's ray casting structure (Embree):
 * a tessellated sphere against the analytic one within its tessellation's
 * bound, a quad against a rectangle, interpolation and texture sampling
 * against values worked out by hand, determinism across threads, and
 * meshes refused. */
#include <stdint.h>

#include "scene/accel.h"
#include "reflect/envmap.h"
#include "reflect/scene.h"
#include "tap.h"

static const double PI = 3.14159265358979323846;

/* A room far away: rays here meet what the test puts in front of them,
 * or nothing. */
#define AWAY "probe box 100 100 100 101 101 101\n"

static rf_scene *
parse(const char *text)
{
	char err[512] = "";
	rf_scene *s = NULL;

	if (rf_scene_parse(&s, text, strlen(text), "test.scene", err, sizeof(err)) < 0)
		printf("# parse: %s\n", err);
	return s;
}

/* A mesh of n vertices and t triangles, one material (the objects'
 * default: white metal, roughness 0.5, reflective); its arrays zeroed. */
static struct rf__mesh
mesh_new(size_t nv, size_t nt, size_t line)
{
	struct rf__mesh m;

	memset(&m, 0, sizeof(m));
	m.line = line;
	m.path = strdup("test.glb");
	m.nvertices = nv;
	m.ntriangles = nt;
	m.positions = calloc(3 * nv, sizeof(float));
	m.normals = calloc(3 * nv, sizeof(float));
	m.tangents = calloc(4 * nv, sizeof(float));
	m.uv[0] = calloc(2 * nv, sizeof(float));
	m.indices = calloc(3 * nt, sizeof(uint32_t));
	m.material = calloc(nt, sizeof(uint32_t));
	m.nmaterials = 1;
	m.materials = calloc(1, sizeof(*m.materials));
	m.materials[0].name = strdup("default");
	m.materials[0].base_colour[0] = m.materials[0].base_colour[1] = 1.0f;
	m.materials[0].base_colour[2] = m.materials[0].base_colour[3] = 1.0f;
	m.materials[0].metallic = 1.0f;
	m.materials[0].roughness = 0.5f;
	m.materials[0].normal_scale = 1.0f;
	m.materials[0].mask = 1.0f;
	return m;
}

static void
set3(float *v, size_t i, double x, double y, double z)
{
	v[3 * i] = (float)x;
	v[3 * i + 1] = (float)y;
	v[3 * i + 2] = (float)z;
}

/* Tangents along +x projected off the normal (any frame does here). */
static void
fill_tangents(struct rf__mesh *m)
{
	size_t i;

	for (i = 0; i < m->nvertices; i++) {
		const float *n = m->normals + 3 * i;
		float t[3] = { 1.0f - n[0] * n[0], -n[0] * n[1], -n[0] * n[2] }, len;

		len = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
		if (len < 1e-3f) {
			t[0] = -n[1] * n[0];
			t[1] = 1.0f - n[1] * n[1];
			t[2] = -n[1] * n[2];
			len = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
		}
		m->tangents[4 * i] = t[0] / len;
		m->tangents[4 * i + 1] = t[1] / len;
		m->tangents[4 * i + 2] = t[2] / len;
		m->tangents[4 * i + 3] = 1.0f;
	}
}

/* An icosphere: the icosahedron's faces split `levels` times, vertices
 * pushed onto the sphere; normals radial.  Every triangle is acute. */
static struct rf__mesh
icosphere(const double c[3], double r, int levels, size_t line)
{
	static const int faces[20][3] = {
		{ 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
		{ 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 },
		{ 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 },
		{ 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 }
	};
	const double g = (1.0 + sqrt(5.0)) / 2.0;
	const double base[12][3] = {
		{ -1, g, 0 }, { 1, g, 0 }, { -1, -g, 0 }, { 1, -g, 0 },
		{ 0, -1, g }, { 0, 1, g }, { 0, -1, -g }, { 0, 1, -g },
		{ g, 0, -1 }, { g, 0, 1 }, { -g, 0, -1 }, { -g, 0, 1 }
	};
	/* Every face split into n^2 by a grid of its barycentric lattice:
	 * vertices duplicated along the edges (a triangle soup per face). */
	const size_t n = (size_t)1 << levels, per_face_v = (n + 1) * (n + 2) / 2;
	struct rf__mesh m = mesh_new(20 * per_face_v, 20 * n * n, line);
	size_t f, i, j, v = 0, t = 0;

	for (f = 0; f < 20; f++) {
		const size_t first = v;

		for (i = 0; i <= n; i++)
			for (j = 0; j <= n - i; j++) {
				double p[3], len = 0;
				int k;

				for (k = 0; k < 3; k++) {
					p[k] = (base[faces[f][0]][k] * (double)(n - i - j) +
					        base[faces[f][1]][k] * (double)i +
					        base[faces[f][2]][k] * (double)j) / (double)n;
					len += p[k] * p[k];
				}
				len = sqrt(len);
				set3(m.normals, v, p[0] / len, p[1] / len, p[2] / len);
				set3(m.positions, v, c[0] + r * p[0] / len, c[1] + r * p[1] / len,
				     c[2] + r * p[2] / len);
				v++;
			}
#define IDX(a, b) (first + (a) * (n + 1) - (a) * ((a) - 1) / 2 + (b))
		for (i = 0; i < n; i++)
			for (j = 0; j < n - i; j++) {
				m.indices[3 * t] = (uint32_t)IDX(i, j);
				m.indices[3 * t + 1] = (uint32_t)IDX(i + 1, j);
				m.indices[3 * t + 2] = (uint32_t)IDX(i, j + 1);
				t++;
				if (j + 1 < n - i) {
					m.indices[3 * t] = (uint32_t)IDX(i + 1, j);
					m.indices[3 * t + 1] = (uint32_t)IDX(i + 1, j + 1);
					m.indices[3 * t + 2] = (uint32_t)IDX(i, j + 1);
					t++;
				}
			}
#undef IDX
	}
	m.ntriangles = t;
	fill_tangents(&m);
	return m;
}

static int
add(rf_scene *s, struct rf__mesh *m)
{
	char err[512] = "";
	int rc = rf__scene_add_mesh(s, m, err, sizeof(err));

	if (rc < 0)
		printf("# add mesh: %s\n", err);
	return rc;
}

static double
angle_between(const double a[3], const float b[3])
{
	double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
	double lb = sqrt((double)b[0] * b[0] + (double)b[1] * b[1] + (double)b[2] * b[2]);
	double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);

	return acos(c > 1 ? 1 : c < -1 ? -1 : c);
}

TEST(tessellated_sphere_within_its_sagitta)
{
	/* Rays toward the centre from 3 units out, along 2000 spread
	 * directions: the analytic sphere is met at t = 2 exactly.  The mesh
	 * has its vertices on the sphere, so its triangles lie inside it: an
	 * acute triangle's plane is r cos(rho) from the centre, rho its
	 * circumscribed cap's angular radius, and a chord c = 2 r sin(a/2)
	 * gives sin(rho) <= c / (r sqrt 3).  So 0 <= t_mesh - 2 <=
	 * r (1 - cos rho) (the sagitta), plus float's rounding of the
	 * vertices. */
	const double c[3] = { 0.25, 1.5, -0.5 }, r = 1.0;
	rf_scene *sm = parse(AWAY "camera position 0 1.5 5 target 0 1.5 0\n");
	rf_scene *sa = parse(AWAY "camera position 0 1.5 5 target 0 1.5 0\n"
	                     "sphere center 0.25 1.5 -0.5 radius 1\n");
	struct rf__mesh m = icosphere(c, r, 3, 4);
	double amax = 0, sin_rho, bound, worst = 0, worst_n = 0;
	size_t i, k, misses = 0;

	ASSERT(sm && sa);
	for (i = 0; i < m.ntriangles; i++)
		for (k = 0; k < 3; k++) {
			const float *p = m.normals + 3 * m.indices[3 * i + k];
			const float *q = m.normals + 3 * m.indices[3 * i + (k + 1) % 3];
			double a = acos((double)p[0] * q[0] + (double)p[1] * q[1] +
			                (double)p[2] * q[2]);

			amax = a > amax ? a : amax;
		}
	sin_rho = 2.0 * sin(amax / 2.0) / sqrt(3.0);
	bound = r * (1.0 - sqrt(1.0 - sin_rho * sin_rho));
	printf("# 1280 triangles, max edge angle %.4f rad, sagitta bound %.6f\n", amax,
	       bound);
	ASSERT_EQ(add(sm, &m), 0);
	for (i = 0; i < 2000; i++) {
		/* a Fibonacci spiral of directions */
		const double z = 1.0 - (2.0 * (double)i + 1.0) / 2000.0;
		const double phi = (double)i * PI * (3.0 - sqrt(5.0)), s = sqrt(1.0 - z * z);
		const double n[3] = { s * cos(phi), s * sin(phi), z };
		const double o[3] = { c[0] + 3 * n[0], c[1] + 3 * n[1], c[2] + 3 * n[2] };
		const double d[3] = { -n[0], -n[1], -n[2] };
		struct rf_hit hm, ha;
		float nf[3];

		ASSERT_EQ(rf_scene_trace(sa, o, d, &ha), 1);
		ASSERT_NEAR(ha.t, 2.0, 1e-12);
		if (rf_scene_trace(sm, o, d, &hm) != 1) {
			misses++;
			continue;
		}
		ASSERT(hm.t >= ha.t - 1e-6);
		ASSERT(hm.t - ha.t <= bound + 1e-6);
		worst = hm.t - ha.t > worst ? hm.t - ha.t : worst;
		/* P on the ray, exactly as o + t d */
		for (k = 0; k < 3; k++)
			ASSERT(hm.P[k] == o[k] + hm.t * d[k]);
		/* the interpolated normal within the largest edge angle */
		for (k = 0; k < 3; k++)
			nf[k] = (float)hm.N[k];
		ASSERT(angle_between(n, nf) <= amax);
		worst_n = angle_between(n, nf) > worst_n ? angle_between(n, nf) : worst_n;
		ASSERT(hm.Ng[0] * n[0] + hm.Ng[1] * n[1] + hm.Ng[2] * n[2] > 0.9);
		ASSERT(hm.mask == 1.0f && hm.metallic == 1.0f && hm.roughness == 0.5f);
	}
	printf("# worst distance error %.6f (bound %.6f), worst normal %.4f rad\n", worst,
	       bound, worst_n);
	ASSERT_EQ(misses, 0);
	/* the bound is tight: the worst ray comes within a third of it */
	ASSERT(worst > bound / 3);
	rf_scene_destroy(sm);
	rf_scene_destroy(sa);
}

/* Two triangles spanning the rectangle x in [-1, 1], y in [0.5, 1.5] at
 * z = -1, facing +z; u along +x, v down the image (glTF's). */
static struct rf__mesh
quad(size_t line)
{
	struct rf__mesh m = mesh_new(4, 2, line);
	static const uint32_t ix[6] = { 0, 1, 2, 0, 2, 3 };
	size_t i;

	set3(m.positions, 0, -1, 0.5, -1);
	set3(m.positions, 1, 1, 0.5, -1);
	set3(m.positions, 2, 1, 1.5, -1);
	set3(m.positions, 3, -1, 1.5, -1);
	for (i = 0; i < 4; i++) {
		set3(m.normals, i, 0, 0, 1);
		m.tangents[4 * i] = 1.0f;
		m.tangents[4 * i + 3] = 1.0f;
		m.uv[0][2 * i] = i == 1 || i == 2 ? 1.0f : 0.0f;
		m.uv[0][2 * i + 1] = i >= 2 ? 0.0f : 1.0f;
	}
	memcpy(m.indices, ix, sizeof(ix));
	return m;
}

/* The quad at depth z, its second triangle (above the diagonal
 * y = 1 + x / 2) a mirror: two materials, matte and mirror. */
static struct rf__mesh
half_mirror_quad(size_t line, float z)
{
	struct rf__mesh m = quad(line);
	int i;

	for (i = 0; i < 4; i++)
		m.positions[3 * i + 2] = z;
	free(m.materials[0].name);
	free(m.materials);
	m.nmaterials = 2;
	m.materials = calloc(2, sizeof(*m.materials));
	m.materials[0].name = strdup("matte");
	m.materials[1].name = strdup("mirror");
	m.materials[1].mask = 1.0f;
	m.material[1] = 1;
	return m;
}

TEST(quad_mesh_as_a_rect)
{
	/* The rectangle as an object, then as a mesh: the same hits. */
	rf_scene *sr = parse(AWAY "rect center 0 1 -1 normal 0 0 1 size 2 1\n");
	rf_scene *sm = parse(AWAY "camera position 0 1 4 target 0 1 0\n");
	struct rf__mesh m = quad(2);
	static const double rays[][6] = {
		{ 0, 1, 4, 0, 0, -1 },
		{ 0.3, 1.2, 3, 0.1, -0.05, -1 },
		{ -2, 0.2, 2, 0.6, 0.3, -1 },
		{ 0.5, 1, -3, 0, 0.1, 1 }, /* from behind */
	};
	size_t i;
	int k;

	ASSERT(sr && sm);
	ASSERT_EQ(add(sm, &m), 0);
	for (i = 0; i < sizeof(rays) / sizeof(rays[0]); i++) {
		double d[3] = { rays[i][3], rays[i][4], rays[i][5] };
		double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
		struct rf_hit hr, hm;

		for (k = 0; k < 3; k++)
			d[k] /= len;
		ASSERT_EQ(rf_scene_trace(sr, rays[i], d, &hr), 1);
		ASSERT_EQ(rf_scene_trace(sm, rays[i], d, &hm), 1);
		ASSERT_NEAR(hm.t, hr.t, 1e-12);
		for (k = 0; k < 3; k++) {
			ASSERT_NEAR(hm.P[k], hr.P[k], 1e-12);
			ASSERT(hm.N[k] == hr.N[k]);
			ASSERT(hm.Ng[k] == hr.Ng[k]);
			ASSERT(hm.T[k] == hr.T[k]);
		}
		ASSERT(hm.roughness == hr.roughness && hm.metallic == hr.metallic &&
		       hm.mask == hr.mask && hm.albedo[0] == hr.albedo[0]);
	}
	ASSERT_STR_EQ(rf_scene_object_kind(sm, 1), "mesh");
	ASSERT_EQ(rf_scene_object_line(sm, 1), 2);
	rf_scene_destroy(sr);
	rf_scene_destroy(sm);
}

TEST(miss_and_the_room_around_a_mesh)
{
	/* Without a room a ray past the quad meets nothing; in a room the
	 * quad hides the wall behind it, and a ray beside it meets the wall;
	 * the mesh's objid follows the objects'. */
	rf_scene *s = parse(AWAY "camera position 0 1 4 target 0 1 0\n");
	rf_scene *r = parse("probe center 0 1.5 0 box -3 0 -2 3 3 2\n"
	                    "sphere center 2 1 0 radius 0.5\n");
	struct rf__mesh m1 = quad(1), m2 = quad(3);
	const double o[3] = { 0, 1, 1 }, ahead[3] = { 0, 0, -1 }, up[3] = { 0, 1, 0 };
	const double beside[3] = { -0.8, 0, -0.6 };
	struct rf_hit h;

	ASSERT(s && r);
	ASSERT_EQ(add(s, &m1), 0);
	ASSERT_EQ(rf_scene_trace(s, o, up, &h), RF_OBJID_NONE);
	ASSERT(h.t == INFINITY && h.mask == 0.0f);
	ASSERT_EQ(add(r, &m2), 0);
	ASSERT_EQ(rf_scene_trace(r, o, ahead, &h), 2);
	ASSERT_NEAR(h.t, 2.0, 1e-12);
	ASSERT_NEAR(h.P[2], -1.0, 1e-15);
	ASSERT_EQ(rf_scene_trace(r, o, beside, &h), RF_WALL_XMIN);
	ASSERT_NEAR(h.t, 3.0 / 0.8, 1e-12);
	ASSERT_EQ(rf_scene_trace(r, o, up, &h), RF_WALL_YMAX);
	rf_scene_destroy(s);
	rf_scene_destroy(r);
}

TEST(barycentric_interpolation)
{
	/* One triangle in z = 0: v0 (0,0), v1 (4,0), v2 (0,4), normals tilted
	 * n0 = (0,0,1), n1 = (0.6,0,0.8), n2 = (0,0.6,0.8); uv (0,0) (1,0)
	 * (0,1).  The ray down through (1, 2) has barycentrics (1/4, 1/2) of
	 * v1 and v2, so N = normalize(1/4 n0 + 1/4 n1 + 1/2 n2) =
	 * normalize(0.15, 0.3, 0.85), uv = (0.25, 0.5). */
	rf_scene *s = parse(AWAY "camera position 0 0 5 target 0 0 0\n");
	struct rf__mesh m = mesh_new(3, 1, 9);
	const double o[3] = { 1, 2, 3 }, d[3] = { 0, 0, -1 };
	const double len = sqrt(0.15 * 0.15 + 0.3 * 0.3 + 0.85 * 0.85);
	double uv[2][2];
	struct rf_hit h;
	int i;

	ASSERT(s);
	set3(m.positions, 0, 0, 0, 0);
	set3(m.positions, 1, 4, 0, 0);
	set3(m.positions, 2, 0, 4, 0);
	set3(m.normals, 0, 0, 0, 1);
	set3(m.normals, 1, 0.6, 0, 0.8);
	set3(m.normals, 2, 0, 0.6, 0.8);
	for (i = 0; i < 3; i++) {
		m.tangents[4 * i] = 1.0f;
		m.tangents[4 * i + 3] = 1.0f;
	}
	m.uv[0][2] = 1.0f;
	m.uv[0][5] = 1.0f;
	m.indices[1] = 1;
	m.indices[2] = 2;
	ASSERT_EQ(add(s, &m), 0);
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
	ASSERT(h.t == 3.0);
	ASSERT(h.P[0] == 1.0 && h.P[1] == 2.0 && h.P[2] == 0.0);
	ASSERT_NEAR(h.N[0], 0.15 / len, 1e-7);
	ASSERT_NEAR(h.N[1], 0.3 / len, 1e-7);
	ASSERT_NEAR(h.N[2], 0.85 / len, 1e-7);
	ASSERT(h.Ng[0] == 0.0 && h.Ng[1] == 0.0 && h.Ng[2] == 1.0);
	ASSERT_EQ(h.prim, 0);
	ASSERT_NEAR(h.bary[0], 0.25, 1e-15);
	ASSERT_NEAR(h.bary[1], 0.5, 1e-15);
	rf__mesh_uv(&s->meshes[0], h.prim, h.bary[0], h.bary[1], uv);
	ASSERT_NEAR(uv[0][0], 0.25, 1e-15);
	ASSERT_NEAR(uv[0][1], 0.5, 1e-15);
	/* T: +x made perpendicular to N */
	ASSERT_NEAR(h.T[0] * h.N[0] + h.T[1] * h.N[1] + h.T[2] * h.N[2], 0.0, 1e-12);
	ASSERT(h.T[0] > 0.98);
	rf_scene_destroy(s);
}

/* A 4 x 2 texture, one channel: row 0 is 0 1 2 3, row 1 is 10 11 12 13. */
static const float texels4x2[8] = { 0, 1, 2, 3, 10, 11, 12, 13 };

static struct rf__texture
tex4x2(enum rf__wrap wu, enum rf__wrap wv)
{
	struct rf__texture t;

	memset(&t, 0, sizeof(t));
	t.pixels = texels4x2;
	t.width = 4;
	t.height = 2;
	t.nchannels = 1;
	t.wrap[0] = wu;
	t.wrap[1] = wv;
	t.transform[0] = t.transform[4] = 1.0f;
	return t;
}

static float
sample(const struct rf__texture *t, double u, double v)
{
	double uv[2][2] = { { u, v }, { u, v } };
	float out[4];

	rf__texture_sample(t, uv, out);
	return out[0];
}

TEST(texture_sampling)
{
	struct rf__texture t = tex4x2(RF__WRAP_REPEAT, RF__WRAP_CLAMP);
	double uv[2][2] = { { 0.375, 0.25 }, { 0.875, 0.75 } };
	float out[4];

	/* texel centres: (i + 1/2) / 4, (j + 1/2) / 2 */
	ASSERT(sample(&t, 0.125, 0.25) == 0.0f);
	ASSERT(sample(&t, 0.625, 0.75) == 12.0f);
	/* halfway between texels 1 and 2 of row 0, then a quarter down to
	 * row 1 (v = 0.25 + 0.25 * 0.5) */
	ASSERT(sample(&t, 0.5, 0.25) == 1.5f);
	ASSERT_NEAR(sample(&t, 0.5, 0.375), 1.5 + 0.25 * 10, 1e-6);
	/* repeat across u = 0: between texel 3 and texel 0 */
	ASSERT(sample(&t, 0.0, 0.25) == 1.5f);
	ASSERT(sample(&t, 1.125, 0.25) == 0.0f);
	ASSERT(sample(&t, -0.875, 0.25) == 0.0f);
	/* clamp in v: above the first row's centre, the first row */
	ASSERT(sample(&t, 0.125, 0.0) == 0.0f);
	ASSERT(sample(&t, 0.125, -3.0) == 0.0f);
	ASSERT(sample(&t, 0.125, 7.5) == 10.0f);
	/* mirror: texels 0 1 2 3 3 2 1 0, 0 1 ... */
	t.wrap[0] = RF__WRAP_MIRROR;
	ASSERT(sample(&t, 1.125, 0.25) == 3.0f);
	ASSERT(sample(&t, 1.875, 0.25) == 0.0f);
	ASSERT(sample(&t, 1.0, 0.25) == 3.0f);
	ASSERT(sample(&t, 2.125, 0.25) == 0.0f);
	ASSERT(sample(&t, -0.125, 0.25) == 0.0f);
	ASSERT(sample(&t, 0.0, 0.25) == 0.0f);
	/* clamp in u */
	t.wrap[0] = RF__WRAP_CLAMP;
	ASSERT(sample(&t, 0.0, 0.25) == 0.0f);
	ASSERT(sample(&t, 1.0, 0.25) == 3.0f);
	/* KHR_texture_transform: u' = 0.5 u + 0.25 (texel 1's centre from
	 * u = -0.25 ... ) and v' = v + 0.5 (row 1) */
	t.transform[0] = 0.5f;
	t.transform[2] = 0.25f;
	t.transform[5] = 0.5f;
	ASSERT(sample(&t, -0.25, 0.25) == 10.0f);
	ASSERT(sample(&t, 0.25, 0.25) == 11.0f);
	/* the second uv set */
	t.transform[0] = 1.0f;
	t.transform[2] = 0.0f;
	t.transform[5] = 0.0f;
	t.texcoord = 1;
	rf__texture_sample(&t, uv, out);
	ASSERT(out[0] == 13.0f && out[1] == 13.0f && out[2] == 13.0f && out[3] == 1.0f);
}

TEST(textured_material_and_emission)
{
	/* The quad with a 2 x 1 RGB base colour texture (red | green) and an
	 * emission texture (grey levels 0.5 | 1) times emission 2, through the
	 * G-buffer: its left half is red, emitting 1; its right green,
	 * emitting 2.  Texel centres at u = 1/4 and 3/4. */
	static const float rg[6] = { 1, 0, 0, 0, 1, 0 }, grey[2] = { 0.5f, 1.0f };
	struct rf__texture base, em;
	rf_scene *s = parse(AWAY "camera position 0 1 4 target 0 1 0 fov 5\n");
	struct rf__mesh m = quad(1);
	struct rf_camera cam;
	rf_gbuffer *g = NULL;
	char err[256] = "";
	float px[8 * 2 * 10];
	size_t x, c, nblend = 0, nred = 0;

	ASSERT(s);
	memset(&base, 0, sizeof(base));
	base.pixels = rg;
	base.width = 2;
	base.height = 1;
	base.nchannels = 3;
	base.transform[0] = base.transform[4] = 1.0f;
	base.wrap[0] = base.wrap[1] = RF__WRAP_CLAMP;
	em = base;
	em.pixels = grey;
	em.nchannels = 1;
	m.materials[0].base_colour_tex = &base;
	m.materials[0].emission_tex = &em;
	m.materials[0].emission[0] = m.materials[0].emission[1] = 2.0f;
	m.materials[0].emission[2] = 2.0f;
	ASSERT_EQ(add(s, &m), 0);
	rf_scene_camera(s, &cam);
	/* 8 x 2 pixels over a view of 5 degrees: every pixel on the quad */
	ASSERT_EQ(rf_gbuffer_create(&g, s, 8, 2, "P,albedo,emission,objid", 1, err,
	                            sizeof(err)), 0);
	ASSERT_EQ(rf_gbuffer_set_camera(g, &cam, err, sizeof(err)), 0);
	ASSERT_EQ(rf_gbuffer_render(g, px, 0, 2), 0);
	for (x = 0; x < 16; x++) {
		const float *p = px + 10 * x;
		/* u = (x + 1) / 2 on the quad; clamped, the texture blends
		 * from red to green between the texel centres 1/4 and 3/4 */
		const double u = (p[0] + 1.0) / 2.0;
		const double f = u < 0.25 ? 0.0 : u > 0.75 ? 1.0 : (u - 0.25) * 2.0;

		ASSERT(p[9] == 1.0f);
		ASSERT_NEAR(p[3], 1.0 - f, 1e-5);
		ASSERT_NEAR(p[4], f, 1e-5);
		ASSERT(p[5] == 0.0f);
		for (c = 0; c < 3; c++)
			ASSERT_NEAR(p[6 + c], 2.0 * (0.5 + 0.5 * f), 1e-5);
		nblend += f > 0.0 && f < 1.0;
		nred += f == 0.0;
	}
	ASSERT(nblend >= 4 && nred >= 2);
	rf_gbuffer_destroy(g);
	rf_scene_destroy(s);
}

/* Positions, normals, objid and depth: 11 channels, objid the 10th. */
#define CHANNELS "P,N,Ng,objid,depth"
#define NCH 11

static int
render(rf_scene *s, int nthreads, float *out, size_t w, size_t h)
{
	struct rf_camera cam;
	rf_gbuffer *g = NULL;
	char err[256] = "";
	int rc;

	rf_scene_camera(s, &cam);
	if ((rc = rf_gbuffer_create(&g, s, w, h, CHANNELS, nthreads, err, sizeof(err))) < 0)
		return rc;
	if ((rc = rf_gbuffer_set_camera(g, &cam, err, sizeof(err))) == 0)
		rc = rf_gbuffer_render(g, out, 0, h);
	rf_gbuffer_destroy(g);
	return rc;
}

TEST(same_bytes_at_any_thread_count)
{
	rf_scene *s = parse("camera position 0 1.5 5 target 0 1.2 0\n"
	                    "probe center 0 1.5 0 box -3 0 -2 3 3 6\n"
	                    "sphere center -1.5 1 0 radius 0.6\n"
	                    "box min 1 0 -1 max 2 1 0\n");
	const double c1[3] = { 0, 1, -0.5 }, c2[3] = { 1.2, 1.8, 0.3 };
	struct rf__mesh m1 = icosphere(c1, 0.7, 4, 5), m2 = icosphere(c2, 0.4, 2, 6);
	const size_t w = 160, h = 90, nch = NCH;
	float *a = malloc(w * h * nch * sizeof(float)), *b = malloc(w * h * nch * sizeof(float));
	size_t i, nmesh = 0;

	ASSERT(s && a && b);
	ASSERT_EQ(add(s, &m1), 0);
	ASSERT_EQ(add(s, &m2), 0);
	ASSERT_EQ(render(s, 1, a, w, h), 0);
	ASSERT_EQ(render(s, 4, b, w, h), 0);
	ASSERT(memcmp(a, b, w * h * nch * sizeof(float)) == 0);
	for (i = 0; i < w * h; i++)
		nmesh += a[i * nch + 9] == 3.0f || a[i * nch + 9] == 4.0f;
	printf("# %zu of %zu pixels on the meshes\n", nmesh, w * h);
	ASSERT(nmesh > w * h / 50);
	free(a);
	free(b);
	rf_scene_destroy(s);
}

TEST(reflective_triangles_passed_through)
{
	/* Quad A at z = -1, reflective; quad B at z = -2 whose lower right
	 * triangle (below the diagonal y = 1 + x / 2) is not reflective, its
	 * other one is (two materials: two geometries on its vertices).
	 * Passing reflective surfaces, a ray through A meets B's first
	 * triangle, or nothing behind the second; otherwise A. */
	rf_scene *s = parse(AWAY "camera position 0 1 4 target 0 1 0\n"
	                         "sphere center 0 1 -1.5 radius 0.1 reflective on\n");
	struct rf__mesh a = quad(1), b = half_mirror_quad(2, -2.0f);
	const double d[3] = { 0, 0, -1 };
	const double low[3] = { 0.5, 0.7, 3 }, high[3] = { -0.5, 1.3, 3 };
	const double mid[3] = { 0, 1, 3 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(add(s, &a), 0);
	ASSERT_EQ(add(s, &b), 0);
	ASSERT_EQ(rf__trace(s, low, NULL, d, NULL, 0, &h), 2);
	ASSERT_NEAR(h.t, 4.0, 1e-12);
	ASSERT_EQ(rf__trace(s, low, NULL, d, NULL, RF__TRACE_SKIP_REFLECTIVE, &h), 3);
	ASSERT_NEAR(h.t, 5.0, 1e-12);
	ASSERT_EQ(h.prim, 0);
	ASSERT(h.mask == 0.0f);
	ASSERT_EQ(rf__trace(s, high, NULL, d, NULL, 0, &h), 2);
	ASSERT_EQ(rf__trace(s, high, NULL, d, NULL, RF__TRACE_SKIP_REFLECTIVE, &h),
	          RF_OBJID_NONE);
	/* the reflective sphere between them: met, or passed */
	ASSERT_EQ(rf__trace(s, mid, NULL, d, NULL, 0, &h), 2);
	ASSERT_EQ(rf__trace(s, mid, NULL, d, NULL, RF__TRACE_SKIP_REFLECTIVE, &h), 3);
	{
		const double behind[3] = { 0, 1, -1.2 };

		ASSERT_EQ(rf__trace(s, behind, NULL, d, NULL, 0, &h), 1);
		ASSERT_NEAR(h.t, 0.2, 1e-12);
		ASSERT_EQ(rf__trace(s, behind, NULL, d, NULL, RF__TRACE_SKIP_REFLECTIVE, &h), 3);
	}
	rf_scene_destroy(s);
}

/* Every field of two hits, bit for bit. */
static int
same_hit(const struct rf_hit *a, const struct rf_hit *b)
{
	return !memcmp(&a->t, &b->t, sizeof(a->t)) && !memcmp(a->P, b->P, sizeof(a->P)) &&
	       !memcmp(a->N, b->N, sizeof(a->N)) && !memcmp(a->Ng, b->Ng, sizeof(a->Ng)) &&
	       !memcmp(a->T, b->T, sizeof(a->T)) &&
	       !memcmp(a->bary, b->bary, sizeof(a->bary)) &&
	       !memcmp(&a->roughness, &b->roughness, sizeof(a->roughness)) &&
	       !memcmp(&a->metallic, &b->metallic, sizeof(a->metallic)) &&
	       !memcmp(a->albedo, b->albedo, sizeof(a->albedo)) &&
	       !memcmp(&a->mask, &b->mask, sizeof(a->mask)) && a->objid == b->objid &&
	       a->prim == b->prim;
}

static uint32_t
next_random(uint32_t *state)
{
	/* xorshift32: any fixed sequence does */
	*state ^= *state << 13;
	*state ^= *state >> 17;
	*state ^= *state << 5;
	return *state;
}

static double
uniform(uint32_t *state)
{
	return (double)(next_random(state) >> 8) / 16777216.0;
}

TEST(packets_meet_what_single_rays_meet)
{
	/* Some 4000 rays from inside a room of objects (a reflective sphere
	 * among them) and meshes (a reflective icosphere, two quads one of
	 * which is half reflective), cast one by one and in packets of every
	 * size from 1 to 8, their flags mixed: all, passing reflective
	 * surfaces, the room alone (the packet's lanes left out of the
	 * search).  Each lane's hit is the single ray's to the bit. */
	rf_scene *s = parse("probe box -3 -1 -4 3 3 3\n"
	                    "camera position 0 1 2.5 target 0 1 0\n"
	                    "sphere center -1.2 1 -0.5 radius 0.4 reflective on\n"
	                    "sphere center 1.5 0.3 0.5 radius 0.3\n"
	                    "box min 0.6 0.8 -1.4 max 1.4 1.6 -0.8\n"
	                    "rect plane y 0.01 min -2.5 -3.5 max 2.5 2.5 roughness 0.3\n");
	const double c[3] = { 0.2, 1.1, -2.2 };
	struct rf__mesh ico = icosphere(c, 0.7, 3, 1), a = quad(2);
	struct rf__mesh b = half_mirror_quad(3, -2.5f);
	static const unsigned kinds[4] = { 0, RF__TRACE_SKIP_REFLECTIVE, RF__TRACE_ROOM_ONLY,
	                                   0 };
	double k[16 * RF__ORIGIN_STRIDE], dirs[8][3], invs[8][3];
	uint32_t state = 12345;
	int j, n, r, bad = 0, meshes = 0, objects = 0, room = 0, passed = 0;

	ASSERT(s);
	ASSERT_EQ(add(s, &ico), 0);
	ASSERT_EQ(add(s, &a), 0);
	ASSERT_EQ(add(s, &b), 0);
	for (r = 0; r < 900; r++) {
		double o[3];
		const double *d[8], *inv[8];
		unsigned flags[8];
		struct rf_hit h8[8], h1;
		const int with_k = r % 2, with_inv = r % 3 != 0;

		n = 1 + r % 8;
		o[0] = -2.5 + 5.0 * uniform(&state);
		o[1] = -0.5 + 3.0 * uniform(&state);
		o[2] = -3.5 + 6.0 * uniform(&state);
		if (with_k)
			rf__trace_prepare(s, o, k);
		for (j = 0; j < n; j++) {
			double len = 0.0;
			int m;

			/* toward a point near the meshes, or anywhere */
			for (m = 0; m < 3; m++) {
				dirs[j][m] = r % 4 == 3 ? 2.0 * uniform(&state) - 1.0
				                        : c[m] + 1.6 * uniform(&state) - 0.8 - o[m];
				len += dirs[j][m] * dirs[j][m];
			}
			len = sqrt(len);
			for (m = 0; m < 3; m++) {
				dirs[j][m] /= len;
				invs[j][m] = 1.0 / dirs[j][m];
			}
			d[j] = dirs[j];
			inv[j] = invs[j];
			flags[j] = kinds[next_random(&state) % 4];
		}
		rf__trace8(s, o, with_k ? k : NULL, n, d, with_inv ? inv : NULL, flags, h8);
		for (j = 0; j < n; j++) {
			rf__trace(s, o, with_k ? k : NULL, d[j], with_inv ? inv[j] : NULL, flags[j],
			          &h1);
			if (!same_hit(&h1, &h8[j]) && bad++ < 5)
				printf("# packet %d lane %d of %d: objid %d t %.17g, alone %d t %.17g\n",
				       r, j, n, h8[j].objid, h8[j].t, h1.objid, h1.t);
			meshes += h1.objid > 4;
			objects += h1.objid >= 1 && h1.objid <= 4;
			room += h1.objid < 0 && flags[j] == RF__TRACE_ROOM_ONLY;
			passed += flags[j] == RF__TRACE_SKIP_REFLECTIVE && h1.mask == 0.0f;
		}
	}
	ASSERT_EQ(bad, 0);
	/* the rays meet every kind of thing */
	printf("# meshes %d objects %d room-only %d passed %d\n", meshes, objects, room, passed);
	ASSERT(meshes > 500 && objects > 300 && room > 500 && passed > 500);
	rf_scene_destroy(s);
}

TEST(capture_sees_an_emissive_mesh)
{
	/* A probe at (0, 1.5, 0) in a room that emits nothing; a matte quad
	 * emitting (2, 1, 0.5) across x in [-1, 1], y in [1, 2] at z = -1.5
	 * fills the middle of the -Z face: its texels there are the
	 * emission (no bounce: nothing shades it).  Made reflective and
	 * hidden (--hide-reflective), the wall behind shows: 0. */
	struct rf_capture_options o;
	rf_cubemap *cube = NULL;
	char err[256] = "";
	size_t i, j;
	int hide;

	for (hide = 0; hide < 2; hide++) {
		rf_scene *s = parse("probe center 0 1.5 0 box -3 0 -2 3 3 2\n"
		                    "room emission 0 0 0\n");
		struct rf__mesh m = quad(1);

		ASSERT(s);
		for (i = 0; i < 4; i++) {
			m.positions[3 * i + 1] += 0.5f;
			m.positions[3 * i + 2] = -1.5f;
		}
		m.materials[0].mask = (float)hide;
		m.materials[0].emission[0] = 2.0f;
		m.materials[0].emission[1] = 1.0f;
		m.materials[0].emission[2] = 0.5f;
		ASSERT_EQ(add(s, &m), 0);
		rf_capture_options_init(&o);
		o.size = 16;
		o.bounces = 0;
		o.hide_reflective = hide;
		ASSERT_EQ(rf_scene_capture(s, 0, &o, &cube, err, sizeof(err)), 0);
		/* the -Z face's middle 4 x 4 texels look within 0.27 rad of -Z:
		 * inside the quad (it spans 0.59 rad to the sides, 0.32 up and
		 * down from the probe's height 1.5) */
		for (j = 6; j < 10; j++)
			for (i = 6; i < 10; i++) {
				const float *t = rf_cubemap_texel_const(cube, 0, RF_FACE_NEG_Z, i, j);

				ASSERT_NEAR(t[0], hide ? 0.0 : 2.0, 1e-6);
				ASSERT_NEAR(t[1], hide ? 0.0 : 1.0, 1e-6);
				ASSERT_NEAR(t[2], hide ? 0.0 : 0.5, 1e-6);
			}
		rf_cubemap_destroy(cube);
		cube = NULL;
		rf_scene_destroy(s);
	}
}

TEST(trace_reflects_an_emissive_mesh)
{
	/* reflect-trace's truth: a near-mirror rectangle at z = -1 facing the
	 * camera at z = 4 reflects what lies behind the camera: a matte
	 * mesh quad at z = 6 emitting 3, wide enough to fill every reflected
	 * lobe.  A white lobe (F = 1) of roughness 0.02 keeps nearly all of
	 * it: each pixel between 2.9 and 3.  Without the mesh: 0. */
	rf_scene *s = parse("room off\nprobe box 100 100 100 101 101 101\n"
	                    "camera position 0 1 4 target 0 1 0 fov 10\n"
	                    "rect center 0 1 -1 normal 0 0 1 size 4 4 roughness 0.02\n");
	struct rf__mesh m = quad(3);
	struct rf_trace_options o;
	rf_tracer *t = NULL;
	char err[256] = "";
	float px[4 * 4 * 5];
	size_t i;

	ASSERT(s);
	for (i = 0; i < 4; i++) {
		/* x in [-10, 10], y in [-9, 11], at z = 6, facing -z */
		m.positions[3 * i] *= 10.0f;
		m.positions[3 * i + 1] = (m.positions[3 * i + 1] - 1.0f) * 20.0f + 1.0f;
		m.positions[3 * i + 2] = 6.0f;
		m.normals[3 * i + 2] = -1.0f;
	}
	m.materials[0].mask = 0.0f;
	m.materials[0].emission[0] = m.materials[0].emission[1] = 3.0f;
	m.materials[0].emission[2] = 3.0f;
	ASSERT_EQ(add(s, &m), 0);
	rf_trace_options_init(&o);
	o.samples = 64;
	ASSERT_EQ(rf_tracer_create(&t, s, 4, 4, &o, err, sizeof(err)), 0);
	ASSERT_EQ(rf_tracer_nchannels(t), 5);
	ASSERT_EQ(rf_tracer_render(t, px, 0, 4), 0);
	for (i = 0; i < 16; i++) {
		ASSERT(px[5 * i + 4] == 1.0f); /* the rectangle */
		ASSERT(px[5 * i] > 2.9f && px[5 * i] <= 3.0f);
		ASSERT(px[5 * i + 1] == px[5 * i] && px[5 * i + 2] == px[5 * i]);
	}
	rf_tracer_destroy(t);
	rf_scene_destroy(s);
}

TEST(bad_meshes_refused)
{
	rf_scene *s = parse(AWAY "camera position 0 1 4 target 0 1 0\n");
	struct rf__mesh m = quad(7), n = quad(8), e = mesh_new(0, 0, 9);
	char err[512] = "";

	ASSERT(s);
	m.positions[4] = NAN;
	ASSERT_EQ(rf__scene_add_mesh(s, &m, err, sizeof(err)), RF_EINVAL);
	printf("# %s\n", err);
	ASSERT(!strncmp(err, "'test.glb'", 10) && strstr(err, "vertex 1") &&
	       strstr(err, "NaN"));
	ASSERT(m.positions == NULL); /* freed */
	n.indices[5] = 4;
	ASSERT_EQ(rf__scene_add_mesh(s, &n, err, sizeof(err)), RF_EINVAL);
	printf("# %s\n", err);
	ASSERT(strstr(err, "'test.glb'") && strstr(err, "triangle 1"));
	ASSERT_EQ(rf__scene_add_mesh(s, &e, err, sizeof(err)), RF_EINVAL);
	ASSERT(strstr(err, "'test.glb'") && strstr(err, "no triangles"));
	ASSERT_EQ(s->nmeshes, 0);
	rf_scene_destroy(s);
}

int
main(void)
{
	RUN(tessellated_sphere_within_its_sagitta);
	RUN(quad_mesh_as_a_rect);
	RUN(miss_and_the_room_around_a_mesh);
	RUN(barycentric_interpolation);
	RUN(texture_sampling);
	RUN(textured_material_and_emission);
	RUN(same_bytes_at_any_thread_count);
	RUN(reflective_triangles_passed_through);
	RUN(packets_meet_what_single_rays_meet);
	RUN(capture_sees_an_emissive_mesh);
	RUN(trace_reflects_an_emissive_mesh);
	RUN(bad_meshes_refused);
	TAP_DONE();
}
