/* reflect-shade: environment radiance through each pixel's lobe. */
#include <getopt.h>
#include <string.h>
#include <unistd.h>

#include "cli_envmap.h"
#include "reflect/shading.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        CLI_PROGRESS_USAGE " "
	        "[--env=FILE] [--layout=L] [--prefiltered] [--srgb=auto|on|off] "
	        "[--rgbm=M[,E]] [--intensity=X] [--size=N] [--nonfinite=error|zero] "
	        "[--mapping=unity|linear|exact] [--steps=N] [--samples=N] "
	        "[--final[=split-sum|unity|hdrp]] [--diffuse=on|off] "
	        "[--diffuse-projection=off|box] "
	        "[--box=XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX] [--center=X,Y,Z] "
	        "[--box-projection=on|off] [--lod=L] [--seed=N] [--blend=on|off] "
	        "[--max-probes=N] [--normal-fade] [--fallback=infinite|none|sky:FILE] "
	        "[--no-cache] "
	        CLI_INVALID_USAGE " " CLI_REGION_USAGE " "
	        CLI_IO_USAGE
	        " [file]\n", argv0);
	exit(EXIT_BAD_INPUT);
}

enum {
	OPT_ENVMAP = 256, /* handed to envmap_opts_parse by name */
	OPT_MAPPING, OPT_STEPS, OPT_SAMPLES, OPT_FINAL, OPT_BOX, OPT_CENTER,
	OPT_PROJECTION, OPT_LOD, OPT_SEED, OPT_INVALID, OPT_DIFFUSE, OPT_DIFFUSE_PROJECTION,
	OPT_BLEND, OPT_MAX_PROBES, OPT_NORMAL_FADE, OPT_FALLBACK, OPT_NO_CACHE, OPT_HELP
};

static const struct option long_options[] = {
	CLI_PROGRESS_OPTION,
	CLI_REGION_OPTIONS,
	{ "env", required_argument, NULL, OPT_ENVMAP },
	{ "layout", required_argument, NULL, OPT_ENVMAP },
	{ "prefiltered", no_argument, NULL, OPT_ENVMAP },
	{ "srgb", required_argument, NULL, OPT_ENVMAP },
	{ "rgbm", required_argument, NULL, OPT_ENVMAP },
	{ "intensity", required_argument, NULL, OPT_ENVMAP },
	{ "size", required_argument, NULL, OPT_ENVMAP },
	{ "nonfinite", required_argument, NULL, OPT_ENVMAP },
	{ "mapping", required_argument, NULL, OPT_MAPPING },
	{ "steps", required_argument, NULL, OPT_STEPS },
	{ "samples", required_argument, NULL, OPT_SAMPLES },
	{ "final", optional_argument, NULL, OPT_FINAL },
	{ "box", required_argument, NULL, OPT_BOX },
	{ "center", required_argument, NULL, OPT_CENTER },
	{ "box-projection", required_argument, NULL, OPT_PROJECTION },
	{ "lod", required_argument, NULL, OPT_LOD },
	{ "diffuse", required_argument, NULL, OPT_DIFFUSE },
	{ "diffuse-projection", required_argument, NULL, OPT_DIFFUSE_PROJECTION },
	{ "seed", required_argument, NULL, OPT_SEED },
	{ "invalid", required_argument, NULL, OPT_INVALID },
	{ "blend", required_argument, NULL, OPT_BLEND },
	{ "max-probes", required_argument, NULL, OPT_MAX_PROBES },
	{ "normal-fade", no_argument, NULL, OPT_NORMAL_FADE },
	{ "fallback", required_argument, NULL, OPT_FALLBACK },
	{ "no-cache", no_argument, NULL, OPT_NO_CACHE },
	{ "help", no_argument, NULL, OPT_HELP },
	{ NULL, 0, NULL, 0 },
};

/* The prefilter's progress: its line when it starts (never for a chain
 * the cache had), then on a terminal how far it is. */
