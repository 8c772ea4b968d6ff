/* Unit tests of image writing and reading (OpenImageIO bridge) and of the
 * display encoding (sRGB, exposure, tone curve). */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include "reflect/reflect.h"
#include "tap.h"

static char dir[256];

static const char *
tmp_path(const char *name)
{
	static char path[512];

	snprintf(path, sizeof(path), "%s/%s", dir, name);
	return path;
}

/* Writes a w x h image of nch channels in two blocks of rows. */
static int
write_image(const char *path, size_t w, size_t h, size_t nch,
            const char *const *names, enum rf_pixel_type type, const float *px,
            char *err, size_t errlen)
{
	rf_image_writer *wr;
	int rc;

	if ((rc = rf_image_writer_open(&wr, path, w, h, nch, names, type, err,
	                               errlen)) < 0)
		return rc;
	if ((rc = rf_image_writer_write_rows(wr, 0, 1, px)) < 0 ||
	    (h > 1 && (rc = rf_image_writer_write_rows(wr, 1, h - 1, px + w * nch)) < 0)) {
		snprintf(err, errlen, "%s", rf_image_writer_error(wr));
		rf_image_writer_close(wr, NULL, 0);
		return rc;
	}
	return rf_image_writer_close(wr, err, errlen);
}

/* Index of a channel of the image read back, -1 when absent (the reader
 * may order an EXR's channels its own way). */
static int
channel_index(const rf_image *img, const char *name)
{
	size_t c;

	for (c = 0; c < rf_image_nchannels(img); c++)
		if (!strcmp(rf_image_channel(img, c), name))
			return (int)c;
	return -1;
}

/* 3 x 2 pixels, 4 channels: values a float keeps exactly, some a half
 * cannot (0.1, 1000.3, 3.14159). */
static const char *const exr_names[] = { "spec.R", "spec.G", "spec.B", "hit.dist" };
static const float exr_px[24] = {
	0.1f, -2.5f, 1000.3f, 1e-3f,
	0.0f, 1.0f, 0.5f, 2.0f,
	3.14159f, -0.75f, 65000.0f, 7.0f,
	0.25f, 0.125f, 1.5f, 1e4f,
	-1.0f, 42.0f, 0.3f, 0.0625f,
	2e-3f, 8.0f, 16.5f, 100.0f,
};

TEST(exr_float_roundtrip)
{
	char err[1024];
	const char *path = tmp_path("float.exr");
	rf_image *img;
	size_t i, c;

	ASSERT_EQ(write_image(path, 3, 2, 4, exr_names, RF_PIXEL_FLOAT, exr_px, err,
	                      sizeof(err)), 0);
	ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_width(img), 3);
	ASSERT_EQ(rf_image_height(img), 2);
	ASSERT_EQ(rf_image_nchannels(img), 4);
	for (c = 0; c < 4; c++) {
		int k = channel_index(img, exr_names[c]);

		if (k < 0)
			TAP_FAIL("channel %s not read back", exr_names[c]);
		for (i = 0; i < 6; i++)
			if (rf_image_pixels(img)[i * 4 + (size_t)k] != exr_px[i * 4 + c])
				TAP_FAIL("%s pixel %zu: %.9g != %.9g", exr_names[c], i,
				         (double)rf_image_pixels(img)[i * 4 + (size_t)k],
				         (double)exr_px[i * 4 + c]);
	}
	rf_image_destroy(img);
}

