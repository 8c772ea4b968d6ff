/* reflect-prefilter: an environment to a GGX-convolved mip chain. */
#include <getopt.h>
#include <math.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <unistd.h>

#include "cli_envmap.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-SvV] [-o OUT] [-s SAMPLES] [-j THREADS] "
	        CLI_PROGRESS_USAGE " "
	        "[--levels=N] [--min-size=N] [--mapping=unity|linear|exact] "
	        "[--steps=N] [--method=filtered|brute] [--plain] [--lod-bias=B] "
	        "[--layout=L] [--size=N] [--srgb=auto|on|off] [--rgbm=M[,E]] "
	        "[--intensity=X] [--nonfinite=error|zero] "
	        "[--dump=latlong|cube|vcross|hcross] "
	        "[--edge-fixup=none|average] [--irradiance=FILE] "
	        "[--ktx-texel=half|float] [--zstd[=LEVEL]] [-f a|f] [-h] "
	        "[ENV]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

struct prefilter_opts {
	const char *output;
	const char *dump;
	const char *irradiance; /* --irradiance=FILE */
	struct rf_prefilter_options pf;
	size_t levels, min_size;
	int plain, verbose;
	int edge_average; /* --edge-fixup=average */
	enum rf_format format;
	int no_header;
	struct rf_ktx_options ktx; /* --ktx-texel, --zstd */
};

static int
ends_ktx2(const char *path)
{
	const char *dot = path ? strrchr(path, '.') : NULL;

	return dot && !strcasecmp(dot, ".ktx2");
}