static void
progress(void *arg, const char *line, double done, double total)
{
	(void)arg;
	if (cli_progress_quiet())
		return;
	if (done == 0.0) {
		if (line)
			fprintf(stderr, "%s: %s\n", argv0, line);
		return;
	}
	if (!isatty(STDERR_FILENO))
		return;
	fprintf(stderr, "\r%s: prefiltering %3.0f%%", argv0, 100.0 * done / total);
	if (done >= total)
		fputc('\n', stderr);
}

/* A damaged cache entry (a disk or a hand that wrote into the cache: it
 * costs a prefilter), replaced texels, and with -v the environments. */
static void
note(void *arg, const char *msg)
{
	(void)arg;
	warn("%s", msg);
}

/* Each frame's command line, before the shader's keys. */
static int
record(void *arg, rf_header *out)
{
	(void)arg;
	cli_record_command(out);
	return 0;
}

/* The tools' loader: capture:SCENE#K too, and a mapped file guarded. */
static int
load(void *arg, rf_cubemap **c, struct rf_chain_info *info, const char *name,
     const struct rf_envmap_options *lo, char *err, size_t errlen)
{
	struct envmap_opts eo;

	(void)arg;
	(void)err;
	(void)errlen;
	eo.path = name;
	eo.load = *lo;
	*c = envmap_load(&eo, info);
	return 0;
}

/* $XDG_CACHE_HOME/reflect, else ~/.cache/reflect; NULL with --no-cache or
 * no home. */
static const char *
cache_dir(int no_cache)
{
	static char dir[4096];
	const char *x = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");

	if (no_cache)
		return NULL;
	if (x && *x == '/')
		snprintf(dir, sizeof(dir), "%s/reflect", x);
	else if (home && *home == '/')
		snprintf(dir, sizeof(dir), "%s/.cache/reflect", home);
	else
		return NULL;
	return dir;
}

struct shade_block {
	rf_shader *shader;
	int failed;  /* a pixel refused (rf_shader_error says why) */
	int gave_up; /* the mode failed in run() (rf_shader_error says why) */
};

static int
shade_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	struct shade_block *sb = arg;
	int rc = rf_shader_run(sb->shader, in, out, y, n);

	sb->failed = rc == RF_EINVAL && *rf_shader_error(sb->shader);
	sb->gave_up = rc == RF_EPLUGIN;
	if (rc < 0 && !sb->failed && !sb->gave_up)
		die_status(rc, NULL);
	return rc;
}

static void
shade_frame(struct cli_io *io, rf_shader *shader, const rf_header *in)
{
	struct shade_block sb = { shader, 0, 0 };
	char err[1024], why[320];
	rf_header *out;
	size_t rows, ncols = rf_header_ncols(in), nrows = rf_header_nrows(in);
	int rc;

	if ((rc = rf_shader_begin_frame(shader, in, &out, err, sizeof(err))) < 0)
		die_status(rc, err);
	cli_io_begin(io, out);
	rows = rf_block_rows(ncols, rf_header_nchannels(out), CLI_BLOCK_BYTES);
	if (rows > nrows)
		rows = nrows ? nrows : 1;
	rc = cli_blocks(io, nrows, rows, ncols * rf_header_nchannels(in),
	                ncols * rf_header_nchannels(out), shade_block, &sb);
	snprintf(why, sizeof(why), "%s", rf_shader_error(shader));
	cli_io_invalid_note(io, rf_shader_invalid_count(shader));
	mode_invalid_note(io, rf_shader_invalid_output_count(shader));
	rf_shader_end_frame(shader);
	if (rc < 0) {
		/* Its threads are joined before we die, as the stage's are. */
		rf_shader_destroy(shader);
		if (sb.gave_up)
			cli_io_plugin_failed(io, why);
		if (sb.failed)
			cli_io_invalid_failed(io, why);
		cli_io_read_failed(io, rc);
	}
	cli_io_end_frame(io);
}

