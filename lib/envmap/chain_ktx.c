/*
 * Pre-convolved cube chains stored as KTX 1 and KTX 2 files: the chains
 * cmft and filament's cmgen write (KTX 1), and those of glTF-IBL-Sampler
 * and KTX-Software's tools (KTX 2).  Our own reader, as for DDS: the
 * formats are simple, and OpenImageIO reads neither as a cube.
 *
 * Orientation.  Both versions store the faces in the order +X -X +Y -Y
 * +Z -Z, each with its first row at t = 0 of OpenGL's and Vulkan's face
 * selection table: KTX 2 requires the orientation "rd" of every cube,
 * and a KTX 1 cube is uploaded to OpenGL as it is stored.  That is the
 * table DDS faces follow, so the faces are mirrored into OpenEXR's
 * orientations as chain_dds.c says (texel.h does it for both).  The
 * KTXorientation key is not read: the specification says it changes no
 * texel's texture coordinates, a cube sampler ignores it, and toktx
 * writes no cube any other way.
 *
 * Sizes.  Every size and offset the header gives is checked against the
 * file's length, and the cube against the memory limit, before anything
 * is allocated; Zstandard levels are inflated into a buffer of the size
 * their faces take, never of the size their frames claim.
 */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef HAVE_ZSTD
#include <zstd.h>
#endif

#include "envmap/envmap-internal.h"
#include "envmap/texel.h"
#include "reflect/envmap.h"

#define KTX_MAX_SIZE 16384u /* as DDS_MAX_SIZE */
#define KTX_MAX_LEVELS 15   /* faces of 16384 texels down to 1 */
#define KTX1_HEADER 64u
#define KTX2_HEADER 80u     /* with the index */
#define KTX2_LEVEL 24u      /* a level index entry */
#define KTX_KV_MAX (1u << 20) /* key/value data read for reflect's keys */

#define KTX_HINT1 "is not supported; convert with ktx extract/toktx to an uncompressed format"
#define KTX_HINT2 "is not supported; convert with ktx extract/toktx to an uncompressed or zstd format"

static const unsigned char ktx1_id[12] = { 0xab, 'K', 'T', 'X', ' ', '1', '1', 0xbb,
	                                   '\r', '\n', 0x1a, '\n' };
static const unsigned char ktx2_id[12] = { 0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb,
	                                   '\r', '\n', 0x1a, '\n' };

static const char *const face_names[6] = { "+X", "-X", "+Y", "-Y", "+Z", "-Z" };

struct ktx {
	const char *path;
	FILE *fp;
	uint64_t file_size;
	int version;
	int swap;                     /* KTX 1 written big-endian */
	unsigned unit;                /* bytes swapped together then */
	struct rf__texel_format fmt;
	const char *format_name;
	uint32_t size, file_levels, scheme;
	size_t levels;                /* those reflect keeps */
	uint64_t offset[KTX_MAX_LEVELS], length[KTX_MAX_LEVELS];
	uint64_t row_stride[KTX_MAX_LEVELS], face_stride[KTX_MAX_LEVELS];
	uint64_t kv_offset, kv_length;
	char *err;
	size_t errlen;
};

