/* Unit tests of the lights' direct light (lib/scene/light.c): a floor
 * of one glTF quad lit by KHR_lights_punctual lights, its outgoing
 * radiance against the values worked out by hand, shadows from an
 * analytic object and from a triangle, and the G-buffer, the truth and
 * the capture reading the same radiance. */
#include <stdint.h>
#include <unistd.h>

#include "reflect/envmap.h"
#include "reflect/image.h"
#include "reflect/scene.h"
#include "scene/scene-internal.h"
#include "tap.h"
#include "gltf-write.h"

#define PI 3.14159265358979323846
/* The floor's base colour: a Lambertian surface sends back a / pi of its
 * irradiance. */
#define ALBEDO_R 0.5
#define ALBEDO_G 0.25
#define ALBEDO_B 1.0

/* A square of half-size h at height y facing +y (two triangles, counter-
 * clockwise seen from above, normals given), material 0 = materials[0],
 * and the lights' nodes after the mesh's: a .gltf in the scratch folder. */
static void
gltf_square(const char *name, double h, double y, const char *material,
            const char *light_nodes, const char *lights)
{
	const float p[4][3] = { { (float)-h, (float)y, (float)-h },
		                { (float)-h, (float)y, (float)h },
		                { (float)h, (float)y, (float)h },
		                { (float)h, (float)y, (float)-h } };
	const float n[4][3] = { { 0, 1, 0 }, { 0, 1, 0 }, { 0, 1, 0 }, { 0, 1, 0 } };
	const uint16_t ix[6] = { 0, 1, 2, 0, 2, 3 };
	unsigned char bytes[sizeof(p) + sizeof(n) + sizeof(ix)];
	char *data, *text, nodes[64] = "0";
	size_t len, k, nlight = 0;
	const char *c;

	memcpy(bytes, p, sizeof(p));
	memcpy(bytes + sizeof(p), n, sizeof(n));
	memcpy(bytes + sizeof(p) + sizeof(n), ix, sizeof(ix));
	for (c = light_nodes; *c; c++)
		nlight += *c == '{' && (c == light_nodes || c[-1] == ',');
	for (k = 0; k < nlight; k++)
		snprintf(nodes + strlen(nodes), sizeof(nodes) - strlen(nodes), ",%zu", k + 1);
	data = b64(bytes, sizeof(bytes));
	len = strlen(data) + 4096 + strlen(material) + strlen(light_nodes) + strlen(lights);
	text = malloc(len);
	snprintf(text, len,
	         "{\"asset\":{\"version\":\"2.0\"},"
	         "\"extensionsUsed\":[\"KHR_lights_punctual\"],"
	         "\"buffers\":[{\"byteLength\":%zu,\"uri\":"
	         "\"data:application/octet-stream;base64,%s\"}],"
	         "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
	         "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":48},"
	         "{\"buffer\":0,\"byteOffset\":96,\"byteLength\":12}],"
	         "\"accessors\":["
	         "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
	         "\"min\":[%g,%g,%g],\"max\":[%g,%g,%g]},"
	         "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
	         "{\"bufferView\":2,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}],"
	         "\"materials\":[%s],"
	         "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},"
	         "\"indices\":2,\"material\":0}]}],"
	         "\"nodes\":[{\"mesh\":0}%s%s],"
	         "\"scenes\":[{\"nodes\":[%s]}],\"scene\":0"
	         "%s%s%s}",
	         sizeof(bytes), data, (double)p[0][0], (double)p[0][1], (double)p[0][2],
	         (double)p[2][0], (double)p[2][1], (double)p[2][2], material,
	         *light_nodes ? "," : "", light_nodes, nodes,
	         *lights ? ",\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[" : "",
	         lights, *lights ? "]}}" : "");
	put_text(name, text);
	free(text);
	free(data);
}

