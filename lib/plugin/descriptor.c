/* A plugin's descriptor checked, once load.c has found its ABI fields
 * good: its fields, its name against its file's, its kind and that
 * kind's output contract, its parameters. */
#include <ctype.h>
#include <math.h>
#include <string.h>

#include "plugin/plugin-internal.h"
#include "util/util.h"
#include "reflect/plugin.h"

/* A sanity bound on a descriptor's parameter count (a garbage nparams
 * would otherwise walk far past the table). */
#define RF_PARAMS_MAX 256

/* The tool that loads each kind, for the advice in messages. */
static const char *
kind_tool(unsigned kind)
{
	switch (kind) {
	case RF_KIND_PROJECTION:
		return "reflect-project";
	case RF_KIND_SHADE:
		return "reflect-shade";
	case RF_KIND_OCCLUSION:
		return "reflect-occlude";
	case RF_KIND_ACCUMULATE:
		return "reflect-accumulate";
	case RF_KIND_FILTER:
		return "reflect-filter";
	}
	return "another tool";
}

const char *
rf_plugin_kind_name(unsigned kind)
{
	switch (kind) {
	case RF_KIND_PROJECTION:
		return "projection";
	case RF_KIND_SHADE:
		return "shade";
	case RF_KIND_OCCLUSION:
		return "occlusion";
	case RF_KIND_ACCUMULATE:
		return "accumulate";
	case RF_KIND_FILTER:
		return "filter";
	}
	return NULL;
}

static int
param_name_valid(const char *s)
{
	if (!s || !islower((unsigned char)*s))
		return 0;
	for (s++; *s; s++)
		if (!islower((unsigned char)*s) && !isdigit((unsigned char)*s) && *s != '_')
			return 0;
	return 1;
}

static int
count_choices(const char *choices)
{
	int n = 1;

	if (!choices || !*choices)
		return 0;
	for (; *choices; choices++)
		if (*choices == '|')
			n++;
	return n;
}

static int
channel_list_valid(const char *const *list)
{
	size_t i, j;

	if (!list)
		return 0;
	for (i = 0; list[i]; i++) {
		if (i >= RF_CHANNELS_MAX || !rf_channel_name_valid(list[i]))
			return 0;
		for (j = 0; j < i; j++)
			if (!strcmp(list[i], list[j]))
				return 0; /* two columns of one name */
	}
	return 1;
}

/* Optional inputs: a channel list whose names are no required input. */
static int
optional_list_valid(const struct rf_plugin *p)
{
	const char *const *opt = rf_plugin_optional_inputs(p);
	size_t i, j;

	if (!channel_list_valid(opt))
		return 0;
	for (i = 0; opt[i]; i++)
		for (j = 0; p->inputs[j]; j++)
			if (!strcmp(opt[i], p->inputs[j]))
				return 0;
	return 1;
}

/* The file name without directory and ".so". */
static void
file_stem(const char *path, char *out, size_t size)
{
	const char *base = strrchr(path, '/');
	size_t n;

	base = base ? base + 1 : path;
	n = strlen(base);
	if (n > 3 && !strcmp(base + n - 3, ".so"))
		n -= 3;
	if (n >= size)
		n = size - 1;
	memcpy(out, base, n);
	out[n] = '\0';
}

/* Every message below reads "plugin 'PATH': what is wrong; the fix", so
 * that a tool can print it as it is (-m) or after "ignoring " (-l). */

/* A name as a message shows it: quoted, control bytes as '?', cut. */
static void
shown_name(const char *name, char *out, size_t size)
{
	size_t i, n = 0;

	out[n++] = '\'';
	for (i = 0; name[i] && n + 5 < size; i++)
		out[n++] = (unsigned char)name[i] < 0x20 || name[i] == 0x7f ? '?' : name[i];
	if (name[i])
		out[n++] = '.', out[n++] = '.', out[n++] = '.';
	out[n++] = '\'';
	out[n] = '\0';
}

