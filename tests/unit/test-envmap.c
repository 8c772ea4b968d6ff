/* Unit tests of environment layouts, decoding and chain files. */
#include <unistd.h>

#include "reflect/envmap.h"
#include "tap.h"

/* A cross or cube image whose slots hold face * 100 + row * 10 + column,
 * in the slot's own pixel coordinates. */
static float *
labelled_layout(enum rf_layout layout, size_t n, const int slots[6][3], size_t *w,
                size_t *h)
{
	float *px;
	size_t i, j;
	int f;

	rf_layout_size(layout, n, w, h);
	px = calloc(*w * *h * 3, sizeof(float));
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				float *p = px + ((slots[f][1] * n + j) * *w + slots[f][0] * n + i) * 3;

				p[0] = (float)(f * 100 + (int)j * 10 + (int)i);
				p[1] = (float)f;
				p[2] = 1.0f;
			}
	return px;
}

/* Reads a layout whose slots are at the given places, turned or not, and
 * checks each cube texel got its slot's pixel. */
static int
check_layout(enum rf_layout layout, const int slots[6][3])
{
	const size_t n = 4;
	size_t w, h, bad, i, j;
	float *px = labelled_layout(layout, n, slots, &w, &h), *back;
	rf_cubemap *c;
	char err[256];
	int f, failures = 0;

	if (rf_cubemap_create(&c, n, 1) < 0 ||
	    rf_envmap_from_pixels(c, px, w, h, 3, layout, NULL, &bad, err, sizeof(err)) < 0) {
		printf("# %s\n", err);
		return 1;
	}
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				const float *t = rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j);
				size_t si = slots[f][2] ? n - 1 - i : i, sj = slots[f][2] ? n - 1 - j : j;

				if (t[0] != (float)(f * 100 + (int)sj * 10 + (int)si)) {
					printf("# %s face %d texel %zu,%zu: %g\n", rf_layout_name(layout),
					       f, i, j, (double)t[0]);
					failures++;
				}
			}
	/* and back to the same image */
	back = malloc(w * h * 3 * sizeof(float));
	rf_envmap_to_pixels(c, 0, layout, back, w, h);
	if (memcmp(back, px, w * h * 3 * sizeof(float)))
		failures++;
	free(back);
	free(px);
	rf_cubemap_destroy(c);
	return failures;
}

/* Slots (column, row, turned) as documented in reflect-prefilter(1). */
TEST(cube_layout)
{
	static const int slots[6][3] = {
		{ 0, 0, 0 }, { 0, 1, 0 }, { 0, 2, 0 }, { 0, 3, 0 }, { 0, 4, 0 }, { 0, 5, 0 },
	};

	ASSERT_EQ(check_layout(RF_LAYOUT_CUBE, slots), 0);
}

TEST(horizontal_cross)
{
	/* middle row +X +Z -X -Z; +Y above and -Y below +Z, turned */
	static const int slots[6][3] = {
		{ 0, 1, 0 }, { 2, 1, 0 }, { 1, 0, 1 }, { 1, 2, 1 }, { 1, 1, 0 }, { 3, 1, 0 },
	};

	ASSERT_EQ(check_layout(RF_LAYOUT_HCROSS, slots), 0);
}

TEST(vertical_cross)
{
	static const int slots[6][3] = {
		{ 0, 1, 0 }, { 2, 1, 0 }, { 1, 0, 1 }, { 1, 2, 1 }, { 1, 1, 0 }, { 1, 3, 1 },
	};

	ASSERT_EQ(check_layout(RF_LAYOUT_VCROSS, slots), 0);
}

/*
 * The cross is the cube unfolded: along every edge where two slots touch
 * in the image, the two faces touch on the cube.  Checked geometrically:
 * the directions of the texels on both sides of the shared image edge are
 * close (a texel apart), for all the vertical cross's touching pairs.
 */
