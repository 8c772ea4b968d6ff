/* reflect-montage: a labelled grid of images and stream channels. */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "cli.h"
#include "reflect/compare.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s -o IMAGE [-V] " CLI_PROGRESS_USAGE " [--columns=N] [-e STOPS] "
	        "[--tone=none|filmic] [--srgb=on|off] [--label-scale=N] "
	        "LABEL=FILE[:CHANNELS][:colour|grey|false|vector][:range=LO,HI]...\n",
	        argv0);
	exit(EXIT_BAD_INPUT);
}

enum { OPT_COLUMNS = 256, OPT_TONE, OPT_SRGB, OPT_LABEL_SCALE, OPT_HELP };

static const struct option long_options[] = {
	{ "columns", required_argument, NULL, OPT_COLUMNS },
	{ "tone", required_argument, NULL, OPT_TONE },
	{ "srgb", required_argument, NULL, OPT_SRGB },
	{ "label-scale", required_argument, NULL, OPT_LABEL_SCALE },
	{ "help", no_argument, NULL, OPT_HELP },
	CLI_PROGRESS_OPTION,
	{ NULL, 0, NULL, 0 },
};

static void
help(void)
{
	printf("usage: %s -o IMAGE [options] LABEL=FILE[:CHANNELS][:MAP][:range=LO,HI]...\n"
	       "Lays images and stream channels out in a labelled grid: colour as\n"
	       "reflect-export shows it, other channels in false colour with a bar\n"
	       "(one channel) or as (v - lo)/(hi - lo) (three).  See reflect-montage(1).\n"
	       "  --columns=N  cells a row (default: all in one row)\n"
	       "  -e STOPS --tone=none|filmic --srgb=on|off  colour cells' encoding\n"
	       "  --label-scale=N  pixels a font pixel (default: the height / 90)\n"
	       "  -V  versions\n"
	       CLI_PROGRESS_HELP, argv0);
	fshut(stdout, "<stdout>");
	exit(0);
}

/* "LABEL=FILE[:CHANNELS][:MAP][:range=LO,HI]" into the cell, its
 * pixels the chosen channels of the file's first frame. */
static void
load_cell(char *arg, struct rf_montage_cell *cell)
{
	char *eq = strchr(arg, '='), *file, *opt, *chans = NULL, *save = NULL;
	const char *map = NULL;
	char err[1024];
	rf_picture *pic;
	const float *px;
	float *sel;
	int idx[4];
	size_t n = 0, i, c, npix;

	if (!eq)
		die("'%s' is not LABEL=FILE[:CHANNELS][:MAP][:range=LO,HI]", arg);
	*eq = '\0';
	cell->label = arg;
	file = strtok_r(eq + 1, ":", &save);
	if (!file)
		die("'%s': no file", arg);
	while ((opt = strtok_r(NULL, ":", &save))) {
		if (!strcmp(opt, "colour") || !strcmp(opt, "grey") || !strcmp(opt, "false") ||
		    !strcmp(opt, "vector")) {
			map = opt;
		} else if (!strncmp(opt, "range=", 6)) {
			float r[2];

			parse_floats(opt + 6, "range", r, 2);
			if (!(r[0] < r[1]))
				die("'%s': range=%s is empty (LO < HI)", cell->label, opt + 6);
			cell->has_range = 1;
			cell->lo = r[0];
			cell->hi = r[1];
		} else if (!chans) {
			chans = opt;
		} else {
			die("'%s': '%s' is neither a map (colour, grey, false, vector) nor "
			    "range=LO,HI", cell->label, opt);
		}
	}
	if (rf_picture_read(&pic, file, err, sizeof(err)) < 0)
		die("%s", err);
	px = rf_picture_pixels(pic);
	if (chans) {
		char *name, *s2 = NULL;

		for (name = strtok_r(chans, ",", &s2); name; name = strtok_r(NULL, ",", &s2)) {
			int k = rf_picture_find_channel(pic, name);

			if (k < 0)
				die("'%s' has no channel '%s'", file, name);
			if (n == 4)
				die("'%s': at most 4 channels a cell", cell->label);
			idx[n++] = k;
		}
	} else if (rf_picture_find_channel(pic, "R") >= 0 && rf_picture_find_channel(pic, "G") >= 0 &&
	           rf_picture_find_channel(pic, "B") >= 0) {
		idx[0] = rf_picture_find_channel(pic, "R");
		idx[1] = rf_picture_find_channel(pic, "G");
		idx[2] = rf_picture_find_channel(pic, "B");
		n = 3;
	} else if (rf_picture_find_channel(pic, "spec.R") >= 0) {
		idx[0] = rf_picture_find_channel(pic, "spec.R");
		idx[1] = rf_picture_find_channel(pic, "spec.G");
		idx[2] = rf_picture_find_channel(pic, "spec.B");
		n = idx[1] >= 0 && idx[2] >= 0 ? 3 : 1;
	} else {
		idx[0] = 0;
		n = 1;
	}
	npix = rf_picture_width(pic) * rf_picture_height(pic);
	sel = emalloc(npix * n * sizeof(float));
	for (i = 0; i < npix; i++)
		for (c = 0; c < n; c++)
			sel[i * n + c] = px[i * rf_picture_nchannels(pic) + (size_t)idx[c]];
	cell->pixels = sel;
	cell->width = rf_picture_width(pic);
	cell->height = rf_picture_height(pic);
	cell->nchannels = n;
	/* what a map is when none is said: colour for R G B (or a layer's),
	 * a vector for X Y Z, grey for a grey image's Y, else false colour */
	if (map) {
		cell->map = !strcmp(map, "colour") ? RF_MONTAGE_COLOUR
		            : !strcmp(map, "grey") ? RF_MONTAGE_GREY
		            : !strcmp(map, "false") ? RF_MONTAGE_FALSE : RF_MONTAGE_VECTOR;
	} else if (n >= 3) {
		const char *last = rf_picture_channel(pic, (size_t)idx[0]);
		const char *dot = strrchr(last, '.');

		cell->map = dot && !strcmp(dot, ".X") ? RF_MONTAGE_VECTOR : RF_MONTAGE_COLOUR;
	} else {
		cell->map = !strcmp(rf_picture_channel(pic, (size_t)idx[0]), "Y") ? RF_MONTAGE_GREY
		                                                              : RF_MONTAGE_FALSE;
	}
	if ((cell->map == RF_MONTAGE_COLOUR || cell->map == RF_MONTAGE_VECTOR) && n < 3)
		die("'%s': a %s cell takes 3 channels, not %zu", cell->label,
		    cell->map == RF_MONTAGE_COLOUR ? "colour" : "vector", n);
	rf_picture_destroy(pic);
}

