/* reflect-compare: how far one image or stream is from another. */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-V] " CLI_PROGRESS_USAGE " [-c CHANNELS] [--mask[=CHANNEL]] [--objid=CHANNEL|none] "
	        "[--erode=N] [--fail=A] [--failpercent=P] [--hardfail=H] [--warn=W] "
	        "[--warnpercent=P] [--peak=P] [-o HEATMAP] [--scale=S] [-f a] [--json] "
	        "[--metric=diff|flip|ldr-flip|hdr-flip] [--ppd=P|--viewing=D,W,PIXELS] "
	        "[--start-exposure=C] [--stop-exposure=C] [--exposures=N] [-j N] A B\n", argv0);
	exit(EXIT_BAD_INPUT);
}

/* Exit status of a comparison over its failure thresholds: 1 and 2 are
 * every tool's bad input and system error. */
enum { EXIT_DIFFERENT = 3 };

enum {
	OPT_MASK = 256, OPT_OBJID, OPT_ERODE, OPT_FAIL, OPT_FAILPERCENT, OPT_HARDFAIL, OPT_WARN,
	OPT_WARNPERCENT, OPT_PEAK, OPT_SCALE, OPT_JSON, OPT_HELP, OPT_METRIC, OPT_PPD, OPT_VIEWING,
	OPT_START, OPT_STOP, OPT_EXPOSURES
};

/* The metrics: values' differences, and FLIP of the kind the pictures
 * call for (LDR for display sRGB, HDR for linear) or named. */
enum { METRIC_DIFF, METRIC_FLIP, METRIC_LDR_FLIP, METRIC_HDR_FLIP };
static const char *const metric_names[] = { "diff", "flip", "ldr-flip", "hdr-flip" };

static const struct option long_options[] = {
	{ "channels", required_argument, NULL, 'c' },
	{ "mask", optional_argument, NULL, OPT_MASK },
	{ "objid", required_argument, NULL, OPT_OBJID },
	{ "erode", required_argument, NULL, OPT_ERODE },
	{ "fail", required_argument, NULL, OPT_FAIL },
	{ "failpercent", required_argument, NULL, OPT_FAILPERCENT },
	{ "hardfail", required_argument, NULL, OPT_HARDFAIL },
	{ "warn", required_argument, NULL, OPT_WARN },
	{ "warnpercent", required_argument, NULL, OPT_WARNPERCENT },
	{ "peak", required_argument, NULL, OPT_PEAK },
	{ "scale", required_argument, NULL, OPT_SCALE },
	{ "json", no_argument, NULL, OPT_JSON },
	{ "help", no_argument, NULL, OPT_HELP },
	{ "metric", required_argument, NULL, OPT_METRIC },
	{ "ppd", required_argument, NULL, OPT_PPD },
	{ "viewing", required_argument, NULL, OPT_VIEWING },
	{ "start-exposure", required_argument, NULL, OPT_START },
	{ "stop-exposure", required_argument, NULL, OPT_STOP },
	{ "exposures", required_argument, NULL, OPT_EXPOSURES },
	CLI_PROGRESS_OPTION,
	{ NULL, 0, NULL, 0 },
};

struct compare_opts {
	const char *channels, *mask, *objid, *heatmap;
	unsigned erode;
	double fail, failpercent, hardfail, warn, warnpercent, peak, scale;
	int ascii, json;
	int metric, exposures_given;
	const char *threads;
	struct rf_flip_options flip;
};

#define MAX_CHANNELS 64

/* Dies: the two share no colour; says what each has. */
static void
no_colour(const rf_picture *a, const rf_picture *b, const char *an, const char *bn)
{
	const rf_picture *p[2] = { a, b };
	const char *n[2] = { an, bn };
	size_t k, i;

	cli_message_start();
	fputs("no colour to compare: neither R G B nor spec.R spec.G spec.B is in both", stderr);
	for (k = 0; k < 2; k++) {
		fputs(k ? "; " : " (", stderr);
		cli_put_quoted(stderr, n[k]);
		fputs(" has", stderr);
		for (i = 0; i < rf_picture_nchannels(p[k]); i++) {
			fputc(' ', stderr);
			cli_put_quoted(stderr, rf_picture_channel(p[k], i));
		}
		if (!rf_picture_nchannels(p[k]))
			fputs(" none", stderr);
	}
	fputs("); name them with -c, as A_NAME=B_NAME where they differ\n", stderr);
	exit(EXIT_BAD_INPUT);
}

