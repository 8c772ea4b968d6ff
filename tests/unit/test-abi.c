/*
 * The plugin ABI, pinned: the layout of every struct a plugin shares with
 * the host, checked against a table of the values on this platform (in
 * the manner of GStreamer's tests/check/gst/gstabi.c).  Changing a struct
 * of <reflect/plugin.h> by accident fails here; changing it on purpose
 * means a new ABI version (see the history in the header) and a new table.
 *
 * Also: rf_plugin_parse_params, the search path, the loader's refusals
 * and a stage over the echo_params test plugin, called directly.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "reflect/host.h"
#include "reflect/plugin.h"
#include "reflect/probe.h"
#include "reflect/reflect.h"
#include "tap.h"

struct abi_entry {
	const char *what;
	size_t got, want;
};

#define SIZE(type, n) { "sizeof(" #type ")", sizeof(type), n }
#define OFFSET(type, member, n) \
	{ "offsetof(" #type ", " #member ")", offsetof(type, member), n }

#if defined(__LP64__)
#define ABI_PLATFORM "LP64"
/* x86_64, aarch64, ppc64le, riscv64, s390x: 8-byte pointers and doubles. */
static const struct abi_entry abi_table[] = {
	SIZE(struct rf_plugin, 128),
	OFFSET(struct rf_plugin, abi_major, 0),
	OFFSET(struct rf_plugin, abi_minor, 4),
	OFFSET(struct rf_plugin, size, 8),
	OFFSET(struct rf_plugin, kind, 12),
	OFFSET(struct rf_plugin, flags, 16),
	OFFSET(struct rf_plugin, name, 24),
	OFFSET(struct rf_plugin, summary, 32),
	OFFSET(struct rf_plugin, version, 40),
	OFFSET(struct rf_plugin, author, 48),
	OFFSET(struct rf_plugin, license, 56),
	OFFSET(struct rf_plugin, nparams, 64),
	OFFSET(struct rf_plugin, params, 72),
	OFFSET(struct rf_plugin, inputs, 80),
	OFFSET(struct rf_plugin, outputs, 88),
	OFFSET(struct rf_plugin, create, 96),
	OFFSET(struct rf_plugin, run, 104),
	OFFSET(struct rf_plugin, destroy, 112),
	OFFSET(struct rf_plugin, optional_inputs, 120), /* ABI 1.1 */

	SIZE(struct rf_param, 56),
	OFFSET(struct rf_param, name, 0),
	OFFSET(struct rf_param, help, 8),
	OFFSET(struct rf_param, min, 16),
	OFFSET(struct rf_param, max, 24),
	OFFSET(struct rf_param, def, 32),
	OFFSET(struct rf_param, flags, 40),
	OFFSET(struct rf_param, choices, 48),

	SIZE(struct rf_host, 208),
	OFFSET(struct rf_host, size, 0),
	OFFSET(struct rf_host, abi_major, 4),
	OFFSET(struct rf_host, abi_minor, 8),
	OFFSET(struct rf_host, ctx, 16),
	OFFSET(struct rf_host, header_get, 24),
	OFFSET(struct rf_host, probe, 32),
	OFFSET(struct rf_host, sample, 40),
	OFFSET(struct rf_host, roughness_to_lod, 48),
	OFFSET(struct rf_host, lod_to_roughness, 56),
	OFFSET(struct rf_host, lod_steps, 64),
	OFFSET(struct rf_host, seed, 68),
	/* ABI 1.1 */
	OFFSET(struct rf_host, project_rays, 72),
	OFFSET(struct rf_host, sample_radiance, 80),
	OFFSET(struct rf_host, env_size, 88),
	OFFSET(struct rf_host, env_levels, 92),
	OFFSET(struct rf_host, dfg, 96),
	OFFSET(struct rf_host, filter_passes, 104),
	OFFSET(struct rf_host, sample_many, 112),
	OFFSET(struct rf_host, fail, 120),
	OFFSET(struct rf_host, declare_bevel, 128),
	OFFSET(struct rf_host, param_string, 136),
	OFFSET(struct rf_host, face_size, 144),
	OFFSET(struct rf_host, texel_solid_angle, 152),
	OFFSET(struct rf_host, pixel_footprint, 160),
	OFFSET(struct rf_host, random_pairs, 168),
	OFFSET(struct rf_host, nprobes, 176),
	OFFSET(struct rf_host, probes, 184),
	OFFSET(struct rf_host, probe_blend, 192),
	OFFSET(struct rf_host, probe_weights, 200),

	SIZE(struct rf_span, 72),
	OFFSET(struct rf_span, size, 0),
	OFFSET(struct rf_span, npix, 4),
	OFFSET(struct rf_span, x, 8),
	OFFSET(struct rf_span, y, 12),
	OFFSET(struct rf_span, width, 16),
	OFFSET(struct rf_span, height, 20),
	OFFSET(struct rf_span, frame, 24),
	OFFSET(struct rf_span, in, 32),
	OFFSET(struct rf_span, out, 40),
	OFFSET(struct rf_span, nvalues, 48),
	OFFSET(struct rf_span, count, 52),
	OFFSET(struct rf_span, band, 56),
	OFFSET(struct rf_span, radius, 64),
	OFFSET(struct rf_span, pass, 68),

	SIZE(struct rf_probe, 160),
	OFFSET(struct rf_probe, center, 0),
	OFFSET(struct rf_probe, box_min, 12),
	OFFSET(struct rf_probe, box_max, 24),
	OFFSET(struct rf_probe, box_projection, 36),
	OFFSET(struct rf_probe, bevel, 40), /* ABI 1.1 */
	OFFSET(struct rf_probe, bevel_grown, 44),
	OFFSET(struct rf_probe, shape, 48), /* ABI 1.2 */
	OFFSET(struct rf_probe, rotated, 52),
	OFFSET(struct rf_probe, rotation, 56),
	OFFSET(struct rf_probe, proxy_shape, 92),
	OFFSET(struct rf_probe, proxy_rotated, 96),
	OFFSET(struct rf_probe, proxy_min, 100),
	OFFSET(struct rf_probe, proxy_max, 112),
	OFFSET(struct rf_probe, proxy_rotation, 124),
};
#define HAVE_ABI_TABLE 1
#endif

