/* reflect-export: write a stream's channels as an image file. */
#include <ctype.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s -o FILE [-V] " CLI_PROGRESS_USAGE " [-c CHANNELS] [-e STOPS] "
	        "[--tone=none|filmic] [--srgb=on|off] [--depth=8|16|half|float] "
	        "[--half] [--downsample=N] [--filter=box|gaussian[:SIGMA]] "
	        "[-H -x W -y H -c CHANNELS] [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

/* Bits of the pixel types a file format stores. */
#define D8 (1u << RF_PIXEL_UINT8)
#define D16 (1u << RF_PIXEL_UINT16)
#define DHALF (1u << RF_PIXEL_HALF)
#define DFLOAT (1u << RF_PIXEL_FLOAT)

/* What each file type takes: the pixel types it stores (its default comes
 * from rf_image_type_for_path) and, as bit n, the channel counts n it
 * holds at its integer depths (or, for .hdr, at all); 0 means any. */
static const struct format {
	const char *ext;
	unsigned depths;
	unsigned counts;
	int nonneg; /* stores no negative values (RGBE) */
} formats[] = {
	{ "exr", DHALF | DFLOAT, 0, 0 },
	{ "hdr", DFLOAT, 1u << 3, 1 },
	{ "png", D8 | D16, 1u << 1 | 1u << 3 | 1u << 4, 0 },
	{ "jpg", D8, 1u << 1 | 1u << 3, 0 },
	{ "jpeg", D8, 1u << 1 | 1u << 3, 0 },
	{ "tif", D8 | D16 | DHALF | DFLOAT, 1u << 1 | 1u << 3 | 1u << 4, 0 },
	{ "tiff", D8 | D16 | DHALF | DFLOAT, 1u << 1 | 1u << 3 | 1u << 4, 0 },
	{ "bmp", D8, 1u << 1 | 1u << 3 | 1u << 4, 0 },
	{ "tga", D8, 1u << 1 | 1u << 3 | 1u << 4, 0 },
	{ "ppm", D8 | D16, 1u << 1 | 1u << 3, 0 },
	{ NULL, 0, 0, 0 },
};

/* Indexed by enum rf_pixel_type. */
static const char *const depth_names[] = { "float", "half", "8", "16" };

struct export_opts {
	const char *output;
	const char *channels; /* -c: "spec", "R,G,B", "all" */
	float scale;          /* 2^stops */
	enum rf_tone tone;
	int srgb;  /* -1: on for 8- and 16-bit files, off for half and float */
	int depth; /* -1: the file type's own; else an rf_pixel_type */
	long downsample; /* -1: the frame's SUPERSAMPLE key, else 1 */
	enum rf_resolve_filter filter;
	double sigma;
	/* Resolved once from the output name. */
	const struct format *format;
	int type;
	int to_stdout; /* -o -, png:-, exr:-: through a file of our own */
};

static int
is_integer(int type)
{
	return type == RF_PIXEL_UINT8 || type == RF_PIXEL_UINT16;
}

/* The output's file type and pixel type, checked before any data is read. */
static void
resolve_format(struct export_opts *o)
{
	const char *dot = strrchr(o->output, '.');
	char ext[8], err[1024];
	size_t i;

	/* libreflect writes PNG and OpenEXR itself; other types need the
	 * image module, and when it cannot be loaded, that is the error. */
	o->type = rf_image_type_for_path(o->output);
	if (o->type < 0 && rf_image_module_check(err, sizeof(err)) < 0)
		die("%s", err);
	o->format = NULL;
	if (dot && o->type >= 0 && strlen(dot + 1) < sizeof(ext)) {
		for (i = 0; dot[1 + i]; i++)
			ext[i] = (char)tolower((unsigned char)dot[1 + i]);
		ext[i] = '\0';
		for (i = 0; formats[i].ext; i++)
			if (!strcmp(formats[i].ext, ext))
				o->format = &formats[i];
	}
	if (!o->format)
		die("cannot write '%s': unknown image type (use .exr, .hdr, .png, "
		    ".jpg, .tif, .bmp, .tga or .ppm)", o->output);
	if (o->depth >= 0) {
		if (!(o->format->depths & (1u << o->depth)))
			die("cannot write '%s': a .%s file does not store %s%s pixels",
			    o->output, o->format->ext, depth_names[o->depth],
			    is_integer(o->depth) ? "-bit" : "");
		o->type = o->depth;
	}
}

