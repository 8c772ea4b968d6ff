/* reflect-join: tiles (REGION) back into their full frames. */
#include <getopt.h>
#include <string.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-V] " CLI_PROGRESS_USAGE " [-f a|f] [-h] [file...]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

enum { OPT_HELP = 256 };

static const struct option long_options[] = {
	{ "help", no_argument, NULL, OPT_HELP },
	CLI_PROGRESS_OPTION,
	{ NULL, 0, NULL, 0 },
};

static void
help(void)
{
	printf("usage: %s [options] [file...]\n"
	       "Puts tiles (frames with REGION, as --region and --tile make them) back\n"
	       "into their full frames, in any order, from files or standard input\n"
	       "(-); a frame is written once its tiles cover it.  See reflect-join(1).\n"
	       "  -f a|f  output format   -h  no output header   -V  versions\n"
	       CLI_PROGRESS_HELP, argv0);
	fshut(stdout, "<stdout>");
	exit(0);
}

/* A full frame being put together: the tiles it has so far. */
struct canvas {
	char *frame;        /* its FRAME ("" without) */
	rf_header *h;       /* the first tile's header, at the full size */
	struct rf_region g; /* the full frame's size */
	size_t ncomp, covered, ntiles;
	size_t (*rects)[4]; /* each tile's x0 y0 x1 y1, and where it came from */
	char **from;
	float *px;
};

static struct canvas *canvases;
static size_t ncanvases;

static const char *
frame_of(const rf_header *h)
{
	const char *f = rf_header_get(h, RF_KEY_FRAME);

	return f ? f : "";
}

/* The channels as one line, to compare tiles by. */
static int
same_channels(const rf_header *a, const rf_header *b)
{
	size_t i;

	if (rf_header_nchannels(a) != rf_header_nchannels(b))
		return 0;
	for (i = 0; i < rf_header_nchannels(a); i++)
		if (strcmp(rf_header_channel(a, i), rf_header_channel(b, i)))
			return 0;
	return 1;
}

static struct canvas *
canvas_for(const rf_header *in, const struct rf_region *g, const char *where)
{
	const char *frame = frame_of(in);
	struct canvas *c;
	size_t i, bytes;

	for (i = 0; i < ncanvases; i++) {
		c = &canvases[i];
		if (strcmp(c->frame, frame))
			continue;
		if (c->g.width != g->width || c->g.height != g->height)
			die("%s is a tile of a %zux%zu frame, %s of a %zux%zu one: tiles of "
			    "one frame share its size", where, g->width, g->height,
			    c->from[0], c->g.width, c->g.height);
		if (!same_channels(c->h, in))
			die("%s has other channels than %s: tiles of one frame have the same "
			    "channels in the same order", where, c->from[0]);
		return c;
	}
	canvases = realloc(canvases, (ncanvases + 1) * sizeof(*canvases));
	if (!canvases)
		die_sys("out of memory");
	c = &canvases[ncanvases++];
	memset(c, 0, sizeof(*c));
	c->frame = estrdup(frame);
	c->g = *g;
	c->ncomp = rf_header_nchannels(in);
	cli_check_frame("the full frame of the tiles", g->width, g->height);
	bytes = g->width * g->height * c->ncomp * sizeof(float);
	if (bytes / sizeof(float) / c->ncomp / g->width != g->height)
		die("%s: a %zux%zu frame of %zu channels is too large", where, g->width,
		    g->height, c->ncomp);
	c->px = emalloc(bytes);
	if (rf_header_dup(&c->h, in) < 0 || rf_header_set_size(c->h, g->width, g->height) < 0 ||
	    rf_header_unset(c->h, RF_KEY_REGION) < 0)
		die_sys("out of memory");
	return c;
}

/* Places the tile's rect, dying when it overlaps one already there. */
static void
place(struct canvas *c, const size_t r[4], const char *where)
{
	size_t i;

	for (i = 0; i < c->ntiles; i++) {
		const size_t *o = c->rects[i];

		if (r[0] < o[2] && o[0] < r[2] && r[1] < o[3] && o[1] < r[3])
			die("%s (pixels %zu,%zu,%zu,%zu) overlaps %s (%zu,%zu,%zu,%zu): each "
			    "pixel comes from one tile (tiles made with --halo go through "
			    "reflect-filter --tile first, which cuts the halo off)", where,
			    r[0], r[1], r[2], r[3], c->from[i], o[0], o[1], o[2], o[3]);
	}
	c->rects = realloc(c->rects, (c->ntiles + 1) * sizeof(*c->rects));
	c->from = realloc(c->from, (c->ntiles + 1) * sizeof(*c->from));
	if (!c->rects || !c->from)
		die_sys("out of memory");
	memcpy(c->rects[c->ntiles], r, 4 * sizeof(size_t));
	c->from[c->ntiles++] = estrdup(where);
	c->covered += (r[2] - r[0]) * (r[3] - r[1]);
}

