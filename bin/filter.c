/* reflect-filter: filters values across pixels, guided by the G-buffer. */
#include <getopt.h>
#include <string.h>

#include "cli.h"
#include "reflect/host.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        CLI_PROGRESS_USAGE " "
	        "[--channels=LIST] [--region=X0,Y0,X1,Y1|--tile=I/N] " CLI_IO_USAGE
	        " [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	CLI_PROGRESS_OPTION,
	{ "region", required_argument, NULL, CLI_OPT_REGION },
	{ "tile", required_argument, NULL, CLI_OPT_TILE },
	{ "channels", required_argument, NULL, 'C' },
	{ "help", no_argument, NULL, CLI_OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static struct rf_filter_options options;
static rf_filter *filter;
static size_t rows_written; /* of this frame, for progress */

/* --region or --tile: the frame is filtered whole and only the tile is
 * written, its rows and columns in the input (a tile with its halo). */
static struct crop {
	int on;
	size_t x, y, w, h, ncomp;
	float *buf;
	size_t cap; /* rows buf holds */
} crop;

static int
option(struct cli_stage_run *r, int opt, const char *arg)
{
	if (opt != 'C')
		return 0;
	options.channels = arg;
	return 1;
}

static void
start(struct cli_stage_run *r)
{
	char err[1024];
	int rc;

	/* the tile is cut from the output, after the neighbours were read */
	r->io.crop_output = 1;
	if ((rc = rf_filter_create(&filter, r->mode.plugin, r->mode.values,
	                           rf_plugin_host_table(r->host), r->nthreads, &options,
	                           err, sizeof(err))) < 0)
		die_status(rc, err);
}

static int
read_rows(void *arg, float *rows, size_t nrows)
{
	cli_io_read(arg, rows, nrows);
	return 0;
}

/* The tile's part of rows y0 .. y0 + nrows - 1 of the input. */
static void
write_cropped(struct cli_io *io, const float *rows, size_t y0, size_t nrows, size_t ncols)
{
	size_t a = y0 > crop.y ? y0 : crop.y, b = y0 + nrows, i;

	if (b > crop.y + crop.h)
		b = crop.y + crop.h;
	if (a >= b)
		return;
	if (b - a > crop.cap) {
		free(crop.buf);
		crop.buf = ecalloc((b - a) * crop.w, crop.ncomp * sizeof(float));
		crop.cap = b - a;
	}
	for (i = a; i < b; i++)
		memcpy(crop.buf + (i - a) * crop.w * crop.ncomp,
		       rows + ((i - y0) * ncols + crop.x) * crop.ncomp,
		       crop.w * crop.ncomp * sizeof(float));
	cli_io_write(io, crop.buf, b - a);
}

static size_t frame_ncols;

static int
write_rows(void *arg, const float *rows, size_t nrows)
{
	if (crop.on)
		write_cropped(arg, rows, rows_written, nrows, frame_ncols);
	else
		cli_io_write(arg, rows, nrows);
	rows_written += nrows;
	cli_progress_rows(rows_written);
	return 0;
}

/* One side of the tile: from the tile's edge at a (start) or b (end)
 * the filter reads reach pixels further, up to the full frame's edges
 * 0 and full; the input holds lo .. hi - 1. */
static size_t
halo_short(size_t a, size_t b, size_t lo, size_t hi, size_t full, size_t reach)
{
	size_t want_lo = a > reach ? a - reach : 0;
	size_t want_hi = full - b > reach ? b + reach : full;

	size_t before = lo > want_lo ? lo - want_lo : 0;
	size_t after = hi < want_hi ? want_hi - hi : 0;

	return before > after ? before : after;
}

/* The output header of the tile asked for (out itself without one),
 * death when the input does not hold it and its halo. */
static rf_header *
crop_frame(struct cli_stage_run *r, const rf_header *in, rf_header *out)
{
	const size_t ncols = rf_header_ncols(in), nrows = rf_header_nrows(in);
	const size_t reach = rf_filter_reach(filter);
	struct rf_region g;
	size_t rect[4], shortx, shorty;
	rf_header *h;

	crop.on = 0;
	if (rf_header_region(in, &g) < 0)
		die("'%s': frame %zu: " RF_KEY_REGION "='%s' is not X0 Y0 WIDTH HEIGHT of a "
		    "full frame that holds this one", r->io.input_name, r->io.frames,
		    rf_header_get(in, RF_KEY_REGION));
	if (!r->io.region.given) {
		if (reach && (ncols != g.width || nrows != g.height))
			warn("'%s': frame %zu is a tile of a %zux%zu frame: near its edges the "
			     "filter misses the pixels around it (give --region or --tile to "
			     "keep only those it has)", r->io.input_name, r->io.frames, g.width,
			     g.height);
		return out;
	}
	cli_region_rect(&r->io.region, g.width, g.height, 1, rect);
	if (rect[0] < g.x0 || rect[1] < g.y0 || rect[2] > g.x0 + ncols ||
	    rect[3] > g.y0 + nrows)
		die("'%s': frame %zu holds pixels %zu,%zu,%zu,%zu of a %zux%zu frame, not all "
		    "of the tile %zu,%zu,%zu,%zu", r->io.input_name, r->io.frames, g.x0, g.y0,
		    g.x0 + ncols, g.y0 + nrows, g.width, g.height, rect[0], rect[1], rect[2],
		    rect[3]);
	shortx = halo_short(rect[0], rect[2], g.x0, g.x0 + ncols, g.width, reach);
	shorty = halo_short(rect[1], rect[3], g.y0, g.y0 + nrows, g.height, reach);
	if (shortx || shorty)
		die("'%s': frame %zu: the mode reads %zu pixels around each it filters, and "
		    "the input lacks up to %zu of them around the tile %zu,%zu,%zu,%zu: "
		    "make it with --halo=%zu", r->io.input_name, r->io.frames, reach,
		    shortx > shorty ? shortx : shorty, rect[0], rect[1], rect[2], rect[3],
		    reach);
	if (rf_header_dup(&h, out) < 0 ||
	    rf_header_set_size(h, rect[2] - rect[0], rect[3] - rect[1]) < 0)
		die_sys("out of memory");
	cli_region_key(h, rect, g.width, g.height);
	crop.on = 1;
	crop.x = rect[0] - g.x0;
	crop.y = rect[1] - g.y0;
	crop.w = rect[2] - rect[0];
	crop.h = rect[3] - rect[1];
	crop.ncomp = rf_header_nchannels(out);
	return h;
}

static void
frame(struct cli_stage_run *r, const rf_header *in)
{
	rf_header *out;
	char err[1024];
	int rc;

	if ((rc = rf_filter_begin_frame(filter, in, &out, err, sizeof(err))) < 0)
		cli_stage_refused(r, rc, err);
	cli_stage_header(r, out, RF_KEY_FILTER);
	frame_ncols = rf_header_ncols(in);
	out = crop_frame(r, in, out);
	cli_io_begin(&r->io, out);
	if (crop.on)
		rf_header_destroy(out);
	rows_written = 0;
	cli_progress_frame(rf_header_nrows(in));
	if ((rc = rf_filter_frame(filter, read_rows, write_rows, &r->io)) < 0) {
		if ((rc == RF_EINVAL || rc == RF_EPLUGIN) && *rf_filter_error(filter))
			die("'%s': frame %zu, %s", r->io.input_name, r->io.frames,
			    rf_filter_error(filter));
		die_status(rc, NULL);
	}
	cli_io_end_frame(&r->io);
}

static void
finish(struct cli_stage_run *r)
{
	rf_filter_destroy(filter);
	free(crop.buf);
}

static const struct cli_stage_tool tool = {
	.kind = RF_KIND_FILTER,
	.spec = "atrous",
	.long_options = long_options,
	.about = "Filters the shaded values of a stream across pixels, guided by\n"
	         "its G-buffer. See reflect-filter(1).\n",
	.help = "  --channels=LIST  what is filtered (default spec.* and R G B)\n"
	        "  --region=X0,Y0,X1,Y1  --tile=I/N  write only that tile, filtered\n"
	        "      from the input's pixels around it too (its halo)\n",
	.usage = usage,
	.option = option,
	.start = start,
	.finish = finish,
	.frame = frame,
};

int
main(int argc, char **argv)
{
	return cli_stage_main(argc, argv, &tool);
}