/* The channels compared: -c's (NAME, or A_NAME=B_NAME), else R G B,
 * else spec.R spec.G spec.B: colour only, so that a pass always means
 * that colours agree, never that a mask or an id did; their indices
 * into cols. */
static size_t
choose_channels(const struct compare_opts *o, const rf_picture *a, const rf_picture *b,
                const char *an, const char *bn, int *acol, int *bcol, char *names,
                size_t names_len)
{
	static const char *const rgb[] = { "R", "G", "B" };
	static const char *const spec[] = { "spec.R", "spec.G", "spec.B" };
	size_t n = 0, i;

	names[0] = '\0';
	if (o->channels) {
		char *list = estrdup(o->channels), *save = NULL, *t, *eq;

		for (t = strtok_r(list, ", ", &save); t; t = strtok_r(NULL, ", ", &save)) {
			const char *bname = t;

			if (n == MAX_CHANNELS)
				die("-c: more than %d channels", MAX_CHANNELS);
			if ((eq = strchr(t, '='))) {
				*eq = '\0';
				bname = eq + 1;
				if (!*t || !*bname || strchr(bname, '='))
					die("-c: '%s=%s' is not A_NAME=B_NAME", t, bname);
			}
			if ((acol[n] = rf_picture_find_channel(a, t)) < 0)
				die("'%s' has no channel '%s'", an, t);
			if ((bcol[n] = rf_picture_find_channel(b, bname)) < 0)
				die("'%s' has no channel '%s'", bn, bname);
			n++;
		}
		free(list);
		if (!n)
			die("-c: no channel named");
	} else {
		const char *const *set = NULL;

		for (i = 0; i < 2 && !set; i++) {
			const char *const *s = i ? spec : rgb;
			size_t k;

			for (k = 0; k < 3 && rf_picture_find_channel(a, s[k]) >= 0 &&
			            rf_picture_find_channel(b, s[k]) >= 0; k++)
				;
			if (k == 3)
				set = s;
		}
		if (!set)
			no_colour(a, b, an, bn);
		for (i = 0; i < 3; i++) {
			acol[n] = rf_picture_find_channel(a, set[i]);
			bcol[n++] = rf_picture_find_channel(b, set[i]);
		}
	}
	for (i = 0; i < n; i++) {
		size_t len = strlen(names);
		const char *na = rf_picture_channel(a, (size_t)acol[i]);
		const char *nb = rf_picture_channel(b, (size_t)bcol[i]);

		if (strcmp(na, nb))
			snprintf(names + len, names_len - len, "%s%s=%s", i ? " " : "", na, nb);
		else
			snprintf(names + len, names_len - len, "%s%s", i ? " " : "", na);
	}
	return n;
}

/* The pixels that count, from the mask channel of A (else B). */
static unsigned char *
make_mask(const struct compare_opts *o, const rf_picture *a, const rf_picture *b,
          const char *an, const char *bn)
{
	const rf_picture *m = rf_picture_find_channel(a, o->mask) >= 0 ? a : b;
	const size_t w = rf_picture_width(a), h = rf_picture_height(a);
	const float *px = rf_picture_pixels(m);
	unsigned char *keep = emalloc(w * h + 1);
	int mc = rf_picture_find_channel(m, o->mask), oc = -1;

	if (mc < 0)
		die("neither '%s' nor '%s' has the mask channel '%s'", an, bn, o->mask);
	if (strcmp(o->objid, "none") && (oc = rf_picture_find_channel(m, o->objid)) < 0 &&
	    strcmp(o->objid, "objid"))
		die("'%s' has no channel '%s' (--objid)", m == a ? an : bn, o->objid);
	rf_compare_mask(keep, w, h, px + mc, oc >= 0 ? px + oc : NULL, rf_picture_nchannels(m),
	                o->erode);
	return keep;
}