/* What is wrong with a parameter's range, default or flags, with the
 * values; NULL when nothing is. */
static const char *
param_inconsistency(const struct rf_param *q, int nchoices, char *buf, size_t size)
{
	if (isnan(q->min) || isnan(q->max) || isnan(q->def))
		rf__format(buf, size, "its range [%g, %g] or its default %g is NaN", q->min,
		           q->max, q->def);
	else if (q->min > q->max)
		rf__format(buf, size, "its range [%g, %g] is empty (min above max)", q->min,
		           q->max);
	else if (!isfinite(q->def) || q->def < q->min || q->def > q->max)
		rf__format(buf, size, "its default %g lies outside its range [%g, %g]", q->def,
		           q->min, q->max);
	else if ((q->flags & (RF_PARAM_INTEGER | RF_PARAM_CHOICE)) && q->def != floor(q->def))
		rf__format(buf, size, "its default %g is not a whole number, as %s needs",
		           q->def, q->flags & RF_PARAM_CHOICE ? "RF_PARAM_CHOICE" : "RF_PARAM_INTEGER");
	else if ((q->flags & RF_PARAM_BOOL) && (q->flags & RF_PARAM_CHOICE))
		rf__format(buf, size, "it sets both RF_PARAM_BOOL and RF_PARAM_CHOICE");
	else if ((q->flags & RF_PARAM_CHOICE) && nchoices == 0)
		rf__format(buf, size, "it sets RF_PARAM_CHOICE but its choices ('%.60s') name "
		           "none", q->choices ? q->choices : "");
	else if ((q->flags & RF_PARAM_CHOICE) && (q->min != 0 || q->max != nchoices - 1))
		rf__format(buf, size, "its %d choices need the range [0, %d], not [%g, %g]",
		           nchoices, nchoices - 1, q->min, q->max);
	else if ((q->flags & RF_PARAM_STRING) && (q->flags & ~RF_PARAM_STRING))
		rf__format(buf, size, "it sets RF_PARAM_STRING with other flags (0x%x)",
		           q->flags);
	else if ((q->flags & RF_PARAM_STRING) && (q->min != 0 || q->max != 0 || q->def != 0))
		rf__format(buf, size, "RF_PARAM_STRING needs min, max and def 0, not %g, %g, "
		           "%g (its default string is choices)", q->min, q->max, q->def);
	else if ((q->flags & RF_PARAM_BOOL) && (q->min != 0 || q->max != 1))
		rf__format(buf, size, "RF_PARAM_BOOL needs the range [0, 1], not [%g, %g]",
		           q->min, q->max);
	else
		return NULL;
	return buf;
}

