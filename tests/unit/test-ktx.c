/*
 * Unit tests of the KTX 1 and KTX 2 cube chain reader and writer.  Every
 * fixture is made here, by a small writer that follows the two
 * specifications (Khronos' KTX 1.1 and KTX 2.0) rather than the reader,
 * into /tmp, and removed after reading.
 */
#include <stdint.h>
#include <unistd.h>
#ifdef HAVE_ZSTD
#include <zstd.h>
#endif

#include "reflect/envmap.h"
#include "tap.h"

/* ---- the KTX writer of the fixtures ---------------------------------------- */

struct fixture;
/* Writes the bytes of texel (i, j) of face f at level k, little-endian
 * (KTX's own texel coordinates: i across, j down, row 0 first). */
typedef void (*texel_fn)(const struct fixture *fx, int f, unsigned k, unsigned i,
                         unsigned j, unsigned char *out);

struct fixture {
	int version;          /* 1 or 2 */
	uint32_t format;      /* vkFormat, or glInternalFormat */
	uint32_t gl_type, gl_format;
	unsigned bytes;       /* per texel */
	unsigned unit;        /* KTX 1 big-endian: bytes swapped together */
	uint32_t width, height, depth, layers, faces, mips, scheme;
	int big_endian;       /* KTX 1 */
	int whole_level;      /* KTX 1: imageSize of all six faces */
	int zstd;             /* KTX 2: compress the levels (scheme 2) */
	uint32_t dfd_model;   /* the DFD's colour model */
	const char *kv[8];    /* key, value, ... NULL */
	texel_fn texel;
	const void *arg;
	long length;          /* > 0: the file is cut to this many bytes */
	int bad_size;         /* > 0: level 0's imageSize or byteLength, changed */
	uint64_t offset0;     /* != 0: level 0's byteOffset, forged */
};

struct buf {
	unsigned char *p;
	size_t len, cap;
};

static void
grow(struct buf *b, size_t n)
{
	if (b->len + n > b->cap) {
		b->cap = (b->len + n) * 2 + 64;
		b->p = realloc(b->p, b->cap);
	}
}

static void
put(struct buf *b, const void *p, size_t n)
{
	grow(b, n);
	memcpy(b->p + b->len, p, n);
	b->len += n;
}

static void
put32(struct buf *b, uint32_t v, int be)
{
	unsigned char x[4] = { v & 255, (v >> 8) & 255, (v >> 16) & 255, v >> 24 };

	if (be) {
		unsigned char t = x[0];

		x[0] = x[3];
		x[3] = t;
		t = x[1];
		x[1] = x[2];
		x[2] = t;
	}
	put(b, x, 4);
}

static void
put64(struct buf *b, uint64_t v)
{
	put32(b, (uint32_t)v, 0);
	put32(b, (uint32_t)(v >> 32), 0);
}

static void
zeros(struct buf *b, size_t n)
{
	grow(b, n);
	memset(b->p + b->len, 0, n);
	b->len += n;
}

static void
set64(struct buf *b, size_t at, uint64_t v)
{
	int i;

	for (i = 0; i < 8; i++)
		b->p[at + i] = (unsigned char)(v >> (8 * i));
}

static void
le32(unsigned char *p, uint32_t v)
{
	p[0] = (unsigned char)v;
	p[1] = (unsigned char)(v >> 8);
	p[2] = (unsigned char)(v >> 16);
	p[3] = (unsigned char)(v >> 24);
}

static void
le16(unsigned char *p, unsigned v)
{
	p[0] = (unsigned char)v;
	p[1] = (unsigned char)(v >> 8);
}

static void
lef(unsigned char *p, float f)
{
	uint32_t u;

	memcpy(&u, &f, sizeof(u));
	le32(p, u);
}

static unsigned
level_size(const struct fixture *fx, unsigned k)
{
	return fx->width >> k ? fx->width >> k : 1;
}

static unsigned
nlevels(const struct fixture *fx)
{
	return fx->mips ? fx->mips : 1;
}

/* Key/value data: each pair's length, key NUL value NUL, padding to 4. */
static void
put_kv(struct buf *b, const struct fixture *fx)
{
	int i;

	for (i = 0; fx->kv[i]; i += 2) {
		size_t k = strlen(fx->kv[i]) + 1, v = strlen(fx->kv[i + 1]) + 1;

		put32(b, (uint32_t)(k + v), fx->big_endian);
		put(b, fx->kv[i], k);
		put(b, fx->kv[i + 1], v);
		zeros(b, (4 - (k + v) % 4) % 4);
	}
}

static size_t
kv_length(const struct fixture *fx)
{
	size_t n = 0;
	int i;

	for (i = 0; fx->kv[i]; i += 2)
		n += 4 + ((strlen(fx->kv[i]) + strlen(fx->kv[i + 1]) + 2 + 3) & ~(size_t)3);
	return n;
}

/* One face of a level, rows padded to `align` bytes (KTX 1: 4). */
static void
put_face(struct buf *b, const struct fixture *fx, int f, unsigned k, unsigned align)
{
	unsigned s = level_size(fx, k), i, j, u;
	unsigned char t[16];

	for (j = 0; j < s; j++) {
		for (i = 0; i < s; i++) {
			memset(t, 0, sizeof(t));
			if (fx->texel)
				fx->texel(fx, f, k, i, j, t);
			if (fx->big_endian && fx->unit > 1)
				for (u = 0; u < fx->bytes; u += fx->unit) {
					unsigned a;

					for (a = 0; a < fx->unit / 2; a++) {
						unsigned char x = t[u + a];

						t[u + a] = t[u + fx->unit - 1 - a];
						t[u + fx->unit - 1 - a] = x;
					}
				}
			put(b, t, fx->bytes);
		}
		zeros(b, (align - s * fx->bytes % align) % align);
	}
}

static void
build_ktx1(struct buf *b, const struct fixture *fx)
{
	static const unsigned char id[12] = { 0xab, 'K', 'T', 'X', ' ', '1', '1', 0xbb,
		                              '\r', '\n', 0x1a, '\n' };
	int be = fx->big_endian, f;
	unsigned k;

	put(b, id, 12);
	put32(b, 0x04030201u, be);
	put32(b, fx->gl_type, be);
	put32(b, fx->unit ? fx->unit : 1, be);
	put32(b, fx->gl_format, be);
	put32(b, fx->format, be);
	put32(b, fx->gl_format, be);
	put32(b, fx->width, be);
	put32(b, fx->height, be);
	put32(b, fx->depth, be);
	put32(b, fx->layers, be);
	put32(b, fx->faces, be);
	put32(b, fx->mips, be);
	put32(b, (uint32_t)kv_length(fx), be);
	put_kv(b, fx);
	for (k = 0; fx->texel && k < nlevels(fx); k++) {
		unsigned s = level_size(fx, k);
		/* GL_UNPACK_ALIGNMENT 4: rows padded; a face then is too */
		uint32_t face = ((s * fx->bytes + 3) & ~3u) * s;

		if (k == 0 && fx->bad_size)
			face += (uint32_t)fx->bad_size;
		put32(b, fx->whole_level ? 6 * face : face, be);
		for (f = 0; f < 6; f++)
			put_face(b, fx, f, k, 4);
	}
}