/* Writes w x h display RGB pixels to path, of the type its name says. */
static void
write_rgb(const char *path, const float *rgb, size_t w, size_t h)
{
	static const char *const names[] = { "R", "G", "B" };
	rf_image_writer *iw;
	char err[1024];
	int type, rc;

	if ((type = rf_image_type_for_path(path)) < 0 && rf_image_module_check(err, sizeof(err)) < 0)
		die("%s", err);
	if (type < 0 && (type = rf_image_type_for_path(path)) < 0)
		die("-o: no image type for '%s' (try .png or .exr)", path);
	/* A failed write's message is the writer's, not err (which held
	 * nothing then), and a full disk is a system error. */
	if ((rc = rf_image_writer_open(&iw, path, w, h, 3, names, (enum rf_pixel_type)type,
	                               err, sizeof(err))) < 0)
		die_status(rc, err);
	if ((rc = rf_image_writer_write_rows(iw, 0, h, rgb)) < 0)
		die_status(rc, rf_image_writer_error(iw));
	if ((rc = rf_image_writer_close(iw, err, sizeof(err))) < 0)
		die_status(rc, err);
}

static void
write_heatmap(const char *path, const struct rf_compare_input *in, double scale)
{
	const size_t w = rf_compare_heatmap_width(in->width, in->height), h = in->height;
	float *rgb = emalloc(w * h * 3 * sizeof(float) + 1);

	rf_compare_heatmap(rgb, in, scale);
	write_rgb(path, rgb, w, h);
	free(rgb);
}

/* A string as JSON has it: a file name may hold quotes, backslashes and
 * control bytes. */
static void
json_string(const char *s)
{
	putchar('"');
	for (; *s; s++) {
		const unsigned char c = (unsigned char)*s;

		if (c == '"' || c == '\\')
			printf("\\%c", c);
		else if (c < 0x20 || c == 0x7f)
			printf("\\u%04x", c);
		else
			putchar(c);
	}
	putchar('"');
}

/* The start of a report in JSON: what was compared. */
static void
json_head(const char *an, const char *bn, const char *names)
{
	fputs("{\n  \"a\": ", stdout);
	json_string(an);
	fputs(",\n  \"b\": ", stdout);
	json_string(bn);
	fputs(",\n  \"channels\": ", stdout);
	json_string(names);
	fputs(",\n", stdout);
}

/* Numbers as JSON has them: no inf or nan. */
static void
json_number(const char *key, double v, int last)
{
	if (isfinite(v))
		printf("  \"%s\": %.9g%s\n", key, v, last ? "" : ",");
	else
		printf("  \"%s\": %s%s\n", key, isnan(v) ? "null" : v > 0 ? "\"inf\"" : "\"-inf\"",
		       last ? "" : ",");
}

/* Prints the figures; the exit status: 0, or EXIT_DIFFERENT when over
 * the failure thresholds (warn_share: the share over --warn). */
static int
report(const struct compare_opts *o, const struct rf_compare_stats *st, double warn_share,
       const char *an, const char *bn, const char *names, const char *const *chname)
{
	const double share = st->npixels ? 100.0 * (double)st->nover / (double)st->npixels : 0.0;
	const int failed = share > o->failpercent || st->max_error > o->hardfail;
	const int warned = !failed && o->warn >= 0 && warn_share > o->warnpercent;

	if (o->json) {
		json_head(an, bn, names);
		printf("  \"pixels\": %zu,\n  \"values\": %zu,\n  \"nonfinite\": %zu,\n", st->npixels,
		       st->nvalues, st->nonfinite);
		json_number("rmse", st->rmse, 0);
		json_number("relative_rmse", st->rel_rmse, 0);
		json_number("mean_b", st->mean_b, 0);
		json_number("psnr", st->psnr, 0);
		json_number("max_error", st->max_error, 0);
		printf("  \"max_at\": [%zu, %zu],\n  \"max_channel\": ", st->max_x, st->max_y);
		json_string(chname[st->max_channel]);
		fputs(",\n", stdout);
		json_number("over_percent", share, 0);
		printf("  \"result\": \"%s\"\n}\n", failed ? "fail" : warned ? "warn" : "pass");
	} else if (o->ascii) {
		printf("%.9g %.9g %.9g %.9g %.9g %zu\n", st->rmse, st->rel_rmse, st->psnr,
		       st->max_error, share, st->npixels);
	} else {
		printf("'%s' against '%s': %s, %zu pixels%s\n", an, bn, names, st->npixels,
		       o->mask ? " (on the mask)" : "");
		printf("  RMSE         %.6g\n", st->rmse);
		printf("  relative     %.6g (of the mean of B, %.6g)\n", st->rel_rmse, st->mean_b);
		printf("  PSNR         %.6g dB (peak %g)\n", st->psnr, o->peak);
		printf("  max error    %.6g at pixel %zu, %zu (channel %s)\n", st->max_error,
		       st->max_x, st->max_y, chname[st->max_channel]);
		printf("  over %-7g %.6g %% of the pixels\n", o->fail, share);
		if (st->nonfinite)
			printf("  not finite   %zu values\n", st->nonfinite);
		printf("%s\n", failed ? "FAIL" : warned ? "WARNING" : "PASS");
	}
	fshut(stdout, "<stdout>");
	return failed ? EXIT_DIFFERENT : 0;
}