int
main(int argc, char **argv)
{
	static const char *const names[] = { "R", "G", "B" };
	struct rf_montage_options mo = { 0, 1.0f, RF_TONE_NONE, 1, 0 };
	struct rf_montage_cell *cells;
	const char *output = NULL;
	char err[1024];
	rf_image_writer *w;
	size_t n, k, width, height;
	float *px;
	int c, rc, type;

	cli_init(argc, argv);
	while ((c = getopt_long(argc, argv, "Vqo:e:", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'o': output = optarg; break;
		case 'e': mo.scale = (float)exp2(parse_number("e", optarg, -64, 64)); break;
		case OPT_COLUMNS: mo.columns = (size_t)parse_whole("columns", optarg, 1, 1024); break;
		case OPT_TONE:
			if (!strcmp(optarg, "none")) mo.tone = RF_TONE_NONE;
			else if (!strcmp(optarg, "filmic")) mo.tone = RF_TONE_FILMIC;
			else die("--tone: '%s' is not none or filmic", optarg);
			break;
		case OPT_SRGB:
			if (strcmp(optarg, "on") && strcmp(optarg, "off"))
				die("--srgb: '%s' is not on or off", optarg);
			mo.srgb = !strcmp(optarg, "on");
			break;
		case OPT_LABEL_SCALE:
			mo.label_scale = (size_t)parse_whole("label-scale", optarg, 1, 64);
			break;
		case OPT_HELP: help(); break;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	if (!output || optind >= argc)
		usage();
	if ((type = rf_image_type_for_path(output)) < 0 &&
	    rf_image_module_check(err, sizeof(err)) < 0)
		die("%s", err);
	if ((type = rf_image_type_for_path(output)) < 0)
		die("cannot write '%s': unknown image type", output);
	n = (size_t)(argc - optind);
	cells = ecalloc(n, sizeof(*cells));
	/* Large pictures take a second or more each to read: progress counts
	 * the files, each cell read and the montage written. */
	cli_progress_unit("file");
	cli_progress_frames(1);
	cli_progress_frame(n + 1);
	for (k = 0; k < n; k++) {
		load_cell(argv[optind + k], &cells[k]);
		cli_progress_rows(k + 1);
	}
	if ((rc = rf_montage(cells, n, &mo, &px, &width, &height)) == RF_ETOOBIG)
		cli_check_frame("the montage (fewer a row: --columns)", width, height);
	if (rc < 0)
		die_status(rc, NULL);
	/* the cells are display values already: 8 bits take them as they are */
	if ((rc = rf_image_writer_open(&w, output, width, height, 3, names,
	                               (enum rf_pixel_type)type, err, sizeof(err))) < 0)
		die_status(rc, err);
	if ((rc = rf_image_writer_write_rows(w, 0, height, px)) < 0)
		die_status(rc, rf_image_writer_error(w));
	if ((rc = rf_image_writer_close(w, err, sizeof(err))) < 0)
		die_status(rc, err);
	cli_progress_rows(n + 1);
	cli_progress_end();
	for (k = 0; k < n; k++)
		free((float *)cells[k].pixels);
	free(cells);
	free(px);
	return 0;
}
