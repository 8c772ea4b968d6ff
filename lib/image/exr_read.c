/*
 * Reading OpenEXR files through OpenEXR's C core, as libreflect already
 * writes them: scanline and tiled parts, MIP-mapped cubes level by level,
 * every compression the core decodes, half, float and uint channels as
 * floats.  A stage that reads its environment from an EXR file then pays
 * for the file, not for loading OpenImageIO's 250 libraries (0.26 s and
 * 127 MB before the first pixel).  What the core reads but this does not
 * handle the way OpenImageIO does (deep data, subsampled channels, RIP
 * maps) is left to the image module.
 */
#include <fcntl.h>
#include <openexr.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/readers.h"
#include "util/util.h"

/* The first message of the library, kept for the caller; nothing printed. */
static _Thread_local char *reason;
static _Thread_local size_t reason_len;

static void
on_error(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
	(void)ctx;
	/* the core quotes the file's bytes ("Invalid type 'box2i^P'"),
	 * which rf__format makes printable */
	if (reason && !reason[0])
		rf__format(reason, reason_len, "%s",
		           msg && *msg ? msg : exr_get_default_error_message(code));
}

int
rf__is_exr(const char *path)
{
	unsigned char magic[4];
	int fd = open(path, O_RDONLY), ok;

	if (fd < 0)
		return 0;
	ok = read(fd, magic, 4) == 4 && magic[0] == 0x76 && magic[1] == 0x2f &&
	     magic[2] == 0x31 && magic[3] == 0x01;
	close(fd);
	return ok;
}

static int
start(exr_context_t *ctx, const char *path, char *why, size_t whylen)
{
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;

	why[0] = '\0';
	reason = why;
	reason_len = whylen;
	init.error_handler_fn = on_error;
	return exr_start_read(ctx, path, &init) == EXR_ERR_SUCCESS ? 0 : RF_EIMAGE;
}

/* The part's levels: 1 for scanlines, the MIP levels of a tiled part;
 * RF_ENOTFOUND for what the module should read (RIP maps, deep data). */
static int
levels_of(exr_context_t ctx, int *tiled, int *nlevels)
{
	exr_storage_t storage;
	int32_t lx, ly;

	if (exr_get_storage(ctx, 0, &storage))
		return RF_EIMAGE;
	if (storage == EXR_STORAGE_SCANLINE) {
		*tiled = 0;
		*nlevels = 1;
		return 0;
	}
	if (storage != EXR_STORAGE_TILED || exr_get_tile_levels(ctx, 0, &lx, &ly))
		return RF_ENOTFOUND;
	if (lx != ly && ly != 1 && lx != 1)
		return RF_ENOTFOUND;
	*tiled = 1;
	*nlevels = lx;
	return 0;
}

/* RF_ENOTFOUND for a compression the C core cannot decode (3.1: DWAA
 * and DWAB, "not yet implemented in C"): OpenEXR's C++ library reads it,
 * through the module.  DWA is the default of Nuke and of the HDRIs that
 * Blender ships. */
static int
core_decodes(exr_context_t ctx)
{
	exr_compression_t comp;

	if (exr_get_compression(ctx, 0, &comp))
		return RF_EIMAGE;
	return comp == EXR_COMPRESSION_DWAA || comp == EXR_COMPRESSION_DWAB ? RF_ENOTFOUND : 0;
}

int
rf__exr_count_levels(const char *path, size_t *nlevels, char *err, size_t errlen)
{
	exr_context_t ctx;
	char why[256];
	int tiled, n, rc;

	if (start(&ctx, path, why, sizeof(why)) < 0) {
		rf__format(err, errlen, "cannot read '%s': %s", path, why);
		return RF_EIMAGE;
	}
	rc = levels_of(ctx, &tiled, &n);
	exr_finish(&ctx);
	if (rc == 0)
		*nlevels = (size_t)n;
	return rc;
}

/* The channels in the order OpenImageIO gives them: by layer (the name
 * up to its last dot; none first), and in a layer R G B A first, then
 * the others by name: spec.R spec.G spec.B, and depth mask N.X N.Y N.Z. */
static _Thread_local const exr_attr_chlist_t *sorting;

static int
special(const char *suffix)
{
	static const char *const rgba[] = { "R", "G", "B", "A" };
	int k;

	for (k = 0; k < 4; k++)
		if (!strcmp(suffix, rgba[k]))
			return k;
	return 4;
}

