/*
 * Pre-convolved cube chains stored as DDS files.
 *
 * Our own reader: the OpenImageIO this project builds against refuses
 * float DDS ("Unsupported compression type"), and the chains other tools
 * bake are mostly float or shared-exponent cubes.  Only uncompressed
 * formats are read; block-compressed ones are refused by name.
 *
 * Orientation.  A DDS cube's faces are addressed with Direct3D's cube
 * texture coordinates, which are OpenGL's face selection table with the
 * first row of the image at v = 0 (sc, tc over |ma|, each mapped to
 * [0, 1]):
 *
 *	face   D3D: u grows toward   v grows toward   reflect (OpenEXR): u   v
 *	+X          -z                 -y                                 +z  -y
 *	-X          +z                 -y                                 -z  -y
 *	+Y          +x                 +z                                 +x  -z
 *	-Y          +x                 -z                                 +x  +z
 *	+Z          +x                 -y                                 -x  -y
 *	-Z          -x                 -y                                 +x  -y
 *
 * (reflect's column is rf_cube_direction.)  The face a direction selects
 * is the same in both; within it, the X and Z faces are mirrored left to
 * right and the Y faces top to bottom.  Each face is flipped on reading
 * so that a direction d reads in reflect the texel Direct3D reads for d,
 * world axes taken as they are: no handedness change is made.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>

#include "envmap/envmap-internal.h"
#include "envmap/texel.h"
#include "reflect/envmap.h"

#define DDS_MAGIC 0x20534444u /* "DDS " */
#define DDS_HEADER_SIZE 124u
#define DDS_PIXELFORMAT_SIZE 32u
#define DDS_DX10_SIZE 20u

#define DDSD_DEPTH 0x800000u
#define DDPF_FOURCC 0x4u
#define DDPF_RGB 0x40u
#define DDSCAPS2_CUBEMAP 0x200u
#define DDSCAPS2_VOLUME 0x200000u
#define DDSCAPS2_FACE(f) (0x400u << (f)) /* +X -X +Y -Y +Z -Z */
#define DDSCAPS2_ALLFACES 0xfc00u
#define DDS_DIM_TEXTURE2D 3u
#define DDS_MISC_TEXTURECUBE 0x4u

/* Faces larger than this are refused before anything is allocated. */
#define DDS_MAX_SIZE 16384u

#define FOURCC(a, b, c, d)                                                   \
	((uint32_t)(a) | (uint32_t)(b) << 8 | (uint32_t)(c) << 16 | (uint32_t)(d) << 24)

static const char *const face_names[6] = { "+X", "-X", "+Y", "-Y", "+Z", "-Z" };

static uint32_t
le32(const unsigned char *p)
{
	return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
	       (uint32_t)p[3] << 24;
}

/* Short names for the refusal message: the block-compressed families by
 * family, the rest by their DXGI name. */
static const char *
dxgi_name(uint32_t f)
{
	static const struct { uint32_t lo, hi; const char *name; } names[] = {
		{ 1, 1, "R32G32B32A32_TYPELESS" }, { 3, 4, "R32G32B32A32_UINT/SINT" },
		{ 5, 5, "R32G32B32_TYPELESS" }, { 7, 8, "R32G32B32_UINT/SINT" },
		{ 9, 9, "R16G16B16A16_TYPELESS" }, { 11, 11, "R16G16B16A16_UNORM" },
		{ 12, 14, "R16G16B16A16_UINT/SNORM/SINT" }, { 15, 22, "two-channel 32-bit" },
		{ 23, 25, "R10G10B10A2" }, { 27, 27, "R8G8B8A8_TYPELESS" },
		{ 30, 32, "R8G8B8A8_UINT/SNORM/SINT" }, { 33, 38, "two-channel 16-bit" },
		{ 39, 47, "one-channel 32-bit" }, { 48, 53, "two-channel 8-bit" },
		{ 54, 54, "R16_FLOAT" }, { 55, 60, "one-channel 16-bit" },
		{ 61, 65, "one-channel 8-bit" }, { 66, 66, "R1_UNORM" },
		{ 68, 69, "packed 4:2:2" }, { 70, 72, "BC1" }, { 73, 75, "BC2" },
		{ 76, 78, "BC3" }, { 79, 81, "BC4" }, { 82, 84, "BC5" },
		{ 85, 85, "B5G6R5_UNORM" }, { 86, 86, "B5G5R5A1_UNORM" },
		{ 89, 89, "R10G10B10_XR_BIAS_A2_UNORM" }, { 90, 90, "B8G8R8A8_TYPELESS" },
		{ 92, 92, "B8G8R8X8_TYPELESS" }, { 94, 96, "BC6H" }, { 97, 99, "BC7" },
	};
	size_t i;

	for (i = 0; i < sizeof(names) / sizeof(names[0]); i++)
		if (f >= names[i].lo && f <= names[i].hi)
			return names[i].name;
	return NULL;
}