static int
check_params(const struct rf_plugin *p, const char *path, char *err, size_t errlen)
{
	char problem[200];
	const char *why;
	uint32_t i, j;

	if (p->nparams && !p->params) {
		rf__format(err, errlen, "plugin '%s': its descriptor declares %u "
		           "parameters but no table; fix the plugin and rebuild it",
		           path, p->nparams);
		return RF_EPLUGIN;
	}
	if (p->nparams > RF_PARAMS_MAX) {
		rf__format(err, errlen, "plugin '%s': it declares %u parameters, more "
		           "than the %d a mode may have; fix the plugin and rebuild it",
		           path, p->nparams, RF_PARAMS_MAX);
		return RF_EPLUGIN;
	}
	for (i = 0; i < p->nparams; i++) {
		const struct rf_param *q = &p->params[i];
		int n = count_choices(q->choices);

		if (!param_name_valid(q->name)) {
			char shown[48] = "(none)";

			if (q->name)
				shown_name(q->name, shown, sizeof(shown));
			rf__format(err, errlen, "plugin '%s': parameter %u is named %s, not "
			           "a name of [a-z][a-z0-9_]* (at most 63 bytes); rename it "
			           "and rebuild the plugin", path, i + 1, shown);
			return RF_EPLUGIN;
		}
		if (!q->help || !*q->help) {
			rf__format(err, errlen, "plugin '%s': parameter '%s' has no help "
			           "text; write one and rebuild the plugin", path, q->name);
			return RF_EPLUGIN;
		}
		if (q->flags & ~(p->abi_minor >= 1 ? RF_PARAM_KNOWN_FLAGS
		                                   : RF_PARAM_INTEGER | RF_PARAM_BOOL | RF_PARAM_CHOICE)) {
			rf__format(err, errlen, "plugin '%s': built for plugin ABI "
			           "%u.%u, its parameter '%s' sets flag bits 0x%x that "
			           "this ABI does not define (this reflect (%s) supports "
			           "ABI %d.%d); use only RF_PARAM_INTEGER, RF_PARAM_BOOL, "
			           "RF_PARAM_CHOICE and RF_PARAM_STRING and rebuild it", path, p->abi_major,
			           p->abi_minor, q->name,
			           q->flags & ~(p->abi_minor >= 1 ? RF_PARAM_KNOWN_FLAGS
			                                          : RF_PARAM_INTEGER | RF_PARAM_BOOL |
			                                                    RF_PARAM_CHOICE),
			           RF_VERSION_STRING, RF_PLUGIN_ABI_MAJOR,
			           RF_PLUGIN_ABI_MINOR);
			return RF_EPLUGIN;
		}
		if ((why = param_inconsistency(q, n, problem, sizeof(problem)))) {
			rf__format(err, errlen, "plugin '%s': parameter '%s': %s; fix the "
			           "plugin and rebuild it", path, q->name, why);
			return RF_EPLUGIN;
		}
		for (j = 0; j < i; j++)
			if (!strcmp(p->params[j].name, q->name)) {
				rf__format(err, errlen, "plugin '%s': parameter '%s' is "
				           "declared twice; fix the plugin and rebuild it",
				           path, q->name);
				return RF_EPLUGIN;
			}
	}
	return 0;
}

static int
writes(const struct rf_plugin *p, const char *name)
{
	size_t i;

	for (i = 0; p->outputs[i]; i++)
		if (!strcmp(p->outputs[i], name))
			return 1;
	return 0;
}

int
rf_plugin_writes_radiance(const struct rf_plugin *p)
{
	if (p->kind != RF_KIND_SHADE)
		return 0;
	if (p->abi_minor >= 1)
		return (p->flags & RF_PLUGIN_RADIANCE) != 0;
	/* ABI 1.0 had no flag: a mode writing spec.* and no roughness.eff
	 * was one that samples itself. */
	return !writes(p, RF_SHADE_ROUGHNESS);
}

int
rf_plugin_traces_raw(const struct rf_plugin *p)
{
	return rf_plugin_writes_radiance(p) && !(p->flags & RF_PLUGIN_PREFILTERED);
}

/* A kind's output contract (plugin.h): a shade mode writes the roughness
 * the host samples with, or with RF_PLUGIN_RADIANCE the radiance; an
 * accumulate mode reads values, not channels, into a state that starts
 * with the value and its variance; an occlusion mode writes its factor. */
