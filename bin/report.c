/* reflect-report: one HTML page of modes against the truth. */
#include <errno.h>
#include <getopt.h>
#include <stdlib.h>
#include <math.h>
#include <string.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-V] " CLI_PROGRESS_USAGE " [-o FILE] [-j N] [--title=TEXT] "
	        "[--stops=LO,HI] "
	        "[--caption=NAME=TEXT]... [--time=NAME=NS]... TRUTH NAME=FILE...\n", argv0);
	exit(EXIT_BAD_INPUT);
}

enum { OPT_TITLE = 256, OPT_CAPTION, OPT_TIME, OPT_STOPS, OPT_HELP };

static const struct option long_options[] = {
	{ "title", required_argument, NULL, OPT_TITLE },
	{ "caption", required_argument, NULL, OPT_CAPTION },
	{ "time", required_argument, NULL, OPT_TIME },
	{ "stops", required_argument, NULL, OPT_STOPS },
	{ "help", no_argument, NULL, OPT_HELP },
	CLI_PROGRESS_OPTION,
	{ NULL, 0, NULL, 0 },
};

/* A NAME=VALUE argument split at its first '='; dies when it has none. */
static char *
split(const char *opt, char *arg)
{
	char *eq = strchr(arg, '=');

	if (!eq || eq == arg)
		die("%s: '%s' is not NAME=%s", opt, arg, strcmp(opt, "--time") ? "TEXT" : "NS");
	*eq = '\0';
	return eq + 1;
}

/* --stops=LO,HI: whole stops, LO <= HI, at most 16 of them. */
static void
parse_stops(const char *arg, int *lo, int *hi)
{
	char *end;
	long a, b;

	errno = 0;
	a = strtol(arg, &end, 10);
	if (end == arg || *end != ',')
		goto bad;
	arg = end + 1;
	b = strtol(arg, &end, 10);
	if (end == arg || *end || errno || a > b || a < -RF_REPORT_STOP_LIMIT ||
	    b > RF_REPORT_STOP_LIMIT || b - a >= 16)
		goto bad;
	*lo = (int)a;
	*hi = (int)b;
	return;
bad:
	die("--stops: '%s' is not LO,HI: whole stops from -%d to %d, LO no more than HI, "
	    "at most 16 of them (e.g. --stops=-2,1)", optarg, RF_REPORT_STOP_LIMIT,
	    RF_REPORT_STOP_LIMIT);
}

/* --caption and --time name modes given on the command line; the
 * report is let go before a refusal, as after any other. */
static void
name_mode(rf_report *r, const char *opt, const char *name)
{
	if (rf_report_find(r, name) < 0) {
		rf_report_destroy(r);
		die("%s: no mode is named '%s' (name a mode as NAME=FILE)", opt, name);
	}
}

/* A picture refused: bad input, as reflect-compare has it, a file that
 * cannot be read included; out of memory is the system's. */
static void
refuse(rf_report *r, int rc, const char *err)
{
	rf_report_destroy(r);
	if (rc == RF_ENOMEM)
		die_status(rc, err);
	die("%s", err);
}

/* The --caption and --time arguments, as many as the command line's:
 * file-scope, so that they stay reachable on every way out (--help,
 * usage(), die()) and LeakSanitizer does not count them lost. */
static char **captions, **times, **captext;
static double *ns;

