/* reflect-import: another renderer's passes (EXR and friends) as a stream. */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "cli.h"
#include "reflect/import.h"
#include "reflect/probe.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-vV] " CLI_PROGRESS_USAGE " [-c OUT=IN]... "
	        "[--preset=none|blender] "
	        "[--up=y|z] [--camera=X,Y,Z] [--roughness=R|CHANNEL] "
	        "[--box=XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX] [--center=X,Y,Z] [-f a|f] [-h] "
	        "FILE...\n", argv0);
	exit(EXIT_BAD_INPUT);
}

#define MAX_FILES 16
#define MAX_MAPS 256

struct source {
	const char *path;
	rf_image *img;
};

struct import_opts {
	struct rf_import_map maps[MAX_MAPS];
	size_t nmaps;
	int preset_blender;
	int z_up;          /* -1: by preset */
	const char *camera;
	const char *roughness;
	struct cli_probe probe;
	int verbose;
	enum rf_format format;
	int no_header;
};

static void
add_map(struct import_opts *o, const char *spec)
{
	const char *eq = strchr(spec, '=');

	if (!eq || eq == spec || !eq[1])
		die("-c: '%s' is not OUT=IN (e.g. P.X=ViewLayer.Position.X)", spec);
	if (o->nmaps >= MAX_MAPS)
		die("-c: more than %d mappings", MAX_MAPS);
	o->maps[o->nmaps].out = estrdup(spec);
	((char *)o->maps[o->nmaps].out)[eq - spec] = '\0';
	o->maps[o->nmaps].in = o->maps[o->nmaps].out + (eq - spec) + 1;
	if (!rf_channel_name_valid(o->maps[o->nmaps].out))
		die("-c: '%s' is not a valid channel name", o->maps[o->nmaps].out);
	o->nmaps++;
}