#define FLOOR_MATERIAL                                                     \
	"{\"name\":\"floor\",\"pbrMetallicRoughness\":{\"baseColorFactor\":" \
	"[0.5,0.25,1,1],\"metallicFactor\":0,\"roughnessFactor\":1}}"
/* A light node at (0, 2, 0) pointing down (-Z turned -90 degrees about X). */
#define NODE_DOWN(i)                                                          \
	"{\"translation\":[0,2,0],\"rotation\":[-0.7071067811865476,0,0,"  \
	"0.7071067811865476],\"extensions\":{\"KHR_lights_punctual\":{\"light\":" \
	#i "}}}"

/* The floor's radiance at (x, 0, z), seen from above (or below). */
static void
floor_at(const rf_scene *s, double x, double z, int from_below, float rgb[3])
{
	const double o[3] = { x, from_below ? -1.0 : 5.0, z };
	const double d[3] = { 0.0, from_below ? 1.0 : -1.0, 0.0 };
	struct rf_hit h;

	rgb[0] = rgb[1] = rgb[2] = -1.0f;
	if (rf_scene_trace(s, o, d, &h) > 0)
		rf__radiance(s, &h, rgb);
}

/* E: the irradiance, per unit of the light's (1, 1, 1) radiometric
 * intensity; the floor sends back albedo E / pi per channel. */
#define ASSERT_LAMBERT(rgb, E, rel)                                        \
	do {                                                               \
		const double e_ = (E), t_ = (rel) * e_ + 1e-9;             \
		ASSERT_NEAR((rgb)[0], ALBEDO_R * e_ / PI, t_ * ALBEDO_R);  \
		ASSERT_NEAR((rgb)[1], ALBEDO_G * e_ / PI, t_ * ALBEDO_G);  \
		ASSERT_NEAR((rgb)[2], ALBEDO_B * e_ / PI, t_ * ALBEDO_B);  \
	} while (0)

/* 683 cd is 1 W/sr: E = I cos / r^2 = 2 / (4 + x^2)^(3/2) under a light
 * 2 m up, with glTF's range window where the light has one. */
TEST(point_light_inverse_square_and_cosine)
{
	const double xs[] = { 0.0, 0.5, 1.0, 2.0, 3.0, 7.5 };
	rf_scene *s;
	float rgb[3];
	size_t i;

	gltf_square("point.gltf", 10, 0, FLOOR_MATERIAL, NODE_DOWN(0),
	            "{\"type\":\"point\",\"intensity\":683}");
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\nmesh point.gltf\n");
	ASSERT(s);
	for (i = 0; i < sizeof(xs) / sizeof(xs[0]); i++) {
		const double r2 = 4.0 + xs[i] * xs[i];

		floor_at(s, xs[i], 0.0, 0, rgb);
		ASSERT_LAMBERT(rgb, 2.0 / (r2 * sqrt(r2)), 1e-5);
		/* the same along z: the light is round */
		floor_at(s, 0.0, -xs[i], 0, rgb);
		ASSERT_LAMBERT(rgb, 2.0 / (r2 * sqrt(r2)), 1e-5);
	}
	/* from below: the light is behind the face */
	floor_at(s, 0.5, 0.0, 1, rgb);
	ASSERT(rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f);
	rf_scene_destroy(s);

	gltf_square("range.gltf", 10, 0, FLOOR_MATERIAL, NODE_DOWN(0),
	            "{\"type\":\"point\",\"intensity\":683,\"range\":3}");
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\nmesh range.gltf\n");
	ASSERT(s);
	/* r^2 = 5: (1 - (r / 3)^4)^2 = (1 - 25 / 81)^2 */
	floor_at(s, 1.0, 0.0, 0, rgb);
	ASSERT_LAMBERT(rgb, 2.0 / (5.0 * sqrt(5.0)) * (56.0 / 81) * (56.0 / 81), 1e-5);
	/* past the range: nothing */
	floor_at(s, 2.5, 0.0, 0, rgb);
	ASSERT(rgb[0] == 0.0f);
	rf_scene_destroy(s);
}