static void
write_frame(struct cli_io *io, struct canvas *c)
{
	cli_record_command(c->h);
	cli_io_begin(io, c->h);
	cli_io_write(io, c->px, c->g.height);
	cli_io_end_frame(io);
	free(c->px);
	c->px = NULL;
}

/* The first pixel no tile of c holds, for the message of a gap. */
static void
first_gap(const struct canvas *c, size_t *gx, size_t *gy)
{
	size_t x, y, i;

	for (y = 0; y < c->g.height; y++)
		for (x = 0; x < c->g.width; x++) {
			for (i = 0; i < c->ntiles; i++) {
				const size_t *r = c->rects[i];

				if (r[0] <= x && x < r[2] && r[1] <= y && y < r[3]) {
					x = r[2] - 1; /* the rest of the tile's row is held */
					break;
				}
			}
			if (i == c->ntiles) {
				*gx = x;
				*gy = y;
				return;
			}
		}
	*gx = *gy = 0;
}

static void
join_input(struct cli_io *io, const char *name)
{
	const rf_header *in;
	char where[512];
	rf_reader *r;
	FILE *fp = stdin;
	float *row;
	size_t k, rect[4], y;
	struct rf_region g;
	struct canvas *c;
	int rc;

	if (strcmp(name, "-") && !(fp = fopen(name, "rb")))
		die("cannot open '%s':", name);
	if ((rc = rf_reader_open(&r, fp, strcmp(name, "-") ? name : "<stdin>", NULL)) < 0)
		die_status(rc, NULL);
	for (k = 0; (rc = rf_reader_next_frame(r, &in)) == 1; k++) {
		snprintf(where, sizeof(where), "'%s' frame %zu", strcmp(name, "-") ? name :
		         "<stdin>", k);
		if (rf_header_region(in, &g) < 0)
			die("%s: " RF_KEY_REGION "='%s' is not X0 Y0 WIDTH HEIGHT of a full frame "
			    "that holds the tile", where, rf_header_get(in, RF_KEY_REGION));
		c = canvas_for(in, &g, where);
		if (!c->px)
			die("%s: FRAME %s was already whole and written: a tile too many",
			    where, *c->frame ? c->frame : "(none)");
		rect[0] = g.x0;
		rect[1] = g.y0;
		rect[2] = g.x0 + rf_header_ncols(in);
		rect[3] = g.y0 + rf_header_nrows(in);
		place(c, rect, where);
		for (y = rect[1]; y < rect[3]; y++) {
			row = c->px + (y * c->g.width + rect[0]) * c->ncomp;
			if ((rc = rf_reader_read_rows(r, row, 1)) < 0)
				die_status(rc, rf_reader_error(r));
		}
		if (c->covered == c->g.width * c->g.height)
			write_frame(io, c);
	}
	if (rc < 0)
		die_status(rc, rf_reader_error(r));
	rf_reader_close(r);
	if (fp != stdin)
		fclose(fp);
}

int
main(int argc, char **argv)
{
	struct cli_io io = { 0 };
	struct rf_writer_options wopt;
	size_t i, x, y;
	int c, rc, k;

	cli_init(argc, argv);
	while ((c = getopt_long(argc, argv, "Vf:hq", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'f': case 'h': cli_io_option(&io, c, optarg); break;
		case OPT_HELP: help(); break;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	wopt.format = io.format;
	wopt.no_header = io.no_header;
	if ((rc = rf_writer_open(&io.writer, stdout, "<stdout>", &wopt)) < 0)
		die_status(rc, NULL);
	cli_guard_stream(io.writer);
	/* The tiles' files are read whole, one after the other: progress
	 * counts them. */
	cli_progress_unit("file");
	cli_progress_frames(1);
	cli_progress_frame(optind == argc ? 1 : (size_t)(argc - optind));
	if (optind == argc)
		join_input(&io, "-");
	for (k = optind; k < argc; k++) {
		join_input(&io, argv[k]);
		cli_progress_rows((size_t)(k - optind + 1));
	}
	for (i = 0; i < ncanvases; i++) {
		if (!canvases[i].px)
			continue;
		first_gap(&canvases[i], &x, &y);
		die("FRAME %s: no tile holds pixel %zu,%zu of the %zux%zu frame (%zu tile%s "
		    "came, first %s): a tile is missing", *canvases[i].frame ?
		    canvases[i].frame : "(none)", x, y, canvases[i].g.width,
		    canvases[i].g.height, canvases[i].ntiles, canvases[i].ntiles == 1 ? "" : "s",
		    canvases[i].from[0]);
	}
	if (!ncanvases)
		die("no tile came: give files of tiles, or tiles on standard input");
	for (i = 0; i < ncanvases; i++) {
		rf_header_destroy(canvases[i].h);
		free(canvases[i].frame);
		free(canvases[i].rects);
		for (x = 0; x < canvases[i].ntiles; x++)
			free(canvases[i].from[x]);
		free(canvases[i].from);
	}
	free(canvases);
	cli_io_close(&io);
	return 0;
}
