/*
 * Unit tests of the DDS chain reader.  Every fixture is written here, by
 * a small DDS writer that follows the format's documentation rather than
 * the reader, into /tmp, and removed after reading.
 */
#include <stdint.h>
#include <unistd.h>

#include "reflect/envmap.h"
#include "tap.h"

#define CUBE_ALL_FACES 0xfe00u /* DDSCAPS2_CUBEMAP and the six face bits */
#define DDPF_FOURCC 0x4u
#define DDPF_RGB 0x40u
#define DDPF_ALPHAPIXELS 0x1u
#define FOURCC(a, b, c, d)                                                   \
	((uint32_t)(a) | (uint32_t)(b) << 8 | (uint32_t)(c) << 16 | (uint32_t)(d) << 24)

/* ---- the DDS writer ------------------------------------------------------ */

struct fixture;
/* Writes the bytes of texel (i, j) of face f at level k (Direct3D's own
 * texel coordinates: i across, j down, row 0 first in the file). */
typedef void (*texel_fn)(const struct fixture *fx, int f, unsigned k, unsigned i,
                         unsigned j, unsigned char *out);

struct fixture {
	const char *magic;
	uint32_t header_size, pf_size;
	uint32_t width, height, mips, caps2, flags, depth;
	int dx10;
	uint32_t dxgi, dim, misc, array;
	uint32_t pf_flags, fourcc, bits, masks[4];
	unsigned bytes;   /* per texel */
	texel_fn texel;
	const void *arg;
	long length;      /* > 0: the file is cut to this many bytes */
};

static void
put32(unsigned char *p, uint32_t v)
{
	p[0] = (unsigned char)v;
	p[1] = (unsigned char)(v >> 8);
	p[2] = (unsigned char)(v >> 16);
	p[3] = (unsigned char)(v >> 24);
}

static void
put16(unsigned char *p, unsigned v)
{
	p[0] = (unsigned char)v;
	p[1] = (unsigned char)(v >> 8);
}

static void
putf(unsigned char *p, float f)
{
	uint32_t u;

	memcpy(&u, &f, sizeof(u));
	put32(p, u);
}

static struct fixture
dx10_cube(uint32_t dxgi, unsigned bytes, uint32_t n, uint32_t mips)
{
	struct fixture fx;

	memset(&fx, 0, sizeof(fx));
	fx.magic = "DDS ";
	fx.header_size = 124;
	fx.pf_size = 32;
	fx.width = fx.height = n;
	fx.mips = mips;
	fx.caps2 = CUBE_ALL_FACES;
	fx.flags = 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000;
	fx.dx10 = 1;
	fx.pf_flags = DDPF_FOURCC;
	fx.fourcc = FOURCC('D', 'X', '1', '0');
	fx.dxgi = dxgi;
	fx.dim = 3;
	fx.misc = 0x4;
	fx.array = 1;
	fx.bytes = bytes;
	return fx;
}

static struct fixture
legacy_cube(uint32_t pf_flags, uint32_t fourcc, uint32_t bits, const uint32_t masks[4],
            unsigned bytes, uint32_t n, uint32_t mips)
{
	struct fixture fx = dx10_cube(0, bytes, n, mips);

	fx.dx10 = 0;
	fx.pf_flags = pf_flags;
	fx.fourcc = fourcc;
	fx.bits = bits;
	if (masks)
		memcpy(fx.masks, masks, sizeof(fx.masks));
	return fx;
}

/* Writes the fixture to a new file in /tmp; its name in path. */
static int
write_fixture(const struct fixture *fx, char path[64])
{
	size_t head = 4 + 124 + (fx->dx10 ? 20 : 0), total = head, at;
	unsigned char *buf;
	unsigned k, i, j;
	FILE *fp;
	int f, fd;

	/* Without texels only the headers are written (the size tests'
	 * headers promise more than could be written). */
	for (k = 0; fx->texel && k < (fx->mips ? fx->mips : 1); k++) {
		size_t s = fx->width >> k ? fx->width >> k : 1;

		total += 6 * s * s * fx->bytes;
	}
	if (!(buf = calloc(1, total)))
		return -1;
	memcpy(buf, fx->magic, 4);
	put32(buf + 4, fx->header_size);
	put32(buf + 8, fx->flags);
	put32(buf + 12, fx->height);
	put32(buf + 16, fx->width);
	put32(buf + 20, fx->width * fx->bytes);
	put32(buf + 24, fx->depth);
	put32(buf + 28, fx->mips);
	put32(buf + 76, fx->pf_size);
	put32(buf + 80, fx->pf_flags);
	put32(buf + 84, fx->fourcc);
	put32(buf + 88, fx->bits);
	for (k = 0; k < 4; k++)
		put32(buf + 92 + 4 * k, fx->masks[k]);
	put32(buf + 108, 0x1000 | 0x8 | 0x400000);
	put32(buf + 112, fx->caps2);
	if (fx->dx10) {
		put32(buf + 128, fx->dxgi);
		put32(buf + 132, fx->dim);
		put32(buf + 136, fx->misc);
		put32(buf + 140, fx->array);
	}
	/* face by face, each face's levels largest first, rows top first */
	at = head;
	if (fx->texel)
		for (f = 0; f < 6; f++)
			for (k = 0; k < (fx->mips ? fx->mips : 1); k++) {
				unsigned s = fx->width >> k ? fx->width >> k : 1;

				for (j = 0; j < s; j++)
					for (i = 0; i < s; i++, at += fx->bytes)
						fx->texel(fx, f, k, i, j, buf + at);
			}
	strcpy(path, "/tmp/reflect-dds-XXXXXX.dds");
	if ((fd = mkstemps(path, 4)) < 0 || !(fp = fdopen(fd, "wb"))) {
		free(buf);
		return -1;
	}
	if (fx->length > 0 && (size_t)fx->length < total)
		total = (size_t)fx->length;
	fwrite(buf, 1, total, fp);
	fclose(fp);
	free(buf);
	return 0;
}