TEST(cross_slots_touch_on_the_cube)
{
	const size_t n = 8;
	size_t w, h, k, pairs = 0;
	float *dir_img;
	rf_cubemap *c;
	size_t x, y;
	int f, ch;

	ASSERT_EQ(rf_cubemap_create(&c, n, 1), 0);
	/* Fill the cube with each texel's own unit direction. */
	for (f = 0; f < 6; f++)
		for (y = 0; y < n; y++)
			for (x = 0; x < n; x++) {
				float d[3], *t = rf_cubemap_texel(c, 0, (enum rf_face)f, x, y), len;

				rf_cube_direction((enum rf_face)f, (x + 0.5f) / n, (y + 0.5f) / n, d);
				len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
				for (ch = 0; ch < 3; ch++)
					t[ch] = d[ch] / len;
			}
	rf_layout_size(RF_LAYOUT_VCROSS, n, &w, &h);
	dir_img = calloc(w * h * 3, sizeof(float));
	rf_envmap_to_pixels(c, 0, RF_LAYOUT_VCROSS, dir_img, w, h);
	/* Every pair of horizontally or vertically adjacent pixels that are
	 * both inside slots: their directions are within ~2 texels. */
	for (y = 0; y < h; y++)
		for (x = 0; x < w; x++)
			for (k = 0; k < 2; k++) {
				size_t x2 = x + (k == 0), y2 = y + (k == 1);
				const float *a, *b;
				float dot;

				if (x2 >= w || y2 >= h)
					continue;
				a = dir_img + (y * w + x) * 3;
				b = dir_img + (y2 * w + x2) * 3;
				if ((a[0] == 0 && a[1] == 0 && a[2] == 0) ||
				    (b[0] == 0 && b[1] == 0 && b[2] == 0))
					continue;
				dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
				pairs++;
				ASSERT(dot > cosf(2.5f * (float)M_PI / 2 / n));
			}
	ASSERT(pairs > 6 * 2 * n * (n - 1));
	free(dir_img);
	rf_cubemap_destroy(c);
}

/* A lat-long holding each pixel's own direction gives every cube texel
 * its direction: the lat-long axes agree with the cube's. */
TEST(latlong_axes_match_cube)
{
	const size_t w = 256, h = 128, n = 16;
	float *px = malloc(w * h * 3 * sizeof(float));
	rf_cubemap *c;
	size_t i, j, bad;
	char err[256];
	double worst = 1.0;
	int f;

	for (j = 0; j < h; j++)
		for (i = 0; i < w; i++)
			rf_latlong_direction((i + 0.5f) / w, (j + 0.5f) / h, px + (j * w + i) * 3);
	ASSERT_EQ(rf_cubemap_create(&c, n, 1), 0);
	ASSERT_EQ(rf_envmap_from_pixels(c, px, w, h, 3, RF_LAYOUT_LATLONG, NULL, &bad, err,
	                                sizeof(err)), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				const float *t = rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j);
				float d[3], len, tl;
				double dot;

				rf_cube_direction((enum rf_face)f, (i + 0.5f) / n, (j + 0.5f) / n, d);
				len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
				tl = sqrtf(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
				dot = (d[0] * t[0] + d[1] * t[1] + d[2] * t[2]) / (len * tl);
				if (dot < worst)
					worst = dot;
			}
	printf("# worst cosine between a texel and its lat-long reading: %.6f\n", worst);
	ASSERT(worst > cos(1.0 * M_PI / 180.0));
	free(px);
	rf_cubemap_destroy(c);
}

/* Area filtering: a lat-long of fine stripes near a pole averages to the
 * stripes' mean instead of aliasing. */
TEST(latlong_filtered_at_poles)
{
	const size_t w = 2048, h = 1024, n = 8;
	float *px = malloc(w * h * 3 * sizeof(float));
	rf_cubemap *c;
	size_t i, j, bad;
	char err[256];

	for (j = 0; j < h; j++)
		for (i = 0; i < w; i++) {
			float v = (i & 1) ? 2.0f : 0.0f;

			px[(j * w + i) * 3] = px[(j * w + i) * 3 + 1] = px[(j * w + i) * 3 + 2] = v;
		}
	ASSERT_EQ(rf_cubemap_create(&c, n, 1), 0);
	ASSERT_EQ(rf_envmap_from_pixels(c, px, w, h, 3, RF_LAYOUT_LATLONG, NULL, &bad, err,
	                                sizeof(err)), 0);
	for (j = 0; j < n; j++)
		for (i = 0; i < n; i++) {
			ASSERT_NEAR(rf_cubemap_texel_const(c, 0, RF_FACE_POS_Y, i, j)[0], 1.0, 0.08);
			ASSERT_NEAR(rf_cubemap_texel_const(c, 0, RF_FACE_POS_Z, i, j)[0], 1.0, 0.08);
		}
	free(px);
	rf_cubemap_destroy(c);
}

