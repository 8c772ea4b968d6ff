/* reflect-accumulate: combines the frames of a stream, value by value. */
#include <getopt.h>

#include "cli.h"
#include "reflect/host.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-alvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        CLI_PROGRESS_USAGE " "
	        "[--channels=LIST] [--stats] [--reset=KEYS] " CLI_REGION_USAGE " " CLI_IO_USAGE
	        " [file]\n",
	        argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	CLI_PROGRESS_OPTION,
	{ "channels", required_argument, NULL, 'C' },
	{ "stats", no_argument, NULL, 'S' },
	{ "reset", required_argument, NULL, 'R' },
	CLI_REGION_OPTIONS,
	{ "help", no_argument, NULL, CLI_OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static struct rf_accumulate_options options;
static int every; /* -a */
static rf_accumulator *acc;
static rf_header *out; /* the last frame's, for the kept result */

static int
option(struct cli_stage_run *r, int opt, const char *arg)
{
	switch (opt) {
	case 'a': every = 1; break;
	case 'C': options.channels = arg; break;
	case 'S': options.stats = 1; break;
	case 'R': options.reset = arg; break;
	default: return 0;
	}
	return 1;
}

static void
start(struct cli_stage_run *r)
{
	char err[1024];
	int rc;

	options.keep = !every;
	if ((rc = rf_accumulator_create(&acc, r->mode.plugin, r->mode.values,
	                                rf_plugin_host_table(r->host), r->nthreads, &options,
	                                err, sizeof(err))) < 0)
		die_status(rc, err);
}

struct accumulate_block {
	struct cli_io *io;
	int result; /* the rows are the result's, from the kept frame */
};

static int
accumulate_block(void *arg, const float *in, float *rows, size_t y, size_t n)
{
	struct accumulate_block *ab = arg;
	int rc = ab->result ? rf_accumulator_result(acc, rows, y, n)
	                    : rf_accumulator_run(acc, in, rows, y, n);

	if ((rc == RF_EINVAL || rc == RF_EPLUGIN) && *rf_accumulator_error(acc))
		die("'%s': frame %zu, %s", ab->io->input_name, ab->io->frames,
		    rf_accumulator_error(acc));
	if (rc < 0)
		die_status(rc, NULL);
	return 0;
}

/* One pass over a frame's rows: from the input (in, or none) to the
 * output (or none). */
static void
pass(struct cli_io *io, const rf_header *in, int with_out)
{
	struct accumulate_block ab = { io, in == NULL };
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

static void
frame(struct cli_stage_run *r, const rf_header *in)
{
	char err[1024];
	int rc;

	if ((rc = rf_accumulator_begin_frame(acc, in, &out, err, sizeof(err))) < 0)
		cli_stage_refused(r, rc, err);
	cli_stage_header(r, out, RF_KEY_ACCUMULATE);
	pass(&r->io, in, every);
}

static void
finish(struct cli_stage_run *r)
{
	if (!every && out) {
		cli_progress_hold();
		pass(&r->io, NULL, 1);
	}
	rf_accumulator_destroy(acc);
}

static const struct cli_stage_tool tool = {
	.kind = RF_KIND_ACCUMULATE,
	.spec = "mean",
	.optstring = "a",
	.long_options = long_options,
	.about = "Combines the frames of a stream value by value (noise rendered\n"
	         "frame after frame). See reflect-accumulate(1).\n",
	.help = "  -a  the running result after every frame (else one at the end)\n"
	        "  --channels=LIST  what is combined (default spec.* and R G B)\n"
	        "  --stats  standard errors as NAME.se channels\n"
	        "  --reset=KEYS  start afresh when one of these header keys changes\n"
	        CLI_REGION_HELP,
	.usage = usage,
	.option = option,
	.start = start,
	.finish = finish,
	.frame = frame,
};

int
main(int argc, char **argv)
{
	return cli_stage_main(argc, argv, &tool);
}