/* Every mismatch is reported, not just the first. */
TEST(struct_layout)
{
#ifdef HAVE_ABI_TABLE
	size_t i, bad = 0;

	for (i = 0; i < sizeof(abi_table) / sizeof(abi_table[0]); i++)
		if (abi_table[i].got != abi_table[i].want) {
			printf("# %s: %zu, the ABI table (%s) says %zu\n",
			       abi_table[i].what, abi_table[i].got, ABI_PLATFORM,
			       abi_table[i].want);
			bad++;
		}
	ASSERT_EQ(bad, 0);
#endif
}

/* The numbers and names a built plugin carries are ABI as well. */
TEST(constants)
{
	ASSERT_EQ(RF_PLUGIN_ABI_MAJOR, 1);
	ASSERT_EQ(RF_PLUGIN_ABI_MINOR, 3);
	ASSERT_EQ(RF_SHAPE_SAME, 0);
	ASSERT_EQ(RF_SHAPE_BOX, 1);
	ASSERT_EQ(RF_SHAPE_SPHERE, 2);
	ASSERT_EQ(RF_SHAPE_INFINITE, 3);
	ASSERT_EQ(RF_PROBE_SIZE_1_1, 48);
	ASSERT_STR_EQ(RF_PLUGIN_ENTRY, "rf_plugin_entry");
	ASSERT_EQ(RF_KIND_PROJECTION, 1);
	ASSERT_EQ(RF_KIND_SHADE, 2);
	ASSERT_EQ(RF_KIND_OCCLUSION, 3);
	ASSERT_EQ(RF_KIND_ACCUMULATE, 4);
	ASSERT_EQ(RF_KIND_FILTER, 5);
	ASSERT_EQ(RF_FILTER_PASSES_MAX, 16);
	ASSERT_EQ(RF_FILTER_RADIUS_MAX, 1024);
	ASSERT_EQ(RF_PARAM_INTEGER, 0x1);
	ASSERT_EQ(RF_PARAM_BOOL, 0x2);
	ASSERT_EQ(RF_PARAM_CHOICE, 0x4);
	ASSERT_EQ(RF_PARAM_STRING, 0x8);
	ASSERT_EQ(RF_SEQUENCE_WHITE, 0);
	ASSERT_EQ(RF_SEQUENCE_BLUE, 1);
	ASSERT_EQ(RF_SEQUENCE_LOW_DISCREPANCY, 2);
	ASSERT_EQ(RF_PROBES_MAX, 16);
	ASSERT_EQ(RF_PARAM_KNOWN_FLAGS, 0xf);
	ASSERT_EQ(RF_PLUGIN_RADIANCE, 0x1);
	ASSERT_EQ(RF_PLUGIN_KNOWN_FLAGS, 0x3);
	ASSERT_EQ(RF_PLUGIN_PREFILTERED, 0x2);
	ASSERT_STR_EQ(RF_SHADE_ROUGHNESS, "roughness.eff");
	ASSERT_STR_EQ(RF_SHADE_SPEC_R, "spec.R");
	ASSERT_STR_EQ(RF_SHADE_SPEC_G, "spec.G");
	ASSERT_STR_EQ(RF_SHADE_SPEC_B, "spec.B");
	ASSERT_STR_EQ(RF_ACCUMULATE_VALUE, "value");
	ASSERT_STR_EQ(RF_ACCUMULATE_VARIANCE, "variance");
	/* The three leading fields never move, whatever the platform. */
	ASSERT_EQ(offsetof(struct rf_plugin, abi_major), 0);
	ASSERT_EQ(offsetof(struct rf_plugin, abi_minor), 4);
	ASSERT_EQ(offsetof(struct rf_plugin, size), 8);
	ASSERT_STR_EQ(rf_plugin_kind_name(RF_KIND_PROJECTION), "projection");
	ASSERT_STR_EQ(rf_plugin_kind_name(RF_KIND_ACCUMULATE), "accumulate");
	ASSERT(rf_plugin_kind_name(0) == NULL);
	ASSERT_STR_EQ(rf_plugin_kind_name(RF_KIND_FILTER), "filter");
	ASSERT(rf_plugin_kind_name(6) == NULL);
}