TEST(exr_half_roundtrip)
{
	char err[1024];
	const char *path = tmp_path("half.exr");
	rf_image *img;
	size_t i, c;
	int k;

	ASSERT_EQ(write_image(path, 3, 2, 4, exr_names, RF_PIXEL_HALF, exr_px, err,
	                      sizeof(err)), 0);
	ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_nchannels(img), 4);
	for (c = 0; c < 4; c++) {
		k = channel_index(img, exr_names[c]);
		if (k < 0)
			TAP_FAIL("channel %s not read back", exr_names[c]);
		for (i = 0; i < 6; i++) {
			double want = exr_px[i * 4 + c];
			double got = rf_image_pixels(img)[i * 4 + (size_t)k];

			/* Half: 11 significant bits, rounded to nearest. */
			if (!(fabs(got - want) <= fabs(want) * 0x1p-11 + 1e-7))
				TAP_FAIL("%s pixel %zu: %.9g != %.9g (half)", exr_names[c],
				         i, got, want);
		}
	}
	/* It really is half: 0.1 becomes 1638 / 16384, the nearest half. */
	k = channel_index(img, "spec.R");
	ASSERT(k >= 0);
	ASSERT(rf_image_pixels(img)[k] == 0.0999755859375f);
	rf_image_destroy(img);
}

/* round(clamp(v) * 255) / 255 */
static double
quantise(double v, double levels)
{
	v = v < 0 ? 0 : v > 1 ? 1 : v;
	return floor(v * levels + 0.5) / levels;
}

TEST(png_8bit_roundtrip)
{
	static const char *const names[] = { "spec.R", "spec.G", "spec.B" };
	/* 0.2 * 255 = 51, 0.25 -> 63.75 -> 64, 0.75 -> 191.25 -> 191,
	 * 0.6 -> 153, out of range clamps. */
	static const float px[12] = {
		0.0f, 1.0f, 0.2f,
		0.25f, 0.75f, 0.6f,
		-0.5f, 1.7f, 0.01f,
		0.999f, 0.4f, 0.8f,
	};
	char err[1024];
	const char *path = tmp_path("rgb.png");
	rf_image *img;
	size_t i;

	ASSERT_EQ(write_image(path, 2, 2, 3, names, RF_PIXEL_UINT8, px, err,
	                      sizeof(err)), 0);
	ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_width(img), 2);
	ASSERT_EQ(rf_image_nchannels(img), 3);
	/* PNG keeps no names: the reader calls them R G B. */
	ASSERT_STR_EQ(rf_image_channel(img, 0), "R");
	ASSERT_STR_EQ(rf_image_channel(img, 1), "G");
	ASSERT_STR_EQ(rf_image_channel(img, 2), "B");
	for (i = 0; i < 12; i++)
		ASSERT_NEAR(rf_image_pixels(img)[i], quantise(px[i], 255), 1e-6);
	ASSERT_NEAR(rf_image_pixels(img)[2], 51 / 255.0, 1e-6);
	ASSERT_NEAR(rf_image_pixels(img)[3], 64 / 255.0, 1e-6);
	ASSERT_NEAR(rf_image_pixels(img)[4], 191 / 255.0, 1e-6);
	rf_image_destroy(img);
}

TEST(png_alpha_is_kept_straight)
{
	static const char *const names[] = { "R", "G", "B", "A" };
	static const float px[8] = { 1.0f, 0.6f, 0.2f, 0.2f, 0.4f, 0.4f, 0.4f, 0.0f };
	char err[1024];
	const char *path = tmp_path("rgba.png");
	rf_image *img;
	size_t i;

	ASSERT_EQ(write_image(path, 2, 1, 4, names, RF_PIXEL_UINT8, px, err,
	                      sizeof(err)), 0);
	ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_nchannels(img), 4);
	ASSERT_STR_EQ(rf_image_channel(img, 3), "A");
	/* Neither divided by alpha when written nor multiplied when read. */
	for (i = 0; i < 8; i++)
		ASSERT_NEAR(rf_image_pixels(img)[i], quantise(px[i], 255), 1e-6);
	rf_image_destroy(img);
}