/* Appends channel c to the selection. */
static void
pick(int *map, size_t *n, int c)
{
	if (*n >= RF_CHANNELS_MAX)
		die("-c: more than %d channels", RF_CHANNELS_MAX);
	map[(*n)++] = c;
}

/* "all"; or names separated by commas, where a layer name such as "spec"
 * stands for spec.R spec.G spec.B (or spec.X spec.Y spec.Z). */
static size_t
select_channels(const rf_header *h, const char *spec, int *map)
{
	static const char *const colour[] = { "R", "G", "B" };
	static const char *const vector[] = { "X", "Y", "Z" };
	const char *p = spec;
	size_t n = 0, len, k;
	char name[RF_CHANNEL_NAME_MAX + 1];
	int c;

	if (!strcmp(spec, "all")) {
		for (k = 0; k < rf_header_nchannels(h); k++)
			pick(map, &n, (int)k);
		return n;
	}
	while (*p) {
		len = strcspn(p, ",");
		if (len == 0 || len > RF_CHANNEL_NAME_MAX)
			die("-c: bad channel list '%s' (names separated by commas, "
			    "a layer name such as spec, or all)", spec);
		memcpy(name, p, len);
		name[len] = '\0';
		p += len + (p[len] == ',');
		if ((c = rf_header_find_channel(h, name)) >= 0) {
			pick(map, &n, c);
			continue;
		}
		/* A layer name stands for its three components. */
		for (k = 0; k < 3; k++) {
			char full[RF_CHANNEL_NAME_MAX + 3];
			int cc, cv;

			snprintf(full, sizeof(full), "%s.%s", name, colour[k]);
			cc = rf_header_find_channel(h, full);
			snprintf(full, sizeof(full), "%s.%s", name, vector[k]);
			cv = rf_header_find_channel(h, full);
			if (cc < 0 && cv < 0) {
				if (k == 0)
					die("input has no channel '%s' (nor %s.R %s.G "
					    "%s.B or %s.X %s.Y %s.Z)", name, name, name,
					    name, name, name, name);
				die("input has no channel '%s.%s' (nor %s.%s) for "
				    "layer '%s'", name, colour[k], name, vector[k], name);
			}
			pick(map, &n, cc >= 0 ? cc : cv);
		}
	}
	if (!n)
		die("-c: no channel chosen");
	return n;
}

