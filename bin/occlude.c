/* reflect-occlude: specular occlusion on shaded reflections. */
#include <getopt.h>
#include <string.h>

#include "cli.h"
#include "reflect/host.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        CLI_INVALID_USAGE " " CLI_IO_USAGE " [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	{ "invalid", required_argument, NULL, 'I' },
	{ "help", no_argument, NULL, '?' + 256 },
	{ NULL, 0, NULL, 0 },
};

struct occlude_block {
	rf_stage *stage;
	int failed; /* the stage refused a pixel (rf_stage_error says why) */
	int gave_up; /* the mode failed in run() (rf_stage_error says why) */
};

static int
occlude_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	struct occlude_block *ob = arg;
	int rc = rf_stage_run(ob->stage, in, out, y, n);

	ob->failed = rc == RF_EINVAL && *rf_stage_error(ob->stage);
	ob->gave_up = rc == RF_EPLUGIN;
	if (rc < 0 && !ob->failed && !ob->gave_up)
		die_status(rc, NULL);
	return rc;
}

static void
occlude_frame(struct cli_io *io, struct cli_mode *mode, const char *spec, int nthreads,
              rf_plugin_host *host, const rf_header *in)
{
	struct rf_probe probe;
	struct occlude_block ob;
	char err[1024], perr[512];
	rf_stage *stage;
	rf_header *out;
	size_t rows;
	int rc, prc;

	prc = rf_probe_resolve(&probe, in, NULL, NULL, NULL, perr, sizeof(perr));
	if (prc < 0 && prc != RF_ENOTFOUND)
		die("%s", perr);
	rf_plugin_host_set_frame(host, in);
	rf_plugin_host_set_probe(host, prc == 0 ? &probe : NULL);
	if ((rc = rf_stage_create(&stage, mode->plugin, mode->values,
	                          rf_plugin_host_table(host), nthreads, err, sizeof(err))) < 0)
		die_status(rc, err);
	rf_stage_set_invalid(stage, io->invalid);
	if ((rc = rf_stage_begin_frame(stage, in, &out, err, sizeof(err))) < 0)
		die_status(rc, err);
	cli_record_command(out);
	if ((rc = rf_header_set(out, RF_KEY_OCCLUSION, spec)) < 0)
		die_header_key(rc);
	cli_io_begin(io, out);
	rows = rf_block_rows(rf_header_ncols(out), rf_header_nchannels(out),
	                     CLI_BLOCK_BYTES);
	if (rows > rf_header_nrows(in))
		rows = rf_header_nrows(in);
	ob.stage = stage;
	ob.failed = ob.gave_up = 0;
	rc = cli_blocks(io, rf_header_nrows(in), rows,
	                rf_header_ncols(in) * rf_header_nchannels(in),
	                rf_header_ncols(out) * rf_header_nchannels(out), occlude_block, &ob);
	if (ob.failed || ob.gave_up)
		snprintf(err, sizeof(err), "%s", rf_stage_error(stage));
	cli_io_invalid_note(io, rf_stage_invalid_count(stage));
	rf_stage_destroy(stage);
	if (ob.gave_up)
		cli_io_plugin_failed(io, err);
	if (ob.failed)
		cli_io_invalid_failed(io, err);
	if (rc < 0)
		cli_io_read_failed(io, rc);
	cli_io_end_frame(io);
}

int
main(int argc, char **argv)
{
	struct cli_io io = { 0 };
	struct cli_mode mode = { 0 };
	const char *spec = "box", *threads = NULL;
	const rf_header *in;
	rf_plugin_host *host;
	int c, list = 0, verbose = 0, nthreads, rc;

	cli_init(argc, argv);
	while ((c = getopt_long(argc, argv, "lvVm:j:" CLI_IO_OPTSTRING, long_options,
	                        NULL)) != -1) {
		if (cli_io_option(&io, c, optarg))
			continue;
		switch (c) {
		case 'l': list = 1; break;
		case 'v': verbose = 1; break;
		case 'V': print_version(); break;
		case 'm': spec = optarg; break;
		case 'j': threads = optarg; break;
		case 'I': cli_io_invalid_option(&io, optarg); break;
		case '?' + 256:
			printf("usage: %s [options] [file]\n"
			       "Darkens the reflection (spec.R G B, and R G B) of a shaded stream\n"
			       "by a specular occlusion term, written as the channel occlusion.\n"
			       "See reflect-occlude(1).\n"
			       "  -m MODE[:K=V...]  occlusion mode (default box); -l lists them\n"
			       "  --invalid=error|clamp|zero  NaN and Inf in what the mode reads\n"
			       "  -j N  threads   -v  say which plugin   -V  versions\n"
			       "  -f a|f  output format   -h  no output header\n"
			       "  -H -x W -y H -c CHANNELS  headerless input\n", argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default: usage();
		}
	}
	if (argc - optind > 1)
		usage();
	if (list)
		mode_list(RF_KIND_OCCLUSION);
	nthreads = cli_threads(threads);
	mode_load(&mode, RF_KIND_OCCLUSION, spec, verbose);
	if ((rc = rf_plugin_host_create(&host)) < 0)
		die_status(rc, NULL);
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &in))
		occlude_frame(&io, &mode, spec, nthreads, host, in);
	rf_plugin_host_destroy(host);
	mode_unload(&mode);
	cli_io_close(&io);
	return 0;
}