TEST(layout_detection_and_checks)
{
	enum rf_layout l;
	size_t face;
	char err[256];

	ASSERT_EQ(rf_layout_detect(64, 384, NULL, &l, err, sizeof(err)), 0);
	ASSERT_EQ(l, RF_LAYOUT_CUBE);
	ASSERT_EQ(rf_layout_detect(512, 256, NULL, &l, err, sizeof(err)), 0);
	ASSERT_EQ(l, RF_LAYOUT_LATLONG);
	ASSERT_EQ(rf_layout_detect(96, 128, NULL, &l, err, sizeof(err)), 0);
	ASSERT_EQ(l, RF_LAYOUT_VCROSS);
	ASSERT_EQ(rf_layout_detect(128, 96, NULL, &l, err, sizeof(err)), 0);
	ASSERT_EQ(l, RF_LAYOUT_HCROSS);
	ASSERT_EQ(rf_layout_detect(500, 256, "latlong", &l, err, sizeof(err)), 0);
	ASSERT_EQ(l, RF_LAYOUT_LATLONG);
	ASSERT(rf_layout_detect(100, 37, NULL, &l, err, sizeof(err)) < 0);
	ASSERT(strstr(err, "100x37"));
	ASSERT(rf_layout_check(RF_LAYOUT_CUBE, 512, 256, &face, err, sizeof(err)) < 0);
	ASSERT(strstr(err, "N x 6N"));
	ASSERT(rf_layout_check(RF_LAYOUT_CUBE, 3, 18, &face, err, sizeof(err)) < 0);
	ASSERT(strstr(err, "odd"));
	ASSERT_EQ(rf_layout_check(RF_LAYOUT_LATLONG, 2048, 1024, &face, err, sizeof(err)), 0);
	ASSERT_EQ(face, 512);
	ASSERT_EQ(rf_layout_check(RF_LAYOUT_LATLONG, 1000, 500, &face, err, sizeof(err)), 0);
	ASSERT_EQ(face, 128);
	ASSERT_EQ(rf_layout_parse("vcross", &l), 0);
	ASSERT(rf_layout_parse("strip", &l) < 0);
}

/* Decoding: sRGB, RGBM (Unity's rgb * m * a^e), intensity, NaN and Inf. */
TEST(decoding)
{
	float px[6 * 4 * 4];
	struct rf_decode dc = { 1, 1, 5.0f, 2.0f, 1.0f };
	rf_cubemap *c;
	size_t bad, k;
	char err[256];
	const float *t;

	for (k = 0; k < 6; k++) {
		px[k * 4] = 0.5f;
		px[k * 4 + 1] = 1.0f;
		px[k * 4 + 2] = 0.0f;
		px[k * 4 + 3] = 0.5f;
	}
	px[3 * 4 + 1] = NAN;
	px[4 * 4 + 2] = INFINITY;
	ASSERT_EQ(rf_cubemap_create(&c, 1, 1), 0);
	ASSERT_EQ(rf_envmap_from_pixels(c, px, 1, 6, 4, RF_LAYOUT_CUBE, &dc, &bad, err,
	                                sizeof(err)), 0);
	ASSERT_EQ(bad, 2);
	t = rf_cubemap_texel_const(c, 0, RF_FACE_POS_X, 0, 0);
	/* sRGB 0.5 is 0.214041 linear; times 5 * 0.5^2 */
	ASSERT_NEAR(t[0], 0.2140411 * 1.25, 1e-5);
	ASSERT_NEAR(t[1], 1.25, 1e-5);
	ASSERT_NEAR(t[2], 0.0, 1e-7);
	ASSERT_NEAR(rf_cubemap_texel_const(c, 0, RF_FACE_NEG_Y, 0, 0)[1], 0.0, 0.0);
	ASSERT_NEAR(rf_cubemap_texel_const(c, 0, RF_FACE_POS_Z, 0, 0)[2], 0.0, 0.0);
	rf_cubemap_destroy(c);
}