static int
dxgi_format(uint32_t f, struct rf__texel_format *fmt)
{
	switch (f) {
	case 2: *fmt = (struct rf__texel_format){ RF__TEXEL_F32, 4, 16, 0 }; return 0;
	case 6: *fmt = (struct rf__texel_format){ RF__TEXEL_F32, 3, 12, 0 }; return 0;
	case 10: *fmt = (struct rf__texel_format){ RF__TEXEL_F16, 4, 8, 0 }; return 0;
	case 26: *fmt = (struct rf__texel_format){ RF__TEXEL_R11G11B10, 3, 4, 0 }; return 0;
	case 67: *fmt = (struct rf__texel_format){ RF__TEXEL_RGB9E5, 3, 4, 0 }; return 0;
	case 28: *fmt = (struct rf__texel_format){ RF__TEXEL_RGBA8, 4, 4, 0 }; return 0;
	case 29: *fmt = (struct rf__texel_format){ RF__TEXEL_RGBA8, 4, 4, 1 }; return 0;
	/* B8G8R8X8 is B8G8R8A8 once alpha is ignored. */
	case 87: case 88: *fmt = (struct rf__texel_format){ RF__TEXEL_BGRA8, 4, 4, 0 }; return 0;
	case 91: case 93: *fmt = (struct rf__texel_format){ RF__TEXEL_BGRA8, 4, 4, 1 }; return 0;
	}
	return RF_EFORMAT;
}

static const char *
fourcc_name(uint32_t cc)
{
	static const struct { uint32_t cc; const char *name; } names[] = {
		{ FOURCC('D', 'X', 'T', '1'), "BC1" }, { FOURCC('D', 'X', 'T', '2'), "BC2" },
		{ FOURCC('D', 'X', 'T', '3'), "BC2" }, { FOURCC('D', 'X', 'T', '4'), "BC3" },
		{ FOURCC('D', 'X', 'T', '5'), "BC3" }, { FOURCC('A', 'T', 'I', '1'), "BC4" },
		{ FOURCC('B', 'C', '4', 'U'), "BC4" }, { FOURCC('B', 'C', '4', 'S'), "BC4" },
		{ FOURCC('A', 'T', 'I', '2'), "BC5" }, { FOURCC('B', 'C', '5', 'U'), "BC5" },
		{ FOURCC('B', 'C', '5', 'S'), "BC5" }, { 36, "A16B16G16R16" },
		{ 110, "Q16W16V16U16" }, { 111, "R16F" }, { 112, "G16R16F" },
		{ 115, "G32R32F" },
	};
	size_t i;

	for (i = 0; i < sizeof(names) / sizeof(names[0]); i++)
		if (names[i].cc == cc)
			return names[i].name;
	return NULL;
}

#define UNSUPPORTED_HINT "is not supported; convert the cube to float RGBA"

