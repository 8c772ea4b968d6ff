/* reflect-occlude: specular occlusion on shaded reflections. */
#include <getopt.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        CLI_PROGRESS_USAGE " "
	        CLI_INVALID_USAGE " " CLI_REGION_USAGE " " CLI_IO_USAGE " [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	CLI_PROGRESS_OPTION,
	CLI_REGION_OPTIONS,
	{ "invalid", required_argument, NULL, 'I' },
	{ "help", no_argument, NULL, CLI_OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static int
option(struct cli_stage_run *r, int opt, const char *arg)
{
	if (opt != 'I')
		return 0;
	cli_io_invalid_option(&r->io, arg);
	return 1;
}

static void
frame(struct cli_stage_run *r, const rf_header *in)
{
	struct rf_probe probe;
	int found = cli_probe_resolve(&probe, in, NULL);
	rf_stage *stage;
	rf_header *out;

	stage = cli_stage_begin(r, in, found ? &probe : NULL, RF_KEY_OCCLUSION, &out);
	cli_stage_rows(&r->io, stage, in, out);
}

static const struct cli_stage_tool tool = {
	.kind = RF_KIND_OCCLUSION,
	.spec = "box",
	.long_options = long_options,
	.about = "Darkens the reflection (spec.R G B, and R G B) of a shaded stream\n"
	         "by a specular occlusion term, written as the channel occlusion.\n"
	         "See reflect-occlude(1).\n",
	.help = "  --invalid=error|clamp|zero  NaN and Inf in what the mode reads\n"
	        CLI_REGION_HELP,
	.usage = usage,
	.option = option,
	.frame = frame,
};

int
main(int argc, char **argv)
{
	return cli_stage_main(argc, argv, &tool);
}
