/* reflect-shade: environment radiance through each pixel's lobe. */
#include <getopt.h>
#include <math.h>
#include <string.h>
#include <unistd.h>

#include "cli_envmap.h"
#include "reflect/host.h"
#include "reflect/shading.h"

static void
usage(void)
{
	fprintf(stderr, "usage: %s [-lvV] [-m MODE[:KEY=VALUE...]] [-j THREADS] "
	        "[--env=FILE] [--layout=L] [--prefiltered] [--srgb=auto|on|off] "
	        "[--rgbm=M[,E]] [--intensity=X] [--size=N] [--nonfinite=error|zero] "
	        "[--mapping=unity|linear|exact] [--steps=N] [--samples=N] "
	        "[--final[=split-sum|unity|hdrp]] [--diffuse=on|off] "
	        "[--diffuse-projection=off|box] "
	        "[--box=XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX] [--center=X,Y,Z] "
	        "[--box-projection=on|off] [--lod=L] [--seed=N] [--blend=on|off] "
	        "[--max-probes=N] [--normal-fade] [--fallback=infinite|none|sky:FILE] "
	        "[--no-cache] "
	        CLI_INVALID_USAGE " "
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

struct shade_opts {
	struct cli_mode mode;
	const char *spec;
	int nthreads, verbose, final;
	struct envmap_opts env;
	struct cli_probe probe;
	int mapping_set;
	enum rf_mapping mapping;
	float steps;       /* 0: the environment's */
	unsigned samples;  /* 0: the prefilter's default */
	uint32_t seed;
	int no_cache;      /* --no-cache */
	/* Blending the frame's probes: on (1) unless --blend=off (0). */
	int blend;
	unsigned max_probes;
	int normal_fade;
	enum rf_blend_fallback fallback;
	const char *sky; /* --fallback=sky:FILE */
};

/* The environment in use, kept across frames while they name the same. */
struct environment {
	char *name; /* as given: a path, or "default" */
	rf_cubemap *cube;
	enum rf_mapping mapping;
	float steps;
	int fresh; /* loaded since the sampling pass last took it */
	int has_sh9; /* the chain kept its irradiance coefficients */
	float sh9[27];
};

/* The prefilter's progress: its line when it starts (never for a chain
 * the cache had), then on a terminal how far it is. */
static void
progress(void *arg, double done, double total)
{
	if (done == 0.0) {
		if (*(const char *)arg)
			fprintf(stderr, "%s\n", (const char *)arg);
		return;
	}
	if (!isatty(STDERR_FILENO))
		return;
	fprintf(stderr, "\r%s: prefiltering %3.0f%%", argv0, 100.0 * done / total);
	if (done >= total)
		fputc('\n', stderr);
}

/* A damaged cache entry: worth a line whenever it happens (a disk or a
 * hand that wrote into the cache), since it costs a prefilter. */
static void
note(void *arg, const char *msg)
{
	(void)arg;
	warn("%s", msg);
}

/* $XDG_CACHE_HOME/reflect, else ~/.cache/reflect; NULL with --no-cache or
 * no home. */
static const char *
cache_dir(const struct shade_opts *o)
{
	static char dir[4096];
	const char *x = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");

	if (o->no_cache)
		return NULL;
	if (x && *x == '/')
		snprintf(dir, sizeof(dir), "%s/reflect", x);
	else if (home && *home == '/')
		snprintf(dir, sizeof(dir), "%s/.cache/reflect", home);
	else
		return NULL;
	return dir;
}

static void
load_environment(const struct shade_opts *o, const char *name, int from_header,
                 struct environment *e)
{
	struct envmap_opts eo = o->env;
	struct rf_shade_env_options so = { 0 };
	struct rf_chain_info info;
	static char line[4400];
	char err[1024];
	rf_cubemap *c;
	int rc;

	line[0] = '\0';
	rf_cubemap_destroy(e->cube);
	e->cube = NULL;
	free(e->name);
	e->name = estrdup(name);
	eo.path = name;
	eo.load.from_header = from_header;
	c = envmap_load(&eo, &info);
	/* A mode tracing its own rays reads level 0: nothing to prefilter. */
	so.raw_ok = rf_plugin_traces_raw(o->mode.plugin);
	if (!info.prefiltered && !so.raw_ok) {
		size_t size = rf_cubemap_size(c), levels;
		char what[4200] = "";

		if (strcmp(name, "default"))
			snprintf(what, sizeof(what), " '%s'", name);
		if (rf_cubemap_levels(c) > 1 && o->verbose)
			warn("'%s' has box-filtered levels, not GGX ones: prefiltering its "
			     "level 0 (--prefiltered takes them as they are)", name);
		/* Worth a line: it is the slow part of a short pipeline.  Said
		 * when the prefilter starts, which a cached chain skips. */
		if (rf_chain_levels(size, 0, 1, &levels, err, sizeof(err)) == 0 && levels > 1)
			snprintf(line, sizeof(line), "%s: prefiltering the environment%s "
			         "(%zux%zu per face, %zu levels)", argv0, what, size, size, levels);
	}
	so.mapping_set = o->mapping_set;
	so.mapping = o->mapping;
	so.steps = o->steps;
	so.samples = o->samples;
	so.as_given = o->env.load.prefiltered;
	so.nthreads = o->nthreads;
	so.progress = progress;
	so.progress_arg = line;
	so.cache_dir = cache_dir(o);
	so.note = note;
	/* REFLECT_CACHE_MB=0 keeps nothing: a byte holds no entry */
	if (getenv("REFLECT_CACHE_MB"))
		so.cache_bytes = ((size_t)strtoul(getenv("REFLECT_CACHE_MB"), NULL, 10) << 20) + 1;
	if ((rc = rf_shade_environment(&e->cube, &e->mapping, &e->steps, c, &info, name, &so,
	                               err, sizeof(err))) < 0)
		die_status(rc, err);
	e->fresh = 1;
	e->has_sh9 = info.has_sh9;
	memcpy(e->sh9, info.sh9, sizeof(e->sh9));
	if (o->verbose)
		warn("environment '%s': %zu texels, %zu levels, mapping %s, steps %g", name,
		     rf_cubemap_size(e->cube), rf_cubemap_levels(e->cube),
		     rf_mapping_name(e->mapping), (double)e->steps);
}

/* The mode's inputs, checked before the environment is loaded, so that a
 * stream that cannot be shaded fails at once, not after a prefilter. */
static void
check_frame(const struct shade_opts *o, rf_shade *shade, const rf_header *in,
            const float *center)
{
	const struct rf_plugin *p = o->mode.plugin;
	char err[1024];
	rf_header *h, *out;
	size_t i;
	int rc;

	for (i = 0; p->inputs[i]; i++)
		if (rf_header_find_channel(in, p->inputs[i]) < 0) {
			char list[512] = "";
			size_t k = 0, j;

			for (j = 0; p->inputs[j] && k + 2 < sizeof(list); j++)
				k += (size_t)snprintf(list + k, sizeof(list) - k, "%s%s",
				                      j ? " " : "", p->inputs[j]);
			die("input has no channel '%s' (mode '%s' reads %s)", p->inputs[i],
			    p->name, list);
		}
	if (rf_header_find_channel(in, "mask") >= 0 && !center)
		die("pixels with mask 0 show the environment seen from the probe "
		    "centre: give --center=X,Y,Z or a stream with PROBE_CENTER");
	if ((rc = rf_header_dup(&h, in)) < 0)
		die_status(rc, NULL);
	for (i = 0; p->outputs[i]; i++)
		if (rf_header_find_channel(h, p->outputs[i]) < 0)
			rf_header_add_channel(h, p->outputs[i]);
	if ((rc = rf_shade_begin_frame(shade, h, center, &out, err, sizeof(err))) < 0)
		die_status(rc, err);
	rf_header_destroy(h);
}

/* What a block of rows needs: the mode's stage, then the sampling pass
 * over the stage's output in place (the stage reserves its channels). */
struct shade_block {
	rf_stage *stage;
	rf_shade *shade;
	int failed; /* the stage refused a pixel (rf_stage_error says why) */
	int gave_up; /* the mode failed in run() (rf_stage_error says why) */
};

static int
shade_block(void *arg, const float *in, float *out, size_t y, size_t n)
{
	struct shade_block *sb = arg;
	int rc = rf_shade_run_stage(sb->shade, sb->stage, in, out, y, n);

	sb->failed = rc == RF_EINVAL &&
	             (*rf_stage_error(sb->stage) || *rf_shade_error(sb->shade));
	sb->gave_up = rc == RF_EPLUGIN;
	if (rc < 0 && !sb->failed && !sb->gave_up)
		die_status(rc, NULL);
	return rc;
}

/* The frame's other probes, each with its environment (PROBEk_ENV), for
 * the pass to blend into b; 0 when the frame has one probe or
 * --blend=off, else how many. */
static uint32_t
set_blend(const struct shade_opts *o, rf_shade *shade, const rf_header *in,
          const struct rf_probe *first, struct environment *env, struct rf_blend *b)
{
	const rf_cubemap *envs[RF_PROBES_MAX + 1] = { NULL };
	enum rf_mapping mappings[RF_PROBES_MAX + 1];
	float steps[RF_PROBES_MAX + 1];
	char err[512], key[32];
	uint32_t k;
	int n, rc;

	n = o->blend ? rf_blend_read(b, in, err, sizeof(err)) : 0;
	if (n < 0)
		die("%s", err);
	if (n < 2 || !first) {
		rf_shade_set_blend(shade, NULL, NULL, NULL, NULL, o->fallback);
		return 0;
	}
	/* the first probe as the options made it */
	b->probes[0] = *first;
	b->max_probes = o->max_probes;
	b->normal_fade = o->normal_fade;
	rf_blend_order(b);
	for (k = 0; k < b->nprobes; k++) {
		const char *name = NULL;

		if (k) {
			snprintf(key, sizeof(key), "PROBE%u_ENV", (unsigned)k + 1);
			name = rf_header_get(in, key);
			if (!name || !*name)
				name = "default";
			if (!env[k].name || strcmp(env[k].name, name))
				load_environment(o, name, 1, &env[k]);
		}
		envs[k] = env[k].cube;
		mappings[k] = env[k].mapping;
		steps[k] = env[k].steps;
	}
	if (o->fallback == RF_BLEND_SKY) {
		struct environment *sky = &env[RF_PROBES_MAX];

		if (!sky->name)
			load_environment(o, o->sky, 0, sky);
		envs[k] = sky->cube;
		mappings[k] = sky->mapping;
		steps[k] = sky->steps;
	}
	if ((rc = rf_shade_set_blend(shade, b, envs, mappings, steps, o->fallback)) < 0)
		die_status(rc, NULL);
	return b->nprobes;
}

/* For a mode that traces its own rays, a stage for each probe after the
 * first, its host holding that probe and its environment, begun as the
 * first stage was so that their rows line up. */
static void
blend_stages(const struct shade_opts *o, rf_shade *shade, const rf_header *in,
             const struct rf_blend *b, struct environment *env, rf_plugin_host **hosts,
             rf_stage **stages)
{
	const char *channel;
	char err[1024];
	rf_header *mid;
	uint32_t k;
	size_t c;
	int rc;

	for (k = 1; k < b->nprobes; k++) {
		if ((rc = rf_plugin_host_create(&hosts[k])) < 0)
			die_status(rc, NULL);
		rf_plugin_host_set_frame(hosts[k], in);
		rf_plugin_host_set_probe(hosts[k], &b->probes[k]);
		rf_plugin_host_set_environment(hosts[k], env[k].cube, env[k].mapping,
		                               env[k].steps);
		if (rf_plugin_traces_raw(o->mode.plugin) &&
		    (rc = rf_plugin_host_set_radiance(hosts[k], env[k].cube)) < 0)
			die_status(rc, NULL);
		rf_plugin_host_set_seed(hosts[k], o->seed);
		if ((rc = rf_stage_create(&stages[k], o->mode.plugin, o->mode.values,
		                          rf_plugin_host_table(hosts[k]), o->nthreads, err,
		                          sizeof(err))) < 0 ||
		    (rc = rf_stage_begin_frame(stages[k], in, &mid, err, sizeof(err))) < 0)
			die_status(rc, err);
		for (c = 0; (channel = rf_shade_channel(shade, c)); c++)
			if ((rc = rf_stage_reserve_channel(stages[k], channel)) < 0)
				die_status(rc, NULL);
	}
	if ((rc = rf_shade_set_blend_stages(shade, stages)) < 0)
		die_status(rc, NULL);
}

static void
shade_frame(struct cli_io *io, const struct shade_opts *o, struct environment *env,
            rf_shade *shade, rf_plugin_host *host, const rf_header *in)
{
	struct rf_probe probe;
	struct shade_block sb;
	float centre[3], *center = NULL;
	char err[1024], perr[512], buf[64], why[320];
	const char *name;
	rf_stage *stage;
	rf_header *mid, *out;
	const char *channel;
	size_t rows, k, ncols = rf_header_ncols(in), nrows = rf_header_nrows(in);
	rf_plugin_host *hosts[RF_PROBES_MAX] = { NULL };
	rf_stage *stages[RF_PROBES_MAX] = { NULL };
	struct rf_blend blend;
	uint32_t nblend, kb;
	int rc, prc;

	prc = rf_probe_resolve(&probe, in, o->probe.box, o->probe.center,
	                       o->probe.projection, perr, sizeof(perr));
	if (prc < 0 && prc != RF_ENOTFOUND)
		die("%s", perr);
	if (prc == 0) {
		center = probe.center;
	} else if (o->probe.center) {
		parse_floats(o->probe.center, "--center", centre, 3);
		center = centre;
	}
	/* Box projection off: the classic lookup along R for every mode, the
	 * distances infinite as for a probe without box projection. */
	rf_shade_set_unprojected(shade, prc == 0 && !probe.box_projection);
	rf_shade_set_probe(shade, prc == 0 && probe.box_projection ? &probe : NULL);
	check_frame(o, shade, in, center);

	name = o->env.path ? o->env.path : rf_header_get(in, RF_KEY_PROBE_ENV);
	if (!name || !*name)
		name = "default";
	if (!env->name || strcmp(env->name, name))
		load_environment(o, name, !o->env.path, env);
	nblend = set_blend(o, shade, in, prc == 0 ? &probe : NULL, env, &blend);

	rf_plugin_host_set_frame(host, in);
	rf_plugin_host_set_probe(host, prc == 0 ? &probe : NULL);
	rf_plugin_host_set_environment(host, env->cube, env->mapping, env->steps);
	/* A mode tracing rays reads the plain levels, made once per environment. */
	if (env->fresh && rf_plugin_traces_raw(o->mode.plugin) &&
	    (rc = rf_plugin_host_set_radiance(host, env->cube)) < 0)
		die_status(rc, NULL);
	rf_plugin_host_set_seed(host, o->seed);
	if ((rc = rf_stage_create(&stage, o->mode.plugin, o->mode.values,
	                          rf_plugin_host_table(host), o->nthreads, err,
	                          sizeof(err))) < 0)
		die_status(rc, err);
	if (prc == 0 && !probe.box_projection) {
		rf_stage_set_input_value(stage, "hit.dist", INFINITY);
		rf_stage_set_input_value(stage, "probe.dist", INFINITY);
	}
	rf_stage_set_invalid(stage, io->invalid);
	rf_shade_set_invalid(shade, io->invalid);
	if ((rc = rf_stage_begin_frame(stage, in, &mid, err, sizeof(err))) < 0)
		die_status(rc, err);
	/* The pass's channels, in the order it would append them. */
	for (k = 0; (channel = rf_shade_channel(shade, k)); k++)
		if ((rc = rf_stage_reserve_channel(stage, channel)) < 0)
			die_status(rc, NULL);
	if ((rc = rf_shade_begin_frame(shade, mid, center, &out, err, sizeof(err))) < 0)
		die_status(rc, err);
	if (nblend && rf_plugin_writes_radiance(o->mode.plugin))
		blend_stages(o, shade, in, &blend, env, hosts, stages);
	/* The pass keeps a copy of the levels: made once per environment. */
	if (env->fresh &&
	    (rc = rf_shade_set_environment(shade, env->cube, env->mapping,
	                                   env->steps)) < 0)
		die_status(rc, NULL);
	if (env->fresh && env->has_sh9)
		rf_shade_set_irradiance(shade, env->sh9);
	env->fresh = 0;

	cli_record_command(out);
	snprintf(buf, sizeof(buf), "%.9g", (double)env->steps);
	if ((rc = rf_header_set(out, RF_KEY_SHADE, o->spec)) < 0 ||
	    (rc = rf_header_set(out, RF_KEY_ENV_MAPPING, rf_mapping_name(env->mapping))) < 0 ||
	    (rc = rf_header_set(out, RF_KEY_ENV_STEPS, buf)) < 0 ||
	    (o->env.path && (rc = rf_header_set(out, RF_KEY_PROBE_ENV, o->env.path)) < 0) ||
	    (prc == 0 && (rc = rf_probe_to_header(&probe, out)) < 0))
		die_header_key(rc);
	cli_io_begin(io, out);

	rows = rf_block_rows(ncols, rf_header_nchannels(out), CLI_BLOCK_BYTES);
	if (rows > nrows)
		rows = nrows ? nrows : 1;
	sb.stage = stage;
	sb.shade = shade;
	sb.failed = sb.gave_up = 0;
	rc = cli_blocks(io, nrows, rows, ncols * rf_header_nchannels(in),
	                ncols * rf_header_nchannels(out), shade_block, &sb);
	if (sb.failed || sb.gave_up)
		snprintf(why, sizeof(why), "%s", *rf_stage_error(stage) ? rf_stage_error(stage)
		                                                       : rf_shade_error(shade));
	cli_io_invalid_note(io, rf_stage_invalid_count(stage) + rf_shade_invalid_count(shade));
	mode_invalid_note(io, rf_stage_invalid_output_count(stage));
	rf_stage_destroy(stage);
	for (kb = 1; kb < RF_PROBES_MAX; kb++) {
		rf_stage_destroy(stages[kb]);
		rf_plugin_host_destroy(hosts[kb]);
	}
	if (rc < 0) {
		/* Its threads are joined before we die, as the stage's are. */
		rf_shade_destroy(shade);
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
	struct shade_opts o;
	struct environment env[RF_PROBES_MAX + 1]; /* the probes', the sky's */
	struct rf_shade_options so = { 0 };
	float centre[3];
	const char *threads = NULL;
	const rf_header *in;
	rf_plugin_host *host;
	rf_shade *shade;
	int c, idx, list = 0, rc, diffuse_given = 0;

	cli_init(argc, argv);
	memset(&o, 0, sizeof(o));
	memset(env, 0, sizeof(env));
	o.spec = "approx";
	o.blend = 1;
	o.max_probes = 2;
	envmap_opts_init(&o.env);
	while ((c = getopt_long(argc, argv, "lvVm:j:" CLI_IO_OPTSTRING, long_options,
	                        &idx)) != -1) {
		if (cli_io_option(&io, c, optarg))
			continue;
		switch (c) {
		case 'l': list = 1; break;
		case 'v': o.verbose = 1; break;
		case 'V': print_version(); break;
		case 'm': o.spec = optarg; break;
		case 'j': threads = optarg; break;
		case OPT_ENVMAP:
			envmap_opts_parse(&o.env, long_options[idx].name, optarg);
			break;
		case OPT_MAPPING:
			if (rf_mapping_parse(optarg, &o.mapping) < 0)
				die("--mapping: '%s' is not unity, linear or exact", optarg);
			o.mapping_set = 1;
			break;
		case OPT_STEPS:
			o.steps = (float)parse_number("steps", optarg, 0.5, 64);
			break;
		case OPT_SAMPLES:
			o.samples = (unsigned)parse_whole("samples", optarg, 1, 65536);
			break;
		case OPT_FINAL: {
			enum rf_final f = RF_FINAL_SPLIT_SUM;

			if (optarg && rf_final_parse(optarg, &f) < 0)
				die("--final: '%s' is not split-sum, unity or hdrp", optarg);
			o.final = (int)f;
			break;
		}
		case OPT_BOX: o.probe.box = optarg; break;
		case OPT_CENTER:
			parse_floats(optarg, "--center", centre, 3);
			o.probe.center = optarg;
			break;
		case OPT_PROJECTION:
			/* Checked now: a stream without a box would never read it. */
			if (strcmp(optarg, "on") && strcmp(optarg, "off") &&
			    strcmp(optarg, "1") && strcmp(optarg, "0"))
				die("--box-projection: '%s' is not on or off", optarg);
			o.probe.projection = optarg;
			break;
		case OPT_DIFFUSE:
			if (strcmp(optarg, "on") && strcmp(optarg, "off"))
				die("--diffuse: '%s' is not on or off", optarg);
			so.diffuse = !strcmp(optarg, "on");
			diffuse_given = 1;
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
			o.seed = (uint32_t)parse_whole("seed", optarg, 0, 4294967295.0);
			break;
		case OPT_INVALID: cli_io_invalid_option(&io, optarg); break;
		case OPT_BLEND:
			if (strcmp(optarg, "on") && strcmp(optarg, "off"))
				die("--blend: '%s' is not on or off", optarg);
			o.blend = !strcmp(optarg, "on");
			break;
		case OPT_MAX_PROBES:
			o.max_probes = (unsigned)parse_whole("max-probes", optarg, 1, RF_PROBES_MAX);
			break;
		case OPT_NORMAL_FADE: o.normal_fade = 1; break;
		case OPT_NO_CACHE: o.no_cache = 1; break;
		case OPT_FALLBACK:
			if (!strcmp(optarg, "infinite"))
				o.fallback = RF_BLEND_INFINITE;
			else if (!strcmp(optarg, "none"))
				o.fallback = RF_BLEND_NONE;
			else if (!strncmp(optarg, "sky:", 4) && optarg[4]) {
				o.fallback = RF_BLEND_SKY;
				o.sky = optarg + 4;
			} else
				die("--fallback: '%s' is not infinite, none or sky:FILE", optarg);
			break;
		case OPT_HELP:
			printf("usage: %s [options] [file]\n"
			       "Samples the environment through each pixel's lobe: a mode gives\n"
			       "the effective roughness (roughness.eff), the environment's mapping\n"
			       "its lod, and D (from reflect-project) the direction; adds spec.R\n"
			       "spec.G spec.B. See reflect-shade(1).\n"
			       "  -m MODE[:K=V...]  none, approx (default), hdrp, godot; -l lists them\n"
			       "  --env=FILE  environment (else PROBE_ENV, else the embedded room);\n"
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
			       "  -j N  threads   -v  say which plugin and environment   -V  versions\n"
			       "  -f a|f  output format   -h  no output header\n"
			       "  -H -x W -y H -c CHANNELS  headerless input\n", argv0);
			fshut(stdout, "<stdout>");
			return 0;
		default: usage();
		}
	}
	if (argc - optind > 1)
		usage();
	if (list)
		mode_list(RF_KIND_SHADE);
	o.nthreads = cli_threads(threads);
	o.env.load.nthreads = o.nthreads;
	mode_load(&o.mode, RF_KIND_SHADE, o.spec, o.verbose);
	/* Loaded before the first frame: a sky that cannot be read is
	 * refused even where every frame has one probe and reads none. */
	if (o.fallback == RF_BLEND_SKY)
		load_environment(&o, o.sky, 0, &env[RF_PROBES_MAX]);
	so.final = o.final;
	if (!diffuse_given)
		so.diffuse = 1; /* with --final, the probe's diffuse light too */
	so.mode_radiance = rf_plugin_writes_radiance(o.mode.plugin);
	so.nthreads = o.nthreads;
	if ((rc = rf_shade_create(&shade, &so)) < 0 || (rc = rf_plugin_host_create(&host)) < 0)
		die_status(rc, NULL);
	cli_io_open(&io, optind < argc ? argv[optind] : NULL);
	while (cli_io_next(&io, &in))
		shade_frame(&io, &o, env, shade, host, in);
	rf_plugin_host_destroy(host);
	rf_shade_destroy(shade);
	for (idx = 0; idx <= RF_PROBES_MAX; idx++) {
		rf_cubemap_destroy(env[idx].cube);
		free(env[idx].name);
	}
	mode_unload(&o.mode);
	cli_io_close(&io);
	return 0;
}