/* ---- rf_plugin_parse_params ------------------------------------------ */

static int
dummy_create(const struct rf_host *host, const double *values, void **state,
             char *err, size_t errlen)
{
	*state = NULL;
	return 0;
}

static void
dummy_run(void *state, const struct rf_span *span)
{
}

static void
dummy_destroy(void *state)
{
}

static const char *const dummy_in[] = { NULL };
static const char *const dummy_out[] = { "x", NULL };

static const struct rf_param test_params[] = {
	{ "scale", "ranged", 0.5, 4, 1, 0, NULL },
	{ "offset", "unbounded", -HUGE_VAL, HUGE_VAL, 0, 0, NULL },
	{ "count", "integer", 1, 8, 3, RF_PARAM_INTEGER, NULL },
	{ "invert", "bool", 0, 1, 0, RF_PARAM_BOOL, NULL },
	{ "shape", "choice", 0, 2, 1, RF_PARAM_CHOICE, "round|square|fail" },
	{ "floor", "bounded below", 0, HUGE_VAL, 2, 0, NULL },
};

static const struct rf_plugin test_plugin = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "tp", "test", "1", "me", "MIT",
	6, test_params, dummy_in, dummy_out,
	dummy_create, dummy_run, dummy_destroy,
};

static const struct rf_plugin no_params = {
	RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR, sizeof(struct rf_plugin),
	RF_KIND_PROJECTION, 0, "none", "test", "1", "me", "MIT",
	0, NULL, dummy_in, dummy_out,
	dummy_create, dummy_run, dummy_destroy,
};

static char msg[1024];

static int
parse(const char *spec, double *v)
{
	msg[0] = '\0';
	return rf_plugin_parse_params(&test_plugin, spec, v, msg, sizeof(msg));
}

/* The spec is refused and the message is exactly `want`. */
#define ASSERT_REFUSED(spec, want)                                         \
	do {                                                               \
		double v_[6];                                              \
		ASSERT_EQ(parse(spec, v_), RF_EINVAL);                     \
		ASSERT_STR_EQ(msg, want);                                  \
	} while (0)

TEST(params_defaults)
{
	double v[6] = { -1, -1, -1, -1, -1, -1 };

	ASSERT_EQ(parse(NULL, v), 0);
	ASSERT_NEAR(v[0], 1, 0);
	ASSERT_NEAR(v[1], 0, 0);
	ASSERT_NEAR(v[2], 3, 0);
	ASSERT_NEAR(v[3], 0, 0);
	ASSERT_NEAR(v[4], 1, 0);
	ASSERT_NEAR(v[5], 2, 0);
	ASSERT_EQ(parse("", v), 0);
	ASSERT_NEAR(v[2], 3, 0);
	/* an empty item is a slip (a stray ':'), refused with where it is */
	ASSERT_EQ(parse("::", v), RF_EINVAL);
	ASSERT(strstr(msg, "an empty parameter in '::'") != NULL);
	ASSERT_EQ(parse("scale=2:", v), RF_EINVAL);
	ASSERT(strstr(msg, "nothing after it") != NULL);
	ASSERT_EQ(parse(":scale=2", v), RF_EINVAL);
	ASSERT(strstr(msg, "nothing before it") != NULL);
}