/* The texel format of the legacy pixel format (no DX10 header). */
static int
legacy_format(const char *path, const unsigned char *pf, struct rf__texel_format *fmt,
              char *err, size_t errlen)
{
	uint32_t flags = le32(pf + 4), cc = le32(pf + 8), bits = le32(pf + 12);
	uint32_t r = le32(pf + 16), g = le32(pf + 20), b = le32(pf + 24);
	const char *name;

	if (flags & DDPF_FOURCC) {
		switch (cc) {
		case 113: *fmt = (struct rf__texel_format){ RF__TEXEL_F16, 4, 8, 0 }; return 0;
		case 116: *fmt = (struct rf__texel_format){ RF__TEXEL_F32, 4, 16, 0 }; return 0;
		case 114: *fmt = (struct rf__texel_format){ RF__TEXEL_F32, 1, 4, 0 }; return 0;
		}
		name = fourcc_name(cc);
		if (cc > 0xffffu) { /* four characters, not a D3DFORMAT number */
			char text[5];
			int i;

			for (i = 0; i < 4; i++) {
				int ch = (int)(cc >> (8 * i) & 0xffu);

				text[i] = ch >= ' ' && ch < 127 ? (char)ch : '?';
			}
			text[4] = 0;
			rf__format(err, errlen, "'%s': FourCC '%s'%s%s%s " UNSUPPORTED_HINT, path,
			           text, name ? " (" : "", name ? name : "", name ? ")" : "");
		} else {
			rf__format(err, errlen, "'%s': D3DFMT %u%s%s%s " UNSUPPORTED_HINT, path,
			           (unsigned)cc, name ? " (" : "", name ? name : "",
			           name ? ")" : "");
		}
		return RF_EFORMAT;
	}
	if ((flags & DDPF_RGB) && bits == 32) {
		if (r == 0xffu && g == 0xff00u && b == 0xff0000u) {
			*fmt = (struct rf__texel_format){ RF__TEXEL_RGBA8, 4, 4, 0 };
			return 0;
		}
		if (r == 0xff0000u && g == 0xff00u && b == 0xffu) {
			*fmt = (struct rf__texel_format){ RF__TEXEL_BGRA8, 4, 4, 0 };
			return 0;
		}
	}
	if (flags & DDPF_RGB)
		rf__format(err, errlen, "'%s': %u-bit RGB with masks R %08x G %08x B %08x "
		           UNSUPPORTED_HINT, path, (unsigned)bits, (unsigned)r, (unsigned)g,
		           (unsigned)b);
	else
		rf__format(err, errlen, "'%s': pixel format flags 0x%x (not RGB) "
		           UNSUPPORTED_HINT, path, (unsigned)flags);
	return RF_EFORMAT;
}

/* Everything the header says, checked. */
struct dds_layout {
	struct rf__texel_format fmt;
	uint32_t size;        /* face width = height */
	uint32_t file_levels; /* mip levels stored per face */
	size_t levels;        /* those reflect keeps */
	uint64_t data;        /* offset of the first texel */
	uint64_t face_bytes;  /* one face with all its stored levels */
};

static uint64_t
level_bytes(const struct dds_layout *l, uint32_t k)
{
	uint64_t s = l->size >> k ? l->size >> k : 1;

	return s * s * l->fmt.bytes;
}

static int
parse_header(const char *path, const unsigned char *h, size_t got,
             struct dds_layout *l, char *err, size_t errlen)
{
	uint32_t flags, height, width, depth, mips, caps2, maxmips, k, dim;
	const unsigned char *pf = h + 4 + 72, *x = NULL;
	int is_cube, f, rc;