/* FLIP's figures, as report() prints the others'. */
static int
report_flip(const struct compare_opts *o, const struct rf_flip_stats *st, const char *an,
            const char *bn, const char *names)
{
	const double share = st->npixels ? 100.0 * (double)st->nover / (double)st->npixels : 0.0;
	const double warn_share = st->npixels ? 100.0 * (double)st->nwarn / (double)st->npixels
	                                      : 0.0;
	const int failed = share > o->failpercent || st->max_error > o->hardfail;
	const int warned = !failed && o->warn >= 0 && warn_share > o->warnpercent;
	const int hdr = o->flip.hdr;

	if (o->json) {
		json_head(an, bn, names);
		printf("  \"metric\": \"%s\",\n  \"pixels\": %zu,\n", hdr ? "hdr-flip" : "ldr-flip",
		       st->npixels);
		json_number("ppd", o->flip.ppd, 0);
		if (hdr) {
			json_number("start_exposure", o->flip.start, 0);
			json_number("stop_exposure", o->flip.stop, 0);
			printf("  \"exposures\": %d,\n", o->flip.nexposures);
		}
		json_number("mean", st->mean, 0);
		json_number("max_error", st->max_error, 0);
		printf("  \"max_at\": [%zu, %zu],\n", st->max_x, st->max_y);
		json_number("over_percent", share, 0);
		printf("  \"result\": \"%s\"\n}\n", failed ? "fail" : warned ? "warn" : "pass");
	} else if (o->ascii) {
		printf("%.9g %.9g %.9g %zu", st->mean, st->max_error, share, st->npixels);
		if (hdr)
			printf(" %.9g %.9g %d", o->flip.start, o->flip.stop, o->flip.nexposures);
		putchar('\n');
	} else {
		printf("'%s' against '%s': %s, %s, %zu pixels%s\n", an, bn,
		       hdr ? "HDR-FLIP" : "LDR-FLIP", names, st->npixels,
		       o->mask ? " (on the mask)" : "");
		printf("  mean         %.6f\n", st->mean);
		printf("  max          %.6f at pixel %zu, %zu\n", st->max_error, st->max_x, st->max_y);
		printf("  viewing      %.4g pixels per degree\n", o->flip.ppd);
		if (hdr)
			printf("  exposures    %d from %.4f to %.4f stops\n", o->flip.nexposures,
			       o->flip.start, o->flip.stop);
		printf("  over %-7g %.6g %% of the pixels\n", o->fail, share);
		printf("%s\n", failed ? "FAIL" : warned ? "WARNING" : "PASS");
	}
	fshut(stdout, "<stdout>");
	return failed ? EXIT_DIFFERENT : 0;
}

/* The kind of FLIP the pictures call for, or die saying why none. */
static void
flip_kind(struct compare_opts *o, const rf_picture *a, const rf_picture *b, const char *an,
          const char *bn, size_t nch)
{
	const int as = rf_picture_srgb(a), bs = rf_picture_srgb(b);

	if (nch != 3)
		die("--metric=%s compares colour: -c names %zu channels, not three (R G B)",
		    metric_names[o->metric], nch);
	if (o->scale > 0)
		die("--scale: FLIP's map is 0 to 1 always");
	if (o->metric == METRIC_FLIP && as != bs)
		die("'%s' is %s, '%s' %s: name the metric, --metric=ldr-flip (the linear one "
		    "clamped to [0, 1]) or convert one", an, as ? "display sRGB" : "linear", bn,
		    bs ? "display sRGB" : "linear");
	if (o->metric == METRIC_HDR_FLIP && (as || bs))
		die("--metric=hdr-flip compares linear pictures, and '%s' is display sRGB: "
		    "use --metric=ldr-flip", as ? an : bn);
	o->flip.hdr = o->metric == METRIC_HDR_FLIP || (o->metric == METRIC_FLIP && !bs);
	o->flip.a_srgb = as;
	o->flip.b_srgb = bs;
	if (!o->flip.hdr && o->exposures_given)
		die("--start-exposure, --stop-exposure and --exposures are HDR-FLIP's, and '%s' "
		    "against '%s' is LDR-FLIP", an, bn);
}