static void
build_ktx2(struct buf *b, const struct fixture *fx)
{
	static const unsigned char id[12] = { 0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb,
		                              '\r', '\n', 0x1a, '\n' };
	unsigned n = nlevels(fx), k, align = fx->bytes % 4 == 0 ? fx->bytes : 4 * fx->bytes;
	size_t dfd = 80 + 24 * (size_t)(n > 16 ? 16 : n), kvd = dfd + 28;
	int f;

	if (fx->bytes == 2 || fx->bytes == 6)
		align = fx->bytes == 2 ? 4 : 12; /* lcm(texel size, 4) */
	put(b, id, 12);
	put32(b, fx->format, 0);
	put32(b, fx->unit ? fx->unit : 1, 0);
	put32(b, fx->width, 0);
	put32(b, fx->height, 0);
	put32(b, fx->depth, 0);
	put32(b, fx->layers, 0);
	put32(b, fx->faces, 0);
	put32(b, fx->mips, 0);
	put32(b, fx->zstd ? 2 : fx->scheme, 0);
	put32(b, (uint32_t)dfd, 0);
	put32(b, 28, 0);
	put32(b, kv_length(fx) ? (uint32_t)kvd : 0, 0);
	put32(b, (uint32_t)kv_length(fx), 0);
	put64(b, 0);
	put64(b, 0);
	/* the level index, filled below; a forged count gets 16 entries */
	zeros(b, 24 * (size_t)(n > 16 ? 16 : n));
	/* A DFD of the basic block's 24 bytes, without samples: the colour
	 * model is what a reader of VK_FORMAT_UNDEFINED needs. */
	put32(b, 28, 0);
	put32(b, 0, 0);
	put32(b, 2u | 24u << 16, 0);
	put32(b, fx->dfd_model ? fx->dfd_model : 1u, 0);
	put32(b, 0, 0);
	put32(b, fx->bytes, 0);
	put32(b, 0, 0);
	put_kv(b, fx);
	/* levels smallest first, the index largest first */
	for (k = n; fx->texel && k-- > 0;) {
		size_t start, raw;

		if (!fx->zstd)
			zeros(b, (align - b->len % align) % align);
		start = b->len;
		for (f = 0; f < 6; f++)
			put_face(b, fx, f, k, 1);
		raw = b->len - start;
#ifdef HAVE_ZSTD
		if (fx->zstd) {
			size_t cap = ZSTD_compressBound(raw), z;
			unsigned char *tmp = malloc(cap);

			z = ZSTD_compress(tmp, cap, b->p + start, raw, 9);
			b->len = start;
			put(b, tmp, z);
			free(tmp);
		}
#endif
		set64(b, 80 + 24 * k, k == 0 && fx->offset0 ? fx->offset0 : start);
		set64(b, 80 + 24 * k + 8, b->len - start + (k == 0 ? fx->bad_size : 0));
		set64(b, 80 + 24 * k + 16, raw);
	}
}

/* Writes the fixture to a new file in /tmp; its name in path. */
static int
write_fixture(const struct fixture *fx, char path[64])
{
	struct buf b = { 0 };
	FILE *fp;
	int fd;

	if (fx->version == 1)
		build_ktx1(&b, fx);
	else
		build_ktx2(&b, fx);
	strcpy(path, fx->version == 1 ? "/tmp/reflect-ktx-XXXXXX.ktx"
	                              : "/tmp/reflect-ktx-XXXXXX.ktx2");
	if ((fd = mkstemps(path, fx->version == 1 ? 4 : 5)) < 0 || !(fp = fdopen(fd, "wb"))) {
		free(b.p);
		return -1;
	}
	if (fx->length > 0 && (size_t)fx->length < b.len)
		b.len = (size_t)fx->length;
	fwrite(b.p, 1, b.len, fp);
	fclose(fp);
	free(b.p);
	return 0;
}

static int
read_fixture(const struct fixture *fx, rf_cubemap **c, struct rf_chain_info *info,
             int *ours, size_t *bad, char path[64], char *err, size_t errlen)
{
	int rc;

	if (write_fixture(fx, path) < 0)
		return -9999;
	rc = rf_chain_read_ktx(c, info, ours, bad, path, err, errlen);
	unlink(path);
	return rc;
}

/* ---- OpenGL's cube, derived independently of the reader -------------------- */

/*
 * The direction through position (u, v) of a face, from OpenGL's cube
 * face selection table (sc, tc over |ma|, u = (sc/|ma| + 1)/2, v = (tc/|ma|
 * + 1)/2, v = 0 the first row, as KTX 2 requires of cubes, "rd"):
 *
 *	+X: sc = -z tc = -y   -X: sc = +z tc = -y   +Y: sc = +x tc = +z
 *	-Y: sc = +x tc = -z   +Z: sc = +x tc = -y   -Z: sc = -x tc = -y
 */
static void
gl_direction(int face, float u, float v, float d[3])
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
enc_f32(const float v[3], unsigned char *o, unsigned nch)
{
	unsigned c;

	for (c = 0; c < nch; c++)
		lef(o + 4 * c, c < 3 ? v[c] : 99.0f);
}

static void enc_f32x4(const float v[3], unsigned char *o) { enc_f32(v, o, 4); }
static void enc_f32x3(const float v[3], unsigned char *o) { enc_f32(v, o, 3); }
static void enc_f32x1(const float v[3], unsigned char *o) { enc_f32(v, o, 1); }

static void
enc_f16(const float v[3], unsigned char *o, unsigned nch)
{
	unsigned c;

	for (c = 0; c < nch; c++)
		le16(o + 2 * c, c < 3 ? small_float_bits((unsigned)v[c], 10) : 0x3c00);
}

static void enc_f16x4(const float v[3], unsigned char *o) { enc_f16(v, o, 4); }
static void enc_f16x3(const float v[3], unsigned char *o) { enc_f16(v, o, 3); }

static void
enc_r11g11b10(const float v[3], unsigned char *o)
{
	le32(o, small_float_bits((unsigned)v[0], 6) | small_float_bits((unsigned)v[1], 6) << 11 |
	        small_float_bits((unsigned)v[2], 5) << 22);
}

/* Shared exponent 24 (bias 15 plus 9 mantissa bits): the mantissas are
 * the integers themselves. */
static void
enc_rgb9e5(const float v[3], unsigned char *o)
{
	le32(o, (uint32_t)v[0] | (uint32_t)v[1] << 9 | (uint32_t)v[2] << 18 | 24u << 27);
}

static void
enc_rgb8(const float v[3], unsigned char *o)
{
	o[0] = (unsigned char)v[0];
	o[1] = (unsigned char)v[1];
	o[2] = (unsigned char)v[2];
}