static uint32_t
rd32(const struct ktx *k, const unsigned char *p)
{
	if (k->swap)
		return (uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 |
		       (uint32_t)p[0] << 24;
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	       (uint32_t)p[3] << 24;
}

static uint64_t
rd64(const struct ktx *k, const unsigned char *p)
{
	return (uint64_t)rd32(k, p) | (uint64_t)rd32(k, p + 4) << 32;
}

/* ---- formats ------------------------------------------------------------ */

struct ktx_format {
	uint32_t id;
	const char *name;
	struct rf__texel_format fmt;
	unsigned unit; /* the size of a number in a texel, for byte swapping */
};

#define F32(n, b) { RF__TEXEL_F32, n, b, 0 }
#define F16(n, b) { RF__TEXEL_F16, n, b, 0 }
#define RGB8(n, s) { RF__TEXEL_RGBA8, n, n, s }
#define BGR8(n, s) { RF__TEXEL_BGRA8, n, n, s }

static const struct ktx_format vk_formats[] = {
	{ 23, "R8G8B8_UNORM", RGB8(3, 0), 1 }, { 29, "R8G8B8_SRGB", RGB8(3, 1), 1 },
	{ 30, "B8G8R8_UNORM", BGR8(3, 0), 1 }, { 36, "B8G8R8_SRGB", BGR8(3, 1), 1 },
	{ 37, "R8G8B8A8_UNORM", RGB8(4, 0), 1 }, { 43, "R8G8B8A8_SRGB", RGB8(4, 1), 1 },
	{ 44, "B8G8R8A8_UNORM", BGR8(4, 0), 1 }, { 50, "B8G8R8A8_SRGB", BGR8(4, 1), 1 },
	/* packed in a little-endian word, these are R G B A bytes */
	{ 51, "A8B8G8R8_UNORM_PACK32", RGB8(4, 0), 1 },
	{ 57, "A8B8G8R8_SRGB_PACK32", RGB8(4, 1), 1 },
	{ 90, "R16G16B16_SFLOAT", F16(3, 6), 2 }, { 97, "R16G16B16A16_SFLOAT", F16(4, 8), 2 },
	{ 100, "R32_SFLOAT", F32(1, 4), 4 }, { 106, "R32G32B32_SFLOAT", F32(3, 12), 4 },
	{ 109, "R32G32B32A32_SFLOAT", F32(4, 16), 4 },
	{ 122, "B10G11R11_UFLOAT_PACK32", { RF__TEXEL_R11G11B10, 3, 4, 0 }, 4 },
	{ 123, "E5B9G9R9_UFLOAT_PACK32", { RF__TEXEL_RGB9E5, 3, 4, 0 }, 4 },
};

/* KTX 1 by glInternalFormat: the sized formats.  filament's cmgen writes
 * R11F_G11F_B10F as glType and glFormat too, so those two are not
 * checked against it. */
static const struct ktx_format gl_formats[] = {
	{ 0x8051, "GL_RGB8", RGB8(3, 0), 1 }, { 0x8c41, "GL_SRGB8", RGB8(3, 1), 1 },
	{ 0x8058, "GL_RGBA8", RGB8(4, 0), 1 }, { 0x8c43, "GL_SRGB8_ALPHA8", RGB8(4, 1), 1 },
	{ 0x881b, "GL_RGB16F", F16(3, 6), 2 }, { 0x881a, "GL_RGBA16F", F16(4, 8), 2 },
	{ 0x822e, "GL_R32F", F32(1, 4), 4 }, { 0x8815, "GL_RGB32F", F32(3, 12), 4 },
	{ 0x8814, "GL_RGBA32F", F32(4, 16), 4 },
	{ 0x8c3a, "GL_R11F_G11F_B10F", { RF__TEXEL_R11G11B10, 3, 4, 0 }, 4 },
	{ 0x8c3d, "GL_RGB9_E5", { RF__TEXEL_RGB9E5, 3, 4, 0 }, 4 },
};

#define GL_UNSIGNED_BYTE 0x1401u
#define GL_FLOAT 0x1406u
#define GL_HALF_FLOAT 0x140bu
#define GL_RGB 0x1907u
#define GL_RGBA 0x1908u
#define GL_BGR 0x80e0u
#define GL_BGRA 0x80e1u

/* The block-compressed families, for the refusal message. */
struct id_range {
	uint32_t lo, hi;
	const char *name;
};

static const struct id_range vk_compressed[] = {
	{ 131, 134, "BC1" }, { 135, 136, "BC2" }, { 137, 138, "BC3" }, { 139, 140, "BC4" },
	{ 141, 142, "BC5" }, { 143, 144, "BC6H" }, { 145, 146, "BC7" },
	{ 147, 152, "ETC2" }, { 153, 156, "EAC" }, { 157, 184, "ASTC" },
	{ 1000054000u, 1000054007u, "PVRTC" }, { 1000066000u, 1000066013u, "ASTC HDR" },
	{ 1000288000u, 1000288029u, "3D ASTC" },
};

static const struct id_range gl_compressed[] = {
	{ 0x83f0, 0x83f1, "BC1" }, { 0x83f2, 0x83f2, "BC2" }, { 0x83f3, 0x83f3, "BC3" },
	{ 0x8c4c, 0x8c4d, "BC1" }, { 0x8c4e, 0x8c4e, "BC2" }, { 0x8c4f, 0x8c4f, "BC3" },
	{ 0x8dbb, 0x8dbc, "BC4" }, { 0x8dbd, 0x8dbe, "BC5" }, { 0x8e8c, 0x8e8d, "BC7" },
	{ 0x8e8e, 0x8e8f, "BC6H" }, { 0x8d64, 0x8d64, "ETC1" }, { 0x9270, 0x9273, "EAC" },
	{ 0x9274, 0x9279, "ETC2" }, { 0x93b0, 0x93bd, "ASTC" }, { 0x93d0, 0x93dd, "ASTC" },
	{ 0x8c00, 0x8c03, "PVRTC" }, { 0x8a54, 0x8a57, "PVRTC" },
};

static const char *
range_name(const struct id_range *r, size_t n, uint32_t id)
{
	size_t i;

	for (i = 0; i < n; i++)
		if (id >= r[i].lo && id <= r[i].hi)
			return r[i].name;
	return NULL;
}

static const struct ktx_format *
find_format(const struct ktx_format *t, size_t n, uint32_t id)
{
	size_t i;

	for (i = 0; i < n; i++)
		if (t[i].id == id)
			return &t[i];
	return NULL;
}

/* KTX 1's texel format: the sized internal format, or an unsized one
 * (GL_RGB, GL_RGBA, as cmft may write) told by glType. */
static int
ktx1_format(struct ktx *k, uint32_t gl_type, uint32_t gl_format, uint32_t internal)
{
	static const struct ktx_format unsized[] = {
		{ GL_UNSIGNED_BYTE, "GL_RGB8", RGB8(3, 0), 1 },
		{ GL_HALF_FLOAT, "GL_RGB16F", F16(3, 6), 2 },
		{ GL_FLOAT, "GL_RGB32F", F32(3, 12), 4 },
		{ GL_UNSIGNED_BYTE, "GL_RGBA8", RGB8(4, 0), 1 },
		{ GL_HALF_FLOAT, "GL_RGBA16F", F16(4, 8), 2 },
		{ GL_FLOAT, "GL_RGBA32F", F32(4, 16), 4 },
	};
	const struct ktx_format *f;
	const char *family = range_name(gl_compressed,
	                                sizeof(gl_compressed) / sizeof(gl_compressed[0]),
	                                internal);

	if (family || gl_type == 0) {
		rf__format(k->err, k->errlen, "'%s': glInternalFormat 0x%04x (%s%sblock-"
		           "compressed) " KTX_HINT1, k->path, (unsigned)internal,
		           family ? family : "", family ? ", " : "");
		return RF_EFORMAT;
	}
	if ((f = find_format(gl_formats, sizeof(gl_formats) / sizeof(gl_formats[0]),
	                     internal)) == NULL &&
	    (internal == GL_RGB || internal == GL_RGBA))
		f = find_format(unsized + (internal == GL_RGBA ? 3 : 0), 3, gl_type);
	if (!f) {
		rf__format(k->err, k->errlen, "'%s': glInternalFormat 0x%04x (glFormat 0x%04x, "
		           "glType 0x%04x) " KTX_HINT1, k->path, (unsigned)internal,
		           (unsigned)gl_format, (unsigned)gl_type);
		return RF_EFORMAT;
	}
	k->fmt = f->fmt;
	k->unit = f->unit;
	k->format_name = f->name;
	/* 8-bit texels in B G R order say so by glFormat alone. */
	if (f->unit == 1 && (gl_format == GL_BGRA || gl_format == GL_BGR))
		k->fmt.kind = RF__TEXEL_BGRA8;
	return 0;
}

/* ---- headers ------------------------------------------------------------ */

/* Reads n bytes at off; the caller has checked they are in the file. */
static int
read_at(struct ktx *k, uint64_t off, void *buf, size_t n)
{
	if (fseeko(k->fp, (off_t)off, SEEK_SET) != 0 || fread(buf, 1, n, k->fp) != n) {
		rf__format(k->err, k->errlen, "cannot read '%s': %s", k->path,
		           ferror(k->fp) ? strerror(errno ? errno : EIO)
		                         : "unexpected end of file");
		return RF_EIO;
	}
	return 0;
}

static int
truncated(struct ktx *k, const char *what, uint64_t end)
{
	rf__format(k->err, k->errlen, "'%s': truncated: %s needs %llu more bytes", k->path,
	           what, (unsigned long long)(end - k->file_size));
	return RF_ETRUNCATED;
}

/* The texture must be one cube: faces, layers and depth say what else
 * it is. */
static int
check_type(struct ktx *k, uint32_t height, uint32_t depth, uint32_t layers, uint32_t faces)
{
	char what[64];

	if (faces == 6 && layers > 1) {
		rf__format(k->err, k->errlen, "'%s': an array of %u cubes; reflect reads one "
		           "cube", k->path, (unsigned)layers);
		return RF_EFORMAT;
	}
	if (faces == 6 && depth == 0)
		return 0;
	if (depth > 0)
		rf__format(what, sizeof(what), "a 3D texture");
	else if (faces != 1)
		rf__format(what, sizeof(what), "a texture of %u faces", (unsigned)faces);
	else if (layers > 0)
		rf__format(what, sizeof(what), "an array of %u %s textures", (unsigned)layers,
		           height ? "2D" : "1D");
	else
		rf__format(what, sizeof(what), "a %s texture", height ? "2D" : "1D");
	rf__format(k->err, k->errlen, "'%s': not a cube map (%s)", k->path, what);
	return RF_EFORMAT;
}

/* Square faces of a size reflect reads, and a level count they have. */
static int
check_size(struct ktx *k, uint32_t width, uint32_t height, uint32_t levels)
{
	uint32_t maxlevels;

	if (width != height) {
		rf__format(k->err, k->errlen, "'%s': cube faces of %ux%u are not square",
		           k->path, (unsigned)width, (unsigned)height);
		return RF_EFORMAT;
	}
	if (width == 0 || width > KTX_MAX_SIZE) {
		rf__format(k->err, k->errlen, "'%s': cube faces of %u texels (1 to %u are read)",
		           k->path, (unsigned)width, KTX_MAX_SIZE);
		return RF_ETOOBIG;
	}
	for (maxlevels = 1; width >> maxlevels; maxlevels++)
		;
	if (levels == 0)
		levels = 1; /* the base level alone, the rest to be generated */
	if (levels > maxlevels) {
		rf__format(k->err, k->errlen, "'%s': %u mip levels claimed; faces of %u have at "
		           "most %u", k->path, (unsigned)levels, (unsigned)width,
		           (unsigned)maxlevels);
		return RF_EFORMAT;
	}
	k->size = width;
	k->file_levels = levels;
	/* rf_cubemap_create's rule, as for DDS: halve while even. */
	for (k->levels = 1; k->levels < levels && !((width >> (k->levels - 1)) & 1);
	     k->levels++)
		;
	return 0;
}

static uint64_t
texels(const struct ktx *k, size_t level)
{
	uint64_t s = k->size >> level;

	return s * s;
}

static int
parse_ktx1(struct ktx *k, const unsigned char *h, size_t got)
{
	uint32_t endian, gl_type, gl_format, internal, width, height, depth, layers, faces;
	uint32_t mips, kv;
	uint64_t off;
	size_t l;
	int rc;

	if (got < KTX1_HEADER)
		return truncated(k, "the KTX header", KTX1_HEADER);
	endian = (uint32_t)h[12] | (uint32_t)h[13] << 8 | (uint32_t)h[14] << 16 |
	         (uint32_t)h[15] << 24;
	if (endian == 0x01020304u) {
		k->swap = 1;
	} else if (endian != 0x04030201u) {
		rf__format(k->err, k->errlen, "'%s': KTX endianness 0x%08x, neither "
		           "0x04030201 nor its reverse", k->path, (unsigned)endian);
		return RF_EFORMAT;
	}
	gl_type = rd32(k, h + 16);
	gl_format = rd32(k, h + 24);
	internal = rd32(k, h + 28);
	width = rd32(k, h + 36);
	height = rd32(k, h + 40);
	depth = rd32(k, h + 44);
	layers = rd32(k, h + 48);
	faces = rd32(k, h + 52);
	mips = rd32(k, h + 56);
	kv = rd32(k, h + 60);
	if ((rc = check_type(k, height, depth, layers, faces)) < 0 ||
	    (rc = ktx1_format(k, gl_type, gl_format, internal)) < 0 ||
	    (rc = check_size(k, width, height, mips)) < 0)
		return rc;
	if ((uint64_t)KTX1_HEADER + kv > k->file_size)
		return truncated(k, "the key/value data", (uint64_t)KTX1_HEADER + kv);
	k->kv_offset = KTX1_HEADER;
	k->kv_length = kv;
	/* Rows are padded to 4 bytes (GL_UNPACK_ALIGNMENT), and so, for a
	 * cube, each face; imageSize is one face's bytes. */
	off = (uint64_t)KTX1_HEADER + kv;
	for (l = 0; l < k->levels; l++) {
		uint64_t s = k->size >> l, row = s * k->fmt.bytes, face, size;
		unsigned char b[4];
		char what[64];
		int f;

		k->row_stride[l] = (row + 3) & ~(uint64_t)3;
		face = k->row_stride[l] * s;
		k->face_stride[l] = (face + 3) & ~(uint64_t)3;
		rf__format(what, sizeof(what), "level %zu's imageSize", l);
		if (off + 4 > k->file_size)
			return truncated(k, what, off + 4);
		if ((rc = read_at(k, off, b, 4)) < 0)
			return rc;
		size = rd32(k, b);
		/* Writers that took the "most textures" rule give the whole
		 * level; either is unambiguous. */
		if (size != face && size != 6 * face) {
			rf__format(k->err, k->errlen, "'%s': level %zu's imageSize is %llu bytes; "
			           "a face of %llu %s texels takes %llu", k->path, l,
			           (unsigned long long)size, (unsigned long long)(s * s),
			           k->format_name, (unsigned long long)face);
			return RF_EFORMAT;
		}
		k->offset[l] = off + 4;
		for (f = 0; f < 6; f++)
			if (k->offset[l] + (f + 1) * k->face_stride[l] > k->file_size) {
				rf__format(what, sizeof(what), "level %zu of face %s", l, face_names[f]);
				return truncated(k, what, k->offset[l] + (f + 1) * k->face_stride[l]);
			}
		off = k->offset[l] + 6 * k->face_stride[l];
	}
	return 0;
}

/* A KTX 2 file of VK_FORMAT_UNDEFINED: the DFD's colour model says which
 * universal format it holds. */
static int
ktx2_undefined(struct ktx *k, const unsigned char *h)
{
	uint32_t dfd = rd32(k, h + 48), dfd_len = rd32(k, h + 52), model = 0;
	unsigned char b[16];
	int rc;

	if (dfd_len >= 16 && dfd <= k->file_size && k->file_size - dfd >= 16) {
		if ((rc = read_at(k, dfd, b, 16)) < 0)
			return rc;
		model = b[12];
	}
	if (model == 166 || model == 163)
		rf__format(k->err, k->errlen, "'%s': Basis Universal %s " KTX_HINT2, k->path,
		           model == 166 ? "UASTC" : "ETC1S");
	else
		rf__format(k->err, k->errlen, "'%s': VK_FORMAT_UNDEFINED (colour model %u) "
		           KTX_HINT2, k->path, (unsigned)model);
	return RF_EFORMAT;
}

static int
ktx2_scheme(struct ktx *k, uint32_t scheme)
{
	switch (scheme) {
	case 0:
		return 0;
	case 1:
		rf__format(k->err, k->errlen, "'%s': BasisLZ supercompression " KTX_HINT2,
		           k->path);
		return RF_EFORMAT;
	case 2:
#ifdef HAVE_ZSTD
		return 0;
#else
		rf__format(k->err, k->errlen, "'%s': Zstandard supercompression needs libzstd, "
		           "which this reflect was built without; rebuild it with libzstd "
		           "(Debian: libzstd-dev) or convert with ktx extract/toktx to an "
		           "uncompressed format", k->path);
		return RF_EFORMAT;
#endif
	case 3:
		rf__format(k->err, k->errlen, "'%s': ZLIB supercompression " KTX_HINT2, k->path);
		return RF_EFORMAT;
	}
	rf__format(k->err, k->errlen, "'%s': supercompression scheme %u " KTX_HINT2, k->path,
	           (unsigned)scheme);
	return RF_EFORMAT;
}

static int
parse_ktx2(struct ktx *k, const unsigned char *h, size_t got)
{
	uint32_t vk, width, height, depth, layers, faces, levels, n;
	const struct ktx_format *f;
	unsigned char b[KTX2_LEVEL];
	size_t l;
	int rc;

	if (got < KTX2_HEADER)
		return truncated(k, "the KTX 2 header", KTX2_HEADER);
	vk = rd32(k, h + 12);
	width = rd32(k, h + 20);
	height = rd32(k, h + 24);
	depth = rd32(k, h + 28);
	layers = rd32(k, h + 32);
	faces = rd32(k, h + 36);
	levels = rd32(k, h + 40);
	k->scheme = rd32(k, h + 44);
	if ((rc = check_type(k, height, depth, layers, faces)) < 0 ||
	    (rc = ktx2_scheme(k, k->scheme)) < 0)
		return rc;
	if (vk == 0)
		return ktx2_undefined(k, h);
	if (!(f = find_format(vk_formats, sizeof(vk_formats) / sizeof(vk_formats[0]), vk))) {
		const char *family = range_name(vk_compressed, sizeof(vk_compressed) /
		                                sizeof(vk_compressed[0]), vk);

		rf__format(k->err, k->errlen, "'%s': vkFormat %u%s%s%s " KTX_HINT2, k->path,
		           (unsigned)vk, family ? " (" : "", family ? family : "",
		           family ? ", block-compressed)" : "");
		return RF_EFORMAT;
	}
	k->fmt = f->fmt;
	k->unit = f->unit;
	k->format_name = f->name;
	if ((rc = check_size(k, width, height, levels)) < 0)
		return rc;
	n = k->file_levels;
	if (KTX2_HEADER + (uint64_t)KTX2_LEVEL * n > k->file_size)
		return truncated(k, "the level index", KTX2_HEADER + (uint64_t)KTX2_LEVEL * n);
	k->kv_offset = rd32(k, h + 56);
	k->kv_length = rd32(k, h + 60);
	for (l = 0; l < k->levels; l++) {
		uint64_t raw = 6 * texels(k, l) * k->fmt.bytes, off, len, unpacked;
		char what[64];

		if ((rc = read_at(k, KTX2_HEADER + KTX2_LEVEL * l, b, sizeof(b))) < 0)
			return rc;
		off = rd64(k, b);
		len = rd64(k, b + 8);
		unpacked = rd64(k, b + 16);
		if (k->scheme == 0 ? len != raw : unpacked != raw) {
			rf__format(k->err, k->errlen, "'%s': level %zu holds %llu bytes; six faces "
			           "of %llu %s texels take %llu", k->path, l,
			           (unsigned long long)(k->scheme == 0 ? len : unpacked),
			           (unsigned long long)texels(k, l), k->format_name,
			           (unsigned long long)raw);
			return RF_EFORMAT;
		}
		if (off > UINT64_MAX - len) {
			rf__format(k->err, k->errlen, "'%s': level %zu lies past any file (offset "
			           "%llu, %llu bytes)", k->path, l, (unsigned long long)off,
			           (unsigned long long)len);
			return RF_EFORMAT;
		}
		rf__format(what, sizeof(what), "level %zu", l);
		if (off + len > k->file_size)
			return truncated(k, what, off + len);
		k->offset[l] = off;
		k->length[l] = len;
		k->row_stride[l] = (k->size >> l) * (uint64_t)k->fmt.bytes;
		k->face_stride[l] = k->row_stride[l] * (k->size >> l);
	}
	return 0;
}

/* ---- reflect's keys ----------------------------------------------------- */

static int
reflect_key(const char *key, const char *v, struct rf_chain_info *info, size_t *levels,
            int *ours)
{
	char *end;
	unsigned long n;

	if (!strcmp(key, "reflect:irradianceSH9")) {
		if (rf__scan_floats(v, info->sh9, 27) < 0)
			return RF_EFORMAT;
		info->has_sh9 = 1;
	} else if (!strcmp(key, "reflect:prefilter")) {
		*ours = 1;
		info->prefiltered = !strcmp(v, "ggx");
	} else if (!strcmp(key, "reflect:mapping")) {
		rf_mapping_parse(v, &info->mapping);
	} else if (!strcmp(key, "reflect:steps")) {
		info->steps = strtof(v, NULL);
	} else if (!strcmp(key, "reflect:samples")) {
		info->samples = (unsigned)strtoul(v, NULL, 10);
	} else if (!strcmp(key, "reflect:base")) {
		info->base_copied = strcmp(v, "filtered") != 0;
	} else if (!strcmp(key, "reflect:levels")) {
		n = strtoul(v, &end, 10);
		if (n >= 1 && !*end && n <= *levels)
			*levels = n;
	}
	return 0;
}

/*
 * The key/value pairs: reflect's own say how the chain was made.  Other
 * keys are skipped, and so is data that does not parse (the pixels do
 * not depend on it) or is too large to be reflect's.
 */
static int
read_keys(struct ktx *k, struct rf_chain_info *info, int *ours)
{
	struct rf_chain_info got = *info;
	unsigned char *kv;
	size_t at = 0, levels = k->levels;
	int rc, mine = 0;

	if (k->kv_length == 0 || k->kv_length > KTX_KV_MAX || k->kv_offset > k->file_size ||
	    k->kv_length > k->file_size - k->kv_offset)
		return 0;
	if (!(kv = malloc((size_t)k->kv_length)))
		return RF_ENOMEM;
	if ((rc = read_at(k, k->kv_offset, kv, (size_t)k->kv_length)) < 0) {
		free(kv);
		return rc;
	}
	/* The last pair's padding may be missing: at can pass the end. */
	while (at <= k->kv_length && k->kv_length - at >= 4) {
		uint32_t n = rd32(k, kv + at);
		const char *key = (const char *)kv + at + 4, *nul;
		char value[512];
		size_t vlen;

		if (n > k->kv_length - at - 4 || !(nul = memchr(key, 0, n)))
			break;
		vlen = n - (size_t)(nul + 1 - key);
		if (!strncmp(key, "reflect:", 8) && vlen < sizeof(value)) {
			memcpy(value, nul + 1, vlen);
			value[vlen] = 0;
			if (reflect_key(key, value, &got, &levels, &mine) < 0) {
				rf__format(k->err, k->errlen, "'%s': key %s needs 27 finite float "
				           "numbers", k->path, key);
				free(kv);
				return RF_EFORMAT;
			}
		}
		at += 4 + (((size_t)n + 3) & ~(size_t)3);
	}
	free(kv);
	if (mine) {
		*info = got;
		k->levels = levels;
		*ours = 1;
	}
	return 0;
}

/* ---- texels ------------------------------------------------------------- */

static void
swap_units(unsigned char *p, size_t n, unsigned unit)
{
	size_t i;
	unsigned j;

	for (i = 0; i + unit <= n; i += unit)
		for (j = 0; j < unit / 2; j++) {
			unsigned char t = p[i + j];

			p[i + j] = p[i + unit - 1 - j];
			p[i + unit - 1 - j] = t;
		}
}

/* One level's six faces from memory (an inflated level) or the file. */
static int
read_level(struct ktx *k, size_t l, const unsigned char *mem, unsigned char *row,
           rf_cubemap *c, struct rf__nonfinite *nf)
{
	size_t n = k->size >> l, j;
	int f, rc;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++) {
			uint64_t at = (uint64_t)f * k->face_stride[l] + j * k->row_stride[l];
			const unsigned char *p = row;

			if (mem)
				p = mem + at;
			else if ((rc = read_at(k, k->offset[l] + at, row,
			                       (size_t)k->row_stride[l])) < 0)
				return rc;
			else if (k->swap && k->unit > 1)
				swap_units(row, n * k->fmt.bytes, k->unit);
			rf__texel_store_gl_row(c, l, f, j, p, &k->fmt, nf);
		}
	return 0;
}