static const char *
default_channels(const rf_header *h)
{
	if (rf_header_find_channel(h, "R") >= 0 && rf_header_find_channel(h, "G") >= 0 &&
	    rf_header_find_channel(h, "B") >= 0)
		return "R,G,B";
	if (rf_header_find_channel(h, "spec.R") >= 0 &&
	    rf_header_find_channel(h, "spec.G") >= 0 &&
	    rf_header_find_channel(h, "spec.B") >= 0)
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

static int
is_alpha_name(const char *name)
{
	size_t n = strlen(name);

	return !strcmp(name, "A") || (n > 2 && !strcmp(name + n - 2, ".A"));
}

/* How many times smaller the picture is than the frame: --downsample, or
 * the SUPERSAMPLE key reflect-gbuffer --supersample wrote. */
static size_t
resolve_factor(const struct export_opts *o, const rf_header *h, size_t frame)
{
	size_t f = o->downsample > 0 ? (size_t)o->downsample : 1;

	if (o->downsample < 0 && rf_header_supersample(h, &f) < 0)
		die("frame %zu: header key %s='%s' is not a whole number in [1, %d] that "
		    "divides the %zux%zu frame's sides", frame, RF_KEY_SUPERSAMPLE,
		    rf_header_get(h, RF_KEY_SUPERSAMPLE), RF_SUPERSAMPLE_MAX, rf_header_ncols(h),
		    rf_header_nrows(h));
	if (rf_header_ncols(h) % f || rf_header_nrows(h) % f)
		die("frame %zu: a %zux%zu frame does not downsample by %zu (its sides are "
		    "not multiples of it); choose another --downsample", frame,
		    rf_header_ncols(h), rf_header_nrows(h), f);
	return f;
}

/* A block of rows on its way to the file: the chosen channels, resolved
 * when the frame is supersampled, encoded. */
struct export_block {
	const struct export_opts *o;
	rf_image_writer *w;
	rf_downsampler *down; /* NULL: the frame is the picture */
	const int *map;
	const unsigned char *alpha;
	size_t nch, ncomp, ncols, out_cols, out_y;
	struct rf_file_encoding enc;
	float *out, *resolved;
};

static int
export_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	struct export_block *eb = arg;
	float *rows = eb->out;
	size_t i, c;
	int rc;

	(void)out;
	(void)y;
	for (i = 0; i < n * eb->ncols; i++)
		for (c = 0; c < eb->nch; c++)
			eb->out[i * eb->nch + c] = in[i * eb->ncomp + (size_t)eb->map[c]];
	if (eb->down) {
		if ((rc = rf_downsampler_push(eb->down, eb->out, n, eb->resolved, &n)) < 0)
			die_status(rc, NULL);
		rows = eb->resolved;
	}
	if (!n)
		return 0;
	rf_file_encode(rows, n * eb->out_cols, eb->nch, eb->alpha, &eb->enc);
	if ((rc = rf_image_writer_write_rows(eb->w, eb->out_y, n, rows)) < 0)
		die_status(rc, rf_image_writer_error(eb->w));
	eb->out_y += n;
	return 0;
}

/* The made file to standard output. */
static void
copy_out(const char *path)
{
	char buf[1 << 16];
	FILE *fp = fopen(path, "rb");
	size_t n;

	if (!fp)
		die("cannot open '%s':", path);
	while ((n = fread(buf, 1, sizeof(buf), fp)) > 0)
		if (fwrite(buf, 1, n, stdout) != n)
			die("cannot write to standard output:");
	fclose(fp);
	if (fflush(stdout) != 0)
		die("cannot write to standard output:");
}