static void
enc_rgba8(const float v[3], unsigned char *o)
{
	enc_rgb8(v, o);
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

#define GL_UNSIGNED_BYTE 0x1401
#define GL_FLOAT 0x1406
#define GL_HALF_FLOAT 0x140b
#define GL_RED 0x1903
#define GL_RGB 0x1907
#define GL_RGBA 0x1908
#define GL_BGRA 0x80e1
#define GL_UNSIGNED_INT_10F_11F_11F_REV 0x8c3b
#define GL_UNSIGNED_INT_5_9_9_9_REV 0x8c3e

struct format {
	const char *name;
	int version;
	uint32_t id, gl_type, gl_format;
	unsigned bytes, unit;
	void (*encode)(const float v[3], unsigned char *out);
	void (*expect)(const float v[3], float out[3]);
};

static const struct format formats[] = {
	/* KTX 2, by vkFormat */
	{ "R32G32B32A32_SFLOAT", 2, 109, 0, 0, 16, 4, enc_f32x4, exp_same },
	{ "R32G32B32_SFLOAT", 2, 106, 0, 0, 12, 4, enc_f32x3, exp_same },
	{ "R32_SFLOAT", 2, 100, 0, 0, 4, 4, enc_f32x1, exp_grey },
	{ "R16G16B16A16_SFLOAT", 2, 97, 0, 0, 8, 2, enc_f16x4, exp_same },
	{ "R16G16B16_SFLOAT", 2, 90, 0, 0, 6, 2, enc_f16x3, exp_same },
	{ "B10G11R11_UFLOAT_PACK32", 2, 122, 0, 0, 4, 4, enc_r11g11b10, exp_same },
	{ "E5B9G9R9_UFLOAT_PACK32", 2, 123, 0, 0, 4, 4, enc_rgb9e5, exp_same },
	{ "R8G8B8A8_UNORM", 2, 37, 0, 0, 4, 1, enc_rgba8, exp_unorm },
	{ "R8G8B8A8_SRGB", 2, 43, 0, 0, 4, 1, enc_rgba8, exp_srgb },
	{ "R8G8B8_UNORM", 2, 23, 0, 0, 3, 1, enc_rgb8, exp_unorm },
	{ "R8G8B8_SRGB", 2, 29, 0, 0, 3, 1, enc_rgb8, exp_srgb },
	{ "B8G8R8A8_UNORM", 2, 44, 0, 0, 4, 1, enc_bgra8, exp_unorm },
	{ "B8G8R8A8_SRGB", 2, 50, 0, 0, 4, 1, enc_bgra8, exp_srgb },
	/* KTX 1, by glInternalFormat */
	{ "GL_RGBA32F", 1, 0x8814, GL_FLOAT, GL_RGBA, 16, 4, enc_f32x4, exp_same },
	{ "GL_RGB32F", 1, 0x8815, GL_FLOAT, GL_RGB, 12, 4, enc_f32x3, exp_same },
	{ "GL_R32F", 1, 0x822e, GL_FLOAT, GL_RED, 4, 4, enc_f32x1, exp_grey },
	{ "GL_RGBA16F", 1, 0x881a, GL_HALF_FLOAT, GL_RGBA, 8, 2, enc_f16x4, exp_same },
	{ "GL_RGB16F", 1, 0x881b, GL_HALF_FLOAT, GL_RGB, 6, 2, enc_f16x3, exp_same },
	{ "GL_R11F_G11F_B10F", 1, 0x8c3a, GL_UNSIGNED_INT_10F_11F_11F_REV, GL_RGB, 4, 4,
	  enc_r11g11b10, exp_same },
	{ "GL_RGB9_E5", 1, 0x8c3d, GL_UNSIGNED_INT_5_9_9_9_REV, GL_RGB, 4, 4, enc_rgb9e5,
	  exp_same },
	{ "GL_RGBA8", 1, 0x8058, GL_UNSIGNED_BYTE, GL_RGBA, 4, 1, enc_rgba8, exp_unorm },
	{ "GL_SRGB8_ALPHA8", 1, 0x8c43, GL_UNSIGNED_BYTE, GL_RGBA, 4, 1, enc_rgba8, exp_srgb },
	{ "GL_RGB8", 1, 0x8051, GL_UNSIGNED_BYTE, GL_RGB, 3, 1, enc_rgb8, exp_unorm },
	{ "GL_SRGB8", 1, 0x8c41, GL_UNSIGNED_BYTE, GL_RGB, 3, 1, enc_rgb8, exp_srgb },
	{ "GL_RGBA8 as BGRA", 1, 0x8058, GL_UNSIGNED_BYTE, GL_BGRA, 4, 1, enc_bgra8, exp_unorm },
	/* unsized, as cmft may write: glType tells */
	{ "GL_RGBA of GL_HALF_FLOAT", 1, GL_RGBA, GL_HALF_FLOAT, GL_RGBA, 8, 2, enc_f16x4,
	  exp_same },
	{ "GL_RGB of GL_UNSIGNED_BYTE", 1, GL_RGB, GL_UNSIGNED_BYTE, GL_RGB, 3, 1, enc_rgb8,
	  exp_unorm },
};

#define NFORMATS (sizeof(formats) / sizeof(formats[0]))

static const struct format *
format_named(const char *name)
{
	size_t i;

	for (i = 0; i < NFORMATS; i++)
		if (!strcmp(formats[i].name, name))
			return &formats[i];
	return NULL;
}

/* The label of KTX's texel (i, j) of face f at level k. */
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
cube(const struct format *fmt, uint32_t n, uint32_t mips)
{
	struct fixture fx;

	memset(&fx, 0, sizeof(fx));
	fx.version = fmt->version;
	fx.format = fmt->id;
	fx.gl_type = fmt->gl_type;
	fx.gl_format = fmt->gl_format;
	fx.bytes = fmt->bytes;
	fx.unit = fmt->unit;
	fx.width = fx.height = n;
	fx.faces = 6;
	fx.mips = mips;
	fx.texel = labelled_texel;
	fx.arg = fmt;
	return fx;
}

/*
 * Reads a labelled cube and checks, at every level, that reflect's cube
 * sampled along the direction through the centre of KTX's texel (i, j)
 * of face f gives that texel's label: the values per face and level, and
 * the orientation, at once.
 */
static int
check_fixture(const struct fixture *fx, const struct format *fmt, size_t want_levels)
{
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c;
	size_t bad, k;
	unsigned i, j, n = fx->width;
	int f, ch, ours = 9, failures = 0;

	if (read_fixture(fx, &c, &info, &ours, &bad, path, err, sizeof(err)) < 0) {
		printf("# %s: %s\n", fmt->name, err);
		return 1;
	}
	if (rf_cubemap_levels(c) != want_levels || rf_cubemap_size(c) != n || bad != 0 ||
	    info.prefiltered != (want_levels > 1) || info.mapping != RF_MAPPING_UNITY ||
	    ours != 0 ||
	    info.steps != (float)(want_levels - 1) || info.base_copied != 1) {
		printf("# %s: %zu levels of %zu, %zu non-finite, ours %d, info %d %d %g %d\n",
		       fmt->name, rf_cubemap_levels(c), rf_cubemap_size(c), bad, ours,
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

					gl_direction(f, (i + 0.5f) / s, (j + 0.5f) / s, d);
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

/* Every format of both versions: an 8-texel cube with its 4 levels (8 4 2
 * 1), whose 3-byte and 6-byte KTX 1 rows of 1, 2 and 4 texels are padded
 * to 4 bytes. */
TEST(labelled_cube_every_format)
{
	size_t k;

	for (k = 0; k < NFORMATS; k++) {
		struct fixture fx = cube(&formats[k], 8, 4);
		int failures = check_fixture(&fx, &formats[k], 4);

		if (failures)
			printf("# %s: %d failures\n", formats[k].name, failures);
		ASSERT_EQ(failures, 0);
	}
}

/* A big-endian KTX 1 (endianness 0x01020304): header and texels swapped
 * in units of the texel's numbers. */
TEST(big_endian_ktx1)
{
	static const char *const names[] = { "GL_RGBA32F", "GL_RGBA16F", "GL_R11F_G11F_B10F",
		                             "GL_RGB9_E5", "GL_RGB8" };
	size_t k;

	for (k = 0; k < sizeof(names) / sizeof(names[0]); k++) {
		const struct format *fmt = format_named(names[k]);
		struct fixture fx = cube(fmt, 4, 3);

		fx.big_endian = 1;
		ASSERT_EQ(check_fixture(&fx, fmt, 3), 0);
	}
}

/* KTX 1's imageSize of the whole level ("most textures") reads too, and
 * no mip count is one level; 12 texels keep 12 6 3, the 1x1 skipped. */
TEST(level_counts_and_image_sizes)
{
	const struct format *f32 = format_named("GL_RGBA32F");
	const struct format *h2 = format_named("R16G16B16A16_SFLOAT");
	struct fixture fx = cube(f32, 4, 3);

	fx.whole_level = 1;
	ASSERT_EQ(check_fixture(&fx, f32, 3), 0);
	fx = cube(f32, 4, 0);
	ASSERT_EQ(check_fixture(&fx, f32, 1), 0);
	fx = cube(h2, 12, 4);
	ASSERT_EQ(check_fixture(&fx, h2, 3), 0);
	fx = cube(h2, 1, 1);
	ASSERT_EQ(check_fixture(&fx, h2, 1), 0);
	/* a cube array of one cube is one cube */
	fx = cube(h2, 4, 3);
	fx.layers = 1;
	ASSERT_EQ(check_fixture(&fx, h2, 3), 0);
}

TEST(zstd_levels)
{
#ifdef HAVE_ZSTD
	static const char *const names[] = { "R16G16B16A16_SFLOAT", "R32G32B32A32_SFLOAT",
		                             "E5B9G9R9_UFLOAT_PACK32", "R8G8B8_SRGB" };
	size_t k;

	for (k = 0; k < sizeof(names) / sizeof(names[0]); k++) {
		const struct format *fmt = format_named(names[k]);
		struct fixture fx = cube(fmt, 8, 4);

		fx.zstd = 1;
		ASSERT_EQ(check_fixture(&fx, fmt, 4), 0);
	}
#else
	printf("# built without libzstd: the refusal is tested instead\n");
#endif
}

/*
 * The orientation pinned on one texel: the top-left texel of KTX's +X
 * face (first row, first column) is, by OpenGL's table, the direction
 * (1, -tc, -sc) with sc = tc = -1 + 1/n: toward +Y and +Z, (1, 0.75, 0.75)
 * for n = 4.  reflect keeps it at column n-1 of row 0 of its +X face (its
 * faces are OpenEXR's, mirrored left to right on X), and maps that texel
 * back to the same direction.
 */
TEST(orientation_of_one_texel)
{
	const struct format *fmt = format_named("R32G32B32A32_SFLOAT");
	struct fixture fx = cube(fmt, 4, 1);
	struct rf_chain_info info;
	char path[64], err[512];
	const float dir[3] = { 1.0f, 0.75f, 0.75f };
	float got[3], d[3], u, v;
	rf_cubemap *c;
	const float *t;

	ASSERT_EQ(read_fixture(&fx, &c, &info, NULL, NULL, path, err, sizeof(err)), 0);
	/* KTX +X (0, 0) holds label (0, 0, 0); its neighbour (1, 0) (1 in G) */
	rf_cubemap_sample_level(c, 0, dir, got);
	ASSERT_NEAR(got[0], 0, 0);
	ASSERT_NEAR(got[1], 0, 0);
	ASSERT_NEAR(got[2], 0, 0);
	ASSERT_EQ(rf_cube_face(dir, &u, &v), RF_FACE_POS_X);
	ASSERT_NEAR(u, 0.875, 1e-6);
	ASSERT_NEAR(v, 0.125, 1e-6);
	t = rf_cubemap_texel_const(c, 0, RF_FACE_POS_X, 3, 0);
	ASSERT_NEAR(t[1], 0, 0);
	ASSERT_NEAR(t[2], 0, 0);
	t = rf_cubemap_texel_const(c, 0, RF_FACE_POS_X, 2, 0);
	ASSERT_NEAR(t[1], 1, 0); /* KTX column 1 */
	rf_cube_direction(RF_FACE_POS_X, 0.875f, 0.125f, d);
	ASSERT_NEAR(d[0], 1, 1e-6);
	ASSERT_NEAR(d[1], 0.75, 1e-6);
	ASSERT_NEAR(d[2], 0.75, 1e-6);
	/* and KTX +Y's top-left looks toward -X and -Z: (-0.75, 1, -0.75) */
	gl_direction(2, 0.125f, 0.125f, d);
	ASSERT_NEAR(d[0], -0.75, 1e-6);
	ASSERT_NEAR(d[2], -0.75, 1e-6);
	rf_cubemap_sample_level(c, 0, d, got);
	ASSERT_NEAR(got[0], 2, 0);
	ASSERT_NEAR(got[1], 0, 0);
	ASSERT_NEAR(got[2], 0, 0);
	rf_cubemap_destroy(c);
}

/* ---- decoding at known values ---------------------------------------------- */

/* One-texel faces holding raw texels (face order). */
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
read_raw(const char *name, const unsigned char *raw, size_t *bad)
{
	struct fixture fx = cube(format_named(name), 1, 1);
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c = NULL;

	fx.texel = raw_texel;
	fx.arg = raw;
	if (read_fixture(&fx, &c, &info, NULL, bad, path, err, sizeof(err)) < 0)
		printf("# %s\n", err);
	return c;
}

static float
texel(const rf_cubemap *c, int f, int ch)
{
	return rf_cubemap_texel_const(c, 0, (enum rf_face)f, 0, 0)[ch];
}

/*
 * (1, 0.5, 0.25) in each packed format, by hand:
 *
 * RGB9E5: m * 2^(e - 15 - 9), no hidden bit.  The largest, 1, takes
 * mantissa 256 with e - 24 = -8, e = 16; then 0.5 is 128 and 0.25 is 64:
 * 256 | 128 << 9 | 64 << 18 | 16 << 27 = 0x81010100.
 *
 * R11G11B10: 5 exponent bits (bias 15) over 6 mantissa bits (5 for blue),
 * hidden bit: 1 = 2^0 is exponent 15, 0.5 exponent 14, 0.25 exponent 13,
 * mantissas 0: 15 << 6 | (14 << 6) << 11 | (13 << 5) << 22 = 0x681c03c0.
 *
 * Half: 1 = 0x3c00, 0.5 = 0x3800, 0.25 = 0x3400.
 */
TEST(packed_floats_by_hand)
{
	unsigned char e5[6 * 4], r11[6 * 4], h[6 * 8];
	size_t bad;
	rf_cubemap *a, *b, *c;
	int f;

	for (f = 0; f < 6; f++) {
		le32(e5 + 4 * f, f == 1 ? (511u | 1u << 9 | 256u << 18 | 31u << 27) : 0x81010100u);
		le32(r11 + 4 * f, 0x681c03c0u);
		le16(h + 8 * f, 0x3c00);
		le16(h + 8 * f + 2, 0x3800);
		le16(h + 8 * f + 4, f == 3 ? 0x7c00 : 0x3400); /* +Inf on -Y */
		le16(h + 8 * f + 6, 0x7e00);                    /* NaN alpha: not read */
	}
	ASSERT((a = read_raw("E5B9G9R9_UFLOAT_PACK32", e5, &bad)) != NULL);
	ASSERT_EQ(bad, 0);
	ASSERT_NEAR(texel(a, 0, 0), 1.0, 0);
	ASSERT_NEAR(texel(a, 0, 1), 0.5, 0);
	ASSERT_NEAR(texel(a, 0, 2), 0.25, 0);
	/* the largest: 511 * 2^(31 - 24) = 65408; 1 * 2^7; 256 * 2^7 */
	ASSERT_NEAR(texel(a, 1, 0), 65408.0, 0);
	ASSERT_NEAR(texel(a, 1, 1), 128.0, 0);
	ASSERT_NEAR(texel(a, 1, 2), 32768.0, 0);
	ASSERT((b = read_raw("GL_R11F_G11F_B10F", r11, &bad)) != NULL);
	ASSERT_NEAR(texel(b, 5, 0), 1.0, 0);
	ASSERT_NEAR(texel(b, 5, 1), 0.5, 0);
	ASSERT_NEAR(texel(b, 5, 2), 0.25, 0);
	ASSERT((c = read_raw("GL_RGBA16F", h, &bad)) != NULL);
	ASSERT_NEAR(texel(c, 2, 0), 1.0, 0);
	ASSERT_NEAR(texel(c, 2, 1), 0.5, 0);
	ASSERT_NEAR(texel(c, 2, 2), 0.25, 0);
	ASSERT_EQ(bad, 1); /* the infinity, zeroed */
	ASSERT_NEAR(texel(c, 3, 2), 0.0, 0);
	rf_cubemap_destroy(a);
	rf_cubemap_destroy(b);
	rf_cubemap_destroy(c);
}

/* 8-bit sRGB decodes to linear: 128 is 0.2158605, 10 is 10/255/12.92. */
TEST(srgb_8bit_to_linear)
{
	static const unsigned char bytes[6][4] = {
		{ 0, 10, 128, 255 }, { 255, 188, 64, 0 }, { 1, 11, 54, 9 },
		{ 200, 100, 50, 0 }, { 0, 0, 0, 0 }, { 255, 255, 255, 255 },
	};
	size_t bad;
	rf_cubemap *s, *u;
	int f, ch;

	ASSERT((s = read_raw("R8G8B8A8_SRGB", &bytes[0][0], &bad)) != NULL);
	ASSERT((u = read_raw("GL_RGBA8", &bytes[0][0], &bad)) != NULL);
	for (f = 0; f < 6; f++)
		for (ch = 0; ch < 3; ch++) {
			double want = srgb_to_linear(bytes[f][ch] / 255.0);

			ASSERT_NEAR(texel(s, f, ch), want, 1e-6 * (1.0 + want));
			ASSERT_NEAR(texel(u, f, ch), bytes[f][ch] / 255.0, 1e-7);
		}
	ASSERT_NEAR(texel(s, 0, 2), 0.2158605, 1e-6);
	ASSERT_NEAR(texel(s, 0, 1), 10.0 / 255.0 / 12.92, 1e-8);
	rf_cubemap_destroy(s);
	rf_cubemap_destroy(u);
}

/* ---- the writer ------------------------------------------------------------- */

static uint32_t
get32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	       (uint32_t)p[3] << 24;
}

static uint64_t
get64(const unsigned char *p)
{
	return (uint64_t)get32(p) | (uint64_t)get32(p + 4) << 32;
}

/* A 8-texel chain of 4 levels of half-exact values (multiples of 1/64
 * below 64), different in every texel. */
static rf_cubemap *
sample_chain(void)
{
	rf_cubemap *c;
	size_t k, i, j, n;
	int f;

	if (rf_cubemap_create(&c, 8, 4) < 0)
		return NULL;
	for (k = 0; k < 4; k++) {
		n = rf_cubemap_level_size(c, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++) {
					float *t = rf_cubemap_texel(c, k, (enum rf_face)f, i, j);

					t[0] = (float)(f + 6 * (int)k) / 4.0f;
					t[1] = (float)i + 0.015625f;
					t[2] = (float)j * 0.5f;
				}
		rf_cubemap_seal_level(c, k);
	}
	return c;
}

static unsigned char *
slurp(const char *path, size_t *len)
{
	FILE *fp = fopen(path, "rb");
	unsigned char *p;
	long n;

	if (!fp)
		return NULL;
	fseek(fp, 0, SEEK_END);
	n = ftell(fp);
	rewind(fp);
	p = malloc((size_t)n);
	*len = fread(p, 1, (size_t)n, fp);
	fclose(fp);
	return p;
}

/* Every texel of every level back as written, and the chain's info. */
static int
round_trip(const rf_cubemap *c, const struct rf_ktx_options *o)
{
	struct rf_chain_info info = { 0 }, back;
	char path[64], err[512];
	rf_cubemap *d;
	size_t k, i, j, n, bad = 9;
	int f, ch, ours = 0, fd, failures = 0;

	info.prefiltered = 0;
	info.mapping = RF_MAPPING_LINEAR;
	info.steps = 3.5f;
	info.samples = 17;
	info.base_copied = 0;
	strcpy(path, "/tmp/reflect-ktxw-XXXXXX");
	if ((fd = mkstemp(path)) < 0)
		return 1;
	close(fd);
	unlink(path);
	strcat(path, o->version == 1 ? ".ktx" : ".ktx2");
	if (rf_chain_write_ktx(c, &info, path, o, err, sizeof(err)) < 0) {
		printf("# write: %s\n", err);
		return 1;
	}
	if (rf_chain_read_ktx(&d, &back, &ours, &bad, path, err, sizeof(err)) < 0) {
		printf("# read: %s\n", err);
		unlink(path);
		return 1;
	}
	unlink(path);
	{
		float sh[27];
		int m;

		/* the diffuse light's coefficients, from the float level 0 */
		rf_cubemap_sh9(c, 0, sh);
		for (m = 0; m < 27 && back.has_sh9; m++)
			if (back.sh9[m] != sh[m])
				back.has_sh9 = 0;
	}
	if (ours != 1 || bad != 0 || back.prefiltered != 0 || back.mapping != RF_MAPPING_LINEAR ||
	    !back.has_sh9 ||
	    back.steps != 3.5f || back.samples != 17 || back.base_copied != 0 ||
	    rf_cubemap_levels(d) != rf_cubemap_levels(c)) {
		printf("# info: ours %d, %zu levels, %d %d %g %u %d\n", ours,
		       rf_cubemap_levels(d), back.prefiltered, (int)back.mapping,
		       (double)back.steps, back.samples, back.base_copied);
		failures++;
	}
	for (k = 0; k < rf_cubemap_levels(c) && !failures; k++) {
		n = rf_cubemap_level_size(c, k);
		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++)
				for (i = 0; i < n; i++)
					for (ch = 0; ch < 3; ch++)
						if (rf_cubemap_texel_const(c, k, (enum rf_face)f, i, j)[ch] !=
						    rf_cubemap_texel_const(d, k, (enum rf_face)f, i, j)[ch] &&
						    failures++ < 3)
							printf("# level %zu face %d (%zu, %zu): %g, not %g\n", k, f,
							       i, j,
							       (double)rf_cubemap_texel_const(d, k, (enum rf_face)f, i,
							                                      j)[ch],
							       (double)rf_cubemap_texel_const(c, k, (enum rf_face)f, i,
							                                      j)[ch]);
	}
	rf_cubemap_destroy(d);
	return failures;
}

TEST(writer_round_trips)
{
	rf_cubemap *c = sample_chain();
	struct rf_ktx_options o = { 1, RF_KTX_RGBA16F, 0 };

	ASSERT(c != NULL);
	ASSERT_EQ(round_trip(c, &o), 0);
	o.texel = RF_KTX_RGBA32F;
	ASSERT_EQ(round_trip(c, &o), 0);
	o.version = 2;
	ASSERT_EQ(round_trip(c, &o), 0);
	o.texel = RF_KTX_RGBA16F;
	ASSERT_EQ(round_trip(c, &o), 0);
#ifdef HAVE_ZSTD
	o.zstd = 19;
	ASSERT_EQ(round_trip(c, &o), 0);
#endif
	rf_cubemap_destroy(c);
}

/* The KTX 2 a reflect chain becomes, field by field: what engines and
 * ktx validate look at. */
TEST(writer_ktx2_layout)
{
	rf_cubemap *c = sample_chain();
	struct rf_chain_info info = { 1, RF_MAPPING_UNITY, 3, 64, 1, 0, { 0 } };
	struct rf_ktx_options o = { 2, RF_KTX_RGBA16F, 0 };
	char path[] = "/tmp/reflect-ktxl-XXXXXX.ktx2", err[512];
	unsigned char *p;
	size_t len, k, kv, kvlen;
	uint64_t prev = 0;
	int fd;

	ASSERT(c != NULL);
	ASSERT((fd = mkstemps(path, 5)) >= 0);
	close(fd);
	ASSERT_EQ(rf_chain_write_ktx(c, &info, path, &o, err, sizeof(err)), 0);
	ASSERT((p = slurp(path, &len)) != NULL);
	unlink(path);
	ASSERT(!memcmp(p, "\xabKTX 20\xbb\r\n\x1a\n", 12));
	ASSERT_EQ(get32(p + 12), 97);  /* VK_FORMAT_R16G16B16A16_SFLOAT */
	ASSERT_EQ(get32(p + 16), 2);   /* typeSize */
	ASSERT_EQ(get32(p + 20), 8);
	ASSERT_EQ(get32(p + 24), 8);
	ASSERT_EQ(get32(p + 28), 0);   /* depth */
	ASSERT_EQ(get32(p + 32), 0);   /* layers */
	ASSERT_EQ(get32(p + 36), 6);   /* faces */
	ASSERT_EQ(get32(p + 40), 4);   /* levels */
	ASSERT_EQ(get32(p + 44), 0);   /* no supercompression */
	/* the DFD right after the level index: 4 float samples, R G B A */
	ASSERT_EQ(get32(p + 48), 80 + 4 * 24);
	ASSERT_EQ(get32(p + 52), 92);
	ASSERT_EQ(get32(p + 176), 92);                /* dfdTotalSize */
	ASSERT_EQ(get32(p + 176 + 8), 2u | 88u << 16); /* version 2, block 88 */
	ASSERT_EQ(get32(p + 176 + 12) & 0xffffff, 0x010101); /* RGBSDA BT709 linear */
	ASSERT_EQ(get32(p + 176 + 20), 8);            /* bytesPlane0 */
	ASSERT_EQ(get32(p + 176 + 28), 15u << 16 | 0xc0u << 24);        /* R */
	ASSERT_EQ(get32(p + 176 + 28 + 48), 48 | 15u << 16 | 0xcfu << 24); /* A */
	/* key/value data: KTXorientation rd first, keys sorted */
	kv = get32(p + 56);
	kvlen = get32(p + 60);
	ASSERT_EQ(kv, 176 + 92);
	ASSERT(kvlen > 0 && kv + kvlen <= len);
	ASSERT_EQ(get32(p + kv), 18);
	ASSERT(!memcmp(p + kv + 4, "KTXorientation\0rd\0", 18));
	ASSERT(!memcmp(p + kv + 24 + 4, "KTXwriter\0reflect ", 18));
	ASSERT(memmem(p + kv, kvlen, "reflect:prefilter\0ggx\0", 22) != NULL);
	ASSERT(memmem(p + kv, kvlen, "reflect:steps\0" "3\0", 16) != NULL);
	ASSERT_EQ(get64(p + 64), 0); /* no global data */
	/* the largest level indexed first and stored last, 8-byte aligned */
	for (k = 4; k-- > 0;) {
		uint64_t off = get64(p + 80 + 24 * k), n = 8 >> k;

		ASSERT_EQ(off % 8, 0);
		ASSERT(off >= kv + kvlen && off > prev);
		ASSERT_EQ(get64(p + 80 + 24 * k + 8), 6 * n * n * 8);
		ASSERT_EQ(get64(p + 80 + 24 * k + 16), 6 * n * n * 8);
		prev = off;
	}
	ASSERT_EQ(prev + 6 * 8 * 8 * 8, len);
	/* level 0, face +X, row 0, texel 0 is reflect's (7, 0): R = 0,
	 * G = 7 + 1/64 = 1.75390625 * 2^2 (exponent 15 + 2, mantissa
	 * 0.75390625 * 1024 = 772: 17 << 10 | 772 = 0x4704), B = 0, A = 1 */
	ASSERT_EQ(p[prev] | p[prev + 1] << 8, 0x0000);
	ASSERT_EQ(p[prev + 2] | p[prev + 3] << 8, 0x4704);
	ASSERT_EQ(p[prev + 6] | p[prev + 7] << 8, 0x3c00);
	free(p);
	rf_cubemap_destroy(c);
}

TEST(writer_ktx1_layout)
{
	rf_cubemap *c = sample_chain();
	struct rf_chain_info info = { 1, RF_MAPPING_UNITY, 3, 64, 1, 0, { 0 } };
	struct rf_ktx_options o = { 1, RF_KTX_RGBA32F, 0 };
	char path[] = "/tmp/reflect-ktxl-XXXXXX.ktx", err[512];
	unsigned char *p;
	size_t len, at, k;

	ASSERT(c != NULL);
	ASSERT(mkstemps(path, 4) >= 0);
	ASSERT_EQ(rf_chain_write_ktx(c, &info, path, &o, err, sizeof(err)), 0);
	ASSERT((p = slurp(path, &len)) != NULL);
	unlink(path);
	ASSERT(!memcmp(p, "\xabKTX 11\xbb\r\n\x1a\n", 12));
	ASSERT_EQ(get32(p + 12), 0x04030201);
	ASSERT_EQ(get32(p + 16), GL_FLOAT);
	ASSERT_EQ(get32(p + 20), 4);
	ASSERT_EQ(get32(p + 24), GL_RGBA);
	ASSERT_EQ(get32(p + 28), 0x8814); /* GL_RGBA32F */
	ASSERT_EQ(get32(p + 32), GL_RGBA);
	ASSERT_EQ(get32(p + 48), 0);      /* not an array */
	ASSERT_EQ(get32(p + 52), 6);
	ASSERT_EQ(get32(p + 56), 4);
	ASSERT(!memcmp(p + 64 + 4, "KTXorientation\0S=r,T=d\0", 23));
	at = 64 + get32(p + 60);
	for (k = 0; k < 4; k++) {
		size_t n = 8 >> k;

		ASSERT_EQ(get32(p + at), n * n * 16); /* one face, not the level */
		at += 4 + 6 * n * n * 16;
	}
	ASSERT_EQ(at, len);
	free(p);
	rf_cubemap_destroy(c);
}

TEST(writer_refusals)
{
	rf_cubemap *c = sample_chain();
	struct rf_chain_info info = { 1, RF_MAPPING_UNITY, 3, 64, 1, 0, { 0 } };
	struct rf_ktx_options o = { 1, RF_KTX_RGBA16F, 3 };
	char err[512];

	ASSERT(c != NULL);
	ASSERT_EQ(rf_chain_write_ktx(c, &info, "/tmp/x.ktx", &o, err, sizeof(err)), RF_EINVAL);
	ASSERT_STR_EQ(err, "'/tmp/x.ktx': KTX 1 has no supercompression; Zstandard needs a "
	              ".ktx2 file");
	o.version = 3;
	ASSERT_EQ(rf_chain_write_ktx(c, &info, "/tmp/x.ktx", &o, err, sizeof(err)), RF_EINVAL);
	o.version = 2;
	o.zstd = 0;
	ASSERT_EQ(rf_chain_write_ktx(c, &info, "/nonexistent/x.ktx2", &o, err, sizeof(err)),
	          RF_EIO);
	ASSERT(!strncmp(err, "cannot write '/nonexistent/x.ktx2': ", 36));
	rf_cubemap_destroy(c);
}

/* ---- refusals ---------------------------------------------------------------- */

static int
refused(const struct fixture *fx, int want_rc, const char *want_fmt)
{
	struct rf_chain_info info;
	char path[64], err[512], want[640];
	rf_cubemap *c = (rf_cubemap *)&info;
	size_t bad;
	int rc = read_fixture(fx, &c, &info, NULL, &bad, path, err, sizeof(err));

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

#define HINT1 "is not supported; convert with ktx extract/toktx to an uncompressed format"
#define HINT2 "is not supported; convert with ktx extract/toktx to an uncompressed or " \
	"zstd format"

TEST(refuses_block_compressed_and_basis)
{
	struct fixture fx = cube(format_named("R16G16B16A16_SFLOAT"), 4, 1);
	struct fixture g = cube(format_named("GL_RGBA16F"), 4, 1);

	fx.format = 143;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': vkFormat 143 (BC6H, block-compressed) "
	                  HINT2), 0);
	fx.format = 146;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': vkFormat 146 (BC7, block-compressed) "
	                  HINT2), 0);
	fx.format = 157;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': vkFormat 157 (ASTC, block-compressed) "
	                  HINT2), 0);
	fx.format = 1000066000u;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': vkFormat 1000066000 (ASTC HDR, "
	                  "block-compressed) " HINT2), 0);
	fx.format = 147;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': vkFormat 147 (ETC2, block-compressed) "
	                  HINT2), 0);
	fx.format = 91; /* R16G16B16A16_UNORM: uncompressed, not read */
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': vkFormat 91 " HINT2), 0);
	/* Basis Universal: vkFormat undefined, the DFD's model tells */
	fx.format = 0;
	fx.scheme = 1;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': BasisLZ supercompression " HINT2), 0);
	fx.scheme = 0;
	fx.dfd_model = 166;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': Basis Universal UASTC " HINT2), 0);
	fx.dfd_model = 163;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': Basis Universal ETC1S " HINT2), 0);
	fx.dfd_model = 1;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': VK_FORMAT_UNDEFINED (colour model 1) "
	                  HINT2), 0);
	fx.format = 97;
	fx.scheme = 3;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': ZLIB supercompression " HINT2), 0);
	fx.scheme = 0x10000;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': supercompression scheme 65536 " HINT2), 0);
	/* KTX 1: by glInternalFormat */
	g.format = 0x8e8f;
	g.gl_type = g.gl_format = 0;
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': glInternalFormat 0x8e8f (BC6H, "
	                  "block-compressed) " HINT1), 0);
	g.format = 0x8d64;
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': glInternalFormat 0x8d64 (ETC1, "
	                  "block-compressed) " HINT1), 0);
	g.format = 0x93b0;
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': glInternalFormat 0x93b0 (ASTC, "
	                  "block-compressed) " HINT1), 0);
	g.format = 0x1234;
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': glInternalFormat 0x1234 (block-compressed) "
	                  HINT1), 0);
	g.format = 0x805b; /* GL_RGBA16 */
	g.gl_type = 0x1403;
	g.gl_format = GL_RGBA;
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': glInternalFormat 0x805b (glFormat 0x1908, "
	                  "glType 0x1403) " HINT1), 0);
}

