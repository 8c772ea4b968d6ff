/*
 * The part of a frame a run makes or keeps: --region=X0,Y0,X1,Y1 (the
 * pixels X0 <= x < X1, Y0 <= y < Y1 of the full frame), --tile=I/N (band
 * I of N bands of whole rows, rows floor(I H / N) to floor((I + 1) H / N)
 * - 1: bands of rows are what the threads already split a frame into,
 * and a tile of whole rows reads its input front to back), and --halo=P,
 * that many more pixels each way where the frame goes on (from an even
 * column and row), for a filter that reads neighbours (reflect-filter
 * crops them off again).  The
 * coordinates are always the full frame's, so that a tile's pixels are
 * the full render's and reflect-join puts them back in place.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

/* A coordinate: digits only, at most RF_FRAME_SIDE_MAX. */
static int
parse_coord(const char *s, char **end, size_t *out)
{
	unsigned long long v;

	if (*s < '0' || *s > '9')
		return -1;
	errno = 0;
	v = strtoull(s, end, 10);
	if (errno || v > RF_FRAME_SIDE_MAX)
		return -1;
	*out = (size_t)v;
	return 0;
}

static void
parse_rect(struct cli_region *r, const char *arg)
{
	size_t v[4];
	const char *s = arg;
	char *end;
	int i;

	for (i = 0; i < 4; i++, s = end + 1)
		if (parse_coord(s, &end, &v[i]) < 0 || *end != (i < 3 ? ',' : '\0'))
			die("--region=%s: expected X0,Y0,X1,Y1, four pixel coordinates of "
			    "the full frame (the pixels X0 <= x < X1, Y0 <= y < Y1)", arg);
	if (v[2] <= v[0] || v[3] <= v[1])
		die("--region=%s: the region holds no pixel (X0 < X1 and Y0 < Y1)", arg);
	r->x0 = v[0];
	r->y0 = v[1];
	r->x1 = v[2];
	r->y1 = v[3];
}

static void
parse_tile(struct cli_region *r, const char *arg)
{
	char *end;

	if (parse_coord(arg, &end, &r->index) < 0 || *end != '/' ||
	    parse_coord(end + 1, &end, &r->count) < 0 || *end || r->count < 1)
		die("--tile=%s: expected I/N, band I (from 0) of N bands of rows", arg);
	if (r->index >= r->count)
		die("--tile=%s: there is no band %zu of %zu (I runs from 0 to %zu)", arg,
		    r->index, r->count, r->count - 1);
}

int
cli_region_option(struct cli_region *r, int opt, const char *arg)
{
	switch (opt) {
	case CLI_OPT_REGION:
	case CLI_OPT_TILE:
		if (r->given && r->given != opt)
			die("--region and --tile: give one of them");
		r->given = opt;
		r->arg = arg;
		if (opt == CLI_OPT_REGION)
			parse_rect(r, arg);
		else
			parse_tile(r, arg);
		return 1;
	case CLI_OPT_HALO:
		r->halo = (size_t)parse_whole("halo", arg, 0, RF_FRAME_SIDE_MAX);
		return 1;
	}
	return 0;
}

void
cli_region_rect(const struct cli_region *r, size_t width, size_t height, size_t scale,
                size_t rect[4])
{
	/* in the options' pixels, scale x scale of the frame's each, so
	 * that a supersampled tile holds whole pixels */
	const size_t w = width / scale, ht = height / scale, h = r->halo;
	int i;

	rect[0] = rect[1] = 0;
	rect[2] = w;
	rect[3] = ht;
	if (r->given == CLI_OPT_REGION) {
		if (r->x1 > w || r->y1 > ht)
			die("--region=%s: past the frame's %zux%zu pixels (X1 <= %zu, Y1 <= %zu)",
			    r->arg, w, ht, w, ht);
		rect[0] = r->x0;
		rect[1] = r->y0;
		rect[2] = r->x1;
		rect[3] = r->y1;
	} else if (r->given == CLI_OPT_TILE) {
		if (r->count > ht)
			die("--tile=%s: %zu bands of a frame of %zu rows leave some empty "
			    "(N at most %zu)", r->arg, r->count, ht, ht);
		rect[1] = r->index * ht / r->count;
		rect[3] = (r->index + 1) * ht / r->count;
	}
	if (r->given && h) {
		rect[0] = rect[0] > h ? rect[0] - h : 0;
		rect[1] = rect[1] > h ? rect[1] - h : 0;
		/* A halo starts on an even column and row: a filter of 2 x 2
		 * quads (quad) pairs a tile's pixels as the full frame does. */
		rect[0] &= ~(size_t)1;
		rect[1] &= ~(size_t)1;
		rect[2] = w - rect[2] > h ? rect[2] + h : w;
		rect[3] = ht - rect[3] > h ? rect[3] + h : ht;
	}
	for (i = 0; i < 4; i++)
		rect[i] *= scale;
}

void
cli_region_key(rf_header *h, const size_t rect[4], size_t width, size_t height)
{
	struct rf_region g = { rect[0], rect[1], width, height };
	int rc;

	if ((rc = rf_header_set_region(h, &g)) < 0)
		die_header_key(rc);
}