#ifdef HAVE_ZSTD
/* A Zstandard level inflated into exactly the bytes its faces take; a
 * frame that claims more, or data that could not be any frame of that
 * size, is refused before the buffer for it is made. */
static int
inflate_level(struct ktx *k, size_t l, unsigned char **out)
{
	size_t raw = (size_t)(6 * k->face_stride[l]), len = (size_t)k->length[l], got;
	unsigned char *src, *dst;
	unsigned long long claim;
	int rc;

	*out = NULL;
	if (len > ZSTD_compressBound(raw)) {
		rf__format(k->err, k->errlen, "'%s': level %zu: %zu bytes of Zstandard data for "
		           "%zu bytes of texels", k->path, l, len, raw);
		return RF_EFORMAT;
	}
	if (!(src = malloc(len ? len : 1)))
		return RF_ENOMEM;
	if ((rc = read_at(k, k->offset[l], src, len)) < 0) {
		free(src);
		return rc;
	}
	claim = ZSTD_getFrameContentSize(src, len);
	if (claim != ZSTD_CONTENTSIZE_UNKNOWN && claim != (unsigned long long)raw) {
		rf__format(k->err, k->errlen, "'%s': level %zu: a Zstandard frame of %s, not the "
		           "%zu bytes of its texels", k->path, l,
		           claim == ZSTD_CONTENTSIZE_ERROR ? "no valid header" : "another size",
		           raw);
		free(src);
		return RF_EFORMAT;
	}
	if (!(dst = malloc(raw))) {
		free(src);
		return RF_ENOMEM;
	}
	got = ZSTD_decompress(dst, raw, src, len);
	free(src);
	if (ZSTD_isError(got) || got != raw) {
		rf__format(k->err, k->errlen, "'%s': level %zu: bad Zstandard data (%s)", k->path,
		           l, ZSTD_isError(got) ? ZSTD_getErrorName(got) : "too short");
		free(dst);
		return RF_EFORMAT;
	}
	*out = dst;
	return 0;
}
#endif

