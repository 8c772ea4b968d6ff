/* reflect-export: write a stream's channels as an image file. */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s -o FILE [-V] [-c CHANNELS] [-e STOPS] "
	        "[--tone=none|filmic] [--srgb=on|off] [--half] "
	        "[-H -x W -y H -c CHANNELS] [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

struct export_opts {
	const char *output;
	const char *channels; /* -c: "spec", "R,G,B", "all" */
	float scale;
	enum rf_tone tone;
	int srgb; /* -1: by file type */
	int half;
};

/* "spec" -> spec.R spec.G spec.B (or .X .Y .Z); "a,b" -> a b. */
static size_t
select_channels(const rf_header *h, const char *spec, int *map, size_t max)
{
	static const char *const colour[] = { "R", "G", "B" };
	static const char *const vector[] = { "X", "Y", "Z" };
	const char *p = spec;
	size_t n = 0, len, k;
	char name[RF_CHANNEL_NAME_MAX + 8];
	int c;

	if (!strcmp(spec, "all")) {
		for (k = 0; k < rf_header_nchannels(h) && k < max; k++)
			map[n++] = (int)k;
		return n;
	}
	while (*p) {
		len = strcspn(p, ",");
		if (len == 0 || len > RF_CHANNEL_NAME_MAX)
			die("-c: bad channel list '%s'", spec);
		snprintf(name, sizeof(name), "%.*s", (int)len, p);
		p += len + (p[len] == ',');
		if ((c = rf_header_find_channel(h, name)) >= 0) {
			if (n < max)
				map[n++] = c;
			continue;
		}
		/* A layer name stands for its three components. */
		for (k = 0; k < 3; k++) {
			char full[2 * RF_CHANNEL_NAME_MAX];
			int cc, cv;

			snprintf(full, sizeof(full), "%s.%s", name, colour[k]);
			cc = rf_header_find_channel(h, full);
			snprintf(full, sizeof(full), "%s.%s", name, vector[k]);
			cv = rf_header_find_channel(h, full);
			if (cc < 0 && cv < 0)
				die("input has no channel '%s' (nor %s.%s)", name, name,
				    colour[k]);
			if (n < max)
				map[n++] = cc >= 0 ? cc : cv;
		}
	}
	return n;
}

static const char *
default_channels(const rf_header *h)
{
	if (rf_header_find_channel(h, "R") >= 0 && rf_header_find_channel(h, "G") >= 0 &&
	    rf_header_find_channel(h, "B") >= 0)
		return "R,G,B";
	if (rf_header_find_channel(h, "spec.R") >= 0)
		return "spec";
	die("input has neither R G B nor spec.R spec.G spec.B; choose channels with -c");
}

/* The file name for a frame: one %d (or %0Nd) in the pattern is replaced
 * by the frame index; nothing else is interpreted. */
static void
output_name(char *buf, size_t size, const char *pattern, size_t frame)
{
	const char *pct = strchr(pattern, '%');
	const char *p;
	int width = 0;

	if (!pct) {
		snprintf(buf, size, "%s", pattern);
		return;
	}
	for (p = pct + 1; *p >= '0' && *p <= '9'; p++)
		width = width * 10 + (*p - '0');
	if (*p != 'd' || width > 12 || strchr(p, '%'))
		die("-o: '%s' may hold one %%d or %%0Nd and no other '%%'", pattern);
	snprintf(buf, size, "%.*s%0*zu%s", (int)(pct - pattern), pattern, width,
	         frame, p + 1);
}

