/* reflect-compare: how far one image or stream is from another. */
#include <getopt.h>
#include <math.h>
#include <string.h>

#include "cli.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-V] [-c CHANNELS] [--mask[=CHANNEL]] [--objid=CHANNEL|none] "
	        "[--erode=N] [--fail=A] [--failpercent=P] [--hardfail=H] [--warn=W] "
	        "[--warnpercent=P] [--peak=P] [-o HEATMAP] [--scale=S] [-f a] [--json] "
	        "A B\n", argv0);
	exit(EXIT_BAD_INPUT);
}

/* Exit status of a comparison over its failure thresholds: 1 and 2 are
 * every tool's bad input and system error. */
enum { EXIT_DIFFERENT = 3 };

enum {
	OPT_MASK = 256, OPT_OBJID, OPT_ERODE, OPT_FAIL, OPT_FAILPERCENT, OPT_HARDFAIL, OPT_WARN,
	OPT_WARNPERCENT, OPT_PEAK, OPT_SCALE, OPT_JSON, OPT_HELP
};

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
	{ NULL, 0, NULL, 0 },
};

struct compare_opts {
	const char *channels, *mask, *objid, *heatmap;
	unsigned erode;
	double fail, failpercent, hardfail, warn, warnpercent, peak, scale;
	int ascii, json;
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

static void
write_heatmap(const char *path, const struct rf_compare_input *in, double scale)
{
	static const char *const names[] = { "R", "G", "B" };
	const size_t w = rf_compare_heatmap_width(in->width, in->height), h = in->height;
	float *rgb = emalloc(w * h * 3 * sizeof(float) + 1);
	rf_image_writer *iw;
	char err[1024];
	int type, rc;

	if ((type = rf_image_type_for_path(path)) < 0 && rf_image_module_check(err, sizeof(err)) < 0)
		die("%s", err);
	if (type < 0 && (type = rf_image_type_for_path(path)) < 0)
		die("-o: no image type for '%s' (try .png or .exr)", path);
	rf_compare_heatmap(rgb, in, scale);
	/* A failed write's message is the writer's, not err (which held
	 * nothing then), and a full disk is a system error. */
	if ((rc = rf_image_writer_open(&iw, path, w, h, 3, names, (enum rf_pixel_type)type,
	                               err, sizeof(err))) < 0)
		die_status(rc, err);
	if ((rc = rf_image_writer_write_rows(iw, 0, h, rgb)) < 0)
		die_status(rc, rf_image_writer_error(iw));
	if ((rc = rf_image_writer_close(iw, err, sizeof(err))) < 0)
		die_status(rc, err);
	free(rgb);
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
		printf("{\n  \"a\": \"%s\",\n  \"b\": \"%s\",\n  \"channels\": \"%s\",\n", an, bn,
		       names);
		printf("  \"pixels\": %zu,\n  \"values\": %zu,\n  \"nonfinite\": %zu,\n", st->npixels,
		       st->nvalues, st->nonfinite);
		json_number("rmse", st->rmse, 0);
		json_number("relative_rmse", st->rel_rmse, 0);
		json_number("mean_b", st->mean_b, 0);
		json_number("psnr", st->psnr, 0);
		json_number("max_error", st->max_error, 0);
		printf("  \"max_at\": [%zu, %zu],\n  \"max_channel\": \"%s\",\n", st->max_x, st->max_y,
		       chname[st->max_channel]);
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

int
main(int argc, char **argv)
{
	struct compare_opts o = { NULL, NULL, "objid", NULL, 1, 1e-6, 0, INFINITY, -1, 0, 1, 0,
	                          0, 0 };
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
	while ((c = getopt_long(argc, argv, "Vc:o:f:", long_options, NULL)) != -1) {
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
			       "  -f a  one line of numbers   --json  a JSON object   -V  versions\n",
			       argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default: usage();
		}
	}
	if (argc - optind != 2)
		usage();
	if (rf_picture_read(&a, argv[optind], err, sizeof(err)) < 0 ||
	    rf_picture_read(&b, argv[optind + 1], err, sizeof(err)) < 0)
		die("%s", err);
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
	rf_compare_stats(&st, &in, o.peak, o.fail, o.warn >= 0 ? o.warn : o.fail);
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
	c = report(&o, &st, warn_share, argv[optind], argv[optind + 1], names, chname);
	free(keep);
	rf_picture_destroy(a);
	rf_picture_destroy(b);
	return c;
}
