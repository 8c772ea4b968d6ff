/*
 * Chains written as KTX 1 and KTX 2 cube maps, for engines and the
 * tools that read them (chain_ktx.c reads them back, and says why the
 * faces are in OpenGL's orientation).  RGBA texels, alpha 1, because
 * three-channel half floats are six bytes a texel, which neither Vulkan
 * nor most GPUs sample; every level of the chain and no other, as KTX
 * needs no full pyramid and the chain's mapping counts its levels.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef HAVE_ZSTD
#include <zstd.h>
#endif

#include "envmap/envmap-internal.h"
#include "envmap/texel.h"
#include "reflect/envmap.h"

#define KTX2_HEADER 80u
#define KTX2_LEVEL 24u
#define DFD_BYTES 92u /* dfdTotalSize, a basic block of 24 bytes, 4 samples of 16 */

struct out {
	FILE *fp;
	const char *path;
	int failed;
};

static void
put(struct out *o, const void *p, size_t n)
{
	if (!o->failed && n && fwrite(p, 1, n, o->fp) != n)
		o->failed = 1;
}

static void
put32(struct out *o, uint32_t v)
{
	unsigned char b[4] = { (unsigned char)v, (unsigned char)(v >> 8),
	                       (unsigned char)(v >> 16), (unsigned char)(v >> 24) };

	put(o, b, 4);
}

static void
put64(struct out *o, uint64_t v)
{
	put32(o, (uint32_t)v);
	put32(o, (uint32_t)(v >> 32));
}

static void
pad(struct out *o, uint64_t at, unsigned align)
{
	static const unsigned char zeros[16];

	if (align > 1 && at % align)
		put(o, zeros, align - at % align);
}

/* ---- key/value data ----------------------------------------------------- */

struct kv {
	unsigned char buf[1024];
	size_t len;
};

/* One pair, its value a NUL-terminated string, padded to 4 bytes.  The
 * caller adds them sorted by key, as KTX 2 requires. */
static void
kv_add(struct kv *kv, const char *key, const char *value)
{
	size_t k = strlen(key) + 1, v = strlen(value) + 1, n = k + v;
	unsigned char *p = kv->buf + kv->len;

	if (kv->len + 4 + n + 3 > sizeof(kv->buf))
		return; /* never: the keys are ours and short */
	p[0] = (unsigned char)n;
	p[1] = (unsigned char)(n >> 8);
	p[2] = p[3] = 0;
	memcpy(p + 4, key, k);
	memcpy(p + 4 + k, value, v);
	kv->len += 4 + n;
	while (kv->len % 4)
		kv->buf[kv->len++] = 0;
}

static void
kv_fill(struct kv *kv, const rf_cubemap *c, const struct rf_chain_info *info, int version)
{
	char levels[32], steps[32], samples[32], writer[64], sh9[27 * 18];
	size_t used = 0, k;
	float sh[27];

	kv->len = 0;
	/* The diffuse light's coefficients from the float level 0, as the
	 * EXR chain keeps them: the file may hold it in half floats. */
	rf_cubemap_sh9(c, 0, sh);
	for (k = 0; k < 27; k++)
		used += (size_t)snprintf(sh9 + used, sizeof(sh9) - used, "%s%.9g", k ? " " : "",
		                         (double)sh[k]);
	rf__format(levels, sizeof(levels), "%zu", rf_cubemap_levels(c));
	rf__format(steps, sizeof(steps), "%.9g", (double)info->steps);
	rf__format(samples, sizeof(samples), "%u", info->samples);
	rf__format(writer, sizeof(writer), "reflect %s", rf_version_string());
	/* KTX 1 spelled the orientation out; KTX 2 made it two letters. */
	kv_add(kv, "KTXorientation", version == 1 ? "S=r,T=d" : "rd");
	if (version == 2)
		kv_add(kv, "KTXwriter", writer);
	kv_add(kv, "reflect:base", info->base_copied ? "copied" : "filtered");
	kv_add(kv, "reflect:irradianceSH9", sh9);
	kv_add(kv, "reflect:levels", levels);
	kv_add(kv, "reflect:mapping", rf_mapping_name(info->mapping));
	kv_add(kv, "reflect:prefilter", info->prefiltered ? "ggx" : "box");
	kv_add(kv, "reflect:samples", samples);
	kv_add(kv, "reflect:steps", steps);
}

/* ---- texels ------------------------------------------------------------- */

static void
enc32(unsigned char *p, uint32_t v)
{
	p[0] = (unsigned char)v;
	p[1] = (unsigned char)(v >> 8);
	p[2] = (unsigned char)(v >> 16);
	p[3] = (unsigned char)(v >> 24);
}