TEST(params_every_type)
{
	double v[6];

	ASSERT_EQ(parse("scale=2.5:offset=-7.25:count=8:invert=yes:shape=fail:"
	                "floor=1e6", v), 0);
	ASSERT_NEAR(v[0], 2.5, 0);
	ASSERT_NEAR(v[1], -7.25, 0);
	ASSERT_NEAR(v[2], 8, 0);
	ASSERT_NEAR(v[3], 1, 0);
	ASSERT_NEAR(v[4], 2, 0);
	ASSERT_NEAR(v[5], 1e6, 0);
	/* order does not matter, unnamed ones keep their default */
	ASSERT_EQ(parse("shape=round:scale=4", v), 0);
	ASSERT_NEAR(v[4], 0, 0);
	ASSERT_NEAR(v[0], 4, 0);
	ASSERT_NEAR(v[2], 3, 0);
	/* bounds are inclusive */
	ASSERT_EQ(parse("scale=0.5:count=1:floor=0", v), 0);
	ASSERT_NEAR(v[0], 0.5, 0);
	ASSERT_NEAR(v[2], 1, 0);
	ASSERT_NEAR(v[5], 0, 0);
	/* an integer may be written as any whole number */
	ASSERT_EQ(parse("count=5.0", v), 0);
	ASSERT_NEAR(v[2], 5, 0);
	ASSERT_EQ(parse("count=+6", v), 0);
	ASSERT_NEAR(v[2], 6, 0);
	ASSERT_EQ(parse("offset=1e-3", v), 0);
	ASSERT_NEAR(v[1], 1e-3, 0);
	ASSERT_EQ(parse("offset=.5", v), 0);
	ASSERT_NEAR(v[1], 0.5, 0);
}

TEST(params_bool_spellings)
{
	static const char *const on[] = { "1", "on", "yes", "true", "TRUE", "Yes" };
	static const char *const off[] = { "0", "off", "no", "false", "OFF" };
	char spec[64];
	double v[6];
	size_t i;

	for (i = 0; i < sizeof(on) / sizeof(on[0]); i++) {
		snprintf(spec, sizeof(spec), "invert=%s", on[i]);
		ASSERT_EQ(parse(spec, v), 0);
		ASSERT_NEAR(v[3], 1, 0);
	}
	for (i = 0; i < sizeof(off) / sizeof(off[0]); i++) {
		snprintf(spec, sizeof(spec), "invert=%s", off[i]);
		ASSERT_EQ(parse(spec, v), 0);
		ASSERT_NEAR(v[3], 0, 0);
	}
}

TEST(params_refused)
{
	ASSERT_REFUSED("size=1", "mode 'tp' has no parameter 'size' (it has: "
	               "scale, offset, count, invert, shape, floor)");
	/* an unknown key is unknown with or without a value */
	ASSERT_REFUSED("size", "mode 'tp' has no parameter 'size' (it has: "
	               "scale, offset, count, invert, shape, floor)");
	ASSERT_REFUSED("=1", "mode 'tp' has no parameter '' (it has: "
	               "scale, offset, count, invert, shape, floor)");
	ASSERT_REFUSED("scale", "mode 'tp': parameter 'scale' has no value "
	               "(write scale=VALUE)");
	ASSERT_REFUSED("scale=abc", "mode 'tp': parameter 'scale' needs a number "
	               "(in [0.5, 4]), not 'abc'");
	ASSERT_REFUSED("scale=", "mode 'tp': parameter 'scale' needs a number "
	               "(in [0.5, 4]), not ''");
	ASSERT_REFUSED("scale=2x", "mode 'tp': parameter 'scale' needs a number "
	               "(in [0.5, 4]), not '2x'");
	ASSERT_REFUSED("scale=0x2", "mode 'tp': parameter 'scale' needs a number "
	               "(in [0.5, 4]), not '0x2'");
	ASSERT_REFUSED("scale= 2", "mode 'tp': parameter 'scale' needs a number "
	               "(in [0.5, 4]), not ' 2'");
	ASSERT_REFUSED("offset=nan", "mode 'tp': parameter 'offset' needs a number "
	               "(any number), not 'nan'");
	ASSERT_REFUSED("offset=-inf", "mode 'tp': parameter 'offset' needs a "
	               "number (any number), not '-inf'");
	ASSERT_REFUSED("offset=1e400", "mode 'tp': parameter 'offset' needs a "
	               "number (any number), not '1e400'");
	ASSERT_REFUSED("scale=4.01", "mode 'tp': parameter 'scale' is 4.01, out of "
	               "its range (in [0.5, 4])");
	ASSERT_REFUSED("scale=-1", "mode 'tp': parameter 'scale' is -1, out of "
	               "its range (in [0.5, 4])");
	ASSERT_REFUSED("floor=-0.1", "mode 'tp': parameter 'floor' is -0.1, out of "
	               "its range (>= 0)");
	ASSERT_REFUSED("count=2.5", "mode 'tp': parameter 'count' must be an "
	               "integer in [1, 8], not 2.5");
	ASSERT_REFUSED("count=9", "mode 'tp': parameter 'count' is 9, out of its "
	               "range (an integer in [1, 8])");
	ASSERT_REFUSED("count=0", "mode 'tp': parameter 'count' is 0, out of its "
	               "range (an integer in [1, 8])");
	ASSERT_REFUSED("invert=maybe", "mode 'tp': parameter 'invert' must be 0 or "
	               "1 (or off/on, no/yes, false/true), not 'maybe'");
	ASSERT_REFUSED("invert=2", "mode 'tp': parameter 'invert' must be 0 or "
	               "1 (or off/on, no/yes, false/true), not '2'");
	ASSERT_REFUSED("shape=oval", "mode 'tp': parameter 'shape' must be one of "
	               "round|square|fail, not 'oval'");
	ASSERT_REFUSED("shape=", "mode 'tp': parameter 'shape' must be one of "
	               "round|square|fail, not ''");
	/* a choice is its name, not its index */
	ASSERT_REFUSED("shape=1", "mode 'tp': parameter 'shape' must be one of "
	               "round|square|fail, not '1'");
	ASSERT_REFUSED("shape=squares", "mode 'tp': parameter 'shape' must be one "
	               "of round|square|fail, not 'squares'");
	ASSERT_REFUSED("count=2:scale=1:count=3", "mode 'tp': parameter 'count' "
	               "is given twice");
	ASSERT_REFUSED("count=2:count=2", "mode 'tp': parameter 'count' is given "
	               "twice");
}