TEST(refuses_zstd_without_libzstd)
{
#ifndef HAVE_ZSTD
	struct fixture fx = cube(format_named("R16G16B16A16_SFLOAT"), 4, 1);

	fx.scheme = 2;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': Zstandard supercompression needs libzstd, "
	                  "which this reflect was built without; rebuild it with libzstd "
	                  "(Debian: libzstd-dev) or convert with ktx extract/toktx to an "
	                  "uncompressed format"), 0);
#else
	/* with it, a level that is no Zstandard frame is refused */
	struct fixture fx = cube(format_named("R16G16B16A16_SFLOAT"), 4, 1);

	fx.scheme = 2; /* but plain bytes */
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': level 0: a Zstandard frame of no valid "
	                  "header, not the 768 bytes of its texels"), 0);
#endif
}

TEST(refuses_non_cubes)
{
	struct fixture fx = cube(format_named("R16G16B16A16_SFLOAT"), 4, 1);
	struct fixture g = cube(format_named("GL_RGBA16F"), 4, 1);

	fx.faces = 1;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a cube map (a 2D texture)"), 0);
	fx.height = 0;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a cube map (a 1D texture)"), 0);
	fx.height = 4;
	fx.layers = 6;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a cube map (an array of 6 2D "
	                  "textures)"), 0);
	fx.layers = 0;
	fx.depth = 4;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a cube map (a 3D texture)"), 0);
	fx.depth = 0;
	fx.faces = 6;
	fx.layers = 2;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': an array of 2 cubes; reflect reads one "
	                  "cube"), 0);
	fx.layers = 0;
	fx.faces = 5;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a cube map (a texture of 5 faces)"), 0);
	g.layers = 3;
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': an array of 3 cubes; reflect reads one "
	                  "cube"), 0);
	g.layers = 0;
	g.depth = 2;
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': not a cube map (a 3D texture)"), 0);
}