/* Level k's six faces as the file stores them: GL's rows, top first. */
static void
encode_level(const rf_cubemap *c, size_t k, enum rf_ktx_texel texel, unsigned char *out)
{
	size_t n = rf_cubemap_level_size(c, k), i, j, ri, rj;
	unsigned bytes = texel == RF_KTX_RGBA32F ? 16 : 8;
	int f, ch;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++, out += bytes) {
				const float *t;
				float v[4];

				rf__gl_texel(f, n, i, j, &ri, &rj);
				t = rf_cubemap_texel_const(c, k, (enum rf_face)f, ri, rj);
				v[0] = t[0];
				v[1] = t[1];
				v[2] = t[2];
				v[3] = 1.0f;
				for (ch = 0; ch < 4; ch++) {
					if (texel == RF_KTX_RGBA32F) {
						uint32_t u;

						memcpy(&u, &v[ch], 4);
						enc32(out + 4 * ch, u);
					} else {
						unsigned h = rf__float_to_half(v[ch]);

						out[2 * ch] = (unsigned char)h;
						out[2 * ch + 1] = (unsigned char)(h >> 8);
					}
				}
			}
}

/* ---- the two layouts ---------------------------------------------------- */

static int
write_ktx1(struct out *o, const rf_cubemap *c, const struct kv *kv,
           enum rf_ktx_texel texel, unsigned char *buf)
{
	static const unsigned char id[12] = { 0xab, 'K', 'T', 'X', ' ', '1', '1', 0xbb,
		                              '\r', '\n', 0x1a, '\n' };
	int f32 = texel == RF_KTX_RGBA32F;
	unsigned bytes = f32 ? 16 : 8;
	size_t levels = rf_cubemap_levels(c), n = rf_cubemap_size(c), k;

	put(o, id, 12);
	put32(o, 0x04030201u);
	put32(o, f32 ? 0x1406u : 0x140bu); /* GL_FLOAT, GL_HALF_FLOAT */
	put32(o, f32 ? 4 : 2);
	put32(o, 0x1908u);                 /* GL_RGBA */
	put32(o, f32 ? 0x8814u : 0x881au); /* GL_RGBA32F, GL_RGBA16F */
	put32(o, 0x1908u);
	put32(o, (uint32_t)n);
	put32(o, (uint32_t)n);
	put32(o, 0);                       /* depth */
	put32(o, 0);                       /* not an array */
	put32(o, 6);
	put32(o, (uint32_t)levels);
	put32(o, (uint32_t)kv->len);
	put(o, kv->buf, kv->len);
	/* Rows of 8 or 16-byte texels need none of KTX 1's padding; a
	 * non-array cube's imageSize is one face. */
	for (k = 0; k < levels; k++) {
		size_t s = rf_cubemap_level_size(c, k), face = s * s * bytes;

		encode_level(c, k, texel, buf);
		put32(o, (uint32_t)face);
		put(o, buf, 6 * face);
	}
	return 0;
}

/* The basic descriptor block of RGBA half floats or floats, linear
 * BT.709, as KTX-Software's createDFDUnpacked makes it. */
static void
write_dfd(struct out *o, enum rf_ktx_texel texel)
{
	static const unsigned channels[4] = { 0, 1, 2, 15 }; /* R G B A */
	unsigned bits = texel == RF_KTX_RGBA32F ? 32 : 16, s;

	put32(o, DFD_BYTES);
	put32(o, 0);                                    /* Khronos, basic format */
	put32(o, 2u | (DFD_BYTES - 4) << 16);           /* version 2, block size */
	put32(o, 1u | 1u << 8 | 1u << 16);              /* RGBSDA, BT.709, linear */
	put32(o, 0);                                    /* one texel a block */
	put32(o, bits / 2);                             /* bytesPlane0: 4 samples */
	put32(o, 0);
	for (s = 0; s < 4; s++) {
		/* FLOAT | SIGNED qualifiers over the channel id */
		put32(o, s * bits | (bits - 1) << 16 | (0xc0u | channels[s]) << 24);
		put32(o, 0);
		put32(o, 0xbf800000u); /* -1.0f */
		put32(o, 0x3f800000u); /* 1.0f */
	}
}

