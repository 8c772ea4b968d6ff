/* reflect-filter: filters values across pixels, guided by the G-buffer. */
#include <getopt.h>
#include <string.h>

#include "cli.h"
#include "reflect/host.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        "[--channels=LIST] " CLI_IO_USAGE " [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	{ "channels", required_argument, NULL, 'C' },
	{ "help", no_argument, NULL, '?' + 256 },
	{ NULL, 0, NULL, 0 },
};

static int
read_rows(void *arg, float *rows, size_t nrows)
{
	cli_io_read(arg, rows, nrows);
	return 0;
}

static int
write_rows(void *arg, const float *rows, size_t nrows)
{
	cli_io_write(arg, rows, nrows);
	return 0;
}

static void
filter_frame(struct cli_io *io, rf_filter *f, const char *spec, const rf_header *in)
{
	rf_header *out;
	char err[1024];
	int rc;

	if ((rc = rf_filter_begin_frame(f, in, &out, err, sizeof(err))) < 0) {
		if (rc == RF_ENOMEM)
			die_status(rc, err);
		die("'%s': %s", io->input_name, err);
	}
	cli_record_command(out);
	if ((rc = rf_header_set(out, RF_KEY_FILTER, spec)) < 0)
		die_header_key(rc);
	cli_io_begin(io, out);
	if ((rc = rf_filter_frame(f, read_rows, write_rows, io)) < 0) {
		if ((rc == RF_EINVAL || rc == RF_EPLUGIN) && *rf_filter_error(f))
			die("'%s': frame %zu, %s", io->input_name, io->frames,
			    rf_filter_error(f));
		die_status(rc, NULL);
	}
	cli_io_end_frame(io);
}

int
main(int argc, char **argv)
{
	struct cli_io io = { 0 };
	struct cli_mode mode = { 0 };
	struct rf_filter_options o = { 0 };
	const char *spec = "atrous", *threads = NULL;
	const rf_header *in;
	rf_plugin_host *host;
	rf_filter *f;
	char err[1024];
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
		case 'C': o.channels = optarg; break;
		case '?' + 256:
			printf("usage: %s [options] [file]\n"
			       "Filters the shaded values of a stream across pixels, guided by\n"
			       "its G-buffer. See reflect-filter(1).\n"
			       "  -m MODE[:K=V...]  filter mode (default atrous); -l lists them\n"
			       "  --channels=LIST  what is filtered (default spec.* and R G B)\n"
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
		mode_list(RF_KIND_FILTER);
	nthreads = cli_threads(threads);
	mode_load(&mode, RF_KIND_FILTER, spec, verbose);
	if ((rc = rf_plugin_host_create(&host)) < 0)
		die_status(rc, NULL);
	if ((rc = rf_filter_create(&f, mode.plugin, mode.values, rf_plugin_host_table(host),
	                           nthreads, &o, err, sizeof(err))) < 0)
		die_status(rc, err);
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &in)) {
		rf_plugin_host_set_frame(host, in);
		filter_frame(&io, f, spec, in);
	}
	rf_filter_destroy(f);
	rf_plugin_host_destroy(host);
	mode_unload(&mode);
	cli_io_close(&io);
	return 0;
}