TEST(refuses_bad_sizes)
{
	struct fixture fx = cube(format_named("R32G32B32A32_SFLOAT"), 32768, 1);
	struct fixture g;

	fx.texel = NULL; /* headers only: nothing could be written */
	ASSERT_EQ(refused(&fx, RF_ETOOBIG, "'%s': cube faces of 32768 texels (1 to 16384 "
	                  "are read)"), 0);
	fx.width = fx.height = 0;
	ASSERT_EQ(refused(&fx, RF_ETOOBIG, "'%s': cube faces of 0 texels (1 to 16384 are "
	                  "read)"), 0);
	fx.width = fx.height = 0xffffffffu;
	ASSERT_EQ(refused(&fx, RF_ETOOBIG, "'%s': cube faces of 4294967295 texels (1 to "
	                  "16384 are read)"), 0);
	fx.width = 8;
	fx.height = 4;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': cube faces of 8x4 are not square"), 0);
	fx.width = fx.height = 8;
	fx.mips = 5;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': 5 mip levels claimed; faces of 8 have at "
	                  "most 4"), 0);
	fx.mips = 0xffffffffu;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': 4294967295 mip levels claimed; faces of 8 "
	                  "have at most 4"), 0);
	/* the largest size, in a file of headers and an index only: the
	 * promised 6 GiB are missing, seen before any allocation */
	fx.width = fx.height = 16384;
	fx.mips = 15;
	fx.length = 80 + 4 * 24;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: the level index needs 264 "
	                  "more bytes"), 0);
	fx.length = 0;
	/* a forged level index: offset near 2^64, or just past the file */
	fx = cube(format_named("R32G32B32A32_SFLOAT"), 4, 1);
	fx.offset0 = UINT64_MAX - 100;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': level 0 lies past any file (offset "
	                  "18446744073709551515, 1536 bytes)"), 0);
	/* the file: 80 + 24 + a DFD of 28, padded to 144, + 1536 = 1680 */
	fx.offset0 = 1u << 30;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: level 0 needs 1073741680 "
	                  "more bytes"), 0);
	fx.offset0 = 0;
	fx.bad_size = 16;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': level 0 holds 1552 bytes; six faces of 16 "
	                  "R32G32B32A32_SFLOAT texels take 1536"), 0);
	g = cube(format_named("GL_RGB8"), 2, 1);
	g.bad_size = -2; /* imageSize without its row padding, 2 x 6 bytes */
	ASSERT_EQ(refused(&g, RF_EFORMAT, "'%s': level 0's imageSize is 14 bytes; a face of "
	                  "4 GL_RGB8 texels takes 16"), 0);
}

