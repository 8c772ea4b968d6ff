/*
 * Reading PNG files with libpng, as libreflect already writes them, so
 * that a PNG normal map, emission image or picture to compare costs no
 * image module.  The values are as stored, 0..1 (8- and 16-bit alike),
 * not linearised, and the channels named as OpenImageIO names them: Y
 * (and A) for grey, R G B (and A) for colour; palettes are expanded, and
 * the colour space is said to be sRGB, as OpenImageIO says it.
 */
#include <errno.h>
#include <png.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "image/readers.h"
#include "util/util.h"

struct reading {
	char *err;
	size_t errlen;
	const char *path;
	FILE *fp;
};

static void
on_error(png_structp png, png_const_charp msg)
{
	struct reading *r = png_get_error_ptr(png);

	rf__format(r->err, r->errlen, "cannot read '%s': %s", r->path, msg);
	png_longjmp(png, 1);
}

static void
on_warning(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

/* libpng's own says only "Read Error" */
static void
read_data(png_structp png, png_bytep data, size_t len)
{
	struct reading *r = png_get_io_ptr(png);

	if (fread(data, 1, len, r->fp) != len)
		png_error(png, ferror(r->fp) ? strerror(errno)
		                             : "the file ends inside a chunk: truncated or damaged");
}

int
rf__is_png(const char *path)
{
	unsigned char sig[8];
	FILE *fp = fopen(path, "rb");
	int ok;

	if (!fp)
		return 0;
	ok = fread(sig, 1, 8, fp) == 8 && !png_sig_cmp(sig, 0, 8);
	fclose(fp);
	return ok;
}

int
rf__png_read(struct rf__image_data *img, const char *path, char *err, size_t errlen)
{
	static const char *const grey[] = { "Y", "A" }, *const colour[] = { "R", "G", "B", "A" };
	struct reading r = { err, errlen, path, NULL };
	png_structp png = NULL;
	png_infop info = NULL;
	png_bytep *volatile rows = NULL;
	unsigned char *volatile data = NULL;
	FILE *fp;
	png_uint_32 w, h, y, x;
	int depth, type, nch, c, rc = RF_EIMAGE;

	memset(img, 0, sizeof(*img));
	if (!(fp = fopen(path, "rb"))) {
		rf__format(err, errlen, "cannot open '%s'", path);
		return RF_EIMAGE;
	}
	if (!(png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r, on_error, on_warning)) ||
	    !(info = png_create_info_struct(png))) {
		rc = RF_ENOMEM;
		goto out;
	}
	if (setjmp(png_jmpbuf(png))) {
		rc = RF_EIMAGE;
		goto out;
	}
	r.fp = fp;
	png_set_read_fn(png, &r, read_data);
	/* Only IHDR, PLTE, tRNS and IDAT make the pixels, and libpng reads
	 * and zeroes a whole text or profile chunk before it looks at it:
	 * a 305-byte file whose tEXt chunk claimed 721 MB cost 707 MB and
	 * 2 s before the read failed.  Every other chunk is skipped as it
	 * streams past. */
	png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, NULL, -1);
	png_read_info(png, info);
	png_get_IHDR(png, info, &w, &h, &depth, &type, NULL, NULL, NULL);
	/* every kind as 8- or 16-bit grey or colour, with or without alpha */
	if (type == PNG_COLOR_TYPE_PALETTE)
		png_set_palette_to_rgb(png);
	if (type == PNG_COLOR_TYPE_GRAY && depth < 8)
		png_set_expand_gray_1_2_4_to_8(png);
	if (png_get_valid(png, info, PNG_INFO_tRNS))
		png_set_tRNS_to_alpha(png);
	if (depth == 16) {
		const uint16_t one = 1;

		if (*(const unsigned char *)&one)
			png_set_swap(png); /* PNG is big-endian; read in host order */
	}
	png_read_update_info(png, info);
	nch = png_get_channels(png, info);
	depth = png_get_bit_depth(png, info);
	if ((rc = rf__image_bounds(path, "png", (size_t)w, (size_t)h, (size_t)nch, err,
	                           errlen)) < 0)
		goto out;
	data = malloc((size_t)h * png_get_rowbytes(png, info));
	rows = malloc((size_t)h * sizeof(*rows));
	img->pixels = malloc((size_t)w * h * (size_t)nch * sizeof(float));
	img->names = calloc((size_t)nch, sizeof(char *));
	img->attr = calloc(2, sizeof(char *));
	if (!data || !rows || !img->pixels || !img->names || !img->attr) {
		rc = RF_ENOMEM;
		goto out;
	}
	for (y = 0; y < h; y++)
		rows[y] = data + (size_t)y * png_get_rowbytes(png, info);
	png_read_image(png, rows);
	png_read_end(png, NULL);
	img->width = w;
	img->height = h;
	img->nchannels = (size_t)nch;
	for (y = 0; y < h; y++)
		for (x = 0; x < w * (png_uint_32)nch; x++)
			img->pixels[(size_t)y * w * (size_t)nch + x] =
				/* as OpenImageIO converts them, to the last bit */
				depth == 16 ? (float)((const uint16_t *)rows[y])[x] / 65535.0f
				            : (float)rows[y][x] * (1.0f / 255.0f);
	for (c = 0; c < nch; c++)
		if (!(img->names[c] = strdup(nch <= 2 ? grey[c] : colour[c]))) {
			rc = RF_ENOMEM;
			goto out;
		}
	img->attr[0] = strdup("oiio:ColorSpace");
	img->attr[1] = strdup("sRGB");
	img->nattr = 1;
	rc = img->attr[0] && img->attr[1] ? 0 : RF_ENOMEM;
out:
	png_destroy_read_struct(png ? &png : NULL, info ? &info : NULL, NULL);
	free(rows);
	free(data);
	fclose(fp);
	if (rc < 0)
		rf__image_data_free(img);
	return rc;
}
