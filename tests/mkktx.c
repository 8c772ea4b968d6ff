/*
 * mkktx FILE KIND N LEVELS: a hand-made KTX 1 or KTX 2 cube, for the
 * shell tests, whose face f at level k holds (f + 10 k, 1, 2) everywhere
 * (alpha 1).  KIND is VERSION-FORMAT:
 *
 *   ktx1-rgba32f ktx1-rgba16f ktx1-rgb9e5
 *   ktx1-r11g11b10    as filament's cmgen writes it: glType and glFormat
 *                     R11F_G11F_B10F too
 *   ktx2-rgba32f ktx2-rgba16f ktx2-rgb9e5 ktx2-b10g11r11
 *   ktx2-zstd         RGBA16F, each level Zstandard-compressed (needs
 *                     libzstd; exit 3 without it)
 *
 * or a kind reflect refuses, written with the same texels:
 *
 *   ktx1-bc6h ktx1-etc1 ktx2-bc6h ktx2-bc7 ktx2-astc ktx2-etc2
 *   ktx2-basislz ktx2-uastc ktx2-zlib ktx2-array ktx2-3d ktx2-2d
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef HAVE_ZSTD
#include <zstd.h>
#endif

struct kind {
	const char *name;
	int version;
	uint32_t format, gl_type, gl_format; /* vkFormat, or glInternalFormat */
	unsigned bytes;
	int texel;                           /* 0 f32, 1 f16, 2 rgb9e5, 3 r11g11b10 */
	uint32_t scheme, layers, depth, faces, model;
};