/* 4 texels, 3 levels of 16-byte texels, KTX 1: 64 bytes of header, then
 * per level 4 bytes of imageSize and six faces of 256, 64, 16 bytes. */
TEST(refuses_truncated_files)
{
	const struct format *g = format_named("GL_RGBA32F"), *v = format_named("R16G16B16A16_SFLOAT");
	struct fixture fx = cube(g, 4, 3);
	static const unsigned char nothing[1];
	char path[64];
	FILE *fp;

	fx.length = 50;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: the KTX header needs 14 more "
	                  "bytes"), 0);
	fx.length = 64 + 2;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: level 0's imageSize needs 2 "
	                  "more bytes"), 0);
	fx.length = 64 + 4 + 3 * 256 + 10;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: level 0 of face -Y needs 246 "
	                  "more bytes"), 0);
	fx.length = 64 + 4 + 6 * 256 + 4 + 6 * 64 + 4 + 6 * 16 - 1;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: level 2 of face -Z needs 1 "
	                  "more bytes"), 0);
	fx.kv[0] = "a";
	fx.kv[1] = "b";
	fx.length = 64 + 3;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: the key/value data needs 5 "
	                  "more bytes"), 0);
	/* KTX 2: 80 bytes of header, 3 index entries, a DFD of 28; the
	 * levels, 768 192 48 bytes, smallest first */
	fx = cube(v, 4, 3);
	fx.length = 79;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: the KTX 2 header needs 1 "
	                  "more bytes"), 0);
	fx.length = 80 + 50;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: the level index needs 22 "
	                  "more bytes"), 0);
	fx.length = 152 + 28 + 4 + 48 + 192 + 768 - 100;
	ASSERT_EQ(refused(&fx, RF_ETRUNCATED, "'%s': truncated: level 0 needs 100 more "
	                  "bytes"), 0);
	fx.length = 11;
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': not a KTX file (no KTX 11 or KTX 20 "
	                  "identifier)"), 0);
	/* an empty file */
	strcpy(path, "/tmp/reflect-ktx-XXXXXX");
	ASSERT(mkstemp(path) >= 0);
	ASSERT((fp = fopen(path, "wb")) != NULL);
	fwrite(nothing, 1, 0, fp);
	fclose(fp);
	{
		struct rf_chain_info info;
		rf_cubemap *c;
		char err[512], want[600];

		ASSERT_EQ(rf_chain_read_ktx(&c, &info, NULL, NULL, path, err, sizeof(err)),
		          RF_EFORMAT);
		snprintf(want, sizeof(want), "'%s': not a KTX file (no KTX 11 or KTX 20 "
		         "identifier)", path);
		ASSERT_STR_EQ(err, want);
	}
	unlink(path);
}

