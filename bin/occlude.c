/* reflect-occlude: specular occlusion on shaded reflections. */
#include <getopt.h>
#include <string.h>

#include "cli.h"
#include "reflect/host.h"
#include "reflect/probe.h"

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

static void
occlude_frame(struct cli_io *io, struct cli_mode *mode, const char *spec, int nthreads,
              rf_plugin_host *host, const rf_header *in)
{
	struct rf_probe probe;
	char err[1024], perr[512];
	rf_stage *stage;
	rf_header *out;
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
	cli_stage_rows(io, stage, in, out);
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