/* Writes, reads and removes a fixture. */
static int
read_fixture(const struct fixture *fx, rf_cubemap **c, struct rf_chain_info *info,
             size_t *bad, char path[64], char *err, size_t errlen)
{
	int rc;

	if (write_fixture(fx, path) < 0)
		return -9999;
	rc = rf_chain_read_dds(c, info, bad, path, err, errlen);
	unlink(path);
	return rc;
}

/* ---- Direct3D's cube, derived independently of the reader ------------------ */

/*
 * The direction through position (u, v) of a face, from the cube face
 * selection table Direct3D shares with OpenGL (sc, tc over |ma|, mapped to
 * [0, 1] as u = (sc/|ma| + 1)/2, v = (tc/|ma| + 1)/2, v = 0 the first row):
 *
 *	+X: sc = -z tc = -y   -X: sc = +z tc = -y   +Y: sc = +x tc = +z
 *	-Y: sc = +x tc = -z   +Z: sc = +x tc = -y   -Z: sc = -x tc = -y
 */
static void
d3d_direction(int face, float u, float v, float d[3])
{
	float s = 2.0f * u - 1.0f, t = 2.0f * v - 1.0f;

	switch (face) {
	case 0: d[0] = 1.0f; d[1] = -t; d[2] = -s; break;
	case 1: d[0] = -1.0f; d[1] = -t; d[2] = s; break;
	case 2: d[0] = s; d[1] = 1.0f; d[2] = t; break;
	case 3: d[0] = s; d[1] = -1.0f; d[2] = -t; break;
	case 4: d[0] = s; d[1] = -t; d[2] = 1.0f; break;
	default: d[0] = -s; d[1] = -t; d[2] = -1.0f; break;
	}
}

/* ---- formats: encoders of small integer labels ----------------------------- */

/* A float of 5 exponent bits (bias 15) and mbits mantissa bits holding
 * the integer n exactly (n small enough). */
static unsigned
small_float_bits(unsigned n, unsigned mbits)
{
	unsigned e = 0;

	if (!n)
		return 0;
	while (n >> (e + 1))
		e++;
	return (e + 15) << mbits | (((n << mbits) >> e) & ((1u << mbits) - 1));
}

static void
enc_f32x4(const float v[3], unsigned char *o)
{
	putf(o, v[0]);
	putf(o + 4, v[1]);
	putf(o + 8, v[2]);
	putf(o + 12, 99.0f); /* alpha, ignored */
}

static void
enc_f32x3(const float v[3], unsigned char *o)
{
	putf(o, v[0]);
	putf(o + 4, v[1]);
	putf(o + 8, v[2]);
}

static void
enc_f32x1(const float v[3], unsigned char *o)
{
	putf(o, v[0]);
}

static void
enc_f16x4(const float v[3], unsigned char *o)
{
	int c;

	for (c = 0; c < 3; c++)
		put16(o + 2 * c, small_float_bits((unsigned)v[c], 10));
	put16(o + 6, 0x3c00);
}

static void
enc_r11g11b10(const float v[3], unsigned char *o)
{
	put32(o, small_float_bits((unsigned)v[0], 6) |
	         small_float_bits((unsigned)v[1], 6) << 11 |
	         small_float_bits((unsigned)v[2], 5) << 22);
}

/* Shared exponent 24 (bias 15 plus 9 mantissa bits): the mantissas are
 * the integers themselves. */
static void
enc_rgb9e5(const float v[3], unsigned char *o)
{
	put32(o, (uint32_t)v[0] | (uint32_t)v[1] << 9 | (uint32_t)v[2] << 18 | 24u << 27);
}

static void
enc_rgba8(const float v[3], unsigned char *o)
{
	o[0] = (unsigned char)v[0];
	o[1] = (unsigned char)v[1];
	o[2] = (unsigned char)v[2];
	o[3] = 7;
}

static void
enc_bgra8(const float v[3], unsigned char *o)
{
	o[0] = (unsigned char)v[2];
	o[1] = (unsigned char)v[1];
	o[2] = (unsigned char)v[0];
	o[3] = 7;
}

