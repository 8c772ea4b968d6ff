/* reflect-accumulate: combines the frames of a stream, value by value. */
#include <getopt.h>
#include <string.h>

#include "cli.h"
#include "reflect/host.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-alvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        "[--channels=LIST] [--stats] [--reset=KEYS] " CLI_IO_USAGE " [file]\n",
	        argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	{ "channels", required_argument, NULL, 'C' },
	{ "stats", no_argument, NULL, 'S' },
	{ "reset", required_argument, NULL, 'R' },
	{ "help", no_argument, NULL, '?' + 256 },
	{ NULL, 0, NULL, 0 },
};

struct accumulate_block {
	struct cli_io *io;
	rf_accumulator *acc;
	int result; /* the rows are the result's, from the kept frame */
};

static int
accumulate_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	struct accumulate_block *ab = arg;
	int rc = ab->result ? rf_accumulator_result(ab->acc, out, y, n)
	                    : rf_accumulator_run(ab->acc, in, out, y, n);

	if ((rc == RF_EINVAL || rc == RF_EPLUGIN) && *rf_accumulator_error(ab->acc))
		die("'%s': frame %zu, %s", ab->io->input_name, ab->io->frames,
		    rf_accumulator_error(ab->acc));
	if (rc < 0)
		die_status(rc, NULL);
	return 0;
}

/* One pass over a frame's rows: from the input (in, or none) to the
 * output (or none). */
static void
pass(struct cli_io *io, rf_accumulator *acc, const rf_header *in, const rf_header *out,
     int with_out)
{
	struct accumulate_block ab = { io, acc, in == NULL };
	size_t ncols = rf_header_ncols(out), rows;
	int rc;

	rows = rf_block_rows(ncols, rf_header_nchannels(out), CLI_BLOCK_BYTES);
	if (rows > rf_header_nrows(out))
		rows = rf_header_nrows(out);
	if (with_out)
		cli_io_begin(io, out);
	rc = cli_blocks(io, rf_header_nrows(out), rows, in ? ncols * rf_header_nchannels(in) : 0,
	                with_out ? ncols * rf_header_nchannels(out) : 0, accumulate_block, &ab);
	if (rc < 0)
		cli_io_read_failed(io, rc);
	if (with_out)
		cli_io_end_frame(io);
}

int
main(int argc, char **argv)
{
	struct cli_io io = { 0 };
	struct cli_mode mode = { 0 };
	struct rf_accumulate_options o = { 0 };
	const char *spec = "mean", *threads = NULL;
	const rf_header *in;
	rf_header *out = NULL;
	rf_plugin_host *host;
	rf_accumulator *acc;
	char err[1024];
	int c, list = 0, verbose = 0, every = 0, nthreads, rc;

	cli_init(argc, argv);
	while ((c = getopt_long(argc, argv, "alvVm:j:" CLI_IO_OPTSTRING, long_options,
	                        NULL)) != -1) {
		if (cli_io_option(&io, c, optarg))
			continue;
		switch (c) {
		case 'a': every = 1; break;
		case 'l': list = 1; break;
		case 'v': verbose = 1; break;
		case 'V': print_version(); break;
		case 'm': spec = optarg; break;
		case 'j': threads = optarg; break;
		case 'C': o.channels = optarg; break;
		case 'S': o.stats = 1; break;
		case 'R': o.reset = optarg; break;
		case '?' + 256:
			printf("usage: %s [options] [file]\n"
			       "Combines the frames of a stream value by value (noise rendered\n"
			       "frame after frame). See reflect-accumulate(1).\n"
			       "  -m MODE[:K=V...]  accumulate mode (default mean); -l lists them\n"
			       "  -a  the running result after every frame (else one at the end)\n"
			       "  --channels=LIST  what is combined (default spec.* and R G B)\n"
			       "  --stats  standard errors as NAME.se channels\n"
			       "  --reset=KEYS  start afresh when one of these header keys changes\n"
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
		mode_list(RF_KIND_ACCUMULATE);
	nthreads = cli_threads(threads);
	mode_load(&mode, RF_KIND_ACCUMULATE, spec, verbose);
	if ((rc = rf_plugin_host_create(&host)) < 0)
		die_status(rc, NULL);
	o.keep = !every;
	if ((rc = rf_accumulator_create(&acc, mode.plugin, mode.values,
	                                rf_plugin_host_table(host), nthreads, &o, err,
	                                sizeof(err))) < 0)
		die_status(rc, err);
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &in)) {
		rf_plugin_host_set_frame(host, in);
		if ((rc = rf_accumulator_begin_frame(acc, in, &out, err, sizeof(err))) < 0) {
			if (rc == RF_ENOMEM)
				die_status(rc, err);
			die("'%s': %s", io.input_name, err);
		}
		cli_record_command(out);
		if ((rc = rf_header_set(out, RF_KEY_ACCUMULATE, spec)) < 0)
			die_header_key(rc);
		pass(&io, acc, in, out, every);
	}
	if (!every && out)
		pass(&io, acc, NULL, out, 1);
	rf_accumulator_destroy(acc);
	rf_plugin_host_destroy(host);
	mode_unload(&mode);
	cli_io_close(&io);
	return 0;
}