/* reflect's keys: another writer's are skipped, a broken SH9 refused as
 * the EXR chain's attribute is. */
TEST(reflect_keys)
{
	const struct format *fmt = format_named("R16G16B16A16_SFLOAT");
	struct fixture fx = cube(fmt, 4, 3);
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c;
	int ours = 9;

	fx.kv[0] = "KTXorientation";
	fx.kv[1] = "rd";
	fx.kv[2] = "reflect:levels";
	fx.kv[3] = "2";
	fx.kv[4] = "reflect:prefilter";
	fx.kv[5] = "box";
	ASSERT_EQ(read_fixture(&fx, &c, &info, &ours, NULL, path, err, sizeof(err)), 0);
	ASSERT_EQ(ours, 1);
	ASSERT_EQ(info.prefiltered, 0);
	ASSERT_EQ(info.has_sh9, 0);
	ASSERT_EQ(rf_cubemap_levels(c), 2);
	rf_cubemap_destroy(c);
	fx.kv[2] = "reflect:irradianceSH9";
	fx.kv[3] = "1 2 3";
	ASSERT_EQ(refused(&fx, RF_EFORMAT, "'%s': key reflect:irradianceSH9 needs 27 finite "
	                  "float numbers"), 0);
	fx.kv[0] = "someone:else";
	fx.kv[1] = "x";
	fx.kv[2] = NULL;
	ASSERT_EQ(check_fixture(&fx, fmt, 3), 0);
}