static int
check_outputs(const struct rf_plugin *p, const char *path, char *err, size_t errlen)
{
	if (p->flags & RF_PLUGIN_RADIANCE && p->kind != RF_KIND_SHADE) {
		rf__format(err, errlen, "plugin '%s': its descriptor sets RF_PLUGIN_RADIANCE, "
		           "which only a shade mode may; clear it and rebuild the plugin",
		           path);
		return RF_EPLUGIN;
	}
	if (p->kind == RF_KIND_ACCUMULATE) {
		if (p->inputs[0] || strcmp(p->outputs[0], RF_ACCUMULATE_VALUE) ||
		    !p->outputs[1] || strcmp(p->outputs[1], RF_ACCUMULATE_VARIANCE)) {
			rf__format(err, errlen, "plugin '%s': an accumulate mode reads no "
			           "channels by name and its state's first slots are '%s' and "
			           "'%s' (reflect-plugin(7)); fix its inputs and outputs and "
			           "rebuild the plugin", path, RF_ACCUMULATE_VALUE,
			           RF_ACCUMULATE_VARIANCE);
			return RF_EPLUGIN;
		}
		return 0;
	}
	if (p->kind == RF_KIND_FILTER) {
		/* its outputs name state carried from pass to pass, not channels */
		if (p->abi_minor < 1) {
			rf__format(err, errlen, "plugin '%s': a filter mode needs plugin ABI "
			           "1.1 (reflect-plugin(7)); rebuild the plugin", path);
			return RF_EPLUGIN;
		}
		if (p->abi_minor < 3 && p->outputs[0]) {
			rf__format(err, errlen, "plugin '%s': built for plugin ABI 1.%u, whose "
			           "filter modes name no outputs; rows carried from pass to "
			           "pass need ABI 1.3: empty its outputs list, or rebuild it "
			           "against this reflect's <reflect/plugin.h>", path,
			           (unsigned)p->abi_minor);
			return RF_EPLUGIN;
		}
		return 0;
	}
	if (p->kind == RF_KIND_OCCLUSION) {
		if (strcmp(p->outputs[0], RF_OCCLUSION) || p->outputs[1]) {
			rf__format(err, errlen, "plugin '%s': an occlusion mode writes one "
			           "channel, '%s' (the host multiplies the reflection by it); "
			           "fix its outputs and rebuild the plugin", path, RF_OCCLUSION);
			return RF_EPLUGIN;
		}
		return 0;
	}
	if (p->kind != RF_KIND_SHADE)
		return 0;
	if (writes(p, RF_SHADE_ROUGHNESS) &&
	    (writes(p, RF_SHADE_SPEC_R) || writes(p, RF_SHADE_SPEC_G) ||
	     writes(p, RF_SHADE_SPEC_B))) {
		rf__format(err, errlen, "plugin '%s': a shade mode writes %s (the host "
		           "samples with it) or, with RF_PLUGIN_RADIANCE, %s %s %s, not both: "
		           "one of them would be dropped; keep one and rebuild the plugin",
		           path, RF_SHADE_ROUGHNESS, RF_SHADE_SPEC_R, RF_SHADE_SPEC_G,
		           RF_SHADE_SPEC_B);
		return RF_EPLUGIN;
	}
	if (rf_plugin_writes_radiance(p)) {
		if (!writes(p, RF_SHADE_SPEC_R) || !writes(p, RF_SHADE_SPEC_G) ||
		    !writes(p, RF_SHADE_SPEC_B)) {
			rf__format(err, errlen, "plugin '%s': a shade mode that writes "
			           "radiance (RF_PLUGIN_RADIANCE) must output %s %s %s; add "
			           "them and rebuild the plugin", path, RF_SHADE_SPEC_R,
			           RF_SHADE_SPEC_G, RF_SHADE_SPEC_B);
			return RF_EPLUGIN;
		}
	} else if (!writes(p, RF_SHADE_ROUGHNESS)) {
		rf__format(err, errlen, "plugin '%s': a shade mode must output %s (or, "
		           "with RF_PLUGIN_RADIANCE, %s %s %s); add it and rebuild the "
		           "plugin", path, RF_SHADE_ROUGHNESS, RF_SHADE_SPEC_R,
		           RF_SHADE_SPEC_G, RF_SHADE_SPEC_B);
		return RF_EPLUGIN;
	}
	return 0;
}

/* Whether a file stem is the plugin's name after its kind and a '-'
 * (projection-box, as reflect names its modes): modes of two kinds may
 * share a name, box the projection and box the occlusion, in one
 * directory. */
