/* reflect-project: reflection vector, lookup direction and distances. */
#include <getopt.h>

#include "cli.h"
#include "reflect/host.h"
#include "reflect/probe.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        CLI_PROGRESS_USAGE " "
	        "[--box=XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX] [--center=X,Y,Z] "
	        "[--box-projection=on|off] " CLI_INVALID_USAGE " " CLI_REGION_USAGE " "
	        CLI_IO_USAGE " [file]\n",
	        argv0);
	exit(EXIT_BAD_INPUT);
}

static const struct option long_options[] = {
	CLI_PROGRESS_OPTION,
	CLI_REGION_OPTIONS,
	{ "box", required_argument, NULL, 'B' },
	{ "center", required_argument, NULL, 'C' },
	{ "box-projection", required_argument, NULL, 'P' },
	{ "invalid", required_argument, NULL, 'I' },
	{ "help", no_argument, NULL, CLI_OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

static struct cli_probe po;

static int
option(struct cli_stage_run *r, int opt, const char *arg)
{
	switch (opt) {
	case 'B': po.box = arg; break;
	case 'C': po.center = arg; break;
	case 'P': po.projection = arg; break;
	case 'I': cli_io_invalid_option(&r->io, arg); break;
	default: return 0;
	}
	return 1;
}

static void
frame(struct cli_stage_run *r, const rf_header *in)
{
	struct rf_probe probe;
	int found = cli_probe_resolve(&probe, in, &po), rc;
	rf_stage *stage;
	rf_header *out;

	/* the shape is the mode's to declare, whatever the input's was */
	probe.bevel = 0.0f;
	probe.bevel_grown = 0;
	stage = cli_stage_begin(r, in, found ? &probe : NULL, RF_KEY_PROJECTION, &out);
	if (found && (rc = rf_probe_to_header(rf_plugin_host_probe(r->host), out)) < 0)
		die_header_key(rc);
	cli_stage_rows(&r->io, stage, in, out);
}

static const struct cli_stage_tool tool = {
	.kind = RF_KIND_PROJECTION,
	.spec = "box",
	.long_options = long_options,
	.about = "Adds R (reflection vector), D (lookup direction), hit.dist and\n"
	         "probe.dist to a G-buffer stream (P, N, V). See reflect-project(1).\n",
	.help = "  --box=...  --center=X,Y,Z  --box-projection=on|off  the probe\n"
	        "  --invalid=error|clamp|zero  NaN, Inf, zero vectors in P N V\n"
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