static void
exp_same(const float v[3], float o[3])
{
	memcpy(o, v, 3 * sizeof(float));
}

static void
exp_grey(const float v[3], float o[3])
{
	o[0] = o[1] = o[2] = v[0];
}

static void
exp_unorm(const float v[3], float o[3])
{
	int c;

	for (c = 0; c < 3; c++)
		o[c] = v[c] / 255.0f;
}

/* IEC 61966-2-1's decoding, in double. */
static double
srgb_to_linear(double x)
{
	return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

static void
exp_srgb(const float v[3], float o[3])
{
	int c;

	for (c = 0; c < 3; c++)
		o[c] = (float)srgb_to_linear(v[c] / 255.0);
}

struct format {
	const char *name;
	int dx10;
	uint32_t dxgi, pf_flags, fourcc, bits, masks[4];
	unsigned bytes;
	void (*encode)(const float v[3], unsigned char *out);
	void (*expect)(const float v[3], float out[3]);
};

static const struct format formats[] = {
	{ "R32G32B32A32_FLOAT", 1, 2, 0, 0, 0, { 0 }, 16, enc_f32x4, exp_same },
	{ "R32G32B32_FLOAT", 1, 6, 0, 0, 0, { 0 }, 12, enc_f32x3, exp_same },
	{ "R16G16B16A16_FLOAT", 1, 10, 0, 0, 0, { 0 }, 8, enc_f16x4, exp_same },
	{ "R11G11B10_FLOAT", 1, 26, 0, 0, 0, { 0 }, 4, enc_r11g11b10, exp_same },
	{ "R9G9B9E5_SHAREDEXP", 1, 67, 0, 0, 0, { 0 }, 4, enc_rgb9e5, exp_same },
	{ "R8G8B8A8_UNORM", 1, 28, 0, 0, 0, { 0 }, 4, enc_rgba8, exp_unorm },
	{ "R8G8B8A8_UNORM_SRGB", 1, 29, 0, 0, 0, { 0 }, 4, enc_rgba8, exp_srgb },
	{ "B8G8R8A8_UNORM", 1, 87, 0, 0, 0, { 0 }, 4, enc_bgra8, exp_unorm },
	{ "B8G8R8X8_UNORM", 1, 88, 0, 0, 0, { 0 }, 4, enc_bgra8, exp_unorm },
	{ "B8G8R8A8_UNORM_SRGB", 1, 91, 0, 0, 0, { 0 }, 4, enc_bgra8, exp_srgb },
	{ "B8G8R8X8_UNORM_SRGB", 1, 93, 0, 0, 0, { 0 }, 4, enc_bgra8, exp_srgb },
	{ "D3DFMT_A16B16G16R16F", 0, 0, DDPF_FOURCC, 113, 0, { 0 }, 8, enc_f16x4, exp_same },
	{ "D3DFMT_A32B32G32R32F", 0, 0, DDPF_FOURCC, 116, 0, { 0 }, 16, enc_f32x4, exp_same },
	{ "D3DFMT_R32F", 0, 0, DDPF_FOURCC, 114, 0, { 0 }, 4, enc_f32x1, exp_grey },
	{ "A8B8G8R8 by masks", 0, 0, DDPF_RGB | DDPF_ALPHAPIXELS, 0, 32,
	  { 0xff, 0xff00, 0xff0000, 0xff000000u }, 4, enc_rgba8, exp_unorm },
	{ "A8R8G8B8 by masks", 0, 0, DDPF_RGB | DDPF_ALPHAPIXELS, 0, 32,
	  { 0xff0000, 0xff00, 0xff, 0xff000000u }, 4, enc_bgra8, exp_unorm },
	{ "X8R8G8B8 by masks", 0, 0, DDPF_RGB, 0, 32, { 0xff0000, 0xff00, 0xff, 0 }, 4,
	  enc_bgra8, exp_unorm },
};

/* The label of Direct3D's texel (i, j) of face f at level k. */
static void
label(int f, unsigned k, unsigned i, unsigned j, float v[3])
{
	v[0] = (float)(f + 10 * (int)k);
	v[1] = (float)i;
	v[2] = (float)j;
}

static void
labelled_texel(const struct fixture *fx, int f, unsigned k, unsigned i, unsigned j,
               unsigned char *out)
{
	const struct format *fmt = fx->arg;
	float v[3];

	label(f, k, i, j, v);
	fmt->encode(v, out);
}

static struct fixture
labelled_cube(const struct format *fmt, uint32_t n, uint32_t mips)
{
	struct fixture fx = fmt->dx10 ? dx10_cube(fmt->dxgi, fmt->bytes, n, mips)
	                              : legacy_cube(fmt->pf_flags, fmt->fourcc, fmt->bits,
	                                            fmt->masks, fmt->bytes, n, mips);

	fx.texel = labelled_texel;
	fx.arg = fmt;
	return fx;
}

/*
 * Reads a labelled cube of the format and checks, at every level, that
 * reflect's cube sampled along the direction through the centre of
 * Direct3D's texel (i, j) of face f gives that texel's label: the values
 * per face and level, and the orientation, at once.
 */
static int
check_labelled(const struct format *fmt, uint32_t n, uint32_t mips, size_t want_levels)
{
	struct fixture fx = labelled_cube(fmt, n, mips);
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c;
	size_t bad, k;
	unsigned i, j;
	int f, ch, failures = 0;

	if (read_fixture(&fx, &c, &info, &bad, path, err, sizeof(err)) < 0) {
		printf("# %s: %s\n", fmt->name, err);
		return 1;
	}
	if (rf_cubemap_levels(c) != want_levels || rf_cubemap_size(c) != n || bad != 0 ||
	    info.prefiltered != (want_levels > 1) || info.mapping != RF_MAPPING_UNITY ||
	    info.steps != (float)(want_levels - 1) || info.base_copied != 1) {
		printf("# %s: %zu levels of %zu, %zu non-finite, info %d %d %g %d\n",
		       fmt->name, rf_cubemap_levels(c), rf_cubemap_size(c), bad,
		       info.prefiltered, (int)info.mapping, (double)info.steps,
		       info.base_copied);
		failures++;
	}
	for (k = 0; k < rf_cubemap_levels(c); k++) {
		unsigned s = n >> k;

		for (f = 0; f < 6; f++)
			for (j = 0; j < s; j++)
				for (i = 0; i < s; i++) {
					float d[3], got[3], v[3], want[3];

					d3d_direction(f, (i + 0.5f) / s, (j + 0.5f) / s, d);
					rf_cubemap_sample_level(c, k, d, got);
					label(f, (unsigned)k, i, j, v);
					fmt->expect(v, want);
					for (ch = 0; ch < 3; ch++)
						if (!(fabsf(got[ch] - want[ch]) <= 1e-5f * (1.0f + want[ch]))) {
							if (failures++ < 5)
								printf("# %s level %zu face %d texel %u,%u: "
								       "%g %g %g, want %g %g %g\n", fmt->name, k,
								       f, i, j, (double)got[0], (double)got[1],
								       (double)got[2], (double)want[0],
								       (double)want[1], (double)want[2]);
							break;
						}
				}
	}
	rf_cubemap_destroy(c);
	return failures;
}

/* Every format: an 8-texel cube with its 4 levels (8 4 2 1). */
TEST(labelled_cube_every_format)
{
	size_t k;

	for (k = 0; k < sizeof(formats) / sizeof(formats[0]); k++) {
		int failures = check_labelled(&formats[k], 8, 4, 4);

		if (failures)
			printf("# %s: %d failures\n", formats[k].name, failures);
		ASSERT_EQ(failures, 0);
	}
}

/* The reader's mirroring in terms of texels: Direct3D's (i, j) is
 * reflect's (n-1-i, j) on the X and Z faces and (i, n-1-j) on the Y faces,
 * and reflect's own geometry agrees: its direction through its texel is
 * Direct3D's through the mirrored one. */
TEST(mirroring_matches_both_tables)
{
	const unsigned n = 4;
	struct fixture fx = labelled_cube(&formats[0], n, 1);
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c;
	unsigned i, j;
	int f;

	ASSERT_EQ(read_fixture(&fx, &c, &info, NULL, path, err, sizeof(err)), 0);
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				int y = f == 2 || f == 3;
				unsigned di = y ? i : n - 1 - i, dj = y ? n - 1 - j : j;
				const float *t = rf_cubemap_texel_const(c, 0, (enum rf_face)f, i, j);
				float a[3], b[3];

				ASSERT_NEAR(t[1], di, 0);
				ASSERT_NEAR(t[2], dj, 0);
				rf_cube_direction((enum rf_face)f, (i + 0.5f) / n, (j + 0.5f) / n, a);
				d3d_direction(f, (di + 0.5f) / n, (dj + 0.5f) / n, b);
				ASSERT_NEAR(a[0], b[0], 1e-6);
				ASSERT_NEAR(a[1], b[1], 1e-6);
				ASSERT_NEAR(a[2], b[2], 1e-6);
			}
	rf_cubemap_destroy(c);
}

