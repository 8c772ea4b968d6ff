/* The main of the tools that run one mode over a stream, frame after
 * frame: reflect-project, -occlude, -filter, -accumulate. */
#include <getopt.h>
#include <string.h>

#include "cli.h"
#include "reflect/host.h"
#include "reflect/probe.h"

static void
help(const struct cli_stage_tool *t)
{
	/* the modes' list runs plugin code: what it prints stays out */
	cli_keep_stdout();
	fprintf(cli_stdout(), "usage: %s [options] [file]\n%s", argv0, t->about);
	mode_help_line(t->kind, t->spec);
	fprintf(cli_stdout(), "%s"
	        "  -j N  threads   -v  say which plugin   -V  versions\n"
	        CLI_PROGRESS_HELP
	        "  -f a|f  output format   -h  no output header\n"
	        "  -H -x W -y H -c CHANNELS  headerless input\n", t->help);
	fshut(cli_stdout(), "<stdout>");
}

int
cli_stage_main(int argc, char **argv, const struct cli_stage_tool *t)
{
	struct cli_stage_run r = { 0 };
	const char *threads = NULL;
	const rf_header *in;
	char optstring[32];
	int c, list = 0, verbose = 0, want_help = 0, rc;

	cli_init(argc, argv);
	snprintf(optstring, sizeof(optstring), "%sqlvVm:j:" CLI_IO_OPTSTRING,
	         t->optstring ? t->optstring : "");
	r.spec = t->spec;
	while ((c = getopt_long(argc, argv, optstring, t->long_options, NULL)) != -1) {
		if (cli_io_option(&r.io, c, optarg) || cli_progress_option(c))
			continue;
		switch (c) {
		case 'l': list = 1; break;
		case 'v': verbose = 1; break;
		case 'V': print_version(); break;
		case 'm': r.spec = optarg; break;
		case 'j': threads = optarg; break;
		case CLI_OPT_HELP: want_help = 1; break;
		default:
			if (!t->option || !t->option(&r, c, optarg))
				t->usage();
		}
	}
	/* -m MODE --help, in either order: that mode's help */
	if (want_help && r.spec != t->spec)
		mode_help(t->kind, r.spec);
	if (want_help) {
		help(t);
		return 0;
	}
	if (argc - optind > 1)
		t->usage();
	if (list)
		mode_list(t->kind);
	r.nthreads = cli_threads(threads);
	mode_load(&r.mode, t->kind, r.spec, verbose);
	if ((rc = rf_plugin_host_create(&r.host)) < 0)
		die_status(rc, NULL);
	if (t->start)
		t->start(&r);
	cli_io_open(&r.io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&r.io, &in)) {
		rf_plugin_host_set_frame(r.host, in);
		mode_note_absent(&r.mode, &r.io, in);
		t->frame(&r, in);
	}
	if (t->finish)
		t->finish(&r);
	rf_plugin_host_destroy(r.host);
	mode_unload(&r.mode);
	cli_io_close(&r.io);
	return 0;
}

void
cli_stage_header(struct cli_stage_run *r, rf_header *out, const char *key)
{
	int rc;

	cli_record_command(out);
	if ((rc = rf_header_set(out, key, r->spec)) < 0)
		die_header_key(rc);
}

void
cli_stage_refused(struct cli_stage_run *r, int rc, const char *err)
{
	if (rc == RF_ENOMEM)
		die_status(rc, err);
	die("'%s': %s", r->io.input_name, err);
}

int
cli_probe_resolve(struct rf_probe *probe, const rf_header *in, const struct cli_probe *po)
{
	static const struct cli_probe none;
	char err[512];
	int rc;

	if (!po)
		po = &none;
	rc = rf_probe_resolve(probe, in, po->box, po->center, po->projection, err, sizeof(err));
	if (rc < 0 && rc != RF_ENOTFOUND)
		die("%s", err);
	return rc == 0;
}

rf_stage *
cli_stage_begin(struct cli_stage_run *r, const rf_header *in, const struct rf_probe *probe,
                const char *key, rf_header **out)
{
	char err[1024];
	rf_stage *stage;
	int rc;

	rf_plugin_host_set_probe(r->host, probe);
	if ((rc = rf_stage_create(&stage, r->mode.plugin, r->mode.values,
	                          rf_plugin_host_table(r->host), r->nthreads, err,
	                          sizeof(err))) < 0)
		die_status(rc, err);
	rf_stage_set_invalid(stage, r->io.invalid);
	if ((rc = rf_stage_begin_frame(stage, in, out, err, sizeof(err))) < 0)
		die_status(rc, err);
	cli_stage_header(r, *out, key);
	return stage;
}
