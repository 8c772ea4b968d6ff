/* Unit tests of scenes: parsing, exact ray casting, normal maps, cameras
 * and the G-buffer renderer, against values worked out by hand. */
#include <stdint.h>

#include "reflect/scene.h"
#include "tap.h"

static rf_scene *
parse(const char *text)
{
	char err[512] = "";
	rf_scene *s = NULL;

	if (rf_scene_parse(&s, text, strlen(text), "test.scene", err, sizeof(err)) < 0)
		printf("# parse: %s\n", err);
	return s;
}

static int
is_unit(const double v[3], double tol)
{
	return fabs(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - 1.0) <= tol;
}

/* Room -3 0 -2 .. 3 3 2 around a capture point at (0, 1.5, 0). */
#define ROOM "probe center 0 1.5 0 box -3 0 -2 3 3 2\n"

TEST(sphere_head_on)
{
	/* From (0,0,5) along -Z at a unit sphere at the origin: the near
	 * root is t = 4 at (0,0,1), the normal (0,0,1). */
	rf_scene *s = parse("probe box -10 -10 -10 10 10 10\n"
	                    "sphere center 0 0 0 radius 1 roughness 0.3\n");
	const double o[3] = { 0, 0, 5 }, d[3] = { 0, 0, -1 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
	ASSERT(h.t == 4.0);
	ASSERT(h.P[0] == 0.0 && h.P[1] == 0.0 && h.P[2] == 1.0);
	ASSERT(h.N[0] == 0.0 && h.N[1] == 0.0 && h.N[2] == 1.0);
	ASSERT(h.Ng[2] == 1.0);
	ASSERT_NEAR(h.roughness, 0.3, 1e-7);
	ASSERT(h.mask == 1.0f && h.metallic == 1.0f && h.albedo[1] == 1.0f);
	rf_scene_destroy(s);
}

TEST(sphere_offset_ray)
{
	/* A ray at height 0.6 meets the unit sphere at z = 0.8: N = P. */
	rf_scene *s = parse("probe box -10 -10 -10 10 10 10\n"
	                    "sphere center 0 0 0 radius 1\n");
	const double o[3] = { 0, 0.6, 5 }, d[3] = { 0, 0, -1 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
	ASSERT_NEAR(h.t, 4.2, 1e-12);
	ASSERT_NEAR(h.P[2], 0.8, 1e-12);
	ASSERT_NEAR(h.N[1], 0.6, 1e-12);
	ASSERT_NEAR(h.N[2], 0.8, 1e-12);
	rf_scene_destroy(s);
}

TEST(inside_sphere_faces_the_eye)
{
	/* From the centre the far side is hit and its normal flipped inward,
	 * as a path tracer shades a back face. */
	rf_scene *s = parse("probe box -10 -10 -10 10 10 10\n"
	                    "sphere center 0 0 0 radius 2\n");
	const double o[3] = { 0, 0, 0 }, d[3] = { 1, 0, 0 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(rf_scene_inside(s, o), 1);
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
	ASSERT(h.t == 2.0);
	ASSERT(h.N[0] == -1.0);
	rf_scene_destroy(s);
}

TEST(room_walls)
{
	static const struct {
		double d[3];
		int objid;
		double n[3], p[3];
	} walls[] = {
		{ { 1, 0, 0 }, RF_WALL_XMAX, { -1, 0, 0 }, { 3, 1.5, 0 } },
		{ { -1, 0, 0 }, RF_WALL_XMIN, { 1, 0, 0 }, { -3, 1.5, 0 } },
		{ { 0, 1, 0 }, RF_WALL_YMAX, { 0, -1, 0 }, { 0, 3, 0 } },
		{ { 0, -1, 0 }, RF_WALL_YMIN, { 0, 1, 0 }, { 0, 0, 0 } },
		{ { 0, 0, 1 }, RF_WALL_ZMAX, { 0, 0, -1 }, { 0, 1.5, 2 } },
		{ { 0, 0, -1 }, RF_WALL_ZMIN, { 0, 0, 1 }, { 0, 1.5, -2 } },
	};
	rf_scene *s = parse(ROOM);
	const double o[3] = { 0, 1.5, 0 };
	struct rf_hit h;
	int i, k;

	ASSERT(s);
	for (i = 0; i < 6; i++) {
		ASSERT_EQ(rf_scene_trace(s, o, walls[i].d, &h), walls[i].objid);
		for (k = 0; k < 3; k++) {
			ASSERT(h.N[k] == walls[i].n[k]);
			ASSERT(h.Ng[k] == walls[i].n[k]);
			ASSERT(h.P[k] == walls[i].p[k]);
		}
		ASSERT(h.mask == 0.0f);
		ASSERT(h.roughness == 1.0f);
		ASSERT(h.metallic == 0.0f);
		ASSERT_STR_EQ(rf_scene_object_kind(s, walls[i].objid), "wall");
	}
	rf_scene_destroy(s);
}

TEST(room_from_outside_and_miss)
{
	/* Outside the room its near walls let the eye through (they face
	 * in); a ray that misses the room sees nothing, with no NaN. */
	rf_scene *s = parse(ROOM);
	const double o[3] = { 0, 1.5, 10 }, in[3] = { 0, 0, -1 }, away[3] = { 0, 0, 1 };
	struct rf_hit h;
	int k;

	ASSERT(s);
	ASSERT(!rf_scene_in_room(s, o));
	ASSERT_EQ(rf_scene_trace(s, o, in, &h), RF_WALL_ZMIN);
	ASSERT(h.t == 12.0);
	ASSERT(h.N[2] == 1.0);
	ASSERT_EQ(rf_scene_trace(s, o, away, &h), RF_OBJID_NONE);
	ASSERT(isinf(h.t) && h.t > 0);
	ASSERT(h.mask == 0.0f);
	for (k = 0; k < 3; k++) {
		ASSERT(isfinite(h.P[k]) && isfinite(h.N[k]) && isfinite(h.Ng[k]));
		ASSERT(h.N[k] == -away[k]);
	}
	ASSERT(h.P[2] > 1e29);
	rf_scene_destroy(s);
}

TEST(box_outside_and_inside)
{
	rf_scene *s = parse("probe box -10 -10 -10 10 10 10\n"
	                    "box min -1 0 -1 max 1 2 1 roughness 0.7 reflective off\n");
	const double o[3] = { 5, 1, 0 }, d[3] = { -1, 0, 0 };
	const double c[3] = { 0, 1, 0 }, up[3] = { 0, 1, 0 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
	ASSERT(h.t == 4.0 && h.P[0] == 1.0 && h.N[0] == 1.0);
	ASSERT_NEAR(h.roughness, 0.7, 1e-7);
	ASSERT(h.mask == 0.0f);
	ASSERT_EQ(rf_scene_inside(s, c), 1);
	ASSERT_EQ(rf_scene_trace(s, c, up, &h), 1);
	ASSERT(h.t == 1.0 && h.P[1] == 2.0 && h.N[1] == -1.0);
	rf_scene_destroy(s);
}

TEST(rect_axis_and_general)
{
	/* The floor mirror: plane y 0.01, x in [-1, 1], z in [-2, 2]; a rect
	 * facing +Z given by centre, normal and size.  Both two-sided. */
	rf_scene *s = parse("probe box -10 -10 -10 10 10 10\n"
	                    "rect plane y 0.01 min -1 -2 max 1 2 smoothness 0.8\n"
	                    "rect center 0 5 -3 normal 0 0 2 size 2 1 metallic 0.25\n");
	const double o[3] = { 0.5, 1.01, 1.5 }, down[3] = { 0, -1, 0 };
	const double o2[3] = { 0.9, 5.4, 0 }, back[3] = { 0, 0, -1 };
	const double o3[3] = { 1.1, 5.4, 0 }, below[3] = { 0.5, -1, 0.25 }, up[3] = { 0, 1, 0 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(rf_scene_trace(s, o, down, &h), 1);
	ASSERT(h.t == 1.0 && h.P[1] == 0.01 && h.N[1] == 1.0);
	ASSERT_NEAR(h.roughness, 0.2, 1e-7);
	ASSERT_EQ(rf_scene_trace(s, o2, back, &h), 2);
	ASSERT(h.t == 3.0 && h.N[2] == 1.0 && h.P[2] == -3.0);
	ASSERT(h.metallic == 0.25f);
	ASSERT_EQ(rf_scene_trace(s, o3, back, &h), RF_WALL_ZMIN); /* beside it */
	ASSERT_EQ(rf_scene_trace(s, below, up, &h), 1);            /* from below */
	ASSERT(h.N[1] == -1.0);
	rf_scene_destroy(s);
}

TEST(nearest_object_wins)
{
	rf_scene *s = parse("probe box -10 -10 -10 10 10 10\n"
	                    "sphere center 0 0 -4 radius 1\n"
	                    "sphere center 0 0 0 radius 1\n");
	const double o[3] = { 0, 0, 5 }, d[3] = { 0, 0, -1 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 2);
	ASSERT(h.t == 4.0);
	rf_scene_destroy(s);
}

static const char *
write_flat_map(float r, float g)
{
	static const char *path = "test-raycast-flat.exr";
	static const char *const names[] = { "R", "G", "B" };
	float px[4 * 4 * 3];
	char err[256];
	rf_image_writer *w;
	int i;

	for (i = 0; i < 16; i++) {
		px[3 * i] = r;
		px[3 * i + 1] = g;
		px[3 * i + 2] = 1.0f;
	}
	if (rf_image_writer_open(&w, path, 4, 4, 3, names, RF_PIXEL_FLOAT, err,
	                         sizeof(err)) < 0) {
		printf("# %s\n", err);
		return NULL;
	}
	if (rf_image_writer_write_rows(w, 0, 4, px) < 0) {
		printf("# %s\n", rf_image_writer_error(w));
		rf_image_writer_close(w, NULL, 0);
		return NULL;
	}
	if (rf_image_writer_close(w, err, sizeof(err)) < 0) {
		printf("# %s\n", err);
		return NULL;
	}
	return path;
}

TEST(flat_normal_map_changes_nothing)
{
	const char *path = write_flat_map(0.5f, 0.5f);
	char text[512];
	rf_scene *s;
	const double o[3] = { 0.3, 0.7, 5 }, d[3] = { 0, 0, -1 };
	const double o2[3] = { 4.2, 2, 0.1 }, down[3] = { 0, -1, 0 };
	struct rf_hit h;

	ASSERT(path);
	snprintf(text, sizeof(text),
	         "probe box -10 -10 -10 10 10 10\n"
	         "sphere center 0 0 0 radius 1 normalmap image %s strength 2\n"
	         "rect plane y 0 min 3 -1 max 5 1 normalmap image %s tiling 3 2\n",
	         path, path);
	ASSERT((s = parse(text)));
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
	ASSERT(h.N[0] == h.Ng[0] && h.N[1] == h.Ng[1] && h.N[2] == h.Ng[2]);
	ASSERT_EQ(rf_scene_trace(s, o2, down, &h), 2);
	ASSERT(h.N[0] == 0.0 && h.N[1] == 1.0 && h.N[2] == 0.0);
	rf_scene_destroy(s);
	remove(path);
}

TEST(tilted_normal_map_follows_the_tangent_frame)
{
	/* R = 1, G = 0.5 at strength 0.5 unpacks to n = (0.5, 0, sqrt 0.75):
	 * on the floor, whose tangent is +X, N = (0.5, sqrt 0.75, 0). */
	const char *path = write_flat_map(1.0f, 0.5f);
	char text[512];
	rf_scene *s;
	const double o[3] = { 0.2, 2, 0.1 }, down[3] = { 0, -1, 0 };
	struct rf_hit h;

	ASSERT(path);
	snprintf(text, sizeof(text),
	         "probe box -10 -10 -10 10 10 10\n"
	         "rect plane y 0 min -1 -1 max 1 1 normalmap image %s strength 0.5\n",
	         path);
	ASSERT((s = parse(text)));
	ASSERT_EQ(rf_scene_trace(s, o, down, &h), 1);
	ASSERT_NEAR(h.N[0], 0.5, 1e-12);
	ASSERT_NEAR(h.N[1], sqrt(0.75), 1e-12);
	ASSERT_NEAR(h.N[2], 0.0, 1e-12);
	ASSERT(h.Ng[1] == 1.0);
	rf_scene_destroy(s);
	remove(path);
}

/* The tangent: unit, perpendicular to N (a bent one too), along the
 * texture's u: +X on a floor, (0, 0, -1) on the wall x = min (y x n),
 * the equator's east on a sphere. */
TEST(tangents_by_hand)
{
	rf_scene *s = parse("probe box -10 0 -10 10 10 10\n"
	                    "sphere center 0 5 0 radius 1\n"
	                    "rect plane y 2 min 4 4 max 6 6 normalmap bumps scale 0.3\n");
	const double down[3] = { 0, -1, 0 }, west[3] = { -1, 0, 0 }, back[3] = { 0, 0, -1 };
	const double o1[3] = { -3, 1, 3 }, o2[3] = { 0, 5, 5 };
	int i, j;
	struct rf_hit h;

	ASSERT(s);
	rf_scene_trace(s, o1, down, &h); /* the floor y = 0 */
	ASSERT(h.Ng[1] == 1.0);
	ASSERT_NEAR(h.T[0], 1, 1e-12);
	ASSERT_NEAR(h.T[1], 0, 1e-12);
	ASSERT_NEAR(h.T[2], 0, 1e-12);
	rf_scene_trace(s, o1, west, &h); /* the wall x = -10, N = (1, 0, 0) */
	ASSERT(h.Ng[0] == 1.0);
	ASSERT_NEAR(h.T[2], -1, 1e-12);
	rf_scene_trace(s, o2, back, &h); /* the sphere's front, N = (0, 0, 1) */
	ASSERT_EQ(h.objid, 1);
	ASSERT_NEAR(h.T[0], 1, 1e-12);
	ASSERT_NEAR(h.T[2], 0, 1e-12);
	for (i = 0; i < 20; i++) /* bumped: perpendicular to the bent N */
		for (j = 0; j < 20; j++) {
			const double o[3] = { 4.05 + 0.1 * i, 3, 4.05 + 0.1 * j };

			rf_scene_trace(s, o, down, &h);
			ASSERT(is_unit(h.T, 1e-12));
			ASSERT(fabs(h.T[0] * h.N[0] + h.T[1] * h.N[1] + h.T[2] * h.N[2]) < 1e-12);
			ASSERT(h.T[0] > 0.5); /* still along +X, leaning with N */
		}
	rf_scene_destroy(s);
	/* the G-buffer gives them on request, the same numbers */
	{
		rf_scene *d = parse("probe box -3 0 -2 3 3 2\ncamera position 0 1.5 1.9 target 0 1 0\n"
		                    "sphere center 0 1 0 radius 0.5 normalmap tiles scale 0.2\n");
		rf_gbuffer *g;
		char err[256];
		float px[16 * 12 * 6];
		int k;

		ASSERT(d);
		ASSERT_EQ(rf_gbuffer_create(&g, d, 16, 12, "N T", 1, err, sizeof(err)), 0);
		ASSERT_EQ(rf_gbuffer_nchannels(g), 6);
		ASSERT_EQ(rf_gbuffer_render(g, px, 0, 12), 0);
		for (k = 0; k < 16 * 12; k++) {
			const float *q = px + 6 * k;
			double t[3] = { q[3], q[4], q[5] };

			ASSERT(is_unit(t, 1e-6));
			ASSERT(fabs(q[0] * q[3] + q[1] * q[4] + q[2] * q[5]) < 1e-6);
		}
		rf_gbuffer_destroy(g);
		rf_scene_destroy(d);
	}
}

TEST(procedural_maps_perturb_and_stay_unit)
{
	static const char *const kinds[] = { "tiles", "bumps", "noise" };
	const double d[3] = { 0, -1, 0 };
	int k, i, j, perturbed;

	for (k = 0; k < 3; k++) {
		char text[512];
		rf_scene *s;

		snprintf(text, sizeof(text),
		         "probe box -10 -10 -10 10 10 10\n"
		         "rect plane y 0 min -4 -4 max 4 4 normalmap %s scale 0.5 strength 1\n"
		         "sphere center 0 0 8 radius 1 normalmap %s scale 0.3\n",
		         kinds[k], kinds[k]);
		ASSERT((s = parse(text)));
		perturbed = 0;
		for (i = 0; i < 40; i++)
			for (j = 0; j < 40; j++) {
				const double o[3] = { -2 + 0.1 * i + 0.003, 1, -2 + 0.1 * j + 0.007 };
				struct rf_hit h;

				ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
				ASSERT(is_unit(h.N, 1e-12));
				ASSERT(h.N[1] > 0); /* never below the surface */
				ASSERT(h.Ng[1] == 1.0);
				perturbed += fabs(h.N[1] - 1.0) > 1e-3;
			}
		if (!(perturbed > 100))
			TAP_FAIL("normalmap %s perturbed %d of 1600 normals", kinds[k], perturbed);
		/* on a sphere too */
		for (i = 0; i < 20; i++) {
			const double o[3] = { -0.9 + 0.09 * i, 0.3, 0 }, dz[3] = { 0, 0, 1 };
			struct rf_hit h;

			ASSERT_EQ(rf_scene_trace(s, o, dz, &h), 2);
			ASSERT(is_unit(h.N, 1e-12));
		}
		rf_scene_destroy(s);
	}
}

TEST(strength_zero_is_flat)
{
	rf_scene *s = parse("probe box -10 -10 -10 10 10 10\n"
	                    "rect plane y 0 min -4 -4 max 4 4 normalmap noise strength 0\n");
	const double o[3] = { 0.123, 1, 0.456 }, d[3] = { 0, -1, 0 };
	struct rf_hit h;

	ASSERT(s);
	ASSERT_EQ(rf_scene_trace(s, o, d, &h), 1);
	ASSERT(h.N[0] == 0.0 && h.N[1] == 1.0 && h.N[2] == 0.0);
	rf_scene_destroy(s);
}

TEST(camera_fov_edges)
{
	/* The top edge of the image is fov/2 above the view direction; the
	 * left edge atan(tan(fov/2) W/H) to the left. */
	struct rf_camera c = { { 1, 2, 3 }, { 1, 2, -7 }, { 0, 1, 0 }, 50.0 };
	const double pi = 3.14159265358979323846;
	double d[3];

	ASSERT_EQ(rf_camera_check(&c, NULL, 0), 0);
	rf_camera_ray(&c, 320, 240, 160, 0, d);
	ASSERT_NEAR(d[0], 0.0, 1e-15);
	ASSERT_NEAR(atan2(d[1], -d[2]), 25.0 * pi / 180.0, 1e-12);
	rf_camera_ray(&c, 320, 240, 0, 120, d);
	ASSERT_NEAR(d[1], 0.0, 1e-15);
	ASSERT_NEAR(atan2(-d[0], -d[2]), atan(tan(25.0 * pi / 180.0) * 320.0 / 240.0),
	            1e-12);
	rf_camera_ray(&c, 320, 240, 160, 120, d);
	ASSERT(d[0] == 0.0 && d[1] == 0.0 && d[2] == -1.0);
}

TEST(camera_checks)
{
	struct rf_camera c = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 1, 0 }, 60.0 };
	char err[256];

	ASSERT_EQ(rf_camera_check(&c, err, sizeof(err)), RF_EINVAL);
	c.target[1] = 5;
	ASSERT_EQ(rf_camera_check(&c, err, sizeof(err)), RF_EINVAL); /* up parallel */
	ASSERT(strstr(err, "parallel"));
	c.up[1] = 0;
	c.up[2] = 1;
	ASSERT_EQ(rf_camera_check(&c, err, sizeof(err)), 0);
	c.fov = 180;
	ASSERT_EQ(rf_camera_check(&c, err, sizeof(err)), RF_EINVAL);
}

TEST(camera_paths)
{
	struct rf_camera c = { { 0, 1.6, 2 }, { 0, 1, 0 }, { 0, 1, 0 }, 60.0 }, out;
	struct rf_camera_path orbit = { RF_PATH_ORBIT, 360.0, { 0, 0, 0 } };
	struct rf_camera_path line = { RF_PATH_LINE, 0, { 2, 1.6, 2 } };

	rf_camera_at_frame(&c, &orbit, 0, 4, &out);
	ASSERT(out.position[0] == 0 && out.position[2] == 2);
	/* a quarter turn about +Y takes +Z to +X */
	rf_camera_at_frame(&c, &orbit, 1, 4, &out);
	ASSERT_NEAR(out.position[0], 2.0, 1e-12);
	ASSERT_NEAR(out.position[1], 1.6, 0);
	ASSERT_NEAR(out.position[2], 0.0, 1e-12);
	ASSERT(out.target[0] == 0 && out.target[2] == 0);
	rf_camera_at_frame(&c, &line, 0, 3, &out);
	ASSERT(out.position[0] == 0);
	rf_camera_at_frame(&c, &line, 1, 3, &out);
	ASSERT(out.position[0] == 1 && out.target[0] == 1);
	rf_camera_at_frame(&c, &line, 2, 3, &out);
	ASSERT(out.position[0] == 2 && out.target[0] == 2 && out.target[2] == 0);
}

/* Renders the whole image with the G-buffer (which skips objects by
 * their screen bounds) and checks every pixel against a plain trace of
 * the same ray: the bounds must never drop a hit. */
static int
gbuffer_matches_trace(const rf_scene *s, const struct rf_camera *cam, size_t w,
                      size_t h, int threads)
{
	rf_gbuffer *g;
	char err[256];
	float *buf;
	size_t x, y, bad = 0, nch;

	if (rf_gbuffer_create(&g, s, w, h, NULL, threads, err, sizeof(err)) < 0 ||
	    rf_gbuffer_set_camera(g, cam, err, sizeof(err)) < 0)
		return -1;
	/* 20 channels, and the emission of a scene that emits */
	nch = rf_gbuffer_nchannels(g);
	if (nch != 20 && nch != 23)
		return -1;
	if (!(buf = malloc(w * h * nch * sizeof(float))))
		return -1;
	rf_gbuffer_render(g, buf, 0, h / 2);
	rf_gbuffer_render(g, buf + w * (h / 2) * nch, h / 2, h - h / 2);
	for (y = 0; y < h; y++)
		for (x = 0; x < w; x++) {
			const float *p = buf + (y * w + x) * nch;
			struct rf_hit hit;
			double d[3];
			int k;

			rf_camera_ray(cam, w, h, x + 0.5, y + 0.5, d);
			rf_scene_trace(s, cam->position, d, &hit);
			if (p[18] != (float)hit.objid || p[19] != (float)hit.t)
				bad++;
			for (k = 0; k < 20; k++)
				if (p[k] != p[k])
					bad++; /* NaN */
		}
	free(buf);
	rf_gbuffer_destroy(g);
	return (int)bad;
}

TEST(gbuffer_bounds_never_drop_a_hit)
{
	rf_scene *s = NULL;
	struct rf_camera cam, near;
	char err[256];
	int f;

	ASSERT_EQ(rf_scene_default(&s, err, sizeof(err)), 0);
	rf_scene_camera(s, &cam);
	ASSERT_EQ(gbuffer_matches_trace(s, &cam, 160, 90, 3), 0);
	/* orbiting, and close to a pillar: objects behind the eye, and the
	 * floor across the eye plane */
	for (f = 0; f < 6; f++) {
		struct rf_camera_path orbit = { RF_PATH_ORBIT, 360.0, { 0, 0, 0 } };

		rf_camera_at_frame(&cam, &orbit, (size_t)f, 6, &near);
		ASSERT_EQ(gbuffer_matches_trace(s, &near, 64, 48, 2), 0);
	}
	near = cam;
	near.position[0] = 1.5;
	near.position[1] = 1.0;
	near.position[2] = -1.0;
	near.target[0] = 1.5;
	near.target[1] = 0.3;
	near.target[2] = -3.0;
	ASSERT_EQ(gbuffer_matches_trace(s, &near, 64, 48, 1), 0);
	rf_scene_destroy(s);
}

TEST(gbuffer_same_bytes_any_threads)
{
	rf_scene *s = NULL;
	rf_gbuffer *g1, *g3;
	char err[256];
	/* the default scene emits: 20 channels and emission.R G B */
	size_t n = 97 * 31 * 23;
	float *a = malloc(n * sizeof(float)), *b = malloc(n * sizeof(float));

	ASSERT(a && b);
	ASSERT_EQ(rf_scene_default(&s, err, sizeof(err)), 0);
	ASSERT_EQ(rf_gbuffer_create(&g1, s, 97, 31, NULL, 1, err, sizeof(err)), 0);
	ASSERT_EQ(rf_gbuffer_create(&g3, s, 97, 31, NULL, 3, err, sizeof(err)), 0);
	ASSERT_EQ(rf_gbuffer_nchannels(g1), 23);
	ASSERT_EQ(rf_gbuffer_render(g1, a, 0, 31), 0);
	ASSERT_EQ(rf_gbuffer_render(g3, b, 0, 7), 0);
	ASSERT_EQ(rf_gbuffer_render(g3, b + 7 * 97 * 23, 7, 24), 0);
	ASSERT(!memcmp(a, b, n * sizeof(float)));
	ASSERT_EQ(rf_gbuffer_render(g3, b, 30, 2), RF_EINVAL);
	rf_gbuffer_destroy(g1);
	rf_gbuffer_destroy(g3);
	rf_scene_destroy(s);
	free(a);
	free(b);
}

TEST(gbuffer_channels)
{
	rf_scene *s = NULL;
	rf_gbuffer *g;
	char err[256];

	ASSERT_EQ(rf_scene_default(&s, err, sizeof(err)), 0);
	ASSERT_EQ(rf_gbuffer_create(&g, s, 4, 4, "P,roughness albedo", 1, err,
	                            sizeof(err)), 0);
	ASSERT_EQ(rf_gbuffer_nchannels(g), 7);
	ASSERT_STR_EQ(rf_gbuffer_channel(g, 2), "P.Z");
	ASSERT_STR_EQ(rf_gbuffer_channel(g, 3), "roughness");
	ASSERT_STR_EQ(rf_gbuffer_channel(g, 6), "albedo.B");
	rf_gbuffer_destroy(g);
	ASSERT_EQ(rf_gbuffer_create(&g, s, 4, 4, "P,Q", 1, err, sizeof(err)),
	          RF_ECHANNEL);
	ASSERT(strstr(err, "'Q'"));
	ASSERT_EQ(rf_gbuffer_create(&g, s, 4, 4, "P P.X", 1, err, sizeof(err)),
	          RF_ECHANNEL);
	rf_scene_destroy(s);
}

TEST(default_scene)
{
	rf_scene *s = NULL;
	const struct rf_scene_probe *p;
	struct rf_camera cam;
	char err[256];

	ASSERT_EQ(rf_scene_default(&s, err, sizeof(err)), 0);
	ASSERT_STR_EQ(rf_scene_name(s), "default");
	ASSERT_EQ(rf_scene_nprobes(s), 1);
	p = rf_scene_probe(s, 0);
	/* The numbers of the worked test vectors (spec section 15). */
	ASSERT(p->box_min[0] == -3 && p->box_min[1] == 0 && p->box_min[2] == -2);
	ASSERT(p->box_max[0] == 3 && p->box_max[1] == 3 && p->box_max[2] == 2);
	ASSERT(p->center[0] == 0 && p->center[1] == 1.5 && p->center[2] == 0);
	ASSERT(p->env == NULL && p->box_projection == 1);
	ASSERT_EQ(rf_scene_nobjects(s), 9);
	rf_scene_camera(s, &cam);
	ASSERT(rf_scene_in_room(s, cam.position));
	ASSERT_EQ(rf_scene_inside(s, cam.position), 0);
	ASSERT_NEAR(cam.position[1], 1.6, 1e-12);
	ASSERT_STR_EQ(rf_scene_object_kind(s, 1), "rect");
	ASSERT_STR_EQ(rf_scene_object_kind(s, 2), "sphere");
	ASSERT_STR_EQ(rf_scene_object_kind(s, 9), "box");
	rf_scene_destroy(s);
}

TEST(parse_errors_name_the_place)
{
	static const struct {
		const char *text, *want;
	} cases[] = {
		{ ROOM "spher center 0 1 0 radius 1\n", "test.scene:2:1: unknown keyword 'spher'" },
		{ ROOM "sphere center 0 1 0 radius\n", "test.scene:2:27: expected a number for 'radius', found the end of the line" },
		{ ROOM "sphere center 0 x 0 radius 1\n", "test.scene:2:17: expected a number for 'center', found 'x'" },
		{ ROOM "sphere center 0 1 0 radius -1\n", "test.scene:2:28: expected a positive radius, found -1" },
		{ ROOM "box min 0 2 0 max 1 1 1\n", "test.scene:2:5: expected min < max on every axis, the box is empty on Y (min 2, max 1)" },
		{ "probe center 0 5 0 box -3 0 -2 3 3 2\n", "test.scene:1:7: expected the probe's centre inside its box, (0 5 0) is outside on Y [0, 3]" },
		{ "# nothing\n", "test.scene:2:1: expected a 'probe' line" },
		{ ROOM "sphere center 0 1 0 radius 1 roughness 2\n", "test.scene:2:40: expected 'roughness' in [0, 1], found 2" },
		{ ROOM "sphere center 0 1 0 radius 1 radius 2\n", "test.scene:2:30: expected each attribute once, 'radius' was given at column 21 already" },
		{ ROOM "sphere center 0 1 0 radus 1\n", "test.scene:2:21: unknown sphere attribute 'radus'" },
		{ ROOM "sphere center 0 1 0\n", "test.scene:2:1: expected 'radius R' on this line" },
		{ ROOM "camera position 0 1 0 target 0 1 0\n", "test.scene:2:1: camera: expected a target apart from the position" },
		{ ROOM "rect plane w 0 min 0 0 max 1 1\n", "test.scene:2:12: expected x, y or z after 'plane', found 'w'" },
		{ ROOM "sphere center 0 1 0 radius 1 \\\n  strength 2\n", "test.scene:3:3: expected a 'normalmap' for 'strength'" },
		{ ROOM "sphere center 0 1 0 radius 1 normalmap image \"no such.png\"\n", "test.scene:2:46: cannot open " },
		{ ROOM "name \"unterminated\n", "test.scene:2:19: expected a closing '\"'" },
	};
	size_t i;

	for (i = 0; i < sizeof(cases) / sizeof(cases[0]); i++) {
		char err[512] = "";
		rf_scene *s = NULL;
		int rc = rf_scene_parse(&s, cases[i].text, strlen(cases[i].text),
		                        "test.scene", err, sizeof(err));

		if (rc != RF_EFORMAT || strncmp(err, cases[i].want, strlen(cases[i].want)))
			TAP_FAIL("case %zu: rc %d, message '%s', expected '%s'", i, rc, err,
			         cases[i].want);
		ASSERT(s == NULL);
	}
}

TEST(format_details)
{
	/* Comments, continuation lines, quoted names, several probes, a camera
	 * matrix (OpenGL convention: looks along -Z of its third column). */
	rf_scene *s = parse("# a comment\n"
	                    "name \"two probes\"  # trailing comment\n"
	                    "probe box -3 0 -2 3 3 2 \\\n"
	                    "      blend 0.25 projection off env \"sky map.exr\"\n"
	                    "probe center 1 1 1 box 0 0 0 2 2 2\n"
	                    "camera matrix 1 0 0 0.5  0 1 0 1.6  0 0 1 1.5  0 0 0 1 fov 45\n");
	const struct rf_scene_probe *p;
	struct rf_camera c;

	ASSERT(s);
	ASSERT_STR_EQ(rf_scene_name(s), "two probes");
	ASSERT_EQ(rf_scene_nprobes(s), 2);
	p = rf_scene_probe(s, 0);
	ASSERT(p->center[0] == 0 && p->center[1] == 1.5 && p->center[2] == 0);
	ASSERT(p->blend == 0.25 && p->box_projection == 0);
	ASSERT_STR_EQ(p->env, "sky map.exr");
	ASSERT(rf_scene_probe(s, 1)->env == NULL);
	ASSERT(rf_scene_probe(s, 2) == NULL);
	rf_scene_camera(s, &c);
	ASSERT(c.position[0] == 0.5 && c.position[1] == 1.6 && c.position[2] == 1.5);
	ASSERT(c.target[0] == 0.5 && c.target[1] == 1.6 && c.target[2] == 0.5);
	ASSERT(c.up[1] == 1 && c.fov == 45);
	rf_scene_destroy(s);
}

TEST(relative_paths_follow_the_scene_file)
{
	const char *text = "probe box -3 0 -2 3 3 2 env room.exr\n";
	char err[256];
	rf_scene *s;

	ASSERT_EQ(rf_scene_parse(&s, text, strlen(text), "scenes/a.scene", err,
	                         sizeof(err)), 0);
	ASSERT_STR_EQ(rf_scene_probe(s, 0)->env, "scenes/room.exr");
	ASSERT_STR_EQ(rf_scene_name(s), "a");
	rf_scene_destroy(s);
}

int
main(void)
{
	RUN(sphere_head_on);
	RUN(sphere_offset_ray);
	RUN(inside_sphere_faces_the_eye);
	RUN(room_walls);
	RUN(room_from_outside_and_miss);
	RUN(box_outside_and_inside);
	RUN(rect_axis_and_general);
	RUN(nearest_object_wins);
	RUN(flat_normal_map_changes_nothing);
	RUN(tilted_normal_map_follows_the_tangent_frame);
	RUN(procedural_maps_perturb_and_stay_unit);
	RUN(strength_zero_is_flat);
	RUN(camera_fov_edges);
	RUN(camera_checks);
	RUN(camera_paths);
	RUN(gbuffer_bounds_never_drop_a_hit);
	RUN(gbuffer_same_bytes_any_threads);
	RUN(gbuffer_channels);
	RUN(default_scene);
	RUN(parse_errors_name_the_place);
	RUN(format_details);
	RUN(relative_paths_follow_the_scene_file);
	RUN(tangents_by_hand);
	TAP_DONE();
}