/* FLIP of A against B (the reference): the exposures, the map, the
 * figures; the exit status. */
static int
run_flip(struct compare_opts *o, const struct rf_compare_input *in, const char *an,
         const char *bn, const char *names)
{
	const size_t w = in->width, h = in->height;
	struct rf_compare_stats vs;
	struct rf_flip_stats st;
	double start, stop;
	float *error;
	int count, rc;

	rf_compare_stats(&vs, in, 1.0, 0.0, 0.0);
	if (vs.nonfinite)
		die("'%s' against '%s': %zu values are not finite (the first at pixel %zu, %zu): "
		    "FLIP compares finite colours", an, bn, vs.nonfinite, vs.max_x, vs.max_y);
	if (o->flip.hdr && (isnan(o->flip.start) || isnan(o->flip.stop))) {
		if (rf_flip_exposures(in, &start, &stop, &count) < 0)
			die("'%s' (the reference): more than half its pixels are black, so HDR-FLIP's "
			    "exposures cannot come from its luminance: give --start-exposure and "
			    "--stop-exposure", bn);
		if (isnan(o->flip.start))
			o->flip.start = start;
		if (isnan(o->flip.stop))
			o->flip.stop = stop;
	}
	/* the count the automatic one would be, from the range in use */
	if (o->flip.hdr && !o->flip.nexposures)
		o->flip.nexposures = (int)fmax(2.0, ceil(o->flip.stop - o->flip.start));
	if (o->flip.hdr && o->flip.start > o->flip.stop)
		die("HDR-FLIP's start exposure %g is above its stop exposure %g", o->flip.start,
		    o->flip.stop);
	o->flip.nthreads = cli_threads(o->threads);
	/* made once nothing above can end the tool, and freed before a
	 * refusal below: LeakSanitizer sees no block left behind */
	error = emalloc(w * h * sizeof(float) + 1);
	if ((rc = rf_compare_flip(error, &o->flip, in)) < 0) {
		free(error);
		die_status(rc, rc == RF_ENOMEM ? "out of memory for FLIP's sums" : rf_strerror(rc));
	}
	cli_progress_rows(3);
	rf_flip_stats(&st, error, w, h, in->keep, o->fail, o->warn >= 0 ? o->warn : o->fail);
	if (!st.npixels) {
		free(error);
		die("'%s' against '%s': no pixel to compare%s", an, bn,
		    o->mask ? ": the mask is empty" : "");
	}
	if (o->heatmap) {
		float *rgb = emalloc(w * h * 3 * sizeof(float) + 1);

		rf_flip_heatmap(rgb, error, w, h, in->keep);
		write_rgb(o->heatmap, rgb, w, h);
		free(rgb);
	}
	free(error);
	cli_progress_rows(o->heatmap ? 4 : 3);
	cli_progress_end();
	return report_flip(o, &st, an, bn, names);
}

