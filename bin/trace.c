/* reflect-trace: the ground truth of a scene, traced. */
#include <getopt.h>
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "reflect/scene.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-V] [-x WIDTH] [-y HEIGHT] " CLI_FRAME_USAGE " "
	        CLI_PROGRESS_USAGE " " CLI_REGION_USAGE " [-j THREADS] [--samples=N] [--masking=separable|correlated] "
	        "[--objects=hidden|visible] [--seed=N] [--first=N --total=N] [--halves] "
	        "[-f a|f] [-h] "
	        "[scene]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

enum { OPT_SAMPLES = 256, OPT_MASKING, OPT_OBJECTS, OPT_SEED, OPT_HALVES, OPT_FIRST,
       OPT_TOTAL, OPT_HELP };

static const struct option long_options[] = {
	CLI_FRAME_OPTIONS,
	CLI_PROGRESS_OPTION,
	CLI_REGION_OPTIONS,
	{ "samples", required_argument, NULL, OPT_SAMPLES },
	{ "masking", required_argument, NULL, OPT_MASKING },
	{ "objects", required_argument, NULL, OPT_OBJECTS },
	{ "seed", required_argument, NULL, OPT_SEED },
	{ "halves", no_argument, NULL, OPT_HALVES },
	{ "first", required_argument, NULL, OPT_FIRST },
	{ "total", required_argument, NULL, OPT_TOTAL },
	{ "help", no_argument, NULL, OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static void
help(void)
{
	printf("usage: %s [options] [scene]\n"
	       "Renders a scene's ground truth: the camera's pixel-centre rays, and on\n"
	       "reflective surfaces the exact one-bounce integral of a white GGX lobe\n"
	       "against the scene's emission.  Writes R G B mask objid.\n"
	       "See reflect-trace(1).\n"
	       "  -x W -y H          image size (default 640x360)\n"
	       CLI_FRAME_HELP
	       CLI_REGION_HELP
	       CLI_PROGRESS_HELP
	       "  --samples=N        samples a pixel (1024)\n"
	       "  --masking=separable|correlated  Smith G (separable, as Cycles 3.4)\n"
	       "  --objects=hidden|visible  reflective objects in reflected rays\n"
	       "  --seed=N   --halves  half1.R G B and half2.R G B too\n"
	       "  --first=I --total=T  samples I .. I+N-1 of a run of T (a split)\n"
	       "  -j N  threads   -f a|f  output format   -h  no header   -V  versions\n",
	       argv0);
	fshut(stdout, "<stdout>");
	exit(0);
}

static rf_header *
frame_header(const rf_scene *s, const rf_tracer *t, const struct rf_camera *cam,
             size_t frame, size_t width, size_t height, const size_t rect[4],
             unsigned samples)
{
	rf_header *h = cli_frame_header(s, cam, frame, rect[2] - rect[0], rect[3] - rect[1]);
	char buf[32];
	size_t k;

	for (k = 0; k < rf_tracer_nchannels(t); k++)
		if (rf_header_add_channel(h, rf_tracer_channel(t, k)) < 0)
			die_sys("out of memory");
	cli_region_key(h, rect, width, height);
	snprintf(buf, sizeof(buf), "%u", samples);
	if (rf_header_set(h, "TRACE_SAMPLES", buf) < 0 ||
	    rf_header_set(h, RF_KEY_SAMPLES, buf) < 0)
		die_sys("out of memory");
	return h;
}

struct tile {
	rf_tracer *t;
	size_t y0; /* the tile's first row in the full frame */
};

static int
trace_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	const struct tile *tl = arg;
	int rc = rf_tracer_render(tl->t, out, tl->y0 + y, n);

	(void)in;
	if (rc < 0)
		die_status(rc, NULL);
	return 0;
}

int
main(int argc, char **argv)
{
	struct rf_trace_options o;
	struct cli_io io = { 0 };
	struct rf_writer_options wopt;
	struct cli_frames frames;
	struct rf_camera start, cam;
	const char *threads = NULL, *file;
	size_t width = 640, height = 360, rows, frame, rect[4];
	struct tile tile;
	char err[1024];
	rf_tracer *t;
	rf_scene *s;
	int c, rc;

	cli_init(argc, argv);
	cli_frames_init(&frames);
	rf_trace_options_init(&o);
	while ((c = getopt_long(argc, argv, "qVx:y:n:j:f:h", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'x': width = parse_count(optarg, 'x', 1, RF_FRAME_SIDE_MAX); break;
		case 'y': height = parse_count(optarg, 'y', 1, RF_FRAME_SIDE_MAX); break;
		case 'j': threads = optarg; break;
		case 'f': case 'h':
		case CLI_OPT_REGION: case CLI_OPT_TILE: case CLI_OPT_HALO:
			cli_io_option(&io, c, optarg);
			break;
		case OPT_SAMPLES: o.samples = (unsigned)parse_whole("samples", optarg, 1, 16777216); break;
		case OPT_MASKING:
			if (strcmp(optarg, "separable") && strcmp(optarg, "correlated"))
				die("--masking: '%s' is not separable or correlated", optarg);
			o.masking_correlated = !strcmp(optarg, "correlated");
			break;
		case OPT_OBJECTS:
			if (strcmp(optarg, "hidden") && strcmp(optarg, "visible"))
				die("--objects: '%s' is not hidden or visible", optarg);
			o.objects_visible = !strcmp(optarg, "visible");
			break;
		case OPT_SEED: o.seed = (uint32_t)parse_whole("seed", optarg, 0, 4294967295.0); break;
		case OPT_HALVES: o.halves = 1; break;
		case OPT_FIRST: o.first = (unsigned)parse_whole("first", optarg, 0, 16777215); break;
		case OPT_TOTAL: o.total = (unsigned)parse_whole("total", optarg, 1, 16777216); break;
		case OPT_HELP: help(); break;
		default:
			if (!cli_frames_option(&frames, c, optarg) && !cli_progress_option(c))
				usage();
		}
	}
	if (argc - optind > 1)
		usage();
	file = cli_input_or_default(optind < argc ? argv[optind] : NULL);
	cli_frames_check(&frames);
	if (o.halves && o.samples < 2)
		die("--halves: %u sample%s cannot make two halves (2 or more for halves)",
		    o.samples, o.samples == 1 ? "" : "s");
	if ((unsigned long)o.first + o.samples > (o.total ? o.total : o.samples))
		die("--first=%u and --samples=%u reach past --total=%u: a run's samples are "
		    "first .. first + samples - 1 of the total", o.first, o.samples,
		    o.total ? o.total : o.samples);
	cli_check_frame("-x -y", width, height);
	/* a tile's pixels are the full frame's: the same rays and seeds */
	cli_region_rect(&io.region, width, height, 1, rect);
	s = cli_load_scene(file);
	o.nthreads = cli_threads(threads);
	if ((rc = rf_tracer_create(&t, s, width, height, &o, err, sizeof(err))) < 0) {
		rf_scene_destroy(s);
		die_status(rc, err);
	}
	wopt.format = io.format;
	wopt.no_header = io.no_header;
	cli_widen_pipe(STDOUT_FILENO);
	if ((rc = rf_writer_open(&io.writer, stdout, "<stdout>", &wopt)) < 0)
		die_status(rc, NULL);
	if ((rc = rf_tracer_set_columns(t, rect[0], rect[2] - rect[0])) < 0)
		die_status(rc, NULL);
	rows = rf_block_rows(rect[2] - rect[0], rf_tracer_nchannels(t), CLI_BLOCK_BYTES);
	if (rows > rect[3] - rect[1])
		rows = rect[3] - rect[1];
	rows = cli_progress_block(rows, rect[3] - rect[1]);
	rf_scene_camera(s, &start);
	cli_progress_frames(frames.last - frames.first + 1);
	for (frame = frames.first; frame <= frames.last; frame++) {
		rf_header *h;

		rf_camera_at_frame(&start, &frames.path, frame, frames.count, &cam);
		if (rf_camera_check(&cam, err, sizeof(err)) < 0 ||
		    (rc = rf_tracer_set_camera(t, &cam)) < 0)
			die("frame %zu: %s", frame, err);
		h = frame_header(s, t, &cam, frame, width, height, rect, o.samples);
		cli_io_begin(&io, h);
		rf_header_destroy(h);
		tile.t = t;
		tile.y0 = rect[1];
		cli_blocks(&io, rect[3] - rect[1], rows, 0,
		           (rect[2] - rect[0]) * rf_tracer_nchannels(t), trace_block, &tile);
		cli_io_end_frame(&io);
	}
	rf_tracer_destroy(t);
	rf_scene_destroy(s);
	cli_io_close(&io);
	return 0;
}