/* 12 texels with levels 12 6 3 1: reflect keeps 12 6 3 (the chain halves
 * while even), and the unread 1x1 level still counts in each face's
 * stride, so the faces after the first read right. */
TEST(odd_tail_levels_skipped)
{
	ASSERT_EQ(check_labelled(&formats[0], 12, 4, 3), 0);
	ASSERT_EQ(check_labelled(&formats[2], 6, 3, 2), 0);
	/* no mip count: one level, a raw environment and no chain */
	ASSERT_EQ(check_labelled(&formats[0], 4, 0, 1), 0);
	/* one texel a face */
	ASSERT_EQ(check_labelled(&formats[4], 1, 1, 1), 0);
}

/* ---- decoding at known values ---------------------------------------------- */

/* One-texel faces holding raw texels (face order), so each is read back
 * untouched by filtering. */
static void
raw_texel(const struct fixture *fx, int f, unsigned k, unsigned i, unsigned j,
          unsigned char *out)
{
	(void)k;
	(void)i;
	(void)j;
	memcpy(out, (const unsigned char *)fx->arg + (size_t)f * fx->bytes, fx->bytes);
}

static rf_cubemap *
read_raw(uint32_t dxgi, unsigned bytes, const unsigned char *raw, size_t *bad)
{
	struct fixture fx = dx10_cube(dxgi, bytes, 1, 1);
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c = NULL;

	fx.texel = raw_texel;
	fx.arg = raw;
	if (read_fixture(&fx, &c, &info, bad, path, err, sizeof(err)) < 0)
		printf("# %s\n", err);
	return c;
}

