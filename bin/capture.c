/* reflect-capture: bake a scene's probe into a cube. */
#include <getopt.h>
#include <math.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "reflect/envmap.h"
#include "reflect/scene.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-V] [-p PROBE|all] [-n SIZE] [-j THREADS] "
	        CLI_PROGRESS_USAGE " [--bounces=N] [--hide-reflective] [--edge-samples=N] "
	        "[--object-samples=N] [--bounce-size=N] [-o FILE] [-f a|f] [-h] "
	        "[scene]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

enum { OPT_BOUNCES = 256, OPT_HIDE, OPT_EDGE, OPT_OBJECT, OPT_BOUNCE_SIZE, OPT_HELP };

static const struct option long_options[] = {
	CLI_PROGRESS_OPTION,
	{ "bounces", required_argument, NULL, OPT_BOUNCES },
	{ "hide-reflective", no_argument, NULL, OPT_HIDE },
	{ "edge-samples", required_argument, NULL, OPT_EDGE },
	{ "object-samples", required_argument, NULL, OPT_OBJECT },
	{ "bounce-size", required_argument, NULL, OPT_BOUNCE_SIZE },
	{ "help", no_argument, NULL, OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static void
help(void)
{
	printf("usage: %s [options] [scene]\n"
	       "Renders a probe's environment from its capture point as a cube\n"
	       "(a stream, or an OpenEXR N x 6N cube with -o FILE.exr), each texel\n"
	       "the mean of its footprint.  See reflect-capture(1).\n"
	       "  -p PROBE|all      the probe, from 1 (default 1)\n"
	       "  -n SIZE           texels a face (default 256)\n"
	       "  --bounces=N       objects lit by the bounce before (default 1;\n"
	       "                    0: objects black)\n"
	       "  --hide-reflective leave reflective objects out\n"
	       "  --edge-samples=N  N x N rays where a texel crosses an edge (16)\n"
	       "  --object-samples=N  N x N rays where it may see an object (4)\n"
	       "  --bounce-size=N   texels a face of the earlier bounces (128)\n"
	       "  -o FILE  output (%%d numbers the probes)   -j N  threads\n"
	       "  -f a|f  stream format   -h  no header   -V  versions\n"
	       CLI_PROGRESS_HELP, argv0);
	fshut(stdout, "<stdout>");
	exit(0);
}

/* The capture's rows for cli_progress: each probe a frame. */
static void
progress(void *arg, size_t done, size_t total)
{
	(void)arg;
	if (!done)
		cli_progress_frame(total);
	else
		cli_progress_rows(done);
}

/* The cube as an N x 6N OpenEXR image of floats (faces +X -X +Y -Y +Z -Z
 * from the top), the layout every environment reader takes. */
static void
write_exr(const rf_cubemap *c, const char *path)
{
	static const char *const names[] = { "R", "G", "B" };
	size_t n = rf_cubemap_size(c);
	char err[1024];
	rf_image_writer *w;
	float *px = emalloc(n * 6 * n * 3 * sizeof(float));
	int rc;

	if ((rc = rf_envmap_to_pixels(c, 0, RF_LAYOUT_CUBE, px, n, 6 * n)) < 0 ||
	    (rc = rf_image_writer_open(&w, path, n, 6 * n, 3, names, RF_PIXEL_FLOAT, err,
	                               sizeof(err))) < 0)
		die_status(rc, err);
	if ((rc = rf_image_writer_write_rows(w, 0, 6 * n, px)) < 0)
		die_status(rc, rf_image_writer_error(w));
	if ((rc = rf_image_writer_close(w, err, sizeof(err))) < 0)
		die_status(rc, err);
	free(px);
}

/* The cube as a raw environment: a one-level chain stream. */
static void
write_stream(const rf_cubemap *c, const char *path, const struct cli_io *io,
             const char *scene, size_t probe)
{
	struct rf_writer_options wopt = { io->format, io->no_header };
	struct rf_chain_info info;
	char err[1024], buf[32];
	FILE *fp = stdout;
	rf_header *base;
	rf_writer *w;
	rf_output *file = NULL;
	int rc;

	memset(&info, 0, sizeof(info));
	info.mapping = RF_MAPPING_DEFAULT;
	info.base_copied = 1;
	/* whole or not at all: an old file stays if this fails */
	if (path && (rc = rf_output_open(&file, path, &fp, err, sizeof(err))) < 0)
		die_status(rc, err);
	if ((rc = rf_header_create(&base)) < 0)
		die_status(rc, NULL);
	cli_record_command(base);
	snprintf(buf, sizeof(buf), "%zu", probe + 1);
	if ((rc = rf_header_set(base, RF_KEY_SCENE, scene)) < 0 ||
	    (rc = rf_header_set(base, "CAPTURE_PROBE", buf)) < 0)
		die_header_key(rc);
	if ((rc = rf_writer_open(&w, fp, path ? path : "<stdout>", &wopt)) < 0)
		die_status(rc, NULL);
	if ((rc = rf_chain_write_stream(c, &info, w, base, err, sizeof(err))) < 0)
		die_status(rc, err);
	rf_writer_close(w);
	rf_header_destroy(base);
	if (file && (rc = rf_output_commit(file, err, sizeof(err))) < 0)
		die_status(rc, err);
}

static void
output_name(char *buf, size_t size, const char *pattern, size_t probe)
{
	const char *pct = strstr(pattern, "%d");

	if (!pct)
		snprintf(buf, size, "%s", pattern);
	else
		snprintf(buf, size, "%.*s%zu%s", (int)(pct - pattern), pattern, probe + 1,
		         pct + 2);
}

int
main(int argc, char **argv)
{
	struct rf_capture_options o;
	struct cli_io io = { 0 };
	const char *output = NULL, *which = "1", *threads = NULL, *file;
	size_t first, last, k;
	rf_scene *s;
	int c;

	cli_init(argc, argv);
	rf_capture_options_init(&o);
	while ((c = getopt_long(argc, argv, "Vp:n:j:o:f:hq", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'p': which = optarg; break;
		case 'n':
			o.size = parse_count(optarg, 'n', 1, 8192);
			/* the cube is written as a frame of N x 6N */
			cli_check_frame("-n (a frame of N x 6N)", o.size, 6 * o.size);
			break;
		case 'j': threads = optarg; break;
		case 'o': output = optarg; break;
		case 'f': case 'h': cli_io_option(&io, c, optarg); break;
		case OPT_BOUNCES: o.bounces = (int)parse_whole("bounces", optarg, 0, 16); break;
		case OPT_HIDE: o.hide_reflective = 1; break;
		case OPT_EDGE: o.edge_samples = (unsigned)parse_whole("edge-samples", optarg, 1, 64); break;
		case OPT_OBJECT:
			o.object_samples = (unsigned)parse_whole("object-samples", optarg, 1, 64);
			break;
		case OPT_BOUNCE_SIZE:
			o.bounce_size = (size_t)parse_whole("bounce-size", optarg, 1, 8192);
			break;
		case OPT_HELP: help(); break;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	if (argc - optind > 1)
		usage();
	file = cli_input_or_default(optind < argc ? argv[optind] : NULL);
	/* every option checked before the scene is loaded */
	if (!output && io.format == RF_FORMAT_FLOAT)
		cli_refuse_terminal("a binary stream");
	first = strcmp(which, "all") ? (size_t)parse_whole("p", which, 1, 1e6) - 1 : 0;
	s = cli_load_scene(file);
	o.nthreads = cli_threads(threads);
	if (!strcmp(which, "all")) {
		last = rf_scene_nprobes(s) - 1;
		if (last > first && (!output || !strstr(output, "%d"))) {
			size_t n = rf_scene_nprobes(s);

			rf_scene_destroy(s);
			die("-p all: the scene has %zu probes; name the files with a %%d in -o", n);
		}
	} else {
		last = first;
		if (first >= rf_scene_nprobes(s)) {
			size_t n = rf_scene_nprobes(s);

			rf_scene_destroy(s);
			die("-p %s: %s has %zu probe%s", which,
			    !file || !strcmp(file, "default") ? "the default scene"
			    : !strcmp(file, "-") ? "<stdin>" : file, n, n == 1 ? "" : "s");
		}
	}
	o.progress = progress;
	cli_progress_frames(last - first + 1);
	for (k = first; k <= last; k++) {
		char err[1024], path[4096];
		const char *dot;
		rf_cubemap *cube;
		int rc;

		if ((rc = rf_scene_capture(s, k, &o, &cube, err, sizeof(err))) < 0) {
			rf_scene_destroy(s);
			die_status(rc, err);
		}
		if (k == last)
			cli_progress_end();
		if (output)
			output_name(path, sizeof(path), output, k);
		dot = output ? strrchr(path, '.') : NULL;
		if (dot && !strcasecmp(dot, ".exr"))
			write_exr(cube, path);
		else if (dot && strcmp(dot, ".rfl") && strcmp(dot, ".stream"))
			die("cannot write '%s': a capture is a stream (.rfl, or standard output) "
			    "or an OpenEXR cube (.exr)", path);
		else
			write_stream(cube, output ? path : NULL, &io, rf_scene_name(s), k);
		rf_cubemap_destroy(cube);
	}
	rf_scene_destroy(s);
	return 0;
}
