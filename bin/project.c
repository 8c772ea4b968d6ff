/* reflect-project: reflection vector, lookup direction and distances. */
#include <getopt.h>
#include <string.h>

#include "cli.h"
#include "reflect/host.h"
#include "reflect/probe.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        "[--box=XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX] [--center=X,Y,Z] "
	        "[--box-projection=on|off] " CLI_INVALID_USAGE " " CLI_IO_USAGE " [file]\n",
	        argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	{ "box", required_argument, NULL, 'B' },
	{ "center", required_argument, NULL, 'C' },
	{ "box-projection", required_argument, NULL, 'P' },
	{ "invalid", required_argument, NULL, 'I' },
	{ "help", no_argument, NULL, '?' + 256 },
	{ NULL, 0, NULL, 0 },
};

static void
project_frame(struct cli_io *io, struct cli_mode *mode, const struct cli_probe *po,
              const char *spec, int nthreads, rf_plugin_host *host, const rf_header *in)
{
	struct rf_probe probe;
	char err[1024], perr[512];
	rf_stage *stage;
	rf_header *out;
	int rc, prc;

	prc = rf_probe_resolve(&probe, in, po->box, po->center, po->projection, perr,
	                       sizeof(perr));
	if (prc < 0 && prc != RF_ENOTFOUND)
		die("%s", perr);
	/* the shape is the mode's to declare, whatever the input's was */
	probe.bevel = 0.0f;
	probe.bevel_grown = 0;
	rf_plugin_host_set_frame(host, in);
	rf_plugin_host_set_probe(host, prc == 0 ? &probe : NULL);
	if ((rc = rf_stage_create(&stage, mode->plugin, mode->values,
	                          rf_plugin_host_table(host), nthreads, err, sizeof(err))) < 0)
		die_status(rc, err);
	rf_stage_set_invalid(stage, io->invalid);
	if ((rc = rf_stage_begin_frame(stage, in, &out, err, sizeof(err))) < 0)
		die_status(rc, err);
	cli_record_command(out);
	if ((rc = rf_header_set(out, RF_KEY_PROJECTION, spec)) < 0 ||
	    (prc == 0 && (rc = rf_probe_to_header(rf_plugin_host_probe(host), out)) < 0))
		die_header_key(rc);
	cli_stage_rows(io, stage, in, out);
}

int
main(int argc, char **argv)
{
	struct cli_io io = { 0 };
	struct cli_mode mode = { 0 };
	struct cli_probe po = { 0 };
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
		case 'B': po.box = optarg; break;
		case 'C': po.center = optarg; break;
		case 'P': po.projection = optarg; break;
		case 'I': cli_io_invalid_option(&io, optarg); break;
		case '?' + 256:
			printf("usage: %s [options] [file]\n"
			       "Adds R (reflection vector), D (lookup direction), hit.dist and\n"
			       "probe.dist to a G-buffer stream (P, N, V). See reflect-project(1).\n"
			       "  -m MODE[:K=V...]  projection mode (default box); -l lists them\n"
			       "  --box=...  --center=X,Y,Z  --box-projection=on|off  the probe\n"
			       "  --invalid=error|clamp|zero  NaN, Inf, zero vectors in P N V\n"
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
		mode_list(RF_KIND_PROJECTION);
	nthreads = cli_threads(threads);
	mode_load(&mode, RF_KIND_PROJECTION, spec, verbose);
	if ((rc = rf_plugin_host_create(&host)) < 0)
		die_status(rc, NULL);
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &in))
		project_frame(&io, &mode, &po, spec, nthreads, host, in);
	rf_plugin_host_destroy(host);
	mode_unload(&mode);
	cli_io_close(&io);
	return 0;
}