static void
export_frame(struct cli_io *io, const struct export_opts *o, const rf_header *h,
             size_t frame)
{
	const char *names[RF_CHANNELS_MAX];
	int map[RF_CHANNELS_MAX];
	char path[4096], err[1024];
	size_t nch, ncomp = rf_header_nchannels(h), ncols = rf_header_ncols(h);
	size_t rows, y, n, i, c, ncolour;
	int type = rf_image_type_for_path(o->output), srgb, rc;
	rf_image_writer *w;
	float *in, *out;

	if (type < 0)
		die("cannot write '%s': unknown image type (use .exr, .hdr, .png, "
		    ".jpg or .tif)", o->output);
	if (type == RF_PIXEL_FLOAT && o->half)
		type = RF_PIXEL_HALF;
	nch = select_channels(h, o->channels ? o->channels : default_channels(h), map,
	                      RF_CHANNELS_MAX);
	if (type == RF_PIXEL_UINT8 && nch != 1 && nch != 3 && nch != 4)
		die("cannot write %zu channels to '%s': 8-bit images take 1, 3 or 4",
		    nch, o->output);
	for (c = 0; c < nch; c++)
		names[c] = rf_header_channel(h, (size_t)map[c]);
	if (type == RF_PIXEL_UINT8 && nch >= 3) {
		static const char *const rgba[] = { "R", "G", "B", "A" };

		for (c = 0; c < nch; c++)
			names[c] = rgba[c];
	}
	srgb = o->srgb >= 0 ? o->srgb : type == RF_PIXEL_UINT8;
	ncolour = nch == 4 ? 3 : nch;
	output_name(path, sizeof(path), o->output, frame);
	if ((rc = rf_image_writer_open(&w, path, ncols, rf_header_nrows(h), nch, names,
	                               (enum rf_pixel_type)type, err, sizeof(err))) < 0)
		die_status(rc, err);
	rows = rf_block_rows(ncols, ncomp, CLI_BLOCK_BYTES);
	if (rows > rf_header_nrows(h))
		rows = rf_header_nrows(h);
	in = emalloc(rows * ncols * ncomp * sizeof(float));
	out = emalloc(rows * ncols * nch * sizeof(float));
	for (y = 0; y < rf_header_nrows(h); y += n) {
		n = rf_header_nrows(h) - y < rows ? rf_header_nrows(h) - y : rows;
		cli_io_read(io, in, n);
		for (i = 0; i < n * ncols; i++)
			for (c = 0; c < nch; c++)
				out[i * nch + c] = in[i * ncomp + (size_t)map[c]];
		if (type == RF_PIXEL_UINT8)
			rf_display_encode(out, n * ncols, nch, ncolour, o->scale, o->tone, srgb);
		else if (o->scale != 1.0f || o->tone != RF_TONE_NONE || srgb)
			rf_display_encode(out, n * ncols, nch, ncolour, o->scale, o->tone, srgb);
		if ((rc = rf_image_writer_write_rows(w, y, n, out, err, sizeof(err))) < 0)
			die_status(rc, err);
	}
	if ((rc = rf_image_writer_close(w, err, sizeof(err))) < 0)
		die_status(rc, err);
	free(in);
	free(out);
}

int
main(int argc, char **argv)
{
	static const struct option long_options[] = {
		{ "tone", required_argument, NULL, 'T' },
		{ "srgb", required_argument, NULL, 'S' },
		{ "half", no_argument, NULL, 'F' },
		{ "help", no_argument, NULL, 'Q' },
		{ NULL, 0, NULL, 0 },
	};
	struct export_opts o = { NULL, NULL, 1.0f, RF_TONE_NONE, -1, 0 };
	struct cli_io io = { 0 };
	const rf_header *h;
	const char *raw_channels = NULL;
	size_t frames = 0;
	double stops;
	char *end;
	int c;

	cli_init(argc, argv);
	while ((c = getopt_long(argc, argv, "Vo:c:e:Hx:y:", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'o': o.output = optarg; break;
		case 'c': o.channels = optarg; raw_channels = optarg; break;
		case 'e':
			stops = strtod(optarg, &end);
			if (end == optarg || *end || !isfinite(stops) || fabs(stops) > 64)
				die("-e: '%s' is not an exposure in stops in [-64, 64]", optarg);
			o.scale = (float)exp2(stops);
			break;
		case 'T':
			if (!strcmp(optarg, "none")) o.tone = RF_TONE_NONE;
			else if (!strcmp(optarg, "filmic")) o.tone = RF_TONE_FILMIC;
			else die("--tone: '%s' is not none or filmic", optarg);
			break;
		case 'S':
			if (!strcmp(optarg, "on")) o.srgb = 1;
			else if (!strcmp(optarg, "off")) o.srgb = 0;
			else die("--srgb: '%s' is not on or off", optarg);
			break;
		case 'F': o.half = 1; break;
		case 'H': case 'x': case 'y':
			cli_io_option(&io, c, optarg);
			break;
		case 'Q':
			printf("usage: %s -o FILE [options] [file]\n"
			       "Writes the channels of each frame as an image (EXR, HDR, PNG, JPEG,\n"
			       "TIFF). -c spec | R,G,B | all picks channels; -e exposure in stops;\n"
			       "--tone=filmic; --srgb=on|off (on for 8-bit files); --half for EXR.\n"
			       "A %%d in FILE numbers the frames. See reflect-export(1).\n", argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default: usage();
		}
	}
	if (!o.output || argc - optind > 1)
		usage();
	if (io.headerless) {
		io.channels = raw_channels;
		o.channels = NULL;
	}
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &h)) {
		if (frames && !strchr(o.output, '%'))
			die("the stream has more than one frame: put %%d in the output "
			    "name ('%s') to number them", o.output);
		export_frame(&io, &o, h, frames++);
	}
	cli_io_close(&io);
	return 0;
}