/* A spot of 683 cd pointing down: full inside the inner cone, the square
 * of the ramp in cos between the cones, nothing outside. */
TEST(spot_light_cone)
{
	const double inner = 0.3, outer = 0.6, angles[] = { 0.0, 0.2, 0.35, 0.45, 0.55, 0.7 };
	rf_scene *s;
	float rgb[3];
	size_t i;

	gltf_square("spot.gltf", 10, 0, FLOOR_MATERIAL, NODE_DOWN(0),
	            "{\"type\":\"spot\",\"intensity\":683,\"spot\":"
	            "{\"innerConeAngle\":0.3,\"outerConeAngle\":0.6}}");
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\nmesh spot.gltf\n");
	ASSERT(s);
	for (i = 0; i < sizeof(angles) / sizeof(angles[0]); i++) {
		const double th = angles[i], c = cos(th);
		double a = (c - cos(outer)) / (cos(inner) - cos(outer));

		a = a < 0 ? 0 : a > 1 ? 1 : a;
		/* r = 2 / cos: E = cos^3 / 4 */
		floor_at(s, 2.0 * tan(th), 0.0, 0, rgb);
		ASSERT_LAMBERT(rgb, a * a * c * c * c / 4.0, 1e-5);
	}
	rf_scene_destroy(s);
}

/* 683 lux from 45 degrees: E = cos 45 everywhere. */
TEST(directional_light_cosine)
{
	rf_scene *s;
	float rgb[3];

	/* -Z turned 45 degrees about X, downward: (0, -1, -1) / sqrt 2 */
	gltf_square("sun.gltf", 10, 0, FLOOR_MATERIAL,
	            "{\"rotation\":[-0.3826834323650898,0,0,0.9238795325112867],"
	            "\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}}",
	            "{\"type\":\"directional\",\"intensity\":683}");
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\nmesh sun.gltf\n");
	ASSERT(s);
	floor_at(s, 0.0, 0.0, 0, rgb);
	ASSERT_LAMBERT(rgb, sqrt(0.5), 1e-5);
	floor_at(s, -8.0, 6.0, 0, rgb);
	ASSERT_LAMBERT(rgb, sqrt(0.5), 1e-5);
	rf_scene_destroy(s);

	/* in a closed room the walls stand between the sun and the floor */
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nmesh sun.gltf\n");
	ASSERT(s);
	floor_at(s, 0.0, 0.0, 0, rgb);
	ASSERT(rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f);
	rf_scene_destroy(s);
}

/* A sphere and a triangle each cast a shadow of the light 2 m up on the
 * floor below them, and nowhere else. */
TEST(shadows_from_objects_and_triangles)
{
	rf_scene *s;
	float rgb[3];

	gltf_square("point.gltf", 10, 0, FLOOR_MATERIAL, NODE_DOWN(0),
	            "{\"type\":\"point\",\"intensity\":683}");
	gltf_square("blocker.gltf", 0.25, 1.0, "{\"name\":\"blocker\"}", "", "");
	s = load("probe box -10 -1 -10 10 6 10 center 5 1 5\nroom off\nmesh point.gltf\n"
	         "sphere center 0 1 0 radius 0.25\n");
	ASSERT(s);
	floor_at(s, 0.0, 0.0, 0, rgb);
	ASSERT(rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f);
	/* the shadow's edge: the tangent from (0, 2) to the sphere reaches
	 * the floor at x = 2 tan(asin(0.25)) = 0.516 */
	floor_at(s, 0.50, 0.0, 0, rgb);
	ASSERT(rgb[0] == 0.0f);
	floor_at(s, 0.54, 0.0, 0, rgb);
	ASSERT_LAMBERT(rgb, 2.0 / pow(4.0 + 0.54 * 0.54, 1.5), 1e-5);
	rf_scene_destroy(s);

	s = load("probe box -10 -1 -10 10 6 10 center 5 1 5\nroom off\nmesh point.gltf\n"
	         "mesh blocker.gltf\n");
	ASSERT(s);
	/* the square's shadow is twice its size: |x| < 0.5 */
	floor_at(s, 0.45, 0.45, 0, rgb);
	ASSERT(rgb[0] == 0.0f);
	floor_at(s, 0.55, 0.0, 0, rgb);
	ASSERT_LAMBERT(rgb, 2.0 / pow(4.0 + 0.55 * 0.55, 1.5), 1e-5);
	rf_scene_destroy(s);
}