int
main(int argc, char **argv)
{
	static const struct option long_options[] = {
		{ "preset", required_argument, NULL, 'P' },
		{ "up", required_argument, NULL, 'U' },
		{ "camera", required_argument, NULL, 'C' },
		{ "roughness", required_argument, NULL, 'R' },
		{ "box", required_argument, NULL, 'B' },
		{ "center", required_argument, NULL, 'E' },
		{ "help", no_argument, NULL, 'Q' },
		CLI_PROGRESS_OPTION,
		{ NULL, 0, NULL, 0 },
	};
	struct import_opts o;
	struct source src[MAX_FILES];
	rf_import *im;
	struct rf_writer_options wopt;
	rf_writer *w;
	rf_header *h;
	char err[1024];
	size_t nsrc = 0, rows, y, n, i;
	float *buf;
	int c, rc;

	cli_init(argc, argv);
	memset(&o, 0, sizeof(o));
	o.z_up = -1;
	while ((c = getopt_long(argc, argv, "vVqc:f:h", long_options, NULL)) != -1) {
		switch (c) {
		case 'v': o.verbose = 1; break;
		case 'V': print_version(); break;
		case 'c': add_map(&o, optarg); break;
		case 'f':
			o.format = parse_format(optarg);
			break;
		case 'h': o.no_header = 1; break;
		case 'P':
			if (!strcmp(optarg, "blender")) o.preset_blender = 1;
			else if (strcmp(optarg, "none")) die("--preset: '%s' is not none or blender", optarg);
			break;
		case 'U':
			if (!strcmp(optarg, "z")) o.z_up = 1;
			else if (!strcmp(optarg, "y")) o.z_up = 0;
			else die("--up: '%s' is not y or z", optarg);
			break;
		case 'C': o.camera = optarg; break;
		case 'R': o.roughness = optarg; break;
		case 'B': o.probe.box = optarg; break;
		case 'E': o.probe.center = optarg; break;
		case 'Q':
			printf("usage: %s [options] FILE...\n"
			       "Turns a renderer's passes (one multi-channel EXR or several\n"
			       "images of one size) into a stream. See reflect-import(1).\n"
			       "  -c OUT=IN  take channel OUT from IN (IN may be FILE:CHANNEL)\n"
			       "  --preset=blender  Blender's pass names, Z up turned to Y up\n"
			       "  --up=y|z  the passes' up axis   --camera=X,Y,Z  derive V\n"
			       "  --roughness=R|CHANNEL  a constant or a channel\n"
			       "  --box=...  --center=X,Y,Z  the probe, as header keys\n"
			       "  -f a|f  -h  -v  -V\n"
			       CLI_PROGRESS_HELP, argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	if (optind >= argc)
		usage();
	if (o.format == RF_FORMAT_FLOAT)
		cli_refuse_terminal("a binary stream");
	if (argc - optind > MAX_FILES)
		die("more than %d input files", MAX_FILES);
	/* A large EXR takes seconds to read, and its stream as long to
	 * write: progress counts the files read and the stream written. */
	cli_progress_unit("file");
	cli_progress_frames(1);
	cli_progress_frame((size_t)(argc - optind) + 1);
	for (; optind < argc; optind++, nsrc++) {
		src[nsrc].path = argv[optind];
		if ((rc = rf_image_read(&src[nsrc].img, argv[optind], err, sizeof(err))) < 0)
			die_status(rc == RF_ENOMEM ? rc : RF_EINVAL, err);
		cli_progress_rows(nsrc + 1);
	}
	{
		struct rf_import_options io;
		const rf_image *imgs[MAX_FILES];
		const char *paths[MAX_FILES];
		float cam[3], box[6];

		memset(&io, 0, sizeof(io));
		for (i = 0; i < nsrc; i++) {
			imgs[i] = src[i].img;
			paths[i] = src[i].path;
		}
		io.maps = o.maps;
		io.nmaps = o.nmaps;
		io.preset = o.preset_blender ? RF_IMPORT_BLENDER : RF_IMPORT_NONE;
		io.z_up = o.z_up < 0 ? o.preset_blender : o.z_up;
		if (o.camera) {
			parse_floats(o.camera, "--camera", cam, 3);
			io.camera = cam;
		}
		io.roughness = o.roughness;
		(void)box;
		if ((rc = rf_import_create(&im, imgs, paths, nsrc, &io, err, sizeof(err))) < 0)
			die_status(rc, err);
	}
	{
		char what[4200];

		snprintf(what, sizeof(what), "'%s'", src[0].path);
		cli_check_frame(what, rf_header_ncols(rf_import_header(im)),
		                rf_header_nrows(rf_import_header(im)));
	}
	if ((rc = rf_header_dup(&h, rf_import_header(im))) < 0)
		die_status(rc, NULL);
	cli_record_command(h);
	if (o.probe.box) {
		struct rf_probe probe;

		if ((rc = rf_probe_resolve(&probe, h, o.probe.box, o.probe.center, NULL, err,
		                           sizeof(err))) < 0)
			die("%s", err);
		if ((rc = rf_probe_to_header(&probe, h)) < 0)
			die_header_key(rc);
	} else if (o.probe.center) {
		die("--center needs --box");
	}
	if (o.verbose) {
		cli_progress_clear();
		fprintf(stderr, "%s: %zux%zu, channels", argv0, rf_header_ncols(h),
		        rf_header_nrows(h));
		for (i = 0; i < rf_header_nchannels(h); i++)
			fprintf(stderr, " %s", rf_header_channel(h, i));
		fputc('\n', stderr);
	}
	wopt.format = o.format;
	wopt.no_header = o.no_header;
	if ((rc = rf_writer_open(&w, stdout, "<stdout>", &wopt)) < 0 ||
	    (rc = rf_writer_begin_frame(w, h)) < 0)
		die_status(rc, rf_writer_error(w));
	rows = rf_block_rows(rf_header_ncols(h), rf_header_nchannels(h), CLI_BLOCK_BYTES);
	buf = emalloc(rows * rf_header_ncols(h) * rf_header_nchannels(h) * sizeof(float));
	for (y = 0; y < rf_header_nrows(h); y += n) {
		n = rf_header_nrows(h) - y < rows ? rf_header_nrows(h) - y : rows;
		rf_import_rows(im, y, n, buf);
		if ((rc = rf_writer_write_rows(w, buf, n)) < 0)
			die_status(rc, rf_writer_error(w));
	}
	if ((rc = rf_writer_end_frame(w)) < 0)
		die_status(rc, rf_writer_error(w));
	cli_progress_rows(nsrc + 1);
	cli_progress_end();
	free(buf);
	rf_writer_close(w);
	rf_header_destroy(h);
	rf_import_destroy(im);
	for (i = 0; i < nsrc; i++)
		rf_image_destroy(src[i].img);
	for (i = 0; i < o.nmaps; i++)
		free((char *)o.maps[i].out);
	fshut(stdout, "<stdout>");
	return 0;
}