	if (got < 4 || le32(h) != DDS_MAGIC) {
		rf__format(err, errlen, "'%s': not a DDS file (no 'DDS ' magic)", path);
		return RF_EFORMAT;
	}
	if (got < 4 + DDS_HEADER_SIZE) {
		rf__format(err, errlen, "'%s': truncated: the DDS header needs %zu more bytes",
		           path, (size_t)(4 + DDS_HEADER_SIZE - got));
		return RF_ETRUNCATED;
	}
	if (le32(h + 4) != DDS_HEADER_SIZE || le32(pf) != DDS_PIXELFORMAT_SIZE) {
		rf__format(err, errlen, "'%s': DDS header of %u bytes with a pixel format of "
		           "%u, not %u and %u", path, (unsigned)le32(h + 4), (unsigned)le32(pf),
		           DDS_HEADER_SIZE, DDS_PIXELFORMAT_SIZE);
		return RF_EFORMAT;
	}
	flags = le32(h + 8);
	height = le32(h + 12);
	width = le32(h + 16);
	depth = le32(h + 24);
	mips = le32(h + 28);
	caps2 = le32(h + 4 + 108);
	is_cube = (caps2 & DDSCAPS2_CUBEMAP) != 0;
	l->data = 4 + DDS_HEADER_SIZE;
	if (le32(pf + 4) & DDPF_FOURCC && le32(pf + 8) == FOURCC('D', 'X', '1', '0')) {
		x = h + 4 + DDS_HEADER_SIZE;
		if (got < 4 + DDS_HEADER_SIZE + DDS_DX10_SIZE) {
			rf__format(err, errlen, "'%s': truncated: the DX10 header needs %zu "
			           "more bytes", path,
			           (size_t)(4 + DDS_HEADER_SIZE + DDS_DX10_SIZE - got));
			return RF_ETRUNCATED;
		}
		l->data += DDS_DX10_SIZE;
		dim = le32(x + 4);
		if (dim != DDS_DIM_TEXTURE2D) {
			rf__format(err, errlen, "'%s': not a cube map (a %s texture)", path,
			           dim == 4 ? "volume" : dim == 2 ? "1D" : "non-2D");
			return RF_EFORMAT;
		}
		/* DirectXTex relies on the misc flag alone, older writers on
		 * caps2 alone: either makes a cube, and a DX10 cube has all six
		 * faces. */
		if (le32(x + 8) & DDS_MISC_TEXTURECUBE) {
			if (!is_cube)
				caps2 |= DDSCAPS2_ALLFACES;
			is_cube = 1;
		}
	}
	if (!is_cube) {
		rf__format(err, errlen, "'%s': not a cube map (a %s texture)", path,
		           (caps2 & DDSCAPS2_VOLUME) || ((flags & DDSD_DEPTH) && depth > 1)
		           ? "volume" : "2D");
		return RF_EFORMAT;
	}
	if ((caps2 & DDSCAPS2_ALLFACES) != DDSCAPS2_ALLFACES) {
		char missing[32] = "";

		for (f = 0; f < 6; f++)
			if (!(caps2 & DDSCAPS2_FACE(f))) {
				strcat(missing, " ");
				strcat(missing, face_names[f]);
			}
		rf__format(err, errlen, "'%s': a cube map without faces%s; reflect needs "
		           "all six", path, missing);
		return RF_EFORMAT;
	}
	if (x) {
		uint32_t dxgi = le32(x), array = le32(x + 12);
		const char *name;

		if (array != 1) {
			rf__format(err, errlen, "'%s': an array of %u cubes; reflect reads one "
			           "cube", path, (unsigned)array);
			return RF_EFORMAT;
		}
		if (dxgi_format(dxgi, &l->fmt) < 0) {
			name = dxgi_name(dxgi);
			rf__format(err, errlen, "'%s': DXGI format %u%s%s%s " UNSUPPORTED_HINT,
			           path, (unsigned)dxgi, name ? " (" : "", name ? name : "",
			           name ? ")" : "");
			return RF_EFORMAT;
		}
	} else if ((rc = legacy_format(path, pf, &l->fmt, err, errlen)) < 0) {
		return rc;
	}
	if (width != height) {
		rf__format(err, errlen, "'%s': cube faces of %ux%u are not square", path,
		           (unsigned)width, (unsigned)height);
		return RF_EFORMAT;
	}
	if (width == 0 || width > DDS_MAX_SIZE) {
		rf__format(err, errlen, "'%s': cube faces of %u texels (1 to %u are read)",
		           path, (unsigned)width, DDS_MAX_SIZE);
		return RF_ETOOBIG;
	}
	for (maxmips = 1; width >> maxmips; maxmips++)
		;
	if (mips == 0)
		mips = 1; /* the count is optional; DirectXTex reads 0 as 1 too */
	if (mips > maxmips) {
		rf__format(err, errlen, "'%s': %u mip levels claimed; faces of %u have at "
		           "most %u", path, (unsigned)mips, (unsigned)width, (unsigned)maxmips);
		return RF_EFORMAT;
	}
	l->size = width;
	l->file_levels = mips;
	/* rf_cubemap_create's rule: halve while even.  The first odd level is
	 * the last one kept; the file's smaller levels are skipped (they
	 * still count in each face's stride). */
	for (l->levels = 1; l->levels < mips && !((width >> (l->levels - 1)) & 1); l->levels++)
		;
	l->face_bytes = 0;
	for (k = 0; k < mips; k++)
		l->face_bytes += level_bytes(l, k);
	return 0;
}

/* The first face level the file does not hold in full. */
static int
check_length(const char *path, const struct dds_layout *l, uint64_t file_size,
             char *err, size_t errlen)
{
	uint64_t end = l->data;
	uint32_t k;
	int f;

	for (f = 0; f < 6; f++)
		for (k = 0; k < l->file_levels; k++) {
			end += level_bytes(l, k);
			if (end > file_size) {
				rf__format(err, errlen, "'%s': truncated: level %u of face %s needs "
				           "%llu more bytes", path, (unsigned)k, face_names[f],
				           (unsigned long long)(end - file_size));
				return RF_ETRUNCATED;
			}
		}
	return 0;
}