static float
texel(const rf_cubemap *c, int f, int ch)
{
	return rf_cubemap_texel_const(c, 0, (enum rf_face)f, 0, 0)[ch];
}

TEST(half_floats)
{
	/* per face: R G B A halves */
	static const unsigned h[6][4] = {
		{ 0x3c00, 0x3800, 0x7bff, 0 },      /* 1, 0.5, 65504 (the largest) */
		{ 0x0001, 0x03ff, 0x0400, 0 },      /* 2^-24, 1023 * 2^-24, 2^-14 */
		{ 0xc000, 0x8000, 0x3555, 0 },      /* -2, -0, 0.333251953125 */
		{ 0x7c00, 0x7e00, 0x3c00, 0x7e00 }, /* Inf, NaN, 1; a NaN alpha */
		{ 0xfc00, 0x4248, 0x5640, 0 },      /* -Inf, 3.140625, 100 */
		{ 0x0000, 0x0000, 0x3c00, 0 },
	};
	unsigned char raw[6 * 8];
	size_t bad;
	rf_cubemap *c;
	int f, ch;

	for (f = 0; f < 6; f++)
		for (ch = 0; ch < 4; ch++)
			put16(raw + 8 * f + 2 * ch, h[f][ch]);
	ASSERT((c = read_raw(10, 8, raw, &bad)) != NULL);
	ASSERT_NEAR(texel(c, 0, 0), 1.0, 0);
	ASSERT_NEAR(texel(c, 0, 1), 0.5, 0);
	ASSERT_NEAR(texel(c, 0, 2), 65504.0, 0);
	ASSERT_NEAR(texel(c, 1, 0), ldexp(1.0, -24), 0);
	ASSERT_NEAR(texel(c, 1, 1), 1023.0 * ldexp(1.0, -24), 0);
	ASSERT_NEAR(texel(c, 1, 2), ldexp(1.0, -14), 0);
	ASSERT_NEAR(texel(c, 2, 0), -2.0, 0);
	ASSERT_NEAR(texel(c, 2, 1), 0.0, 0);
	ASSERT_NEAR(texel(c, 2, 2), 0.333251953125, 0);
	ASSERT_NEAR(texel(c, 4, 1), 3.140625, 0);
	ASSERT_NEAR(texel(c, 4, 2), 100.0, 0);
	/* Inf, NaN and -Inf become 0 and are counted; alpha is not read */
	ASSERT_EQ(bad, 3);
	ASSERT_NEAR(texel(c, 3, 0), 0.0, 0);
	ASSERT_NEAR(texel(c, 3, 1), 0.0, 0);
	ASSERT_NEAR(texel(c, 3, 2), 1.0, 0);
	ASSERT_NEAR(texel(c, 4, 0), 0.0, 0);
	rf_cubemap_destroy(c);
}

TEST(r11g11b10_floats)
{
	/* 11-bit: 5 exponent bits (bias 15), 6 mantissa; 10-bit: 5 mantissa */
#define PACK(r, g, b) ((uint32_t)(r) | (uint32_t)(g) << 11 | (uint32_t)(b) << 22)
	static const uint32_t t[6] = {
		PACK(15u << 6, 14u << 6, 15u << 5),          /* 1, 0.5, 1 */
		PACK(30u << 6 | 63, 1, 30u << 5 | 31),       /* 65024, 2^-20, 64512 */
		PACK(1u << 6, 63, 1),                        /* 2^-14, 63 * 2^-20, 2^-19 */
		PACK(31u << 6, 31u << 6 | 1, 31u << 5 | 1),  /* Inf, NaN, NaN */
		PACK(16u << 6 | 32, 0, 17u << 5 | 16),       /* 3, 0, 6 */
		PACK(0, 0, 0),
	};
#undef PACK
	unsigned char raw[6 * 4];
	size_t bad;
	rf_cubemap *c;
	int f;

	for (f = 0; f < 6; f++)
		put32(raw + 4 * f, t[f]);
	ASSERT((c = read_raw(26, 4, raw, &bad)) != NULL);
	ASSERT_NEAR(texel(c, 0, 0), 1.0, 0);
	ASSERT_NEAR(texel(c, 0, 1), 0.5, 0);
	ASSERT_NEAR(texel(c, 0, 2), 1.0, 0);
	ASSERT_NEAR(texel(c, 1, 0), 65024.0, 0);
	ASSERT_NEAR(texel(c, 1, 1), ldexp(1.0, -20), 0);
	ASSERT_NEAR(texel(c, 1, 2), 64512.0, 0);
	ASSERT_NEAR(texel(c, 2, 0), ldexp(1.0, -14), 0);
	ASSERT_NEAR(texel(c, 2, 1), 63.0 * ldexp(1.0, -20), 0);
	ASSERT_NEAR(texel(c, 2, 2), ldexp(1.0, -19), 0);
	ASSERT_NEAR(texel(c, 4, 0), 3.0, 0);
	ASSERT_NEAR(texel(c, 4, 2), 6.0, 0);
	ASSERT_EQ(bad, 3);
	ASSERT_NEAR(texel(c, 3, 0), 0.0, 0);
	rf_cubemap_destroy(c);
}