static int
read_levels(struct ktx *k, rf_cubemap *c, struct rf__nonfinite *nf)
{
	unsigned char *row = malloc((size_t)k->row_stride[0]), *mem = NULL;
	size_t l;
	int rc = 0;

	if (!row)
		return RF_ENOMEM;
	for (l = 0; l < k->levels && rc == 0; l++) {
#ifdef HAVE_ZSTD
		if (k->scheme == 2 && (rc = inflate_level(k, l, &mem)) < 0)
			break;
#endif
		rc = read_level(k, l, mem, row, c, nf);
		free(mem);
		mem = NULL;
	}
	free(row);
	if (rc < 0)
		return rc;
	for (l = 0; l < k->levels; l++)
		rf_cubemap_seal_level(c, l);
	return 0;
}

int
rf_chain_read_ktx(rf_cubemap **cp, struct rf_chain_info *info, int *is_reflect,
                  size_t *nonfinite, const char *path, char *err, size_t errlen)
{
	struct rf__nonfinite nf = { 0 };
	int rc = rf__chain_read_ktx(cp, info, is_reflect, &nf, path, err, errlen);

	if (nonfinite)
		*nonfinite = nf.count;
	return rc;
}

int
rf__chain_read_ktx(rf_cubemap **cp, struct rf_chain_info *info, int *is_reflect,
                   struct rf__nonfinite *nf, const char *path, char *err, size_t errlen)
{
	unsigned char h[KTX2_HEADER];
	struct ktx k;
	char msg[256];
	off_t file_size;
	size_t got;
	int rc, ours = 0;