TEST(params_none)
{
	double v[1] = { 42 };

	ASSERT_EQ(rf_plugin_parse_params(&no_params, "", v, msg, sizeof(msg)), 0);
	ASSERT_NEAR(v[0], 42, 0); /* nothing written */
	ASSERT_EQ(rf_plugin_parse_params(&no_params, "x=1", v, msg, sizeof(msg)),
	          RF_EINVAL);
	ASSERT_STR_EQ(msg, "mode 'none' has no parameter 'x' (it takes none)");
}

TEST(params_long_item)
{
	char spec[2000];
	double v[6];

	memset(spec, 'a', sizeof(spec) - 1);
	spec[sizeof(spec) - 1] = '\0';
	ASSERT_EQ(parse(spec, v), RF_EINVAL);
	ASSERT(strstr(msg, "is too long") != NULL);
	/* the message is bounded by its buffer */
	ASSERT(strlen(msg) < sizeof(msg));
}

/* ---- search path and loader ------------------------------------------ */

TEST(search_path)
{
	const char *user = getenv("REFLECT_PLUGIN_PATH");
	const char *sys = getenv("REFLECT_PLUGIN_SYSTEM_PATH");
	char *save_user = user ? strdup(user) : NULL;
	char *save_sys = sys ? strdup(sys) : NULL;
	const char *got;

	setenv("REFLECT_PLUGIN_PATH", "/a:/b", 1);
	setenv("REFLECT_PLUGIN_SYSTEM_PATH", "/c", 1);
	ASSERT_STR_EQ(rf_plugin_search_path(), "/a:/b:/c");
	setenv("REFLECT_PLUGIN_SYSTEM_PATH", "", 1);
	ASSERT_STR_EQ(rf_plugin_search_path(), "/a:/b");
	unsetenv("REFLECT_PLUGIN_PATH");
	ASSERT_STR_EQ(rf_plugin_search_path(), "");
	setenv("REFLECT_PLUGIN_PATH", "", 1);
	ASSERT_STR_EQ(rf_plugin_search_path(), "");
	/* unset system path: the installed directory comes last */
	setenv("REFLECT_PLUGIN_PATH", "/a", 1);
	unsetenv("REFLECT_PLUGIN_SYSTEM_PATH");
	got = rf_plugin_search_path();
#ifdef REFLECT_PLUGINDIR
	ASSERT_STR_EQ(got, "/a:" REFLECT_PLUGINDIR);
#else
	ASSERT(!strncmp(got, "/a:/", 4));
#endif

	if (save_user)
		setenv("REFLECT_PLUGIN_PATH", save_user, 1);
	else
		unsetenv("REFLECT_PLUGIN_PATH");
	if (save_sys)
		setenv("REFLECT_PLUGIN_SYSTEM_PATH", save_sys, 1);
	else
		unsetenv("REFLECT_PLUGIN_SYSTEM_PATH");
	free(save_user);
	free(save_sys);
}

static const char *
test_plugins(void)
{
	const char *dir = getenv("REFLECT_TEST_PLUGINS");

	return dir && *dir ? dir : NULL;
}

/* Loads dir/name.so as a projection mode: the status, message in msg. */
static int
load(const char *name, unsigned kind, rf_module **m)
{
	char path[4096];

	snprintf(path, sizeof(path), "%s/%s.so", test_plugins(), name);
	msg[0] = '\0';
	return rf_module_load_file(m, path, kind, msg, sizeof(msg));
}

