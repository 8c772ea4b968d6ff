/* reflect-filter: filters values across pixels, guided by the G-buffer. */
#include <getopt.h>

#include "cli.h"
#include "reflect/host.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        CLI_PROGRESS_USAGE " "
	        "[--channels=LIST] " CLI_IO_USAGE " [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	CLI_PROGRESS_OPTION,
	{ "channels", required_argument, NULL, 'C' },
	{ "help", no_argument, NULL, CLI_OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static struct rf_filter_options options;
static rf_filter *filter;
static size_t rows_written; /* of this frame, for progress */

static int
option(struct cli_stage_run *r, int opt, const char *arg)
{
	if (opt != 'C')
		return 0;
	options.channels = arg;
	return 1;
}

static void
start(struct cli_stage_run *r)
{
	char err[1024];
	int rc;

	if ((rc = rf_filter_create(&filter, r->mode.plugin, r->mode.values,
	                           rf_plugin_host_table(r->host), r->nthreads, &options,
	                           err, sizeof(err))) < 0)
		die_status(rc, err);
}

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
	rows_written += nrows;
	cli_progress_rows(rows_written);
	return 0;
}

static void
frame(struct cli_stage_run *r, const rf_header *in)
{
	rf_header *out;
	char err[1024];
	int rc;

	if ((rc = rf_filter_begin_frame(filter, in, &out, err, sizeof(err))) < 0)
		cli_stage_refused(r, rc, err);
	cli_stage_header(r, out, RF_KEY_FILTER);
	cli_io_begin(&r->io, out);
	rows_written = 0;
	cli_progress_frame(rf_header_nrows(in));
	if ((rc = rf_filter_frame(filter, read_rows, write_rows, &r->io)) < 0) {
		if ((rc == RF_EINVAL || rc == RF_EPLUGIN) && *rf_filter_error(filter))
			die("'%s': frame %zu, %s", r->io.input_name, r->io.frames,
			    rf_filter_error(filter));
		die_status(rc, NULL);
	}
	cli_io_end_frame(&r->io);
}

static void
finish(struct cli_stage_run *r)
{
	rf_filter_destroy(filter);
}

static const struct cli_stage_tool tool = {
	.kind = RF_KIND_FILTER,
	.spec = "atrous",
	.long_options = long_options,
	.about = "Filters the shaded values of a stream across pixels, guided by\n"
	         "its G-buffer. See reflect-filter(1).\n",
	.help = "  --channels=LIST  what is filtered (default spec.* and R G B)\n",
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