static void
export_frame(struct cli_io *io, const struct export_opts *o, const rf_header *h,
             size_t frame)
{
	static int map[RF_CHANNELS_MAX];
	static const char *names[RF_CHANNELS_MAX];
	static unsigned char alpha[RF_CHANNELS_MAX], nearest[RF_CHANNELS_MAX];
	char path[4096], err[1024];
	size_t nch, ncomp = rf_header_nchannels(h), ncols = rf_header_ncols(h);
	size_t nrows = rf_header_nrows(h), rows, c, k, factor = resolve_factor(o, h, frame);
	int integer = is_integer(o->type), srgb, rc;
	struct export_block eb;
	rf_output *scratch = NULL;
	rf_image_writer *w;

	nch = select_channels(h, o->channels ? o->channels : default_channels(h), map);
	if (o->format->counts && (integer || !(o->format->depths & (D8 | D16))) &&
	    (nch > 31 || !(o->format->counts & (1u << nch))))
		die("cannot write %zu channels to '%s': %s%s.%s files take %s "
		    "channels; choose them with -c", nch, o->output,
		    integer ? depth_names[o->type] : "", integer ? "-bit " : "",
		    o->format->ext, !integer ? "3" : o->format->counts & (1u << 4)
		    ? "1, 3 or 4" : "1 or 3");
	for (c = 0; c < nch; c++) {
		names[c] = rf_header_channel(h, (size_t)map[c]);
		alpha[c] = (unsigned char)is_alpha_name(names[c]);
		/* An average of object numbers is no object's. */
		nearest[c] = !strcmp(names[c], "objid");
	}
	if (integer && nch >= 3) {
		/* 8- and 16-bit files are pictures: R G B and alpha. */
		static const char *const rgba[] = { "R", "G", "B", "A" };

		for (c = 0; c < nch; c++) {
			names[c] = rgba[c];
			alpha[c] = c == 3;
		}
	}
	if (!strcmp(o->format->ext, "exr"))
		for (c = 0; c < nch; c++)
			for (k = 0; k < c; k++)
				if (!strcmp(names[c], names[k]))
					die("-c: channel '%s' is chosen twice; an EXR file "
					    "holds each name once", names[c]);
	srgb = o->srgb >= 0 ? o->srgb : integer;
	if (o->to_stdout) {
		/* OpenEXR seeks back to its offsets: the image is made in a
		 * file of our own, removed however the tool ends
		 * (lib/util/output.c), then copied out */
		const char *dir = getenv("TMPDIR");

		snprintf(path, sizeof(path), "%s/reflect-export.%s", dir && *dir ? dir : "/tmp",
		         o->format->ext);
		if ((rc = rf_output_begin(&scratch, path, err, sizeof(err))) < 0)
			die_status(rc, err);
		snprintf(path, sizeof(path), "%s", rf_output_file(scratch));
	} else {
		output_name(path, sizeof(path), o->output, frame);
	}
	if ((rc = rf_image_writer_open(&w, path, ncols / factor, nrows / factor, nch, names,
	                               (enum rf_pixel_type)o->type, err,
	                               sizeof(err))) < 0)
		die_status(rc, err);
	rows = rf_block_rows(ncols, ncomp, CLI_BLOCK_BYTES);
	if (rows > nrows)
		rows = nrows;
	eb.o = o;
	eb.w = w;
	eb.map = map;
	eb.alpha = alpha;
	eb.nch = nch;
	eb.ncomp = ncomp;
	eb.ncols = ncols;
	eb.out_cols = ncols / factor;
	eb.out_y = 0;
	eb.down = NULL;
	eb.resolved = NULL;
	if (factor > 1) {
		if ((rc = rf_downsampler_create(&eb.down, ncols, nrows, nch, factor, o->filter,
		                                o->sigma, nearest)) < 0)
			die_status(rc, NULL);
		eb.resolved = emalloc(rf_downsampler_max_rows(eb.down, rows) * eb.out_cols *
		                      nch * sizeof(float));
	}
	eb.enc.scale = o->scale;
	eb.enc.tone = o->tone;
	eb.enc.srgb = srgb;
	eb.enc.integer = integer;
	eb.enc.nonneg = o->format->nonneg;
	eb.out = emalloc(rows * ncols * nch * sizeof(float));
	rc = cli_blocks(io, nrows, rows, ncols * ncomp, 0, export_block, &eb);
	free(eb.out);
	free(eb.resolved);
	rf_downsampler_destroy(eb.down);
	if (rc < 0)
		cli_io_read_failed(io, rc);
	if ((rc = rf_image_writer_close(w, err, sizeof(err))) < 0)
		die_status(rc, err);
	if (o->to_stdout) {
		copy_out(path);
		rf_output_discard(scratch);
	} else {
		static char made[4096];

		snprintf(made, sizeof(made), "%s", path);
		io->made = made;
	}
}

