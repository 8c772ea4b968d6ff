/* reflect-gbuffer: ray cast a scene into a G-buffer stream. */
#include <getopt.h>
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "reflect/scene.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-vV] [-x WIDTH] [-y HEIGHT] " CLI_FRAME_USAGE " "
	        CLI_PROGRESS_USAGE " " CLI_REGION_USAGE " [-j THREADS] [-c CHANNELS] "
	        "[--supersample=N] [-f a|f] [-h] "
	        "[--print-default-scene] [scene]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

enum { OPT_SUPERSAMPLE = 256, OPT_PRINT_DEFAULT, OPT_HELP };

static const struct option long_options[] = {
	CLI_FRAME_OPTIONS,
	CLI_PROGRESS_OPTION,
	CLI_REGION_OPTIONS,
	{ "supersample", required_argument, NULL, OPT_SUPERSAMPLE },
	{ "print-default-scene", no_argument, NULL, OPT_PRINT_DEFAULT },
	{ "help", no_argument, NULL, OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static void
help(void)
{
	printf("usage: %s [options] [scene]\n"
	       "Ray casts a scene (reflect-scene(5); the embedded default when none is\n"
	       "given) into a G-buffer stream: P N Ng V roughness metallic albedo mask\n"
	       "objid depth, with the camera and probes as header keys.\n"
	       "See reflect-gbuffer(1).\n"
	       "  -x W -y H          image size (default 640x360)\n"
	       CLI_FRAME_HELP
	       CLI_REGION_HELP
	       CLI_PROGRESS_HELP
	       "  --supersample=N    N x N samples a pixel: a frame N times larger,\n"
	       "                     resolved by reflect-export\n"
	       "  -c CHANNELS        channels to write, e.g. P,N,V,roughness\n"
	       "  -j N  threads   -v  flag a camera inside an object   -V  versions\n"
	       "  -f a|f  output format   -h  no output header\n"
	       "  --print-default-scene  print the embedded scene and exit\n", argv0);
	fshut(stdout, "<stdout>");
	exit(0);
}

static rf_header *
frame_header(const rf_scene *s, const rf_gbuffer *g, const struct rf_camera *cam,
             size_t frame, size_t width, size_t height, const size_t rect[4],
             size_t supersample)
{
	rf_header *h = cli_frame_header(s, cam, frame, rect[2] - rect[0], rect[3] - rect[1]);
	char buf[32];
	size_t i;

	for (i = 0; i < rf_gbuffer_nchannels(g); i++)
		if (rf_header_add_channel(h, rf_gbuffer_channel(g, i)) < 0)
			die_sys("out of memory");
	cli_region_key(h, rect, width, height);
	snprintf(buf, sizeof(buf), "%zu", supersample);
	if (supersample > 1 && rf_header_set(h, RF_KEY_SUPERSAMPLE, buf) < 0)
		die_sys("out of memory");
	return h;
}

/* -v: a camera inside an object sees that object's inside. */
static void
flag_camera(const rf_scene *s, const struct rf_camera *cam, const char *file,
            size_t frame)
{
	const double *p = cam->position;
	int id = rf_scene_inside(s, p);

	if (id)
		warn("frame %zu: the camera at (%g %g %g) is inside %s %d (%s:%zu)", frame,
		     p[0], p[1], p[2], rf_scene_object_kind(s, id), id, file,
		     rf_scene_object_line(s, id));
	if (!rf_scene_in_room(s, p))
		warn("frame %zu: the camera at (%g %g %g) is outside the room; rays that "
		     "miss it see nothing (objid 0)", frame, p[0], p[1], p[2]);
}

struct tile {
	rf_gbuffer *g;
	size_t y0; /* the tile's first row in the full frame */
};

/* Rows y..y+n of the tile while the block before is being written. */
static int
render_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	const struct tile *t = arg;
	int rc = rf_gbuffer_render(t->g, out, t->y0 + y, n);

	(void)in;
	if (rc < 0)
		die_status(rc, NULL);
	return 0;
}

int
main(int argc, char **argv)
{
	struct cli_io io = { 0 };
	struct cli_frames frames;
	struct rf_camera start, cam;
	struct rf_writer_options wopt;
	const char *channels = NULL, *threads = NULL, *file;
	size_t width = 640, height = 360, frame, rows, supersample = 1, rect[4];
	char err[1024];
	struct tile tile;
	rf_gbuffer *g;
	rf_scene *s;
	int c, rc, verbose = 0;

	cli_init(argc, argv);
	cli_frames_init(&frames);
	while ((c = getopt_long(argc, argv, "qvVx:y:n:j:c:f:h", long_options, NULL)) != -1) {
		switch (c) {
		case 'v': verbose = 1; break;
		case 'V': print_version(); break;
		case 'x': width = parse_count(optarg, 'x', 1, RF_FRAME_SIDE_MAX); break;
		case 'y': height = parse_count(optarg, 'y', 1, RF_FRAME_SIDE_MAX); break;
		case 'j': threads = optarg; break;
		case 'c': channels = optarg; break;
		case 'f': case 'h':
		case CLI_OPT_REGION: case CLI_OPT_TILE: case CLI_OPT_HALO:
			cli_io_option(&io, c, optarg);
			break;
		case OPT_SUPERSAMPLE:
			supersample = (size_t)parse_whole("supersample", optarg, 1, 16);
			break;
		case OPT_PRINT_DEFAULT:
			fputs(rf_scene_default_text(), stdout);
			fshut(stdout, "<stdout>");
			return 0;
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
	/* The samples of a pixel are the pixels of a frame N times larger:
	 * their rays cross it at the centres of an N x N grid. */
	cli_check_frame(supersample > 1 ? "-x -y --supersample" : "-x -y",
	                width * supersample, height * supersample);
	width *= supersample;
	height *= supersample;
	/* a tile's pixels are the full frame's: the same rays, rows and
	 * columns of the full frame, and the full size in REGION */
	cli_region_rect(&io.region, width, height, supersample, rect);
	s = cli_load_scene(file);
	if ((rc = rf_gbuffer_create(&g, s, width, height, channels, cli_threads(threads),
	                            err, sizeof(err))) < 0)
		die_status(rc, err);
	wopt.format = io.format;
	wopt.no_header = io.no_header;
	cli_widen_pipe(STDOUT_FILENO);
	if ((rc = rf_writer_open(&io.writer, stdout, "<stdout>", &wopt)) < 0)
		die_status(rc, NULL);
	if ((rc = rf_gbuffer_set_columns(g, rect[0], rect[2] - rect[0])) < 0)
		die_status(rc, NULL);
	rows = rf_block_rows(rect[2] - rect[0], rf_gbuffer_nchannels(g), CLI_BLOCK_BYTES);
	if (rows > rect[3] - rect[1])
		rows = rect[3] - rect[1];
	rf_scene_camera(s, &start);
	cli_progress_frames(frames.last - frames.first + 1);
	for (frame = frames.first; frame <= frames.last; frame++) {
		rf_header *h;

		rf_camera_at_frame(&start, &frames.path, frame, frames.count, &cam);
		if ((rc = rf_gbuffer_set_camera(g, &cam, err, sizeof(err))) < 0)
			die("frame %zu: %s", frame, err);
		if (verbose)
			flag_camera(s, &cam, file ? file : "<default>", frame);
		h = frame_header(s, g, &cam, frame, width, height, rect, supersample);
		cli_io_begin(&io, h);
		rf_header_destroy(h);
		tile.g = g;
		tile.y0 = rect[1];
		cli_blocks(&io, rect[3] - rect[1], rows, 0,
		           (rect[2] - rect[0]) * rf_gbuffer_nchannels(g), render_block, &tile);
		cli_io_end_frame(&io);
	}
	rf_gbuffer_destroy(g);
	rf_scene_destroy(s);
	cli_io_close(&io);
	return 0;
}