static double
now(clockid_t clock)
{
	struct timespec t;

	clock_gettime(clock, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The texel rows of every level as the rows of one frame. */
static void
progress(void *arg, double done, double total)
{
	int *started = arg;

	if (!*started) {
		cli_progress_frames(1);
		cli_progress_frame((size_t)total);
		*started = 1;
	}
	cli_progress_rows((size_t)done);
}

static void
dump_levels(const rf_cubemap *c, const char *spec)
{
	enum rf_layout layout;
	char path[4096], err[1024];
	static const char *const names[] = { "R", "G", "B" };
	size_t k;
	int rc;

	if (rf_layout_parse(spec, &layout) < 0 || layout == RF_LAYOUT_AUTO ||
	    layout == RF_LAYOUT_MIRRORBALL || layout == RF_LAYOUT_ANGULAR)
		die("--dump: '%s' is not latlong, cube, vcross or hcross", spec);
	for (k = 0; k < rf_cubemap_levels(c); k++) {
		size_t n = rf_cubemap_level_size(c, k), w, h;
		rf_image_writer *iw;
		float *px;

		rf_layout_size(layout, n, &w, &h);
		if (layout == RF_LAYOUT_LATLONG && n < 8)
			rf_layout_size(layout, 8, &w, &h); /* small levels still legible */
		px = emalloc(w * h * 3 * sizeof(float));
		rf_envmap_to_pixels(c, k, layout, px, w, h);
		snprintf(path, sizeof(path), "level%zu-%s.exr", k, spec);
		if ((rc = rf_image_writer_open(&iw, path, w, h, 3, names, RF_PIXEL_HALF, err,
		                               sizeof(err))) < 0)
			die_status(rc, err);
		if ((rc = rf_image_writer_write_rows(iw, 0, h, px)) < 0)
			die_status(rc, rf_image_writer_error(iw));
		if ((rc = rf_image_writer_close(iw, err, sizeof(err))) < 0)
			die_status(rc, err);
		warn("wrote '%s'", path);
		free(px);
	}
}

static void
write_chain(const struct prefilter_opts *o, const char *output, const rf_cubemap *c,
            const struct rf_chain_info *info)
{
	struct rf_writer_options wopt = { o->format, o->no_header };
	char err[1024];
	rf_header *base;
	rf_writer *w;
	rf_output *file = NULL;
	FILE *fp = stdout;
	const char *name = "<stdout>";
	int rc;

	if ((rc = rf_header_create(&base)) < 0)
		die_status(rc, NULL);

	if (output) {
		const char *dot = strrchr(output, '.');

		if (dot && (!strcasecmp(dot, ".ktx") || !strcasecmp(dot, ".ktx2"))) {
			struct rf_ktx_options ko = o->ktx;

			ko.version = dot[4] ? 2 : 1;
			if (ko.version == 1)
				ko.zstd = 0; /* --zstd is for the .ktx2 of -o or --irradiance */
			if ((rc = rf_chain_write_ktx(c, info, output, &ko, err, sizeof(err))) < 0)
				die_status(rc, err);
			rf_header_destroy(base);
			return;
		}
		if (dot && strcmp(dot, ".rfl") && strcmp(dot, ".stream")) {
			if ((rc = rf_chain_write_file(c, info, output, err, sizeof(err))) < 0)
				die_status(rc, err);
			rf_header_destroy(base);
			return;
		}
		/* whole or not at all: an old file stays if this fails */
		if ((rc = rf_output_open(&file, output, &fp, err, sizeof(err))) < 0)
			die_status(rc, err);
		name = output;
	}
	cli_record_command(base);
	if ((rc = rf_writer_open(&w, fp, name, &wopt)) < 0)
		die_status(rc, NULL);
	if ((rc = rf_chain_write_stream(c, info, w, base, err, sizeof(err))) < 0)
		die_status(rc, err);
	rf_writer_close(w);
	rf_header_destroy(base);
	if (file && (rc = rf_output_commit(file, err, sizeof(err))) < 0)
		die_status(rc, err);
}

int
main(int argc, char **argv)
{
	static const struct option long_options[] = {
		{ "env", required_argument, NULL, 0 },
		{ "layout", required_argument, NULL, 0 },
		{ "srgb", required_argument, NULL, 0 },
		{ "rgbm", required_argument, NULL, 0 },
		{ "intensity", required_argument, NULL, 0 },
		{ "size", required_argument, NULL, 0 },
		{ "prefiltered", no_argument, NULL, 0 },
		{ "nonfinite", required_argument, NULL, 0 },
		{ "levels", required_argument, NULL, 'L' },
		{ "min-size", required_argument, NULL, 'M' },
		{ "mapping", required_argument, NULL, 'P' },
		{ "steps", required_argument, NULL, 'T' },
		{ "method", required_argument, NULL, 'X' },
		{ "plain", no_argument, NULL, 'N' },
		{ "lod-bias", required_argument, NULL, 'B' },
		{ "dump", required_argument, NULL, 'D' },
		{ "edge-fixup", required_argument, NULL, 'E' },
		{ "irradiance", required_argument, NULL, 'I' },
		{ "ktx-texel", required_argument, NULL, 'K' },
		{ "zstd", optional_argument, NULL, 'Z' },
		{ "help", no_argument, NULL, 'Q' },
		CLI_PROGRESS_OPTION,
		{ NULL, 0, NULL, 0 },
	};
	struct prefilter_opts o;
	struct envmap_opts eo;
	struct rf_chain_info info;
	rf_cubemap *src, *out;
	const char *threads = NULL;
	char err[1024];
	int c, idx, rc, progress_started = 0;

	cli_init(argc, argv);
	memset(&o, 0, sizeof(o));
	rf_prefilter_defaults(&o.pf);
	o.min_size = 1;
	envmap_opts_init(&eo);
	while ((c = getopt_long(argc, argv, "qSvVo:s:j:f:h", long_options, &idx)) != -1) {
		switch (c) {
		case 0:
			envmap_opts_parse(&eo, long_options[idx].name, optarg);
			break;
		case 'S': eo.load.strict = 1; break;
		case 'v': o.verbose = 1; break;
		case 'V': print_version(); break;
		case 'o': o.output = optarg; break;
		case 's': o.pf.samples = (unsigned)parse_count(optarg, 's', 1, 1 << 16); break;
		case 'j': threads = optarg; break;
		case 'f':
			o.format = parse_format(optarg);
			break;
		case 'h': o.no_header = 1; break;
		case 'L': o.levels = (size_t)parse_whole("levels", optarg, 2, 16); break;
		case 'M': o.min_size = (size_t)parse_whole("min-size", optarg, 1, 1 << 14); break;
		case 'P':
			if (rf_mapping_parse(optarg, &o.pf.mapping) < 0)
				die("--mapping: '%s' is not unity, linear or exact", optarg);
			break;
		case 'T': o.pf.steps = (float)parse_number("steps", optarg, 0.5, 64); break;
		case 'X':
			if (!strcmp(optarg, "filtered")) o.pf.method = RF_PREFILTER_FILTERED;
			else if (!strcmp(optarg, "brute")) o.pf.method = RF_PREFILTER_BRUTE;
			else die("--method: '%s' is not filtered or brute", optarg);
			break;
		case 'N': o.plain = 1; break;
		case 'B': o.pf.lod_bias = (float)parse_number("lod-bias", optarg, -4, 4); break;
		case 'D': o.dump = optarg; break;
		case 'I': o.irradiance = optarg; break;
		case 'K':
			if (!strcmp(optarg, "half")) o.ktx.texel = RF_KTX_RGBA16F;
			else if (!strcmp(optarg, "float")) o.ktx.texel = RF_KTX_RGBA32F;
			else die("--ktx-texel: '%s' is not half or float", optarg);
			break;
		case 'Z':
			o.ktx.zstd = 3; /* zstd's own default */
			if (optarg) {
				double z = parse_number("zstd", optarg, 1, 22);

				if (z != (int)z)
					die("--zstd: '%s' is not a level 1 to 22", optarg);
				o.ktx.zstd = (int)z;
			}
			break;
		case 'E':
			if (!strcmp(optarg, "average")) o.edge_average = 1;
			else if (strcmp(optarg, "none")) die("--edge-fixup: '%s' is not none or average", optarg);
			break;
		case 'Q':
			printf("usage: %s [options] [ENV]\n"
			       "Convolves an environment (lat-long, N x 6N cube, cross, six faces\n"
			       "with %%d or %%s in the name, a stream, or the embedded room when\n"
			       "none is given) into a GGX mip chain. See reflect-prefilter(1).\n"
			       "  -o OUT  .exr: MIP-mapped OpenEXR cube; .ktx, .ktx2: KTX cube;\n"
			       "          .rfl: stream (stdout without -o)\n"
			       "  --ktx-texel=half|float  a KTX file's RGBA texels (half)\n"
			       "  --zstd[=LEVEL]  Zstandard levels in a .ktx2 file (level 3)\n"
			       "  -s N  GGX samples at level 1 (64), x3 per rougher level\n"
			       "  --levels=N --min-size=N --mapping=unity|linear|exact --steps=N\n"
			       "  --method=filtered|brute  --plain (box mips)  --lod-bias=B\n"
			       "  --dump=latlong|cube|vcross|hcross  each level to levelK-LAYOUT.exr\n"
			       "  --edge-fixup=none|average  equal edge texels for per-face readers\n"
			       "  --irradiance=FILE  also a 32-texel cube of E / pi (diffuse light)\n"
			       "  --nonfinite=error|zero  a NaN or Inf texel refused (error, as -S)\n"
			       "          or replaced with 0\n"
			       "  -j N threads  -v  -V\n"
			       CLI_PROGRESS_HELP, argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default:
			if (!cli_progress_option(c))
				usage();
		}
	}
	if (argc - optind > 1 || (argc - optind == 1 && eo.path))
		usage();
	if (o.format == RF_FORMAT_FLOAT && !o.output && !o.dump)
		cli_refuse_terminal("a binary stream");
	if (o.ktx.zstd && !ends_ktx2(o.output) && !ends_ktx2(o.irradiance))
		die("--zstd: no KTX 2 file to write (-o or --irradiance ending in .ktx2)");
	if (optind < argc)
		eo.path = argv[optind];
	else if (!eo.path)
		eo.path = cli_input_or_default(NULL);
	/* the chain's first level is a frame of N x 6N */
	if (eo.load.size)
		cli_check_frame("--size (a frame of N x 6N)", eo.load.size, 6 * eo.load.size);
	o.pf.nthreads = cli_threads(threads);
	eo.load.nthreads = o.pf.nthreads;
	o.pf.progress = progress;
	o.pf.progress_arg = &progress_started;
	src = envmap_load(&eo, &info);
	if (o.irradiance) {
		/* the diffuse light as a cube of its own: 32 texels a face */
		struct rf_chain_info ii = info;
		rf_cubemap *irr = envmap_cube_new(32, 1);

		if ((rc = rf_cubemap_irradiance(src, 0, irr)) < 0)
			die_status(rc, NULL);
		ii.prefiltered = 0;
		ii.steps = 0;
		write_chain(&o, o.irradiance, irr, &ii);
		rf_cubemap_destroy(irr);
	}
	if (info.prefiltered || rf_cubemap_levels(src) > 1) {
		/* A chain is written as it is: a change of form, not of content. */
		warn("'%s' is already a %s chain of %zu levels; writing it as it is", eo.path,
		     info.prefiltered ? "prefiltered" : "plain", rf_cubemap_levels(src));
		if (o.dump)
			dump_levels(src, o.dump);
		if (!o.dump || o.output)
			write_chain(&o, o.output, src, &info);
		rf_cubemap_destroy(src);
		fshut(stdout, "<stdout>");
		return 0;
	}
	out = envmap_cube_new(rf_cubemap_size(src),
	                      envmap_chain_levels(rf_cubemap_size(src), o.levels, o.min_size));
	info.mapping = o.pf.mapping;
	info.steps = o.pf.steps > 0 ? o.pf.steps : (float)(rf_cubemap_levels(out) - 1);
	info.base_copied = 1;
	if (o.plain) {
		size_t f, i, j;

		for (f = 0; f < 6; f++)
			for (j = 0; j < rf_cubemap_size(src); j++)
				for (i = 0; i < rf_cubemap_size(src); i++)
					memcpy(rf_cubemap_texel(out, 0, (enum rf_face)f, i, j),
					       rf_cubemap_texel_const(src, 0, (enum rf_face)f, i, j),
					       3 * sizeof(float));
		rf_cubemap_seal_level(out, 0);
		rf_cubemap_box_chain(out, 0);
		info.prefiltered = 0;
	} else {
		if (rf_cubemap_levels(out) < 2)
			die("a chain of one level has nothing to convolve: the cube is %zu "
			    "texels (use a larger --size or a smaller --min-size)",
			    rf_cubemap_size(src));
		double wall = now(CLOCK_MONOTONIC), cpu = now(CLOCK_PROCESS_CPUTIME_ID);
		double samples = 0;
		size_t k;

		if ((rc = rf_prefilter(src, out, &o.pf, err, sizeof(err))) < 0)
			die_status(rc, err);
		wall = now(CLOCK_MONOTONIC) - wall;
		cpu = now(CLOCK_PROCESS_CPUTIME_ID) - cpu;
		for (k = 1; k < rf_cubemap_levels(out); k++)
			samples += 6.0 * (double)rf_cubemap_level_size(out, k) *
			           (double)rf_cubemap_level_size(out, k) *
			           (double)rf_prefilter_level_samples(o.pf.samples, k);
		if (o.verbose && o.pf.method == RF_PREFILTER_FILTERED)
			fprintf(stderr, "%s: %.1f M GGX samples in %.3f s (%.3f s cpu, %d "
			        "threads): %.1f M samples per cpu second\n", argv0,
			        samples / 1e6, wall, cpu, o.pf.nthreads, samples / cpu / 1e6);
		info.prefiltered = 1;
		info.samples = o.pf.method == RF_PREFILTER_BRUTE ? 0 : o.pf.samples;
	}
	if (o.edge_average) {
		size_t k;

		for (k = 0; k < rf_cubemap_levels(out); k++)
			rf_cubemap_average_edges(out, k);
	}
	if (o.verbose)
		fprintf(stderr, "%s: %zu levels of %zu..%zu texels, mapping %s, steps %g, %s\n",
		        argv0, rf_cubemap_levels(out), rf_cubemap_size(out),
		        rf_cubemap_level_size(out, rf_cubemap_levels(out) - 1),
		        rf_mapping_name(info.mapping), (double)info.steps,
		        o.plain ? "box-filtered" : "GGX-prefiltered");
	if (o.dump)
		dump_levels(out, o.dump);
	if (!o.dump || o.output)
		write_chain(&o, o.output, out, &info);
	rf_cubemap_destroy(src);
	rf_cubemap_destroy(out);
	cli_progress_end();
	fshut(stdout, "<stdout>");
	return 0;
}