static int
kind_prefixed(const char *stem, const struct rf_plugin *p)
{
	const char *kind = rf_plugin_kind_name(p->kind);
	size_t n = kind ? strlen(kind) : 0;

	return n && !strncmp(stem, kind, n) && stem[n] == '-' && !strcmp(stem + n + 1, p->name);
}

int
rf__descriptor_check(const struct rf_plugin *p, const char *path, unsigned kind,
                     char *err, size_t errlen)
{
	uint32_t known;
	int rc;
	char stem[256];
	const char *missing = NULL;

	if (!p->name || !*p->name)
		missing = "name";
	else if (!p->summary || !*p->summary)
		missing = "summary";
	else if (!p->version || !*p->version)
		missing = "version";
	else if (!p->author || !*p->author)
		missing = "author";
	else if (!p->license || !*p->license)
		missing = "license";
	else if (!p->create || !p->run || !p->destroy)
		missing = "create, run or destroy function";
	else if (!channel_list_valid(p->inputs))
		missing = "valid input channel list (NULL-terminated, names unique)";
	else if (!channel_list_valid(p->outputs) ||
	         (!p->outputs[0] && p->kind != RF_KIND_FILTER))
		missing = "valid output channel list (NULL-terminated, names unique, "
		          "at least one but for a filter mode)";
	else if (rf_plugin_optional_inputs(p) && !optional_list_valid(p))
		missing = "valid optional input list (NULL-terminated, names unique, "
		          "none of them an input)";
	if (missing) {
		rf__format(err, errlen, "plugin '%s': its descriptor has no %s; fill "
		           "it in and rebuild the plugin", path, missing);
		return RF_EPLUGIN;
	}
	file_stem(path, stem, sizeof(stem));
	if (strcmp(stem, p->name) && !kind_prefixed(stem, p)) {
		const char *kn = rf_plugin_kind_name(p->kind);

		rf__format(err, errlen, "plugin '%s': its descriptor is named '%.60s', "
		           "but a plugin's name must equal its file name; rename the "
		           "file to '%s%s%.60s%s%.60s.so', or set the name to '%.60s'",
		           path, p->name, kn ? kn : "", kn ? "-" : "", kn ? p->name : "",
		           kn ? ".so' or '" : "", p->name, stem);
		return RF_EPLUGIN;
	}
	known = p->abi_minor >= 1 ? RF_PLUGIN_KNOWN_FLAGS : 0;
	if (p->flags & ~known) {
		rf__format(err, errlen, "plugin '%s': built for plugin ABI %u.%u, its "
		           "descriptor sets flags 0x%x that ABI %u.%u does not define "
		           "(this reflect (%s) supports ABI %d.%d); clear them and "
		           "rebuild it", path, p->abi_major, p->abi_minor, p->flags & ~known,
		           p->abi_major, p->abi_minor, RF_VERSION_STRING,
		           RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR);
		return RF_EPLUGIN;
	}
	if (!rf_plugin_kind_name(p->kind)) {
		rf__format(err, errlen, "plugin '%s': built for plugin ABI %u.%u, its "
		           "descriptor has kind %u, which this ABI does not define "
		           "(this reflect (%s) supports ABI %d.%d); set an RF_KIND_* "
		           "value and rebuild it", path, p->abi_major, p->abi_minor,
		           p->kind, RF_VERSION_STRING, RF_PLUGIN_ABI_MAJOR,
		           RF_PLUGIN_ABI_MINOR);
		return RF_EPLUGIN;
	}
	if (kind && p->kind != kind) {
		rf__format(err, errlen, "plugin '%s': it is a %s mode, not a %s mode; "
		           "use it with %s", path, rf_plugin_kind_name(p->kind),
		           rf_plugin_kind_name(kind), kind_tool(p->kind));
		return RF_EPLUGIN;
	}
	if ((rc = check_outputs(p, path, err, errlen)) < 0)
		return rc;
	return check_params(p, path, err, errlen);
}