TEST(rgb9e5_shared_exponent)
{
	/* value = mantissa * 2^(exponent - 15 - 9), no hidden bit */
#define PACK(r, g, b, e) \
	((uint32_t)(r) | (uint32_t)(g) << 9 | (uint32_t)(b) << 18 | (uint32_t)(e) << 27)
	static const uint32_t t[6] = {
		PACK(256, 128, 0, 16),   /* 1, 0.5, 0 */
		PACK(511, 1, 256, 31),   /* 65408 (the largest), 128, 32768 */
		PACK(1, 0, 0, 0),        /* 2^-24 */
		PACK(511, 511, 511, 0),  /* 511 * 2^-24 */
		PACK(3, 5, 7, 24),       /* 3, 5, 7 */
		PACK(0, 0, 0, 0),
	};
#undef PACK
	unsigned char raw[6 * 4];
	size_t bad;
	rf_cubemap *c;
	int f;

	for (f = 0; f < 6; f++)
		put32(raw + 4 * f, t[f]);
	ASSERT((c = read_raw(67, 4, raw, &bad)) != NULL);
	ASSERT_EQ(bad, 0);
	ASSERT_NEAR(texel(c, 0, 0), 1.0, 0);
	ASSERT_NEAR(texel(c, 0, 1), 0.5, 0);
	ASSERT_NEAR(texel(c, 0, 2), 0.0, 0);
	ASSERT_NEAR(texel(c, 1, 0), 65408.0, 0);
	ASSERT_NEAR(texel(c, 1, 1), 128.0, 0);
	ASSERT_NEAR(texel(c, 1, 2), 32768.0, 0);
	ASSERT_NEAR(texel(c, 2, 0), ldexp(1.0, -24), 0);
	ASSERT_NEAR(texel(c, 3, 2), 511.0 * ldexp(1.0, -24), 0);
	ASSERT_NEAR(texel(c, 4, 0), 3.0, 0);
	ASSERT_NEAR(texel(c, 4, 1), 5.0, 0);
	ASSERT_NEAR(texel(c, 4, 2), 7.0, 0);
	rf_cubemap_destroy(c);
}

/* 8-bit sRGB decodes to linear (the linear segment below 0.04045 too);
 * UNORM reads the byte over 255; B8G8R8A8 swaps R and B. */
TEST(srgb_8bit)
{
	static const unsigned char bytes[6][4] = {
		{ 0, 10, 128, 255 }, { 255, 188, 64, 0 }, { 1, 11, 54, 9 },
		{ 200, 100, 50, 0 }, { 0, 0, 0, 0 }, { 255, 255, 255, 255 },
	};
	size_t bad;
	rf_cubemap *s, *u, *b;
	unsigned char swapped[6][4];
	int f, ch;

	for (f = 0; f < 6; f++) {
		swapped[f][0] = bytes[f][2];
		swapped[f][1] = bytes[f][1];
		swapped[f][2] = bytes[f][0];
		swapped[f][3] = bytes[f][3];
	}
	ASSERT((s = read_raw(29, 4, &bytes[0][0], &bad)) != NULL);
	ASSERT((u = read_raw(28, 4, &bytes[0][0], &bad)) != NULL);
	ASSERT((b = read_raw(91, 4, &swapped[0][0], &bad)) != NULL);
	for (f = 0; f < 6; f++)
		for (ch = 0; ch < 3; ch++) {
			double want = srgb_to_linear(bytes[f][ch] / 255.0);

			ASSERT_NEAR(texel(s, f, ch), want, 1e-6 * (1.0 + want));
			ASSERT_NEAR(texel(b, f, ch), want, 1e-6 * (1.0 + want));
			ASSERT_NEAR(texel(u, f, ch), bytes[f][ch] / 255.0, 1e-7);
		}
	/* spot values: sRGB 128 is 0.2158605 linear, 10 is 10/255/12.92 */
	ASSERT_NEAR(texel(s, 0, 2), 0.2158605, 1e-6);
	ASSERT_NEAR(texel(s, 0, 1), 10.0 / 255.0 / 12.92, 1e-8);
	rf_cubemap_destroy(s);
	rf_cubemap_destroy(u);
	rf_cubemap_destroy(b);
}