static int
compare_channels(const void *pa, const void *pb)
{
	const char *a = sorting->entries[*(const int *)pa].name.str;
	const char *b = sorting->entries[*(const int *)pb].name.str;
	const char *da = strrchr(a, '.'), *db = strrchr(b, '.');
	size_t la = da ? (size_t)(da - a) : 0, lb = db ? (size_t)(db - b) : 0;
	const char *sa = da ? da + 1 : a, *sb = db ? db + 1 : b;
	int c = strncmp(a, b, la < lb ? la : lb);

	if (la != lb || c)
		return c ? c : la < lb ? -1 : 1;
	if (special(sa) != special(sb))
		return special(sa) - special(sb);
	return strcmp(sa, sb);
}

static int
channel_order(const exr_attr_chlist_t *list, int *order)
{
	int i;

	if (list->num_channels > 1024)
		return -1;
	for (i = 0; i < list->num_channels; i++)
		order[i] = i;
	/* the sort's comparison reads the list; one reader a thread */
	sorting = list;
	qsort(order, (size_t)list->num_channels, sizeof(int), compare_channels);
	return list->num_channels;
}

static int
keep_attributes(exr_context_t ctx, struct rf__image_data *img)
{
	int32_t count, i;
	size_t n = 0;
	exr_envmap_t env;

	if (exr_get_attribute_count(ctx, 0, &count))
		return 0;
	if (!(img->attr = calloc(2 * (size_t)count + 3, sizeof(char *))))
		return RF_ENOMEM;
	if (exr_attr_get_envmap(ctx, 0, "envmap", &env) == EXR_ERR_SUCCESS) {
		img->attr[n++] = strdup("envmap");
		img->attr[n++] = strdup(env == EXR_ENVMAP_CUBE ? "cube" : "latlong");
	}
	for (i = 0; i < count; i++) {
		const exr_attribute_t *a;

		if (exr_get_attribute_by_index(ctx, 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) ||
		    a->type != EXR_ATTR_STRING || !a->string || !a->string->str)
			continue;
		img->attr[n++] = strdup(a->name);
		img->attr[n++] = strndup(a->string->str, (size_t)a->string->length);
	}
	img->nattr = n / 2;
	for (i = 0; i < (int32_t)n; i++)
		if (!img->attr[i])
			return RF_ENOMEM;
	return 0;
}

/* Decodes one chunk into img's floats at (x0, y0) of the level. */
static exr_result_t
decode_chunk(exr_context_t ctx, const exr_chunk_info_t *ci, exr_decode_pipeline_t *dec,
             int *ready, struct rf__image_data *img, const int *slot, int x0, int y0)
{
	exr_result_t rv;
	int16_t c;

	rv = *ready ? exr_decoding_update(ctx, 0, ci, dec)
	            : exr_decoding_initialize(ctx, 0, ci, dec);
	if (rv)
		return rv;
	*ready = 1;
	for (c = 0; c < dec->channel_count; c++) {
		exr_coding_channel_info_t *ch = &dec->channels[c];

		ch->user_bytes_per_element = 4;
		ch->user_data_type = EXR_PIXEL_FLOAT;
		ch->user_pixel_stride = (int32_t)(img->nchannels * sizeof(float));
		ch->user_line_stride = (int32_t)(img->width * img->nchannels * sizeof(float));
		ch->decode_to_ptr = (uint8_t *)(img->pixels + ((size_t)y0 * img->width +
		                                               (size_t)x0) * img->nchannels +
		                                (size_t)slot[c]);
	}
	if ((rv = exr_decoding_choose_default_routines(ctx, 0, dec)))
		return rv;
	return exr_decoding_run(ctx, 0, dec);
}