/* Light reaches what is not reflective and not metal: a mirror and a
 * metal floor send back their emission alone; the emission adds. */
TEST(reflective_and_metal_take_no_direct_light)
{
	rf_scene *s;
	float rgb[3];

	gltf_square("point.gltf", 10, 0,
	            "{\"name\":\"floor\",\"emissiveFactor\":[0.125,0.25,0.5],"
	            "\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.25,1,1],"
	            "\"metallicFactor\":0.25}}",
	            NODE_DOWN(0), "{\"type\":\"point\",\"intensity\":683}");
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\nmesh point.gltf\n");
	ASSERT(s);
	floor_at(s, 0.0, 0.0, 0, rgb);
	/* E = 1 / 4, three quarters of it diffuse */
	ASSERT_NEAR(rgb[0], 0.125 + 0.75 * ALBEDO_R * 0.25 / PI, 1e-6);
	ASSERT_NEAR(rgb[2], 0.5 + 0.75 * ALBEDO_B * 0.25 / PI, 1e-6);
	rf_scene_destroy(s);
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\n"
	         "mesh point.gltf reflective on\n");
	ASSERT(s);
	floor_at(s, 0.0, 0.0, 0, rgb);
	ASSERT(rgb[0] == 0.125f && rgb[1] == 0.25f && rgb[2] == 0.5f);
	rf_scene_destroy(s);
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\n"
	         "mesh point.gltf metallic 1\n");
	ASSERT(s);
	floor_at(s, 0.0, 0.0, 0, rgb);
	ASSERT(rgb[0] == 0.125f && rgb[1] == 0.25f && rgb[2] == 0.5f);
	rf_scene_destroy(s);
}

/* reflect-gbuffer's emission and reflect-trace's colour of a pixel that
 * does not reflect are the radiance of the surface it sees; the capture's
 * texel straight down is that of the floor below the probe. */