static const struct kind kinds[] = {
	{ "ktx1-rgba32f", 1, 0x8814, 0x1406, 0x1908, 16, 0, 0, 0, 0, 6, 1 },
	{ "ktx1-rgba16f", 1, 0x881a, 0x140b, 0x1908, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx1-rgb9e5", 1, 0x8c3d, 0x8c3e, 0x1907, 4, 2, 0, 0, 0, 6, 1 },
	{ "ktx1-r11g11b10", 1, 0x8c3a, 0x8c3a, 0x8c3a, 4, 3, 0, 0, 0, 6, 1 },
	{ "ktx2-rgba32f", 2, 109, 0, 0, 16, 0, 0, 0, 0, 6, 1 },
	{ "ktx2-rgba16f", 2, 97, 0, 0, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx2-rgb9e5", 2, 123, 0, 0, 4, 2, 0, 0, 0, 6, 1 },
	{ "ktx2-b10g11r11", 2, 122, 0, 0, 4, 3, 0, 0, 0, 6, 1 },
	{ "ktx2-zstd", 2, 97, 0, 0, 8, 1, 2, 0, 0, 6, 1 },
	{ "ktx1-bc6h", 1, 0x8e8f, 0, 0, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx1-etc1", 1, 0x8d64, 0, 0, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx2-bc6h", 2, 143, 0, 0, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx2-bc7", 2, 145, 0, 0, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx2-astc", 2, 157, 0, 0, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx2-etc2", 2, 147, 0, 0, 8, 1, 0, 0, 0, 6, 1 },
	{ "ktx2-basislz", 2, 0, 0, 0, 8, 1, 1, 0, 0, 6, 163 },
	{ "ktx2-uastc", 2, 0, 0, 0, 8, 1, 0, 0, 0, 6, 166 },
	{ "ktx2-zlib", 2, 97, 0, 0, 8, 1, 3, 0, 0, 6, 1 },
	{ "ktx2-array", 2, 97, 0, 0, 8, 1, 0, 2, 0, 6, 1 },
	{ "ktx2-3d", 2, 97, 0, 0, 8, 1, 0, 0, 4, 1, 1 },
	{ "ktx2-2d", 2, 97, 0, 0, 8, 1, 0, 0, 0, 1, 1 },
};

static void
put32(FILE *f, uint32_t v)
{
	unsigned char b[4] = { v & 255, (v >> 8) & 255, (v >> 16) & 255, v >> 24 };

	fwrite(b, 1, 4, f);
}

static void
put64(FILE *f, uint64_t v)
{
	put32(f, (uint32_t)v);
	put32(f, (uint32_t)(v >> 32));
}

/* The integer n (below 64) as a float of 5 exponent bits and mbits of
 * mantissa: half floats, and the 11- and 10-bit floats. */
static uint32_t
small(unsigned n, unsigned mbits)
{
	unsigned e = 0;

	if (!n)
		return 0;
	while (n >> (e + 1))
		e++;
	return (e + 15) << mbits | (((n << mbits) >> e) & ((1u << mbits) - 1));
}

static void
texel(const struct kind *k, unsigned v, unsigned char *o)
{
	const float f[4] = { (float)v, 1.0f, 2.0f, 1.0f };
	uint32_t u;
	int c;

	switch (k->texel) {
	case 0:
		memcpy(o, f, 16); /* the tests run little-endian */
		break;
	case 1:
		for (c = 0; c < 4; c++) {
			u = c == 3 ? 0x3c00u : small((unsigned)f[c], 10);
			o[2 * c] = u & 255;
			o[2 * c + 1] = u >> 8;
		}
		break;
	case 2: /* shared exponent 24: the mantissas are the integers */
		u = v | 1u << 9 | 2u << 18 | 24u << 27;
		memcpy(o, &u, 4);
		break;
	default:
		u = small(v, 6) | small(1, 6) << 11 | small(2, 5) << 22;
		memcpy(o, &u, 4);
		break;
	}
}

/* All six faces of level l, rows tight (they are, at 4 bytes and up). */
static unsigned char *
level(const struct kind *k, unsigned n, unsigned l, size_t *len)
{
	size_t s = n >> l, face, i;
	unsigned char *p;
	int f;

	face = s * s * k->bytes;
	*len = 6 * face;
	if (!(p = malloc(*len)))
		exit(2);
	for (f = 0; f < 6; f++)
		for (i = 0; i < s * s; i++)
			texel(k, (unsigned)f + 10 * l, p + f * face + i * k->bytes);
	return p;
}

int
main(int argc, char **argv)
{
	const struct kind *k = NULL;
	unsigned n, levels, l;
	size_t i, len;
	FILE *f;

	if (argc != 5)
		return 1;
	for (i = 0; i < sizeof(kinds) / sizeof(kinds[0]); i++)
		if (!strcmp(kinds[i].name, argv[2]))
			k = &kinds[i];
	n = (unsigned)atoi(argv[3]);
	levels = (unsigned)atoi(argv[4]);
	if (!k || !n || !levels || levels > 16)
		return 1;
#ifndef HAVE_ZSTD
	if (k->scheme == 2)
		return 3;
#endif
	if (!(f = fopen(argv[1], "wb")))
		return 2;
	if (k->version == 1) {
		fwrite("\xabKTX 11\xbb\r\n\x1a\n", 1, 12, f);
		put32(f, 0x04030201u);
		put32(f, k->gl_type);
		put32(f, k->texel == 1 ? 2 : 4);
		put32(f, k->gl_format);
		put32(f, k->format);
		put32(f, k->gl_format);
		put32(f, n);
		put32(f, n);
		put32(f, k->depth);
		put32(f, k->layers);
		put32(f, k->faces);
		put32(f, levels);
		put32(f, 0); /* no key/value data */
		for (l = 0; l < levels; l++) {
			unsigned char *p = level(k, n, l, &len);

			put32(f, (uint32_t)(len / 6)); /* a cube's imageSize: one face */
			fwrite(p, 1, len, f);
			free(p);
		}
		return fclose(f) != 0;
	}
	{
		uint64_t off[16], sizes[16], raw[16], at = 80 + 24 * levels + 28;

		fwrite("\xabKTX 20\xbb\r\n\x1a\n", 1, 12, f);
		put32(f, k->format);
		put32(f, k->texel == 1 ? 2 : 4);
		put32(f, n);
		put32(f, n);
		put32(f, k->depth);
		put32(f, k->layers);
		put32(f, k->faces);
		put32(f, levels);
		put32(f, k->scheme);
		put32(f, 80 + 24 * levels); /* the DFD */
		put32(f, 28);
		put32(f, 0);                /* no key/value data */
		put32(f, 0);
		put64(f, 0);
		put64(f, 0);
		/* the level index, written once the sizes are known */
		for (l = 0; l < levels * 3; l++)
			put64(f, 0);
		/* a basic DFD block without samples: enough for the colour model */
		put32(f, 28);
		put32(f, 0);
		put32(f, 2u | 24u << 16);
		put32(f, k->model | 1u << 8 | 1u << 16);
		put32(f, 0);
		put32(f, k->bytes);
		put32(f, 0);
		for (l = levels; l-- > 0;) {
			unsigned char *p = level(k, n, l, &len), *out = p;

			raw[l] = sizes[l] = len;
#ifdef HAVE_ZSTD
			if (k->scheme == 2) {
				size_t cap = ZSTD_compressBound(len);

				if (!(out = malloc(cap)))
					return 2;
				sizes[l] = ZSTD_compress(out, cap, p, len, 19);
			}
#endif
			if (k->scheme == 0)
				for (; at % k->bytes; at++)
					fputc(0, f);
			off[l] = at;
			fwrite(out, 1, (size_t)sizes[l], f);
			at += sizes[l];
			if (out != p)
				free(out);
			free(p);
		}
		fseek(f, 80, SEEK_SET);
		for (l = 0; l < levels; l++) {
			put64(f, off[l]);
			put64(f, sizes[l]);
			put64(f, k->scheme == 1 ? 0 : raw[l]);
		}
	}
	return fclose(f) != 0;
}