static int
write_ktx2(struct out *o, const rf_cubemap *c, const struct kv *kv,
           const struct rf_ktx_options *opt, unsigned char *buf, unsigned char *zbuf,
           size_t zcap, char *err, size_t errlen)
{
	static const unsigned char id[12] = { 0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb,
		                              '\r', '\n', 0x1a, '\n' };
	int f32 = opt->texel == RF_KTX_RGBA32F;
	unsigned bytes = f32 ? 16 : 8, align = opt->zstd ? 1 : bytes;
	size_t levels = rf_cubemap_levels(c), n = rf_cubemap_size(c), k;
	uint64_t dfd = KTX2_HEADER + (uint64_t)KTX2_LEVEL * levels, at;
	uint64_t offset[32], length[32], raw[32];

	put(o, id, 12);
	put32(o, f32 ? 109 : 97); /* VK_FORMAT_R32G32B32A32_SFLOAT, _R16G16B16A16_ */
	put32(o, f32 ? 4 : 2);    /* typeSize */
	put32(o, (uint32_t)n);
	put32(o, (uint32_t)n);
	put32(o, 0);              /* depth */
	put32(o, 0);              /* layers */
	put32(o, 6);
	put32(o, (uint32_t)levels);
	put32(o, opt->zstd ? 2 : 0);
	put32(o, (uint32_t)dfd);
	put32(o, DFD_BYTES);
	put32(o, (uint32_t)(dfd + DFD_BYTES));
	put32(o, (uint32_t)kv->len);
	put64(o, 0);              /* no supercompression global data */
	put64(o, 0);
	/* The level index is written again once the levels' sizes are
	 * known; zeros hold its place. */
	for (k = 0; k < levels; k++) {
		put64(o, 0);
		put64(o, 0);
		put64(o, 0);
	}
	write_dfd(o, opt->texel);
	put(o, kv->buf, kv->len);
	at = dfd + DFD_BYTES + kv->len;
	/* Smallest level first, each aligned to its texel size when stored
	 * plain (mipPadding). */
	for (k = levels; k-- > 0;) {
		size_t s = rf_cubemap_level_size(c, k);
		const unsigned char *data = buf;

		raw[k] = 6 * (uint64_t)s * s * bytes;
		length[k] = raw[k];
		encode_level(c, k, opt->texel, buf);
#ifdef HAVE_ZSTD
		if (opt->zstd) {
			size_t z = ZSTD_compress(zbuf, zcap, buf, (size_t)raw[k], opt->zstd);

			if (ZSTD_isError(z)) {
				rf__format(err, errlen, "cannot write '%s': Zstandard: %s", o->path,
				           ZSTD_getErrorName(z));
				return RF_EIO;
			}
			length[k] = z;
			data = zbuf;
		}
#else
		(void)zbuf;
		(void)zcap;
		(void)err;
		(void)errlen;
#endif
		pad(o, at, align);
		if (at % align)
			at += align - at % align;
		offset[k] = at;
		put(o, data, (size_t)length[k]);
		at += length[k];
	}
	if (!o->failed && fseeko(o->fp, KTX2_HEADER, SEEK_SET) != 0)
		o->failed = 1;
	for (k = 0; k < levels; k++) {
		put64(o, offset[k]);
		put64(o, length[k]);
		put64(o, raw[k]);
	}
	return 0;
}

/* ---- the file ----------------------------------------------------------- */

int
rf_chain_write_ktx(const rf_cubemap *c, const struct rf_chain_info *info, const char *path,
                   const struct rf_ktx_options *opt, char *err, size_t errlen)
{
	size_t n = rf_cubemap_size(c), bytes, raw, zcap = 0;
	unsigned char *buf = NULL, *zbuf = NULL;
	struct out o = { NULL, path, 0 };
	struct kv kv;
	rf_output *file = NULL;
	int rc = 0, saved;

	if (opt->version != 1 && opt->version != 2) {
		rf__format(err, errlen, "'%s': KTX version %d; 1 or 2 are written", path,
		           opt->version);
		return RF_EINVAL;
	}
	if (opt->zstd && opt->version == 1) {
		rf__format(err, errlen, "'%s': KTX 1 has no supercompression; Zstandard needs "
		           "a .ktx2 file", path);
		return RF_EINVAL;
	}
#ifndef HAVE_ZSTD
	if (opt->zstd) {
		rf__format(err, errlen, "'%s': Zstandard supercompression needs libzstd, which "
		           "this reflect was built without (Debian: libzstd-dev)", path);
		return RF_EINVAL;
	}
#else
	if (opt->zstd < 0 || opt->zstd > ZSTD_maxCLevel()) {
		rf__format(err, errlen, "'%s': Zstandard level %d; 1 to %d are made", path,
		           opt->zstd, ZSTD_maxCLevel());
		return RF_EINVAL;
	}
#endif
	if (rf_cubemap_levels(c) > 32) /* never: faces of at most 2^31 */
		return RF_EINVAL;
	bytes = opt->texel == RF_KTX_RGBA32F ? 16 : 8;
	raw = 6 * n * n * bytes;
	if (!(buf = malloc(raw))) {
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		return RF_ENOMEM;
	}
#ifdef HAVE_ZSTD
	if (opt->zstd && !(zbuf = malloc(zcap = ZSTD_compressBound(raw)))) {
		free(buf);
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		return RF_ENOMEM;
	}
#endif
	kv_fill(&kv, c, info, opt->version);
	/* Through a file beside path renamed over it (lib/util/output.c): a
	 * failure leaves an old file whole. */
	if ((rc = rf_output_open(&file, path, &o.fp, err, errlen)) < 0)
		goto out;
	errno = 0;
	if (opt->version == 1)
		rc = write_ktx1(&o, c, &kv, opt->texel, buf);
	else
		rc = write_ktx2(&o, c, &kv, opt, buf, zbuf, zcap, err, errlen);
	saved = errno;
	if (o.failed && rc == 0) {
		rf__format(err, errlen, "cannot write '%s': %s", path,
		           strerror(saved ? saved : EIO));
		rc = RF_EIO;
	}
	if (rc < 0)
		rf_output_discard(file);
	else
		rc = rf_output_commit(file, err, errlen);
out:
	free(buf);
	free(zbuf);
	return rc;
}