TEST(loader_refusals)
{
	static const char *const broken[] = {
		"bad_major", "bad_minor", "bad_size", "no_entry", "bad_name",
		"bad_param_flags", "bad_flags", "no_summary", "bad_optional",
	};
	rf_module *m = (rf_module *)&m;
	size_t i;

	if (!test_plugins()) {
		printf("# REFLECT_TEST_PLUGINS is not set: run through make check\n");
		ASSERT(0);
	}
	for (i = 0; i < sizeof(broken) / sizeof(broken[0]); i++) {
		ASSERT_EQ(load(broken[i], RF_KIND_PROJECTION, &m), RF_EPLUGIN);
		ASSERT(m == NULL);
		ASSERT(strstr(msg, broken[i]) != NULL); /* names the file */
		ASSERT(strchr(msg, '\n') == NULL);
	}
	/* a good plugin of another kind: refused when a kind is asked for */
	ASSERT_EQ(load("shade_kind", RF_KIND_PROJECTION, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "use it with reflect-shade") != NULL);
	ASSERT_EQ(load("shade_kind", 0, &m), 0);
	ASSERT_EQ(rf_module_plugin(m)->kind, RF_KIND_SHADE);
	ASSERT_EQ(rf_plugin_writes_radiance(rf_module_plugin(m)), 0);
	ASSERT_EQ(rf_plugin_traces_raw(rf_module_plugin(m)), 0);
	rf_module_unload(m);
	/* The output contract of a kind, and the flag that chooses it. */
	ASSERT_EQ(load("shade_no_roughness", RF_KIND_SHADE, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "a shade mode must output roughness.eff (or, with "
	                   "RF_PLUGIN_RADIANCE, spec.R spec.G spec.B)") != NULL);
	ASSERT_EQ(load("radiance_no_spec", RF_KIND_SHADE, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "(RF_PLUGIN_RADIANCE) must output spec.R spec.G spec.B") != NULL);
	ASSERT_EQ(load("radiance_projection", RF_KIND_PROJECTION, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "which only a shade mode may") != NULL);
	/* Messages that say what is wrong, with the values. */
	ASSERT_EQ(load("bad_param_range", RF_KIND_PROJECTION, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "parameter 'gain': its default 12 lies outside its range "
	                   "[0, 10]") != NULL);
	ASSERT_EQ(load("bad_param_name", RF_KIND_PROJECTION, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "parameter 1 is named 'Gain', not a name of [a-z][a-z0-9_]*") != NULL);
	ASSERT_EQ(load("shade_both", RF_KIND_SHADE, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "writes roughness.eff (the host samples with it) or, with "
	                   "RF_PLUGIN_RADIANCE, spec.R spec.G spec.B, not both") != NULL);
	ASSERT_EQ(load("accumulate_channels", RF_KIND_ACCUMULATE, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "an accumulate mode reads no channels by name and its "
	                   "state's first slots are 'value' and 'variance'") != NULL);
	ASSERT_EQ(load("flags_abi_1_0", RF_KIND_SHADE, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "sets flags 0x1 that ABI 1.0 does not define") != NULL);
	ASSERT_EQ(load("filter_outputs_abi_1_2", RF_KIND_FILTER, &m), RF_EPLUGIN);
	ASSERT(strstr(msg, "built for plugin ABI 1.2, whose filter modes name no outputs; "
	                   "rows carried from pass to pass need ABI 1.3") != NULL);
	ASSERT_EQ(load("shade_radiance", RF_KIND_SHADE, &m), 0);
	ASSERT_EQ(rf_plugin_writes_radiance(rf_module_plugin(m)), 1);
	ASSERT_EQ(rf_plugin_traces_raw(rf_module_plugin(m)), 1);
	rf_module_unload(m);
	/* A 1.0 mode had no flag: its outputs still say it samples itself. */
	ASSERT_EQ(load("shade_radiance_1_0", RF_KIND_SHADE, &m), 0);
	ASSERT_EQ(rf_module_plugin(m)->abi_minor, 0);
	ASSERT_EQ(rf_plugin_writes_radiance(rf_module_plugin(m)), 1);
	rf_module_unload(m);
	ASSERT_EQ(load("nonexistent", 0, &m), RF_ENOTFOUND);
	ASSERT(strstr(msg, "cannot open plugin") != NULL);
	msg[0] = '\0';
	ASSERT_EQ(rf_module_load_file(&m, test_plugins(), 0, msg, sizeof(msg)),
	          RF_EPLUGIN);
	ASSERT(strstr(msg, "not a regular file") != NULL);
}