static int
read_levels(FILE *fp, const char *path, const struct dds_layout *l, rf_cubemap *c,
            struct rf__nonfinite *nf, char *err, size_t errlen)
{
	size_t row_bytes = (size_t)l->size * l->fmt.bytes, k, j;
	unsigned char *row = malloc(row_bytes);
	uint64_t off;
	int f;

	if (!row)
		return RF_ENOMEM;
	for (f = 0; f < 6; f++) {
		off = l->data + (uint64_t)f * l->face_bytes;
		for (k = 0; k < l->levels; k++) {
			size_t n = l->size >> k;

			/* X and Z faces are mirrored left to right, Y faces top
			 * to bottom (see the top of this file). */
			if (fseeko(fp, (off_t)off, SEEK_SET) != 0)
				goto io;
			for (j = 0; j < n; j++) {
				if (fread(row, l->fmt.bytes, n, fp) != n)
					goto io;
				rf__texel_store_gl_row(c, k, f, j, row, &l->fmt, nf);
			}
			off += level_bytes(l, (uint32_t)k);
		}
	}
	free(row);
	for (k = 0; k < l->levels; k++)
		rf_cubemap_seal_level(c, k);
	return 0;
io:
	rf__format(err, errlen, "cannot read '%s': %s", path,
	           ferror(fp) ? strerror(errno ? errno : EIO) : "unexpected end of file");
	free(row);
	return RF_EIO;
}

int
rf_chain_read_dds(rf_cubemap **cp, struct rf_chain_info *info, size_t *nonfinite,
                  const char *path, char *err, size_t errlen)
{
	struct rf__nonfinite nf = { 0 };
	int rc = rf__chain_read_dds(cp, info, &nf, path, err, errlen);

	if (nonfinite)
		*nonfinite = nf.count;
	return rc;
}

int
rf__chain_read_dds(rf_cubemap **cp, struct rf_chain_info *info, struct rf__nonfinite *nf,
                   const char *path, char *err, size_t errlen)
{
	unsigned char h[4 + DDS_HEADER_SIZE + DDS_DX10_SIZE];
	char msg[256];
	struct dds_layout l;
	off_t file_size;
	size_t got;
	FILE *fp;
	int rc;

	*cp = NULL;
	memset(info, 0, sizeof(*info));
	info->mapping = RF_MAPPING_DEFAULT;
	info->base_copied = 1;
	if ((rc = rf__regular_file(path, err, errlen)) < 0)
		return rc;
	if (!(fp = fopen(path, "rb"))) {
		rf__format(err, errlen, "cannot open '%s': %s", path, strerror(errno));
		return RF_EIO;
	}
	if (fseeko(fp, 0, SEEK_END) != 0 || (file_size = ftello(fp)) < 0 ||
	    fseeko(fp, 0, SEEK_SET) != 0) {
		rf__format(err, errlen, "cannot read '%s': %s", path, strerror(errno));
		fclose(fp);
		return RF_EIO;
	}
	got = fread(h, 1, sizeof(h), fp);
	/* Every size is checked against the file before the cube is
	 * allocated: a forged header cannot ask for more memory than the
	 * file's own size implies. */
	if ((rc = parse_header(path, h, got, &l, err, errlen)) < 0 ||
	    (rc = check_length(path, &l, (uint64_t)file_size, err, errlen)) < 0) {
		fclose(fp);
		return rc;
	}
	if ((rc = rf_cubemap_check_size(l.size, l.levels, msg, sizeof(msg))) < 0 ||
	    (rc = rf_cubemap_create(cp, l.size, l.levels)) < 0) {
		rf__format(err, errlen, "'%s': %s", path, rc == RF_ETOOBIG ? msg : rf_strerror(rc));
		fclose(fp);
		return rc;
	}
	if ((rc = read_levels(fp, path, &l, *cp, nf, err, errlen)) < 0) {
		rf_cubemap_destroy(*cp);
		*cp = NULL;
		fclose(fp);
		return rc;
	}
	fclose(fp);
	/* a cube without mips is an environment, not a chain of one level */
	info->prefiltered = l.levels > 1;
	info->mapping = RF_MAPPING_UNITY;
	info->steps = (float)(l.levels - 1);
	return 0;
}