TEST(nonfinite_float_texels)
{
	unsigned char raw[6 * 16];
	size_t bad = 99;
	rf_cubemap *c;
	int f;

	for (f = 0; f < 6; f++) {
		putf(raw + 16 * f, 1.0f);
		putf(raw + 16 * f + 4, f == 1 ? NAN : 2.0f);
		putf(raw + 16 * f + 8, f == 5 ? -INFINITY : 3.0f);
		putf(raw + 16 * f + 12, NAN); /* alpha: ignored, not counted */
	}
	ASSERT((c = read_raw(2, 16, raw, &bad)) != NULL);
	ASSERT_EQ(bad, 2);
	ASSERT_NEAR(texel(c, 1, 1), 0.0, 0);
	ASSERT_NEAR(texel(c, 5, 2), 0.0, 0);
	ASSERT_NEAR(texel(c, 5, 1), 2.0, 0);
	rf_cubemap_destroy(c);
}

/* ---- refusals ---------------------------------------------------------------- */

/* Reads a fixture that must be refused with status rc and the message
 * fmt % path. */
static int
refused(const struct fixture *fx, int want_rc, const char *want_fmt)
{
	struct rf_chain_info info;
	char path[64], err[512], want[640];
	rf_cubemap *c = (rf_cubemap *)&info;
	size_t bad;
	int rc = read_fixture(fx, &c, &info, &bad, path, err, sizeof(err));

	snprintf(want, sizeof(want), want_fmt, path);
	if (rc != want_rc || c != NULL || strcmp(err, want)) {
		printf("# status %d (want %d), cube %p\n#  got:  %s\n#  want: %s\n", rc,
		       want_rc, (void *)c, rc < 0 ? err : "(read)", want);
		if (rc == 0)
			rf_cubemap_destroy(c);
		return 1;
	}
	return 0;
}

#define HINT "is not supported; convert the cube to float RGBA"

TEST(refuses_bad_magic_and_header)
{
	struct fixture fx = labelled_cube(&formats[0], 4, 1);

	fx.magic = "DDZ ";
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a DDS file (no 'DDS ' magic)"), 0);
	fx.magic = "DDS ";
	fx.header_size = 100;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': DDS header of 100 bytes with a pixel "
	                  "format of 32, not 124 and 32"), 0);
	fx.header_size = 124;
	fx.length = 50;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED,
	                  "'%s': truncated: the DDS header needs 78 more bytes"), 0);
	fx.length = 140;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED,
	                  "'%s': truncated: the DX10 header needs 8 more bytes"), 0);
	fx.length = 2;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a DDS file (no 'DDS ' magic)"), 0);
}

TEST(refuses_non_cubes)
{
	struct fixture fx = labelled_cube(&formats[0], 4, 1);
	struct fixture legacy = labelled_cube(&formats[12], 4, 1);
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c;

	fx.caps2 = 0;
	fx.misc = 0;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a cube map (a 2D texture)"), 0);
	legacy.caps2 = 0;
	ASSERT_EQ(refused(&legacy, RF_EFORMAT, "'%s': not a cube map (a 2D texture)"), 0);
	legacy.caps2 = 0x200000;
	legacy.depth = 4;
	ASSERT_EQ(refused(&legacy, RF_EFORMAT, "'%s': not a cube map (a volume texture)"), 0);
	fx.dim = 4;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a cube map (a volume texture)"), 0);
	/* a DX10 cube needs only the misc flag (DirectXTex's reading) */
	fx = labelled_cube(&formats[0], 4, 1);
	fx.caps2 = 0;
	ASSERT_EQ(read_fixture(&fx, &c, &info, NULL, path, err, sizeof(err)), 0);
	rf_cubemap_destroy(c);
	fx = labelled_cube(&formats[0], 4, 1);
	fx.array = 2;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': an array of 2 cubes; reflect reads one "
	                  "cube"), 0);
}

TEST(refuses_missing_faces)
{
	struct fixture fx = labelled_cube(&formats[12], 4, 1);

	fx.caps2 = 0x200 | 0x400 | 0x800 | 0x1000; /* +X -X +Y */
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': a cube map without faces -Y +Z -Z; "
	                  "reflect needs all six"), 0);
	fx.caps2 = 0x200;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': a cube map without faces +X -X +Y -Y "
	                  "+Z -Z; reflect needs all six"), 0);
}

/* 4 texels, 3 levels of 16-byte texels: a face is 256 + 64 + 16 bytes
 * after 148 of headers; face -Y (the fourth) ends at 148 + 4 * 336. */