TEST(png_16bit_roundtrip)
{
	/* Away from ties (0.7 * 65535 = 45874.5 in float rounds either way):
	 * 0.2 -> 13107, 0.6 -> 39321, 1/3 -> 21845. */
	static const float px[3] = { 0.2f, 0.6f, 1.0f / 3.0f };
	char err[1024];
	const char *path = tmp_path("grey16.png");
	rf_image *img;
	size_t i;

	ASSERT_EQ(write_image(path, 3, 1, 1, NULL, RF_PIXEL_UINT16, px, err,
	                      sizeof(err)), 0);
	ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_nchannels(img), 1);
	for (i = 0; i < 3; i++)
		ASSERT_NEAR(rf_image_pixels(img)[i], quantise(px[i], 65535), 1e-7);
	/* 1/3 * 65535 = 21845 exactly. */
	ASSERT_NEAR(rf_image_pixels(img)[2], 21845 / 65535.0, 1e-7);
	rf_image_destroy(img);
}

/* Rows in blocks of 1, 15, 16 and 5 (and the rest), across the OpenEXR
 * chunks of 16 rows and the PNG rows: each value read back as written. */
static int
write_in_odd_blocks(const char *path, size_t w, size_t h, size_t nch,
                    const char *const *names, enum rf_pixel_type type,
                    const float *px, char *err, size_t errlen)
{
	static const size_t blocks[] = { 1, 15, 16, 5 };
	rf_image_writer *wr;
	size_t y = 0, k = 0, n;
	int rc;

	if ((rc = rf_image_writer_open(&wr, path, w, h, nch, names, type, err,
	                               errlen)) < 0)
		return rc;
	for (; y < h; y += n, k++) {
		n = k < 4 ? blocks[k] : h - y;
		n = n < h - y ? n : h - y;
		if ((rc = rf_image_writer_write_rows(wr, y, n, px + y * w * nch)) < 0) {
			snprintf(err, errlen, "%s", rf_image_writer_error(wr));
			rf_image_writer_close(wr, NULL, 0);
			return rc;
		}
	}
	return rf_image_writer_close(wr, err, errlen);
}

TEST(exr_odd_blocks_and_default_names)
{
	enum { W = 5, H = 61, N = 3 };
	static float px[W * H * N];
	static const char *const rgb[] = { "R", "G", "B" };
	const char *path = tmp_path("blocks.exr");
	enum rf_pixel_type types[2] = { RF_PIXEL_FLOAT, RF_PIXEL_HALF };
	char err[1024];
	rf_image *img;
	size_t i, c, t;
	int k;

	/* Multiples of 1/8 in [-64, 64): exact in half too. */
	for (i = 0; i < W * H * N; i++)
		px[i] = (float)((int)(i * 37 % 1024) - 512) / 8.0f;
	for (t = 0; t < 2; t++) {
		/* No names: OpenImageIO's defaults, R G B for 3 channels. */
		ASSERT_EQ(write_in_odd_blocks(path, W, H, N, NULL, types[t], px, err,
		                              sizeof(err)), 0);
		ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
		ASSERT_EQ(rf_image_width(img), W);
		ASSERT_EQ(rf_image_height(img), H);
		ASSERT_EQ(rf_image_nchannels(img), N);
		for (c = 0; c < N; c++) {
			if ((k = channel_index(img, rgb[c])) < 0)
				TAP_FAIL("no channel %s", rgb[c]);
			for (i = 0; i < W * H; i++)
				if (rf_image_pixels(img)[i * N + (size_t)k] != px[i * N + c])
					TAP_FAIL("%s pixel %zu: %.9g != %.9g", rgb[c], i,
					         (double)rf_image_pixels(img)[i * N + (size_t)k],
					         (double)px[i * N + c]);
		}
		rf_image_destroy(img);
	}
	/* One channel without a name is Y. */
	ASSERT_EQ(write_image(path, 2, 1, 1, NULL, RF_PIXEL_FLOAT, px, err,
	                      sizeof(err)), 0);
	ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
	ASSERT_STR_EQ(rf_image_channel(img, 0), "Y");
	rf_image_destroy(img);
}