TEST(loader_by_name)
{
	const char *user = getenv("REFLECT_PLUGIN_PATH");
	char *save = user ? strdup(user) : NULL;
	rf_module *m;
	int rc;

	if (!test_plugins())
		ASSERT(0);
	setenv("REFLECT_PLUGIN_PATH", test_plugins(), 1);
	msg[0] = '\0';
	rc = rf_module_load(&m, "echo_params", RF_KIND_PROJECTION, msg, sizeof(msg));
	ASSERT_EQ(rc, 0);
	ASSERT_STR_EQ(rf_module_plugin(m)->name, "echo_params");
	ASSERT(strstr(rf_module_path(m), "/echo_params.so") != NULL);
	rf_module_unload(m);
	ASSERT_EQ(rf_module_load(&m, "bad_major", RF_KIND_PROJECTION, msg,
	                         sizeof(msg)), RF_EPLUGIN);
	ASSERT_EQ(rf_module_load(&m, "nosuch", RF_KIND_PROJECTION, msg, sizeof(msg)),
	          RF_ENOTFOUND);
	ASSERT(strstr(msg, "unknown projection mode 'nosuch'") != NULL);
	ASSERT_EQ(rf_module_load(&m, "../echo_params", RF_KIND_PROJECTION, msg,
	                         sizeof(msg)), RF_ENOTFOUND); /* a path: no such file */
	ASSERT_EQ(rf_module_load(&m, "a b", RF_KIND_PROJECTION, msg, sizeof(msg)),
	          RF_EINVAL);
	if (save)
		setenv("REFLECT_PLUGIN_PATH", save, 1);
	else
		unsetenv("REFLECT_PLUGIN_PATH");
	free(save);
}

/* ---- a stage over echo_params ---------------------------------------- */

TEST(stage_runs_plugin)
{
	struct rf_host host;
	rf_module *m;
	rf_stage *s;
	rf_header *h, *out;
	const struct rf_plugin *p;
	double values[5];
	/* 3 columns x 4 rows of "extra N.X echo.count" */
	float in[4][3][3], res[4][3][10];
	size_t x, y;
	int c;

	if (!test_plugins())
		ASSERT(0);
	ASSERT_EQ(load("echo_params", RF_KIND_PROJECTION, &m), 0);
	p = rf_module_plugin(m);
	ASSERT_EQ(rf_plugin_parse_params(p, "scale=2:offset=0.5:count=7:invert=on",
	                                 values, msg, sizeof(msg)), 0);
	memset(&host, 0, sizeof(host));
	host.size = sizeof(host);
	host.abi_major = RF_PLUGIN_ABI_MAJOR;
	host.abi_minor = RF_PLUGIN_ABI_MINOR;
	ASSERT_EQ(rf_stage_create(&s, p, values, &host, 3, msg, sizeof(msg)), 0);
	ASSERT_EQ(rf_header_create(&h), 0);
	ASSERT_EQ(rf_header_set_size(h, 3, 4), 0);
	ASSERT_EQ(rf_header_set_channels(h, "extra N.X echo.count"), 0);
	ASSERT_EQ(rf_header_set(h, "FRAME", "6"), 0);
	ASSERT_EQ(rf_stage_begin_frame(s, h, &out, msg, sizeof(msg)), 0);
	/* echo.count already in the input: overwritten in place, others added */
	ASSERT_EQ(rf_header_nchannels(out), 10);
	ASSERT_STR_EQ(rf_header_channel(out, 2), "echo.count");
	ASSERT_STR_EQ(rf_header_channel(out, 3), "echo.scale");
	ASSERT_STR_EQ(rf_header_channel(out, 9), "echo.frame");
	for (y = 0; y < 4; y++)
		for (x = 0; x < 3; x++) {
			in[y][x][0] = -1.0f;
			in[y][x][1] = (float)(10 * y + x);
			in[y][x][2] = 99.0f;
		}
	ASSERT_EQ(rf_stage_run(s, &in[0][0][0], &res[0][0][0], 0, 4), 0);
	/* zero rows touch nothing (worker 0 once redid its last block) */
	res[0][0][0] = 12345.0f;
	ASSERT_EQ(rf_stage_run(s, &in[0][0][0], &res[0][0][0], 0, 0), 0);
	ASSERT_NEAR(res[0][0][0], 12345.0f, 0);
	res[0][0][0] = -1.0f;
	ASSERT_EQ(rf_stage_run(s, &in[0][0][0], &res[0][0][0], 2, 3), RF_EINVAL);
	for (y = 0; y < 4; y++)
		for (x = 0; x < 3; x++) {
			float *px = res[y][x];

			ASSERT_NEAR(px[0], -1, 0);                /* extra kept */
			ASSERT_NEAR(px[1], 10 * y + x, 0);        /* N.X kept */
			ASSERT_NEAR(px[2], 7, 0);                 /* echo.count */
			ASSERT_NEAR(px[3], 2, 0);                 /* echo.scale */
			ASSERT_NEAR(px[4], 0.5, 0);               /* echo.offset */
			ASSERT_NEAR(px[5], 1, 0);                 /* echo.invert */
			ASSERT_NEAR(px[6], 0, 0);                 /* echo.shape */
			ASSERT_NEAR(px[7], 2 * (10 * y + x) + 0.5, 1e-6); /* echo.nx */
			ASSERT_NEAR(px[8], y, 0);                 /* echo.y */
			ASSERT_NEAR(px[9], 6, 0);                 /* echo.frame */
		}
	rf_stage_destroy(s);
	rf_header_destroy(h);

	/* create() fails: its two-line message arrives as one line */
	ASSERT_EQ(rf_plugin_parse_params(p, "shape=fail", values, msg, sizeof(msg)), 0);
	c = rf_stage_create(&s, p, values, &host, 2, msg, sizeof(msg));
	ASSERT_EQ(c, RF_EPLUGIN);
	ASSERT(s == NULL);
	ASSERT_STR_EQ(msg, "mode 'echo_params': shape=fail asked for a failure "
	               "in create");
	rf_module_unload(m);
}