TEST(refuses_truncated_data)
{
	struct fixture fx = labelled_cube(&formats[0], 4, 3);

	fx.length = 148 + 4 * 336 - 10;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED,
	                  "'%s': truncated: level 2 of face -Y needs 10 more bytes"), 0);
	fx.length = 148 + 100;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED,
	                  "'%s': truncated: level 0 of face +X needs 156 more bytes"), 0);
	/* the very last byte */
	fx.length = 148 + 6 * 336 - 1;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED,
	                  "'%s': truncated: level 2 of face -Z needs 1 more bytes"), 0);
	/* headers only */
	fx.length = 148;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED,
	                  "'%s': truncated: level 0 of face +X needs 256 more bytes"), 0);
}

TEST(refuses_unsupported_formats)
{
	struct fixture fx = dx10_cube(71, 8, 4, 1);
	static const uint32_t rgb24[4] = { 0xff0000, 0xff00, 0xff, 0 };
	static const uint32_t rgb10a2[4] = { 0x3ff, 0xffc00, 0x3ff00000, 0xc0000000u };

	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': DXGI format 71 (BC1) " HINT), 0);
	fx.dxgi = 95;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': DXGI format 95 (BC6H) " HINT), 0);
	fx.dxgi = 11;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': DXGI format 11 (R16G16B16A16_UNORM) "
	                  HINT), 0);
	fx.dxgi = 250;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': DXGI format 250 " HINT), 0);
	fx = legacy_cube(DDPF_FOURCC, FOURCC('D', 'X', 'T', '5'), 0, NULL, 16, 4, 1);
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': FourCC 'DXT5' (BC3) " HINT), 0);
	fx.fourcc = FOURCC('A', 'B', 'C', '\1');
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': FourCC 'ABC?' " HINT), 0);
	fx.fourcc = 111;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': D3DFMT 111 (R16F) " HINT), 0);
	fx = legacy_cube(DDPF_RGB, 0, 24, rgb24, 3, 4, 1);
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': 24-bit RGB with masks R 00ff0000 "
	                  "G 0000ff00 B 000000ff " HINT), 0);
	fx = legacy_cube(DDPF_RGB | DDPF_ALPHAPIXELS, 0, 32, rgb10a2, 4, 4, 1);
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': 32-bit RGB with masks R 000003ff "
	                  "G 000ffc00 B 3ff00000 " HINT), 0);
	fx = legacy_cube(0x20000, 0, 8, rgb24, 1, 4, 1); /* luminance */
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': pixel format flags 0x20000 (not RGB) "
	                  HINT), 0);
}

TEST(refuses_bad_sizes)
{
	struct fixture fx = dx10_cube(2, 16, 32768, 1);

	/* refused from the header alone: no data written, nothing allocated */
	ASSERT_EQ(refused(&fx, RF_ETOOBIG, "'%s': cube faces of 32768 texels (1 to 16384 "
	                  "are read)"), 0);
	fx.width = fx.height = 0;
	ASSERT_EQ(refused(&fx, RF_ETOOBIG, "'%s': cube faces of 0 texels (1 to 16384 are "
	                  "read)"), 0);
	fx.width = fx.height = 0xffffffffu;
	ASSERT_EQ(refused(&fx, RF_ETOOBIG, "'%s': cube faces of 4294967295 texels (1 to "
	                  "16384 are read)"), 0);
	/* the largest size, in a file of headers only: the promised 4 GiB of
	 * level 0 are missing, which is seen before any allocation */
	fx.width = fx.height = 16384;
	fx.mips = 15;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: level 0 of face +X needs "
	                  "4294967296 more bytes"), 0);
	fx.mips = 16;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': 16 mip levels claimed; faces of 16384 "
	                  "have at most 15"), 0);
	fx.mips = 0xffffffffu;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': 4294967295 mip levels claimed; faces of "
	                  "16384 have at most 15"), 0);
	fx = labelled_cube(&formats[0], 8, 5);
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': 5 mip levels claimed; faces of 8 have at "
	                  "most 4"), 0);
	fx = labelled_cube(&formats[0], 8, 1);
	fx.height = 4;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': cube faces of 8x4 are not square"), 0);
}

TEST(refuses_missing_file)
{
	struct rf_chain_info info;
	rf_cubemap *c;
	char err[512];

	ASSERT_EQ(rf_chain_read_dds(&c, &info, NULL, "/nonexistent/x.dds", err, sizeof(err)),
	          RF_EIO);
	ASSERT(c == NULL);
	ASSERT_STR_EQ(err, "cannot open '/nonexistent/x.dds': No such file or directory");
}

int
main(void)
{
	RUN(labelled_cube_every_format);
	RUN(mirroring_matches_both_tables);
	RUN(odd_tail_levels_skipped);
	RUN(half_floats);
	RUN(r11g11b10_floats);
	RUN(rgb9e5_shared_exponent);
	RUN(srgb_8bit);
	RUN(nonfinite_float_texels);
	RUN(refuses_bad_magic_and_header);
	RUN(refuses_non_cubes);
	RUN(refuses_missing_faces);
	RUN(refuses_truncated_data);
	RUN(refuses_unsupported_formats);
	RUN(refuses_bad_sizes);
	RUN(refuses_missing_file);
	TAP_DONE();
}