static rf_cubemap *
small_chain(struct rf_chain_info *info)
{
	struct rf_prefilter_options o;
	rf_cubemap *src, *out;
	char err[256];

	rf_cubemap_create(&src, 16, 1);
	rf_default_environment_cube(src);
	rf_cubemap_create(&out, 16, 4);
	rf_prefilter_defaults(&o);
	rf_prefilter(src, out, &o, err, sizeof(err));
	rf_cubemap_destroy(src);
	memset(info, 0, sizeof(*info));
	info->prefiltered = 1;
	info->mapping = RF_MAPPING_EXACT;
	info->steps = 3;
	info->samples = 64;
	info->base_copied = 1;
	return out;
}

static double
max_difference(const rf_cubemap *a, const rf_cubemap *b)
{
	double worst = 0.0;
	size_t k, i, j;
	int f, ch;

	for (k = 0; k < rf_cubemap_levels(a); k++)
		for (f = 0; f < 6; f++)
			for (j = 0; j < rf_cubemap_level_size(a, k); j++)
				for (i = 0; i < rf_cubemap_level_size(a, k); i++)
					for (ch = 0; ch < 3; ch++) {
						double d = fabs(rf_cubemap_texel_const(a, k, (enum rf_face)f, i, j)[ch] -
						                (double)rf_cubemap_texel_const(b, k, (enum rf_face)f, i, j)[ch]);

						if (d > worst)
							worst = d;
					}
	return worst;
}

TEST(chain_stream_roundtrip)
{
	struct rf_chain_info info, back_info;
	rf_cubemap *c = small_chain(&info), *back;
	struct rf_writer_options wo = { RF_FORMAT_FLOAT, 0 };
	FILE *fp = tmpfile();
	rf_writer *w;
	rf_reader *r;
	char err[256];

	ASSERT_EQ(rf_writer_open(&w, fp, "tmp", &wo), 0);
	ASSERT_EQ(rf_chain_write_stream(c, &info, w, NULL, err, sizeof(err)), 0);
	rf_writer_close(w);
	rewind(fp);
	ASSERT_EQ(rf_reader_open(&r, fp, "tmp", NULL), 0);
	ASSERT_EQ(rf_chain_read_stream(&back, &back_info, r, err, sizeof(err)), 0);
	ASSERT_EQ(rf_cubemap_levels(back), 4);
	ASSERT_EQ(back_info.prefiltered, 1);
	ASSERT_EQ(back_info.mapping, RF_MAPPING_EXACT);
	ASSERT_NEAR(back_info.steps, 3, 0);
	ASSERT_EQ(back_info.samples, 64);
	ASSERT(max_difference(c, back) == 0.0);
	rf_reader_close(r);
	fclose(fp);
	rf_cubemap_destroy(back);
	rf_cubemap_destroy(c);
}

TEST(chain_exr_roundtrip)
{
	struct rf_chain_info info, back_info;
	rf_cubemap *c = small_chain(&info), *back;
	char path[] = "/tmp/reflect-chain-XXXXXX.exr", err[512];
	int fd = mkstemps(path, 4), ours;
	size_t levels;

	ASSERT(fd >= 0);
	close(fd);
	ASSERT_EQ(rf_chain_write_file(c, &info, path, err, sizeof(err)), 0);
	/* 16 x 96 rounds down to 1x1 in 7 levels: 4 of them the cube's */
	ASSERT_EQ(rf_image_count_levels(path, &levels, err, sizeof(err)), 0);
	ASSERT_EQ(levels, 7);
	ASSERT_EQ(rf_chain_read_file(&back, &back_info, &ours, path, err, sizeof(err)), 0);
	ASSERT_EQ(ours, 1);
	ASSERT_EQ(rf_cubemap_levels(back), 4);
	ASSERT_EQ(back_info.mapping, RF_MAPPING_EXACT);
	ASSERT_EQ(back_info.prefiltered, 1);
	/* half floats: 3 significant digits on values up to ~18 */
	ASSERT(max_difference(c, back) < 0.02);
	unlink(path);
	rf_cubemap_destroy(back);
	rf_cubemap_destroy(c);
}

/* After the edge fixup, the two texels on either side of every edge (and
 * the three at every corner) hold one value, so a reader that clamps at
 * each face's edge shows no seam there; nothing away from edges moves. */