/* A mode built for ABI 1.1 reads the probes array at 1.1's stride (48
 * bytes a probe), and is refused a frame with a probe it cannot see. */
TEST(old_modes_see_old_probes)
{
	rf_plugin_host *host;
	rf_module *m;
	rf_stage *s;
	rf_header *h, *out;
	struct rf_probe probe;
	float in[3] = { 0.0f, 0.0f, 1.0f }, res[11];

	if (!test_plugins())
		ASSERT(0);
	ASSERT_EQ(load("probes_abi_1_1", RF_KIND_PROJECTION, &m), 0);
	ASSERT_EQ(rf_header_create(&h), 0);
	ASSERT_EQ(rf_header_set_size(h, 1, 1), 0);
	ASSERT_EQ(rf_header_set_channels(h, "N.X N.Y N.Z"), 0);
	ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_BOX, "-1 -2 -3 1 2 3"), 0);
	ASSERT_EQ(rf_header_set(h, "PROBE2_BOX", "-7 -8 -9 7 8 9.5"), 0);
	ASSERT_EQ(rf_plugin_host_create(&host), 0);
	rf_plugin_host_set_frame(host, h);
	ASSERT_EQ(rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	rf_plugin_host_set_probe(host, &probe);
	ASSERT_EQ(rf_stage_create(&s, rf_module_plugin(m), NULL, rf_plugin_host_table(host), 1,
	                          msg, sizeof(msg)), 0);
	ASSERT_EQ(rf_stage_begin_frame(s, h, &out, msg, sizeof(msg)), 0);
	ASSERT_EQ(rf_stage_run(s, in, res, 0, 1), 0);
	ASSERT_NEAR(res[3], -1, 0);
	ASSERT_NEAR(res[4], -7, 0);  /* 112 bytes on, where 1.2's stride would miss */
	ASSERT_NEAR(res[5], 9.5, 0);
	ASSERT_NEAR(res[6], 2, 0);
	/* a frame whose second probe turns: refused, the probe named */
	ASSERT_EQ(rf_header_set(h, "PROBE2_ROTATION", "0 30 0"), 0);
	rf_plugin_host_set_frame(host, h);
	msg[0] = '\0';
	ASSERT_EQ(rf_stage_begin_frame(s, h, &out, msg, sizeof(msg)), RF_EPLUGIN);
	ASSERT(strstr(msg, "mode 'probes_abi_1_1' was built for plugin ABI 1.1, which knows "
	                   "axis-aligned probe boxes only, and probe 2 is a rotated box") != NULL);
	rf_stage_destroy(s);
	/* and refused at once when the frame has it already; a sphere */
	ASSERT_EQ(rf_header_unset(h, "PROBE2_ROTATION"), 0);
	ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_SHAPE, "sphere"), 0);
	ASSERT_EQ(rf_header_set(h, RF_KEY_PROBE_BOX, "-1 -1 -1 1 1 1"), 0);
	ASSERT_EQ(rf_probe_resolve(&probe, h, NULL, NULL, NULL, msg, sizeof(msg)), 0);
	rf_plugin_host_set_frame(host, h);
	rf_plugin_host_set_probe(host, &probe);
	ASSERT_EQ(rf_stage_create(&s, rf_module_plugin(m), NULL, rf_plugin_host_table(host), 1,
	                          msg, sizeof(msg)), RF_EPLUGIN);
	ASSERT(strstr(msg, "probe 1 is a sphere") != NULL);
	rf_header_destroy(h);
	rf_plugin_host_destroy(host);
	rf_module_unload(m);
}

int
main(void)
{
#ifndef HAVE_ABI_TABLE
	printf("ok 1 - struct_layout # SKIP no ABI table for this platform: "
	       "add one to tests/unit/test-abi.c\n");
	tap_count++;
#else
	RUN(struct_layout);
#endif
	RUN(constants);
	RUN(params_defaults);
	RUN(params_every_type);
	RUN(params_bool_spellings);
	RUN(params_refused);
	RUN(params_none);
	RUN(params_long_item);
	RUN(search_path);
	RUN(loader_refusals);
	RUN(loader_by_name);
	RUN(stage_runs_plugin);
	RUN(old_modes_see_old_probes);
	TAP_DONE();
}