int
rf__exr_read_level(struct rf__image_data *img, const char *path, size_t level,
                   char *err, size_t errlen)
{
	const exr_attr_chlist_t *list;
	exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
	exr_attr_box2i_t dw;
	exr_context_t ctx;
	char why[256];
	int order[1024], slot[1024], tiled, nlevels, ready = 0, n, i, rc = 0;
	int32_t w, h;
	exr_result_t rv = EXR_ERR_SUCCESS;

	memset(img, 0, sizeof(*img));
	if (start(&ctx, path, why, sizeof(why)) < 0) {
		rf__format(err, errlen, "cannot read '%s': %s", path, why);
		return RF_EIMAGE;
	}
	if ((rc = levels_of(ctx, &tiled, &nlevels)) < 0 || (rc = core_decodes(ctx)) < 0)
		goto out;
	if ((int)level >= nlevels) {
		rf__format(err, errlen, "'%s' has %d level%s, not %zu", path, nlevels,
		           nlevels == 1 ? "" : "s", level + 1);
		rc = RF_EINVAL;
		goto out;
	}
	if (exr_get_channels(ctx, 0, &list) || exr_get_data_window(ctx, 0, &dw) ||
	    (n = channel_order(list, order)) <= 0) {
		rc = RF_ENOTFOUND;
		goto out;
	}
	for (i = 0; i < list->num_channels; i++)
		if (list->entries[i].x_sampling != 1 || list->entries[i].y_sampling != 1) {
			rc = RF_ENOTFOUND; /* subsampled: OpenImageIO upsamples them */
			goto out;
		}
	if (tiled) {
		if (exr_get_level_sizes(ctx, 0, (int)level, (int)level, &w, &h)) {
			rc = RF_ENOTFOUND;
			goto out;
		}
	} else {
		w = dw.max.x - dw.min.x + 1;
		h = dw.max.y - dw.min.y + 1;
	}
	/* a header's sizes are checked before they are believed: at most
	 * 2^28 values (1 GB of floats), a 16k x 16k cube of RGBA */
	if (w < 1 || h < 1 ||
	    (rc = rf__image_bounds(path, "openexr", (size_t)w, (size_t)h, (size_t)n, err,
	                           errlen)) < 0) {
		if (w < 1 || h < 1)
			rf__format(err, errlen, "'%s': a %dx%d image of %d channels is out of "
			           "range", path, w, h, n);
		rc = RF_ETOOBIG;
		goto out;
	}
	img->width = (size_t)w;
	img->height = (size_t)h;
	img->nchannels = (size_t)n;
	if (!(img->pixels = calloc((size_t)w * (size_t)h * (size_t)n, sizeof(float))) ||
	    !(img->names = calloc((size_t)n, sizeof(char *)))) {
		rc = RF_ENOMEM;
		goto out;
	}
	for (i = 0; i < n; i++) {
		/* the decoder lists the channels in the file's order */
		slot[order[i]] = i;
		if (!(img->names[i] = strdup(list->entries[order[i]].name.str))) {
			rc = RF_ENOMEM;
			goto out;
		}
	}
	if ((rc = keep_attributes(ctx, img)) < 0)
		goto out;
	if (tiled) {
		uint32_t tw, th;
		exr_tile_level_mode_t lm;
		exr_tile_round_mode_t rm;
		int tx, ty;

		if (exr_get_tile_descriptor(ctx, 0, &tw, &th, &lm, &rm) || !tw || !th) {
			rc = RF_ENOTFOUND;
			goto out;
		}
		for (ty = 0; !rv && (int64_t)ty * th < h; ty++)
			for (tx = 0; !rv && (int64_t)tx * tw < w; tx++) {
				exr_chunk_info_t ci;

				if (!(rv = exr_read_tile_chunk_info(ctx, 0, tx, ty, (int)level,
				                                    (int)level, &ci)))
					rv = decode_chunk(ctx, &ci, &dec, &ready, img, slot,
					                  tx * (int)tw, ty * (int)th);
			}
	} else {
		int32_t lines, y;

		if (exr_get_scanlines_per_chunk(ctx, 0, &lines) || lines < 1) {
			rc = RF_ENOTFOUND;
			goto out;
		}
		for (y = dw.min.y; !rv && y <= dw.max.y; y += lines) {
			exr_chunk_info_t ci;

			if (!(rv = exr_read_scanline_chunk_info(ctx, 0, y, &ci)))
				rv = decode_chunk(ctx, &ci, &dec, &ready, img, slot, 0,
				                  ci.start_y - dw.min.y);
		}
	}
	if (rv == EXR_ERR_FEATURE_NOT_IMPLEMENTED) {
		rc = RF_ENOTFOUND; /* another coding the core cannot decode */
	} else if (rv) {
		rf__format(err, errlen, "cannot read '%s': %s", path,
		           why[0] ? why : exr_get_default_error_message(rv));
		rc = RF_EIMAGE;
	}
out:
	if (ready)
		exr_decoding_destroy(ctx, &dec);
	exr_finish(&ctx);
	reason = NULL;
	if (rc < 0)
		rf__image_data_free(img);
	return rc;
}

void
rf__image_data_free(struct rf__image_data *img)
{
	size_t i;

	for (i = 0; img->names && i < img->nchannels; i++)
		free(img->names[i]);
	for (i = 0; img->attr && i < 2 * img->nattr; i++)
		free(img->attr[i]);
	free(img->names);
	free(img->attr);
	free(img->pixels);
	memset(img, 0, sizeof(*img));
}