	*cp = NULL;
	if (is_reflect)
		*is_reflect = 0;
	memset(info, 0, sizeof(*info));
	info->mapping = RF_MAPPING_DEFAULT;
	info->base_copied = 1;
	memset(&k, 0, sizeof(k));
	k.path = path;
	k.err = err;
	k.errlen = errlen;
	if ((rc = rf__regular_file(path, err, errlen)) < 0)
		return rc;
	if (!(k.fp = fopen(path, "rb"))) {
		rf__format(err, errlen, "cannot open '%s': %s", path, strerror(errno));
		return RF_EIO;
	}
	if (fseeko(k.fp, 0, SEEK_END) != 0 || (file_size = ftello(k.fp)) < 0 ||
	    fseeko(k.fp, 0, SEEK_SET) != 0) {
		rf__format(err, errlen, "cannot read '%s': %s", path, strerror(errno));
		fclose(k.fp);
		return RF_EIO;
	}
	k.file_size = (uint64_t)file_size;
	got = fread(h, 1, sizeof(h), k.fp);
	if (got >= 12 && !memcmp(h, ktx1_id, 12)) {
		k.version = 1;
		rc = parse_ktx1(&k, h, got);
	} else if (got >= 12 && !memcmp(h, ktx2_id, 12)) {
		k.version = 2;
		rc = parse_ktx2(&k, h, got);
	} else {
		rf__format(err, errlen, "'%s': not a KTX file (no KTX 11 or KTX 20 identifier)",
		           path);
		rc = RF_EFORMAT;
	}
	info->prefiltered = 1;
	info->mapping = RF_MAPPING_UNITY;
	if (rc == 0)
		rc = read_keys(&k, info, &ours);
	if (rc == 0 && (rc = rf_cubemap_check_size(k.size, k.levels, msg, sizeof(msg))) < 0) {
		rf__format(err, errlen, "'%s': %s", path, msg);
	} else if (rc == 0 && (rc = rf_cubemap_create(cp, k.size, k.levels)) < 0) {
		rf__format(err, errlen, "'%s': %s", path, rf_strerror(rc));
	} else if (rc == 0 && (rc = read_levels(&k, *cp, nf)) < 0) {
		if (rc == RF_ENOMEM)
			rf__format(err, errlen, "'%s': %s", path, rf_strerror(rc));
		rf_cubemap_destroy(*cp);
		*cp = NULL;
	} else if (rc == RF_ENOMEM) {
		rf__format(err, errlen, "'%s': %s", path, rf_strerror(rc));
	}
	fclose(k.fp);
	if (rc < 0) {
		memset(info, 0, sizeof(*info));
		info->mapping = RF_MAPPING_DEFAULT;
		info->base_copied = 1;
		return rc;
	}
	if (!ours) {
		/* as a DDS: without mips, an environment */
		info->prefiltered = k.levels > 1;
		info->steps = (float)(k.levels - 1);
	}
	if (is_reflect)
		*is_reflect = ours;
	return 0;
}