TEST(edge_fixup_makes_edges_equal)
{
	const size_t n = 8;
	rf_cubemap *c, *orig;
	size_t i, j;
	int f, a, b, ch;

	ASSERT_EQ(rf_cubemap_create(&c, n, 1), 0);
	ASSERT_EQ(rf_cubemap_create(&orig, n, 1), 0);
	rf_default_environment_cube(c);
	rf_default_environment_cube(orig);
	rf_cubemap_average_edges(c, 0);
	/* Each edge texel, and the texel its direction lands in when pushed
	 * just over the edge onto the neighbouring face. */
	for (f = 0; f < 6; f++)
		for (i = 0; i < n; i++) {
			float e = 0.25f / n, t = (i + 0.5f) / n;
			float inside[4][2] = { { e, t }, { 1 - e, t }, { t, e }, { t, 1 - e } };
			float over[4][2] = { { -e, t }, { 1 + e, t }, { t, -e }, { t, 1 + e } };

			for (a = 0; a < 4; a++) {
				float d[3], u, v;
				enum rf_face g;
				const float *p, *q;
				size_t gi, gj;

				rf_cube_direction((enum rf_face)f, over[a][0], over[a][1], d);
				g = rf_cube_face(d, &u, &v);
				ASSERT(g != (enum rf_face)f);
				gi = (size_t)(u * n);
				gj = (size_t)(v * n);
				p = rf_cubemap_texel_const(c, 0, (enum rf_face)f, (size_t)(inside[a][0] * n),
				                           (size_t)(inside[a][1] * n));
				q = rf_cubemap_texel_const(c, 0, g, gi < n ? gi : n - 1, gj < n ? gj : n - 1);
				for (ch = 0; ch < 3; ch++)
					ASSERT_NEAR(p[ch], q[ch], 1e-6);
			}
		}
	/* interior texels are untouched */
	for (f = 0; f < 6; f++)
		for (j = 1; j + 1 < n; j++)
			for (i = 1; i + 1 < n; i++)
				for (b = 0; b < 3; b++)
					ASSERT(rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j)[b] ==
					       rf_cubemap_texel_const(orig, 0, (enum rf_face)f, i, j)[b]);
	rf_cubemap_destroy(c);
	rf_cubemap_destroy(orig);
}

/* The embedded room renders to the same bytes on 1 and 3 threads, and a
 * texel is the mean of the room over a 4 x 4 grid of points inside it. */
TEST(default_room_threads)
{
	rf_cubemap *a, *b;
	size_t n = 32, i, j;
	int f;
	const float *t;

	ASSERT_EQ(rf_cubemap_create(&a, n, 1), 0);
	ASSERT_EQ(rf_cubemap_create(&b, n, 1), 0);
	rf_default_environment_cube(a);
	rf_default_environment_cube_threads(b, 3);
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++)
				ASSERT(!memcmp(rf_cubemap_texel_const(a, 0, (enum rf_face)f, i, j),
				               rf_cubemap_texel_const(b, 0, (enum rf_face)f, i, j),
				               3 * sizeof(float)));
	for (f = 0; f < 6; f++) {
		double want[3] = { 0, 0, 0 };
		int si, sj, k;

		i = 5 + 4 * (size_t)f;
		j = 27 - 3 * (size_t)f;
		for (sj = 0; sj < 4; sj++)
			for (si = 0; si < 4; si++) {
				float d[3], rgb[3];

				rf_cube_direction((enum rf_face)f, ((float)i + (si + 0.5f) / 4) / (float)n,
				                  ((float)j + (sj + 0.5f) / 4) / (float)n, d);
				rf_default_environment(d, rgb);
				for (k = 0; k < 3; k++)
					want[k] += rgb[k] / 16.0;
			}
		t = rf_cubemap_texel_const(b, 0, (enum rf_face)f, i, j);
		for (k = 0; k < 3; k++)
			ASSERT_NEAR(t[k], want[k], 1e-5 * want[k] + 1e-6);
	}
	rf_cubemap_destroy(a);
	rf_cubemap_destroy(b);
}

/* The loader is a library call: every failure is a status and a message
 * naming the file, never an exit. */