TEST(gbuffer_trace_and_capture_agree)
{
	const size_t W = 16, H = 12;
	struct rf_camera cam;
	struct rf_capture_options co;
	struct rf_trace_options to;
	rf_gbuffer *g = NULL;
	rf_tracer *t = NULL;
	rf_cubemap *cube = NULL;
	rf_scene *s;
	float *gb = NULL, *tr = NULL, rgb[3];
	char err[256];
	size_t i, j, nch, ntr, er = 0, objid = 0;

	gltf_square("point.gltf", 10, 0, FLOOR_MATERIAL, NODE_DOWN(0),
	            "{\"type\":\"point\",\"intensity\":683}");
	s = load("probe box -10 -1 -10 10 6 10 center 0 1.5 0\nroom off\nmesh point.gltf\n"
	         "camera position 0 4 3 target 0 0 0 fov 60\n");
	ASSERT(s);
	rf_scene_camera(s, &cam);
	ASSERT(rf_gbuffer_create(&g, s, W, H, NULL, 1, err, sizeof(err)) == 0);
	nch = rf_gbuffer_nchannels(g);
	for (i = 0; i < nch; i++) {
		if (!strcmp(rf_gbuffer_channel(g, i), "emission.R"))
			er = i;
		if (!strcmp(rf_gbuffer_channel(g, i), "objid"))
			objid = i;
	}
	ASSERT(er > 0 && objid > 0);
	rf_trace_options_init(&to);
	to.samples = 4;
	ASSERT(rf_tracer_create(&t, s, W, H, &to, err, sizeof(err)) == 0);
	ntr = rf_tracer_nchannels(t);
	gb = malloc(W * H * nch * sizeof(float));
	tr = malloc(W * H * ntr * sizeof(float));
	ASSERT(gb && tr);
	ASSERT(rf_gbuffer_render(g, gb, 0, H) == 0);
	ASSERT(rf_tracer_render(t, tr, 0, H) == 0);
	for (j = 0; j < H; j++)
		for (i = 0; i < W; i++) {
			const float *px = gb + (j * W + i) * nch, *tp = tr + (j * W + i) * ntr;
			double d[3];
			struct rf_hit h;

			rf_camera_ray(&cam, W, H, (double)i + 0.5, (double)j + 0.5, d);
			rf_scene_trace(s, cam.position, d, &h);
			rf__radiance(s, &h, rgb);
			ASSERT((int)px[objid] == h.objid);
			ASSERT_NEAR(px[er], rgb[0], 1e-6 * (1 + rgb[0]));
			ASSERT_NEAR(px[er + 2], rgb[2], 1e-6 * (1 + rgb[2]));
			ASSERT_NEAR(tp[0], rgb[0], 1e-6 * (1 + rgb[0]));
			ASSERT(h.objid <= 0 || rgb[0] > 0.0f);
		}
	rf_capture_options_init(&co);
	co.size = 64;
	co.bounces = 0;
	ASSERT(rf_scene_capture(s, 0, &co, &cube, err, sizeof(err)) == 0);
	{
		/* the -y face's centre texel looks straight down on the floor
		 * below the light: E = 1 / 2^2 */
		const float *tx = rf_cubemap_texel(cube, 0, RF_FACE_NEG_Y, 32, 32);

		ASSERT_LAMBERT(tx, 0.25, 2e-3);
	}
	rf_cubemap_destroy(cube);
	free(gb);
	free(tr);
	rf_tracer_destroy(t);
	rf_gbuffer_destroy(g);
	rf_scene_destroy(s);
}

/* A lat-long sky of w x w/2 texels whose radiance at each texel's centre
 * direction d is a + b d.y: linear in d, so that its irradiance is
 * exactly E(n) = pi a + (2 pi / 3) b n.y (the l = 0 and 1 bands). */
static void
sky_linear(const char *name, size_t w, float a, float b)
{
	const size_t h = w / 2;
	float *px = malloc(w * h * 3 * sizeof(float));
	rf_image_writer *wr;
	char path[512], err[256];
	size_t i, j;

	for (j = 0; j < h; j++)
		for (i = 0; i < w; i++) {
			float d[3];

			rf_latlong_direction(((float)i + 0.5f) / (float)w,
			                     ((float)j + 0.5f) / (float)h, d);
			px[3 * (j * w + i)] = px[3 * (j * w + i) + 1] =
				px[3 * (j * w + i) + 2] = a + b * d[1];
		}
	snprintf(path, sizeof(path), "%s/%s", dir, name);
	if (rf_image_writer_open(&wr, path, w, h, 3, NULL, RF_PIXEL_FLOAT, err,
	                         sizeof(err)) < 0 ||
	    rf_image_writer_write_rows(wr, 0, h, px) < 0 ||
	    rf_image_writer_close(wr, err, sizeof(err)) < 0)
		printf("# sky: %s\n", err);
	free(px);
}

/* Under a sky of radiance 1 + d.y a matte floor facing up receives
 * pi (1 + 2/3) and sends back albedo 5/3; facing down (from below) it
 * receives pi (1 - 2/3); rays that leave see the sky itself. */