int
main(int argc, char **argv)
{
	const char *out = NULL, *title = "reflect-report", *threads = NULL;
	char err[1024];
	size_t ncaptions = 0, ntimes = 0, i;
	rf_output *o = NULL;
	rf_report *r;
	FILE *fp;
	int c, rc, nthreads, lo = 0, hi = 0, stops = 0;

	cli_init(argc, argv);
	captions = emalloc((size_t)argc * sizeof(*captions));
	times = emalloc((size_t)argc * sizeof(*times));
	captext = emalloc((size_t)argc * sizeof(*captext));
	ns = emalloc((size_t)argc * sizeof(*ns));
	while ((c = getopt_long(argc, argv, "Vo:j:q", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'o': out = optarg; break;
		case 'j': threads = optarg; break;
		case OPT_TITLE: title = optarg; break;
		case OPT_CAPTION: captions[ncaptions++] = optarg; break;
		case OPT_TIME: times[ntimes++] = optarg; break;
		case OPT_STOPS: parse_stops(optarg, &lo, &hi); stops = 1; break;
		case OPT_HELP:
			printf("usage: %s [options] TRUTH NAME=FILE...\n"
			       "One HTML page of every mode against the truth: a table of their\n"
			       "errors, a viewer that flips and wipes between them, their FLIP maps.\n"
			       "The pictures are streams or image files. See reflect-report(1).\n"
			       "  -o FILE  the page (default: standard output)\n"
			       "  --title=TEXT  its title   -j N  threads   -V  versions\n"
			       "  --stops=LO,HI  linear pictures' exposures (default -4,3)\n"
			       "  --caption=NAME=TEXT  a mode's caption\n"
			       "  --time=NAME=NS  a mode's time in nanoseconds a pixel\n"
			       CLI_PROGRESS_HELP, argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	if (argc - optind < 2)
		usage();
	nthreads = cli_threads(threads);
	/* the command line whole before the first picture is read */
	for (i = (size_t)optind + 1; i < (size_t)argc; i++)
		if (!strchr(argv[i], '=') || argv[i][0] == '=')
			die("'%s' has no name: give each mode as NAME=FILE",
			    argv[i] + (argv[i][0] == '='));
	for (i = 0; i < ncaptions; i++)
		captext[i] = split("--caption", captions[i]);
	for (i = 0; i < ntimes; i++)
		ns[i] = parse_number("time", split("--time", times[i]), 0, INFINITY);
	/* Each picture is read and scored (FLIP) in one call, seconds for a
	 * large one: progress counts the truth, the modes and the page. */
	cli_progress_unit("picture");
	cli_progress_frames(1);
	cli_progress_frame((size_t)(argc - optind) + 1);
	if ((rc = rf_report_create(&r, argv[optind], err, sizeof(err))) < 0)
		refuse(NULL, rc, err);
	cli_progress_rows(1);
	if (stops && (rc = rf_report_stops(r, lo, hi)) < 0)
		refuse(r, rc, rc == RF_ENOMEM ? "out of memory" : "--stops: refused");
	for (i = (size_t)optind + 1; i < (size_t)argc; i++) {
		char *eq = strchr(argv[i], '=');

		*eq = '\0';
		if ((rc = rf_report_add(r, argv[i], eq + 1, NAN, nthreads, err, sizeof(err))) < 0)
			refuse(r, rc, err);
		cli_progress_rows(i - (size_t)optind + 1);
	}
	for (i = 0; i < ncaptions; i++) {
		name_mode(r, "--caption", captions[i]);
		if (rf_report_caption(r, captions[i], captext[i]) < 0)
			refuse(r, RF_ENOMEM, "out of memory");
	}
	for (i = 0; i < ntimes; i++) {
		name_mode(r, "--time", times[i]);
		rf_report_time(r, times[i], ns[i]);
	}
	if (out && (rc = rf_output_open(&o, out, &fp, err, sizeof(err))) < 0) {
		rf_report_destroy(r);
		die_status(rc, err);
	}
	if (!out)
		fp = stdout;
	rc = rf_report_write(r, fp, title, err, sizeof(err));
	rf_report_destroy(r);
	if (rc < 0)
		die_status(rc, err);
	if (o && (rc = rf_output_commit(o, err, sizeof(err))) < 0)
		die_status(rc, err);
	if (!o)
		fshut(stdout, "<stdout>");
	cli_progress_rows((size_t)(argc - optind) + 1);
	cli_progress_end();
	free(captions);
	free(times);
	free(captext);
	free(ns);
	return 0;
}