int
main(int argc, char **argv)
{
	struct cli_io io = { 0 };
	struct cli_mode mode = { 0 };
	struct rf_shader_options so;
	struct envmap_opts env;
	char err[1024];
	float centre[3];
	const char *threads = NULL, *spec = "approx";
	const rf_header *in;
	rf_shader *shader;
	int c, idx, list = 0, verbose = 0, no_cache = 0, want_help = 0, mode_given = 0, rc;

	cli_init(argc, argv);
	rf_shader_options_init(&so);
	envmap_opts_init(&env);
	while ((c = getopt_long(argc, argv, "qlvVm:j:" CLI_IO_OPTSTRING, long_options,
	                        &idx)) != -1) {
		if (cli_io_option(&io, c, optarg) || cli_progress_option(c))
			continue;
		switch (c) {
		case 'l': list = 1; break;
		case 'v': verbose = 1; break;
		case 'V': print_version(); break;
		case 'm': spec = optarg; mode_given = 1; break;
		case 'j': threads = optarg; break;
		case OPT_ENVMAP:
			envmap_opts_parse(&env, long_options[idx].name, optarg);
			break;
		case OPT_MAPPING:
			if (rf_mapping_parse(optarg, &so.mapping) < 0)
				die("--mapping: '%s' is not unity, linear or exact", optarg);
			so.mapping_set = 1;
			break;
		case OPT_STEPS:
			so.steps = (float)parse_number("steps", optarg, 0.5, 64);
			break;
		case OPT_SAMPLES:
			so.samples = (unsigned)parse_whole("samples", optarg, 1, 65536);
			break;
		case OPT_FINAL: {
			enum rf_final f = RF_FINAL_SPLIT_SUM;

			if (optarg && rf_final_parse(optarg, &f) < 0)
				die("--final: '%s' is not split-sum, unity or hdrp", optarg);
			so.final = (int)f;
			break;
		}
		case OPT_BOX: so.box = optarg; break;
		case OPT_CENTER:
			parse_floats(optarg, "--center", centre, 3);
			so.center = optarg;
			break;
		case OPT_PROJECTION:
			/* Checked now: a stream without a box would never read it. */
			if (strcmp(optarg, "on") && strcmp(optarg, "off") &&
			    strcmp(optarg, "1") && strcmp(optarg, "0"))
				die("--box-projection: '%s' is not on or off", optarg);
			so.projection = optarg;
			break;
		case OPT_DIFFUSE:
			if (strcmp(optarg, "on") && strcmp(optarg, "off"))
				die("--diffuse: '%s' is not on or off", optarg);
			so.diffuse = !strcmp(optarg, "on");
			break;
		case OPT_DIFFUSE_PROJECTION:
			if (strcmp(optarg, "off") && strcmp(optarg, "box"))
				die("--diffuse-projection: '%s' is not off or box", optarg);
			so.diffuse_box = !strcmp(optarg, "box");
			break;
		case OPT_LOD:
			so.lod = (float)parse_number("lod", optarg, 0, 64);
			so.force_lod = 1;
			break;
		case OPT_SEED:
			so.seed = (uint32_t)parse_whole("seed", optarg, 0, 4294967295.0);
			break;
		case OPT_INVALID: cli_io_invalid_option(&io, optarg); break;
		case OPT_BLEND:
			if (strcmp(optarg, "on") && strcmp(optarg, "off"))
				die("--blend: '%s' is not on or off", optarg);
			so.blend = !strcmp(optarg, "on");
			break;
		case OPT_MAX_PROBES:
			so.max_probes = (unsigned)parse_whole("max-probes", optarg, 1, RF_PROBES_MAX);
			break;
		case OPT_NORMAL_FADE: so.normal_fade = 1; break;
		case OPT_NO_CACHE: no_cache = 1; break;
		case OPT_FALLBACK:
			if (!strcmp(optarg, "infinite"))
				so.fallback = RF_BLEND_INFINITE;
			else if (!strcmp(optarg, "none"))
				so.fallback = RF_BLEND_NONE;
			else if (!strncmp(optarg, "sky:", 4) && optarg[4]) {
				so.fallback = RF_BLEND_SKY;
				so.sky = optarg + 4;
			} else
				die("--fallback: '%s' is not infinite, none or sky:FILE", optarg);
			break;
		case OPT_HELP: want_help = 1; break;
		default: usage();
		}
	}
	/* -m MODE --help, in either order: that mode's help */
	if (want_help && mode_given)
		mode_help(RF_KIND_SHADE, spec);
	if (want_help) {
		/* the modes' list runs plugin code: what it prints stays out */
		cli_keep_stdout();
		fprintf(cli_stdout(), "usage: %s [options] [file]\n"
		        "Samples the environment through each pixel's lobe: a mode gives\n"
		        "the effective roughness (roughness.eff), the environment's mapping\n"
		        "its lod, and D (from reflect-project) the direction; adds spec.R\n"
		        "spec.G spec.B. See reflect-shade(1).\n", argv0);
		mode_help_line(RF_KIND_SHADE, "approx");
		fprintf(cli_stdout(), "  --env=FILE  environment (else PROBE_ENV, else the embedded room);\n"
		        "      raw ones are prefiltered on the fly (--samples=N) and kept in\n"
		        "      $XDG_CACHE_HOME/reflect for the next run (--no-cache: not)\n"
		        "  --prefiltered --layout=L --srgb= --rgbm= --intensity= --size=N\n"
		        "  --nonfinite=error|zero  a NaN or Inf texel refused (error) or 0\n"
		        "  --mapping=unity|linear|exact --steps=N  roughness to lod\n"
		        "  --final[=split-sum|unity|hdrp]  also R G B: spec x the split sum's\n"
		        "      F0 A + B, Unity Standard's or HDRP's term\n"
		        "  --box=... --center=X,Y,Z --box-projection=on|off  the probe (off:\n"
		        "      every mode the classic lookup along R)\n"
		        "  --lod=L  every mirror read at lod L (the mips' debug view)\n"
		        "  --diffuse=on|off  with --final, albedo (1 - metallic) E(N) / pi too (on)\n"
		        "  --diffuse-projection=off|box  E at N, or box-projected from P\n"
		        "  --seed=N  for modes that draw samples\n"
		        "  --blend=on|off  blend the frame's probes (on), --max-probes=N (2)\n"
		        "      a pixel, --normal-fade, --fallback=infinite|none|sky:FILE\n"
		        "  --invalid=error|clamp|zero  NaN, Inf, roughness out of [0, 1]\n"
		        CLI_REGION_HELP
		        "  -j N  threads   -v  say which plugin and environment   -V  versions\n"
		        CLI_PROGRESS_HELP
		        "  -f a|f  output format   -h  no output header\n"
		        "  -H -x W -y H -c CHANNELS  headerless input\n");
		fshut(cli_stdout(), "<stdout>");
		return 0;
	}
	if (argc - optind > 1)
		usage();
	if (list)
		mode_list(RF_KIND_SHADE);
	so.nthreads = cli_threads(threads);
	mode_load(&mode, RF_KIND_SHADE, spec, verbose);
	so.mode = mode.plugin;
	so.values = mode.values;
	so.spec = spec;
	so.invalid = io.invalid;
	so.env = env.path;
	so.envmap = env.load;
	so.load = load;
	so.cache_dir = cache_dir(no_cache);
	/* REFLECT_CACHE_MB=0 keeps nothing: a byte holds no entry */
	if (getenv("REFLECT_CACHE_MB"))
		so.cache_bytes = ((size_t)strtoul(getenv("REFLECT_CACHE_MB"), NULL, 10) << 20) + 1;
	so.header = record;
	so.progress = progress;
	so.note = note;
	so.verbose = verbose;
	if ((rc = rf_shader_create(&shader, &so, err, sizeof(err))) < 0)
		die_status(rc, err);
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &in)) {
		mode_note_absent(&mode, &io, in);
		shade_frame(&io, shader, in);
	}
	rf_shader_destroy(shader);
	mode_unload(&mode);
	cli_io_close(&io);
	return 0;
}