TEST(sky_lights_and_is_seen)
{
	rf_scene *s;
	struct rf_hit h;
	const double up[3] = { 0, 1, 0 }, side[3] = { 1, 0, 0 }, o[3] = { 0, 5, 0 };
	float rgb[3];

	sky_linear("sky.exr", 256, 1.0f, 1.0f);
	gltf_square("plain.gltf", 10, 0, FLOOR_MATERIAL, "", "");
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\nmesh plain.gltf\n"
	         "sky sky.exr strength 2\n");
	ASSERT(s);
	floor_at(s, 3.0, -2.0, 0, rgb);
	ASSERT_LAMBERT(rgb, 2.0 * PI * 5.0 / 3.0, 1e-3);
	floor_at(s, 3.0, -2.0, 1, rgb);
	ASSERT_LAMBERT(rgb, 2.0 * PI / 3.0, 2e-3);
	/* the sky straight up is 2 (1 + 1), sideways 2 */
	ASSERT(rf_scene_trace(s, o, up, &h) == RF_OBJID_NONE);
	rf__radiance(s, &h, rgb);
	ASSERT_NEAR(rgb[0], 4.0, 2e-2);
	ASSERT(rf_scene_trace(s, o, side, &h) == RF_OBJID_NONE);
	rf__radiance(s, &h, rgb);
	ASSERT_NEAR(rgb[1], 2.0, 1e-2);
	rf_scene_destroy(s);

	/* a reflective floor takes none of it */
	s = load("probe box -10 -1 -10 10 6 10 center 0 1 0\nroom off\n"
	         "mesh plain.gltf reflective on\nsky sky.exr\n");
	ASSERT(s);
	floor_at(s, 0.0, 0.0, 0, rgb);
	ASSERT(rgb[0] == 0.0f && rgb[1] == 0.0f && rgb[2] == 0.0f);
	rf_scene_destroy(s);
}

static int
scene_error(const char *text, const char *want)
{
	char err[1024] = "", name[512];
	rf_scene *s = NULL;
	int rc;

	snprintf(name, sizeof(name), "%s/test.scene", dir);
	rc = rf_scene_parse(&s, text, strlen(text), name, err, sizeof(err));
	rf_scene_destroy(s);
	printf("# %s\n", err);
	return rc < 0 && strstr(err, want) != NULL;
}

TEST(sky_errors)
{
	ASSERT(scene_error("probe box -1 -1 -1 1 1 1\nsky nowhere.exr\n",
	                   "test.scene:2:5: cannot open"));
	ASSERT(scene_error("probe box -1 -1 -1 1 1 1\nsky sky.exr strength -1\n",
	                   "test.scene:2:13: expected a strength of 0 or more"));
	ASSERT(scene_error("probe box -1 -1 -1 1 1 1\nsky sky.exr glow 1\n", "'glow'"));
	ASSERT(scene_error("probe box -1 -1 -1 1 1 1\nsky sky.exr\nsky sky.exr\n",
	                   "test.scene:3:1: a second 'sky' (the first is on line 2)"));
	ASSERT(scene_error("probe box -1 -1 -1 1 1 1\nsky plain.gltf\n", "test.scene:2:5:"));
}

int
main(void)
{
	const char *tmp = getenv("TMPDIR");

	snprintf(dir, sizeof(dir), "%s/test-light-XXXXXX", tmp && *tmp ? tmp : "/tmp");
	if (!mkdtemp(dir)) {
		printf("Bail out! cannot make a directory\n");
		return 1;
	}
	RUN(point_light_inverse_square_and_cosine);
	RUN(spot_light_cone);
	RUN(directional_light_cosine);
	RUN(shadows_from_objects_and_triangles);
	RUN(reflective_and_metal_take_no_direct_light);
	RUN(gbuffer_trace_and_capture_agree);
	RUN(sky_lights_and_is_seen);
	RUN(sky_errors);
	{
		char cmd[512];

		snprintf(cmd, sizeof(cmd), "rm -rf '%s'", dir);
		if (!tap_failed && system(cmd) != 0)
			printf("# cannot remove %s\n", dir);
	}
	TAP_DONE();
}