TEST(load_reports_instead_of_exiting)
{
	struct rf_envmap_options o;
	struct rf_chain_info info, back_info;
	rf_cubemap *c = small_chain(&info), *back;
	struct rf_writer_options wo = { RF_FORMAT_FLOAT, 0 };
	char path[] = "/tmp/reflect-load-XXXXXX.rfl", err[512];
	int fd = mkstemps(path, 4);
	size_t bad = 99, levels;
	rf_writer *w;
	FILE *fp;

	ASSERT(fd >= 0);
	ASSERT(fp = fdopen(fd, "wb"));
	ASSERT_EQ(rf_writer_open(&w, fp, path, &wo), 0);
	ASSERT_EQ(rf_chain_write_stream(c, &info, w, NULL, err, sizeof(err)), 0);
	rf_writer_close(w);
	fclose(fp);
	rf_envmap_options_init(&o);

	/* A stream file: the chain with its info, nothing replaced. */
	ASSERT_EQ(rf_envmap_load(&back, &back_info, path, &o, &bad, err, sizeof(err)), 0);
	ASSERT_EQ(bad, 0);
	ASSERT_EQ(rf_cubemap_levels(back), 4);
	ASSERT_EQ(back_info.prefiltered, 1);
	ASSERT_EQ(back_info.mapping, RF_MAPPING_EXACT);
	ASSERT(max_difference(c, back) == 0.0);
	rf_cubemap_destroy(back);
	unlink(path);

	/* Gone: RF_ENOTFOUND, the path and the reason. */
	ASSERT_EQ(rf_envmap_load(&back, &back_info, path, &o, NULL, err, sizeof(err)),
	          RF_ENOTFOUND);
	ASSERT(back == NULL);
	ASSERT(strstr(err, path) && strstr(err, "No such file"));

	/* A directory is no environment; a header may not name stdin. */
	ASSERT_EQ(rf_envmap_load(&back, &back_info, "/tmp", &o, NULL, err, sizeof(err)),
	          RF_EINVAL);
	ASSERT(strstr(err, "'/tmp': not a regular file (a directory)"));
	o.from_header = 1;
	ASSERT_EQ(rf_envmap_load(&back, &back_info, "-", &o, NULL, err, sizeof(err)),
	          RF_EINVAL);
	ASSERT(strstr(err, "PROBE_ENV '-'"));
	o.from_header = 0;

	/* Face patterns need one %d or %s. */
	ASSERT_EQ(rf_envmap_load(&back, &back_info, "face%x.png", &o, NULL, err,
	                         sizeof(err)), RF_EINVAL);
	ASSERT(strstr(err, "needs one %d"));

	/* The embedded room at the size asked for, one level, raw. */
	o.size = 8;
	ASSERT_EQ(rf_envmap_load(&back, &back_info, NULL, &o, NULL, err, sizeof(err)), 0);
	ASSERT_EQ(rf_cubemap_size(back), 8);
	ASSERT_EQ(rf_cubemap_levels(back), 1);
	ASSERT_EQ(back_info.prefiltered, 0);
	rf_cubemap_destroy(back);

	/* Chain lengths: 256 gives Unity's 7 levels, 6 cannot halve twice. */
	ASSERT_EQ(rf_chain_levels(256, 0, 1, &levels, err, sizeof(err)), 0);
	ASSERT_EQ(levels, 7);
	ASSERT_EQ(rf_chain_levels(256, 0, 64, &levels, err, sizeof(err)), 0);
	ASSERT_EQ(levels, 3);
	ASSERT_EQ(rf_chain_levels(6, 3, 1, &levels, err, sizeof(err)), RF_EINVAL);
	ASSERT(strstr(err, "a 6-texel cube has no 3 levels (it halves to 3)"));
	rf_cubemap_destroy(c);
}

int
main(void)
{
	RUN(cube_layout);
	RUN(horizontal_cross);
	RUN(vertical_cross);
	RUN(cross_slots_touch_on_the_cube);
	RUN(latlong_axes_match_cube);
	RUN(latlong_filtered_at_poles);
	RUN(layout_detection_and_checks);
	RUN(decoding);
	RUN(chain_stream_roundtrip);
	RUN(chain_exr_roundtrip);
	RUN(load_reports_instead_of_exiting);
	RUN(edge_fixup_makes_edges_equal);
	RUN(default_room_threads);
	TAP_DONE();
}