TEST(refuses_bad_endianness_and_missing_file)
{
	struct fixture fx = cube(format_named("GL_RGBA32F"), 4, 1);
	struct rf_chain_info info;
	char path[64], err[512];
	rf_cubemap *c;
	unsigned char b[4] = { 1, 2, 2, 1 };
	FILE *fp;
	int rc;

	ASSERT_EQ(write_fixture(&fx, path), 0);
	ASSERT((fp = fopen(path, "r+b")) != NULL);
	fseek(fp, 12, SEEK_SET);
	fwrite(b, 1, 4, fp);
	fclose(fp);
	rc = rf_chain_read_ktx(&c, &info, NULL, NULL, path, err, sizeof(err));
	unlink(path);
	ASSERT_EQ(rc, RF_EFORMAT);
	ASSERT(strstr(err, "KTX endianness 0x01020201, neither 0x04030201 nor its reverse"));
	ASSERT_EQ(rf_chain_read_ktx(&c, &info, NULL, NULL, "/nonexistent/x.ktx2", err,
	                            sizeof(err)), RF_EIO);
	ASSERT(c == NULL);
	ASSERT_STR_EQ(err, "cannot open '/nonexistent/x.ktx2': No such file or directory");
}

int
main(void)
{
	RUN(labelled_cube_every_format);
	RUN(big_endian_ktx1);
	RUN(level_counts_and_image_sizes);
	RUN(zstd_levels);
	RUN(orientation_of_one_texel);
	RUN(packed_floats_by_hand);
	RUN(srgb_8bit_to_linear);
	RUN(writer_round_trips);
	RUN(writer_ktx2_layout);
	RUN(writer_ktx1_layout);
	RUN(writer_refusals);
	RUN(refuses_block_compressed_and_basis);
	RUN(refuses_zstd_without_libzstd);
	RUN(refuses_non_cubes);
	RUN(refuses_bad_sizes);
	RUN(refuses_truncated_files);
	RUN(reflect_keys);
	RUN(refuses_bad_endianness_and_missing_file);
	TAP_DONE();
}