/* --viewing=DISTANCE,WIDTH,PIXELS: pixels per degree. */
static double
parse_viewing(const char *arg)
{
	char *list = estrdup(arg), *save = NULL, *t;
	double v[3];
	int n = 0;

	for (t = strtok_r(list, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		if (n == 3)
			break;
		v[n] = parse_number(n == 0 ? "viewing's distance" : n == 1 ? "viewing's width"
		                                                           : "viewing's pixels",
		                    t, n == 2 ? 1 : 1e-3, n == 2 ? 1e6 : 1e3);
		n++;
	}
	free(list);
	if (n != 3 || t)
		die("--viewing: '%s' is not DISTANCE,WIDTH,PIXELS (metres, metres, pixels: "
		    "0.7,0.7,3840)", arg);
	v[0] = rf_flip_ppd(v[0], v[1], v[2]);
	if (v[0] < 1 || v[0] > 1000)
		die("--viewing: '%s' makes %g pixels per degree, outside [1, 1000]", arg, v[0]);
	return v[0];
}

int
main(int argc, char **argv)
{
	struct compare_opts o = { NULL, NULL, "objid", NULL, 1, 1e-6, 0, INFINITY, -1, 0, 1, 0,
	                          0, 0, METRIC_DIFF, 0, NULL,
	                          { 0, 0, 0, 0.0, NAN, NAN, 0, 1 } };
	int acol[MAX_CHANNELS], bcol[MAX_CHANNELS], c;
	const char *chname[MAX_CHANNELS];
	char names[1024], err[1024];
	struct rf_compare_input in;
	struct rf_compare_stats st;
	rf_picture *a, *b;
	unsigned char *keep = NULL;
	double warn_share = 0.0;
	size_t n, i;

	cli_init(argc, argv);
	o.flip.ppd = RF_FLIP_PPD_DEFAULT;
	while ((c = getopt_long(argc, argv, "Vqc:o:f:j:", long_options, NULL)) != -1) {
		switch (c) {
		case 'V': print_version(); break;
		case 'c': o.channels = optarg; break;
		case 'o': o.heatmap = optarg; break;
		case 'f':
			if (strcmp(optarg, "a"))
				die("-f: '%s' is not a (one line of numbers)", optarg);
			o.ascii = 1;
			break;
		case OPT_MASK: o.mask = optarg ? optarg : "mask"; break;
		case OPT_OBJID: o.objid = optarg; break;
		case OPT_ERODE: o.erode = (unsigned)parse_number("erode", optarg, 0, 1000); break;
		case OPT_FAIL: o.fail = parse_number("fail", optarg, 0, INFINITY); break;
		case OPT_FAILPERCENT: o.failpercent = parse_number("failpercent", optarg, 0, 100); break;
		case OPT_HARDFAIL: o.hardfail = parse_number("hardfail", optarg, 0, INFINITY); break;
		case OPT_WARN: o.warn = parse_number("warn", optarg, 0, INFINITY); break;
		case OPT_WARNPERCENT: o.warnpercent = parse_number("warnpercent", optarg, 0, 100); break;
		case OPT_PEAK: o.peak = parse_number("peak", optarg, 1e-30, INFINITY); break;
		case OPT_SCALE: o.scale = parse_number("scale", optarg, 0, INFINITY); break;
		case OPT_JSON: o.json = 1; break;
		case 'j': o.threads = optarg; break;
		case OPT_METRIC:
			for (i = 0; i < 4 && strcmp(optarg, metric_names[i]); i++)
				;
			if (i == 4)
				die("--metric: '%s' is not diff, flip, ldr-flip or hdr-flip", optarg);
			o.metric = (int)i;
			break;
		case OPT_PPD: o.flip.ppd = parse_number("ppd", optarg, 1, 1000); break;
		case OPT_VIEWING: o.flip.ppd = parse_viewing(optarg); break;
		case OPT_START:
			o.flip.start = parse_number("start-exposure", optarg, -200, 200);
			o.exposures_given = 1;
			break;
		case OPT_STOP:
			o.flip.stop = parse_number("stop-exposure", optarg, -200, 200);
			o.exposures_given = 1;
			break;
		case OPT_EXPOSURES:
			o.flip.nexposures = (int)parse_number("exposures", optarg, 1, 400);
			if (o.flip.nexposures != parse_number("exposures", optarg, 1, 400))
				die("--exposures: '%s' is not a whole number", optarg);
			o.exposures_given = 1;
			break;
		case OPT_HELP:
			printf("usage: %s [options] A B\n"
			       "How far A is from B: two images (any type reflect reads) or streams.\n"
			       "Exit 0 when they agree within the thresholds, 3 when they do not.\n"
			       "See reflect-compare(1).\n"
			       "  -c CHANNELS  compared (default R G B, else spec.*); A_NAME=B_NAME\n"
			       "      where the two name a channel differently\n"
			       "  --mask[=CHANNEL] --objid=CHANNEL|none --erode=N  the pixels\n"
			       "      that count: on the mask, N pixels from another object (1)\n"
			       "  --fail=A --failpercent=P --hardfail=H  fail when over P %% of the\n"
			       "      pixels differ by more than A, or one by more than H\n"
			       "  --warn=W --warnpercent=P  warn likewise (exit 0)\n"
			       "  --peak=P  PSNR's peak (1)   -o FILE  heat map   --scale=S  its top\n"
			       "  -f a  one line of numbers   --json  a JSON object   -V  versions\n"
			       "  --metric=diff|flip|ldr-flip|hdr-flip  values' differences (diff),\n"
			       "      or FLIP: LDR for display sRGB pictures, HDR for linear ones\n"
			       "  --ppd=P  FLIP's pixels per degree (67, from --viewing=0.7,0.7,3840:\n"
			       "      metres away, metres wide, pixels wide)\n"
			       "  --start-exposure=C --stop-exposure=C --exposures=N  HDR-FLIP's\n"
			       "      (from B's luminance)   -j N  threads\n"
			       CLI_PROGRESS_HELP, argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	if (argc - optind != 2)
		usage();
	/* Two large EXRs take seconds to read and FLIP as long to measure:
	 * progress counts the steps, each picture read, the measure and the
	 * map written. */
	cli_progress_unit("step");
	cli_progress_frames(1);
	cli_progress_frame(o.heatmap ? 4 : 3);
	if (rf_picture_read(&a, argv[optind], err, sizeof(err)) < 0)
		die("%s", err);
	cli_progress_rows(1);
	if (rf_picture_read(&b, argv[optind + 1], err, sizeof(err)) < 0)
		die("%s", err);
	cli_progress_rows(2);
	if (rf_picture_width(a) != rf_picture_width(b) ||
	    rf_picture_height(a) != rf_picture_height(b))
		die("'%s' is %zux%zu, '%s' %zux%zu: compare pictures of one size", argv[optind],
		    rf_picture_width(a), rf_picture_height(a), argv[optind + 1],
		    rf_picture_width(b), rf_picture_height(b));
	n = choose_channels(&o, a, b, argv[optind], argv[optind + 1], acol, bcol, names,
	                    sizeof(names));
	for (i = 0; i < n; i++)
		chname[i] = rf_picture_channel(a, (size_t)acol[i]);
	if (o.mask)
		keep = make_mask(&o, a, b, argv[optind], argv[optind + 1]);
	in.a = rf_picture_pixels(a);
	in.b = rf_picture_pixels(b);
	in.a_stride = rf_picture_nchannels(a);
	in.b_stride = rf_picture_nchannels(b);
	in.a_col = acol;
	in.b_col = bcol;
	in.nch = n;
	in.width = rf_picture_width(a);
	in.height = rf_picture_height(a);
	in.keep = keep;
	if (o.metric != METRIC_DIFF) {
		flip_kind(&o, a, b, argv[optind], argv[optind + 1], n);
		c = run_flip(&o, &in, argv[optind], argv[optind + 1], names);
		free(keep);
		rf_picture_destroy(a);
		rf_picture_destroy(b);
		return c;
	}
	rf_compare_stats(&st, &in, o.peak, o.fail, o.warn >= 0 ? o.warn : o.fail);
	cli_progress_rows(3);
	if (!st.npixels && o.mask)
		die("'%s' against '%s': no pixel to compare: the mask '%s' is empty%s", argv[optind],
		    argv[optind + 1], o.mask, o.erode ? " once eroded (try a smaller --erode)" : "");
	if (!st.npixels)
		die("'%s' against '%s': no pixel to compare", argv[optind], argv[optind + 1]);
	warn_share = st.npixels ? 100.0 * (double)st.nwarn / (double)st.npixels : 0.0;
	if (o.heatmap)
		write_heatmap(o.heatmap, &in, o.scale > 0 ? o.scale
		                                          : (isfinite(st.max_error) && st.max_error > 0
		                                                 ? st.max_error : 1.0));
	cli_progress_rows(o.heatmap ? 4 : 3);
	cli_progress_end();
	c = report(&o, &st, warn_share, argv[optind], argv[optind + 1], names, chname);
	free(keep);
	rf_picture_destroy(a);
	rf_picture_destroy(b);
	return c;
}