int
main(int argc, char **argv)
{
	static const struct option long_options[] = {
		{ "tone", required_argument, NULL, 'T' },
		{ "srgb", required_argument, NULL, 'S' },
		{ "depth", required_argument, NULL, 'D' },
		{ "half", no_argument, NULL, 'F' },
		{ "downsample", required_argument, NULL, 'W' },
		{ "filter", required_argument, NULL, 'L' },
		{ "help", no_argument, NULL, 'Q' },
		CLI_PROGRESS_OPTION,
		{ NULL, 0, NULL, 0 },
	};
	struct export_opts o = { NULL, NULL, 1.0f, RF_TONE_NONE, -1, -1, -1, RF_RESOLVE_BOX,
	                         RF_RESOLVE_SIGMA_DEFAULT, NULL, 0, 0 };
	struct cli_io io = { 0 };
	const rf_header *h;
	const char *channels = NULL;
	size_t frames = 0, k;
	double stops;
	char *end;
	int c;

	cli_init(argc, argv);
	while ((c = getopt_long(argc, argv, "qVo:c:e:Hx:y:", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'o': o.output = optarg; break;
		case 'c': channels = optarg; break;
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
		case 'D':
			for (k = 0; k < 4 && strcmp(optarg, depth_names[k]); k++)
				;
			if (k == 4)
				die("--depth: '%s' is not 8, 16, half or float", optarg);
			o.depth = (int)k;
			break;
		case 'F': o.depth = RF_PIXEL_HALF; break;
		case 'W':
			o.downsample = (long)parse_whole("downsample", optarg, 1, 16);
			break;
		case 'L':
			if (!strcmp(optarg, "box")) {
				o.filter = RF_RESOLVE_BOX;
			} else if (!strcmp(optarg, "gaussian")) {
				o.filter = RF_RESOLVE_GAUSSIAN;
			} else if (!strncmp(optarg, "gaussian:", 9)) {
				o.filter = RF_RESOLVE_GAUSSIAN;
				o.sigma = parse_number("filter=gaussian", optarg + 9,
				                       RF_RESOLVE_SIGMA_MIN, RF_RESOLVE_SIGMA_MAX);
			} else {
				die("--filter: '%s' is not box or gaussian[:SIGMA]", optarg);
			}
			break;
		case 'H': case 'x': case 'y':
			cli_io_option(&io, c, optarg);
			break;
		case 'Q':
			printf("usage: %s -o FILE [options] [file]\n"
			       "Writes the channels of each frame as an image: PNG with libpng, EXR\n"
			       "with OpenEXR, and HDR, JPEG, TIFF, BMP, TGA, PPM through OpenImageIO\n"
			       "(loaded for those only). See reflect-export(1).\n"
			       "  -o FILE  the image; a %%d in FILE numbers the frames; - (or png:-,\n"
			       "           exr:-) writes it to standard output\n"
			       "  -c spec | R,G,B | all  the channels (default R,G,B, else spec)\n"
			       "  -e STOPS  exposure   --tone=none|filmic   --srgb=on|off\n"
			       "  --depth=8|16|half|float  pixel type   --half  same as --depth=half\n"
			       "  --downsample=N  resolve N x N samples a pixel (default: the\n"
			       "                  frame's SUPERSAMPLE, from reflect-gbuffer)\n"
			       "  --filter=box|gaussian[:SIGMA]  its filter (SIGMA in pixels, 0.4)\n"
			       "  -H -x W -y H -c CHANNELS  headerless input (all channels written)\n"
			       "  -V  versions\n"
			       CLI_PROGRESS_HELP, argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	if (!o.output || argc - optind > 1)
		usage();
	if (io.headerless) {
		/* -c names the input's channels; all of them are written. */
		if (channels)
			cli_io_option(&io, 'c', channels);
		o.channels = "all";
	} else {
		o.channels = channels;
	}
	/* standard output: PNG unless it says EXR */
	if (!strcmp(o.output, "-") || !strcmp(o.output, "png:-") || !strcmp(o.output, "exr:-")) {
		o.to_stdout = 1;
		o.output = strcmp(o.output, "exr:-") ? "<stdout>.png" : "<stdout>.exr";
		cli_refuse_terminal("an image");
	}
	resolve_format(&o);
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &h)) {
		if (frames && o.to_stdout)
			die("the stream has more than one frame, and standard output takes "
			    "one image");
		if (frames && !strchr(o.output, '%'))
			die("the stream has more than one frame: put %%d in the output "
			    "name ('%s') to number them", o.output);
		export_frame(&io, &o, h, frames++);
	}
	cli_io_close(&io);
	return 0;
}