TEST(png_odd_blocks_grey_alpha)
{
	enum { W = 3, H = 40, N = 2 };
	static float px[W * H * N];
	const char *path = tmp_path("ga.png");
	char err[1024];
	rf_image *img;
	size_t i;

	for (i = 0; i < W * H * N; i++)
		px[i] = (float)(i * 7 % 256) / 255.0f;
	ASSERT_EQ(write_in_odd_blocks(path, W, H, N, NULL, RF_PIXEL_UINT8, px, err,
	                              sizeof(err)), 0);
	ASSERT_EQ(rf_image_read(&img, path, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_height(img), H);
	ASSERT_EQ(rf_image_nchannels(img), N);
	for (i = 0; i < W * H * N; i++)
		ASSERT_NEAR(rf_image_pixels(img)[i] * 255.0f, (double)(i * 7 % 256), 1e-4);
	rf_image_destroy(img);
}

TEST(writer_errors_png_exr)
{
	static const float px[8] = { 0 };
	static const char *const twice[] = { "a", "a" };
	char err[1024] = "";
	rf_image_writer *wr;

	/* PNG: rows in order, all of them; the writer is freed all the same. */
	ASSERT_EQ(rf_image_writer_open(&wr, tmp_path("order.png"), 1, 2, 3, NULL,
	                               RF_PIXEL_UINT16, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_writer_write_rows(wr, 0, 3, px), RF_EINVAL);
	ASSERT(strstr(rf_image_writer_error(wr), "rows out of order") != NULL);
	ASSERT_EQ(rf_image_writer_write_rows(wr, 0, 1, px), 0);
	ASSERT_EQ(rf_image_writer_close(wr, err, sizeof(err)), RF_EINVAL);
	ASSERT(strstr(err, "'") && strstr(err, "order.png': image is incomplete"));
	/* OpenEXR holds each name once. */
	ASSERT(rf_image_writer_open(&wr, tmp_path("twice.exr"), 1, 1, 2, twice,
	                            RF_PIXEL_HALF, err, sizeof(err)) < 0);
	ASSERT(wr == NULL);
	ASSERT(strstr(err, "cannot write '") == err);
	ASSERT(strstr(err, "twice.exr': channel 'a' is given twice") != NULL);
	/* A directory is no file: the system says so, a system error. */
	ASSERT_EQ(mkdir(tmp_path("d.exr"), 0777), 0);
	ASSERT_EQ(rf_image_writer_open(&wr, tmp_path("d.exr"), 1, 1, 1, NULL,
	                               RF_PIXEL_FLOAT, err, sizeof(err)), RF_EIO);
	ASSERT(strstr(err, strerror(EISDIR)) != NULL);
	ASSERT_EQ(mkdir(tmp_path("d.png"), 0777), 0);
	ASSERT_EQ(rf_image_writer_open(&wr, tmp_path("d.png"), 1, 1, 1, NULL,
	                               RF_PIXEL_UINT8, err, sizeof(err)), RF_EIO);
	ASSERT(strstr(err, strerror(EISDIR)) != NULL);
	rmdir(tmp_path("d.exr"));
	rmdir(tmp_path("d.png"));
}

TEST(writer_errors)
{
	static const float px[4] = { 0 };
	char err[1024] = "";
	rf_image_writer *wr;

	/* Rows must come in order, and all of them. */
	ASSERT_EQ(rf_image_writer_open(&wr, tmp_path("order.exr"), 1, 2, 2, NULL,
	                               RF_PIXEL_FLOAT, err, sizeof(err)), 0);
	ASSERT_EQ(rf_image_writer_write_rows(wr, 1, 1, px), RF_EINVAL);
	ASSERT(strstr(rf_image_writer_error(wr), "rows out of order") != NULL);
	ASSERT_EQ(rf_image_writer_write_rows(wr, 0, 1, px), 0);
	ASSERT_EQ(rf_image_writer_close(wr, err, sizeof(err)), RF_EINVAL);
	ASSERT(strstr(err, "image is incomplete") != NULL);
	ASSERT(strstr(err, "order.exr") != NULL);
	/* A directory that is not there: the system's reason, a system error. */
	ASSERT_EQ(rf_image_writer_open(&wr, tmp_path("no/such/dir.png"), 1, 1, 1,
	                               NULL, RF_PIXEL_UINT8, err, sizeof(err)),
	          RF_EIO);
	ASSERT(wr == NULL);
	ASSERT(strstr(err, "cannot write '") == err);
	ASSERT(strstr(err, strerror(ENOENT)) != NULL);
	/* Nothing writes .xyz, and sizes must be at least 1. */
	ASSERT(rf_image_writer_open(&wr, tmp_path("a.xyz"), 1, 1, 1, NULL,
	                            RF_PIXEL_FLOAT, err, sizeof(err)) < 0);
	ASSERT(rf_image_writer_open(&wr, tmp_path("a.exr"), 0, 1, 1, NULL,
	                            RF_PIXEL_FLOAT, err, sizeof(err)) < 0);
	/* Reading a file that is not there says why. */
	{
		rf_image *img;

		ASSERT(rf_image_read(&img, tmp_path("missing.exr"), err, sizeof(err)) < 0);
		ASSERT(strstr(err, strerror(ENOENT)) != NULL);
	}
}

TEST(type_for_path)
{
	ASSERT_EQ(rf_image_type_for_path("a.exr"), RF_PIXEL_FLOAT);
	ASSERT_EQ(rf_image_type_for_path("a.hdr"), RF_PIXEL_FLOAT);
	ASSERT_EQ(rf_image_type_for_path("A.PNG"), RF_PIXEL_UINT8);
	ASSERT_EQ(rf_image_type_for_path("x.jpeg"), RF_PIXEL_UINT8);
	ASSERT_EQ(rf_image_type_for_path("frame%04d.tif"), RF_PIXEL_UINT8);
	ASSERT_EQ(rf_image_type_for_path("noextension"), -1);
	ASSERT_EQ(rf_image_type_for_path("dir.exr/noextension"), -1);
	ASSERT_EQ(rf_image_type_for_path("a.xyz"), -1);
	ASSERT_EQ(rf_image_type_for_path("a.pfm"), -1); /* listed, not writable */
}

/* The sRGB transfer functions (IEC 61966-2-1), in double. */
static double
srgb_encode_ref(double x)
{
	return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
}

static double
srgb_decode_ref(double y)
{
	return y <= 0.04045 ? y / 12.92 : pow((y + 0.055) / 1.055, 2.4);
}

TEST(srgb_known_points)
{
	/* Values worked out by hand from the formula. */
	ASSERT(rf_srgb_encode(0.0f) == 0.0f);
	ASSERT(rf_srgb_encode(1.0f) == 1.0f);
	ASSERT_NEAR(rf_srgb_encode(0.001f), 0.01292, 1e-7);        /* linear part */
	ASSERT_NEAR(rf_srgb_encode(0.0031308f), 0.0404499, 1e-6);  /* the knee */
	ASSERT_NEAR(rf_srgb_encode(0.5f), 0.735356983, 1e-6);
	ASSERT_NEAR(rf_srgb_encode(0.18f), 0.461356129, 1e-6);     /* mid grey */
	ASSERT_NEAR(rf_srgb_encode(0.25f), 0.537098730, 1e-6);
	ASSERT_NEAR(rf_srgb_decode(0.5f), 0.214041140, 1e-6);
	ASSERT_NEAR(rf_srgb_decode(0.04045f), 0.0031308, 1e-7);
	ASSERT_NEAR(rf_srgb_decode(1.0f), 1.0, 1e-6);
	/* Outside [0, 1]: encode clamps, NaN is 0. */
	ASSERT(rf_srgb_encode(-1.0f) == 0.0f);
	ASSERT(rf_srgb_encode(2.0f) == 1.0f);
	ASSERT(rf_srgb_encode(NAN) == 0.0f);
	ASSERT(rf_srgb_decode(-0.5f) == 0.0f);
	ASSERT(rf_srgb_decode(NAN) == 0.0f);
}

TEST(srgb_matches_formula_and_inverts)
{
	int i;

	for (i = 0; i <= 1000; i++) {
		double x = i / 1000.0;
		float e = rf_srgb_encode((float)x), d = rf_srgb_decode((float)x);

		ASSERT_NEAR(e, srgb_encode_ref(x), 1e-6);
		ASSERT_NEAR(d, srgb_decode_ref(x), 1e-6);
		ASSERT_NEAR(rf_srgb_decode(e), x, 2e-6 + 1e-5 * x);
		ASSERT_NEAR(rf_srgb_encode(d), x, 2e-6 + 1e-5 * x);
	}
}

TEST(display_encode)
{
	/* One pixel of R G B A: exposure x2 then sRGB on R G B, A clamped. */
	float v[8] = { 0.25f, 2.0f, NAN, 0.5f, -1.0f, 0.0015f, 0.09f, 1.5f };

	rf_display_encode(v, 2, 4, 3, 2.0f, RF_TONE_NONE, 1);
	ASSERT_NEAR(v[0], 0.735356983, 1e-6); /* 0.5 encoded */
	ASSERT(v[1] == 1.0f);                 /* 4 clamps */
	ASSERT(v[2] == 0.0f);                 /* NaN -> 0 */
	ASSERT(v[3] == 0.5f);                 /* alpha: not scaled, not encoded */
	ASSERT(v[4] == 0.0f);
	ASSERT_NEAR(v[5], 12.92 * 0.003, 1e-7);
	ASSERT_NEAR(v[6], 0.461356129, 1e-6); /* 0.18 encoded */
	ASSERT(v[7] == 1.0f);                 /* alpha 1.5 clamps */

	/* The filmic curve x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14),
	 * without sRGB: 1 -> 2.54 / 3.16; 0.5 -> 0.6425 / 1.0425. */
	{
		float f[3] = { 1.0f, 0.5f, 1e6f };

		rf_display_encode(f, 3, 1, 1, 1.0f, RF_TONE_FILMIC, 0);
		ASSERT_NEAR(f[0], 2.54 / 3.16, 1e-6);
		ASSERT_NEAR(f[1], 0.6425 / 1.0425, 1e-6);
		ASSERT(f[2] == 1.0f);
	}
}

int
main(void)
{
	snprintf(dir, sizeof(dir), "%s/test-image.XXXXXX",
	         getenv("TMPDIR") && *getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
	if (!mkdtemp(dir)) {
		printf("Bail out! cannot make a temporary directory\n");
		return 1;
	}
	RUN(exr_float_roundtrip);
	RUN(exr_half_roundtrip);
	RUN(png_8bit_roundtrip);
	RUN(png_alpha_is_kept_straight);
	RUN(png_16bit_roundtrip);
	RUN(exr_odd_blocks_and_default_names);
	RUN(png_odd_blocks_grey_alpha);
	RUN(writer_errors_png_exr);
	RUN(writer_errors);
	RUN(type_for_path);
	RUN(srgb_known_points);
	RUN(srgb_matches_formula_and_inverts);
	RUN(display_encode);
	{
		static const char *const files[] = {
			"float.exr", "half.exr", "rgb.png", "rgba.png", "grey16.png",
			"order.exr", "blocks.exr", "ga.png", "order.png", "twice.exr",
			NULL
		};
		size_t i;

		for (i = 0; files[i]; i++)
			unlink(tmp_path(files[i]));
		rmdir(dir);
	}
	TAP_DONE();
}
