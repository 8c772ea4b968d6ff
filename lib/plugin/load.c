/* Finding, loading and checking plugins. */
#include <ctype.h>
#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "plugin/plugin-internal.h"
#include "util/util.h"
#include "reflect/plugin.h"

#ifndef REFLECT_PLUGINDIR_REL
#define REFLECT_PLUGINDIR_REL ""
#endif
#ifndef REFLECT_PLUGINDIR
#define REFLECT_PLUGINDIR "/usr/local/lib/reflect-1"
#endif

/* A sanity bound on a descriptor's parameter count (a garbage nparams
 * would otherwise walk far past the table). */
#define RF_PARAMS_MAX 256

struct rf_module {
	void *handle;
	char *path;
	const struct rf_plugin *plugin;
};

/* The end of a member: what a descriptor of some minor version must hold. */
#define END_OF(type, member) (offsetof(type, member) + sizeof(((type *)0)->member))

/* Size of the descriptor at each minor version of the current major: a
 * plugin must be at least as large as its own minor version says.  Each
 * entry is the end of the last field of that version, never sizeof, so
 * that appending fields for 1.1 leaves the 1.0 entry as it was. */
static const size_t descriptor_size[RF_PLUGIN_ABI_MINOR + 1] = {
	END_OF(struct rf_plugin, destroy),         /* 1.0 */
	END_OF(struct rf_plugin, optional_inputs), /* 1.1 */
};

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
		if (p->abi_minor < 1 || p->outputs[0]) {
			rf__format(err, errlen, "plugin '%s': a filter mode (plugin ABI 1.1) "
			           "writes the values it filters, not channels by name: its "
			           "outputs list must be empty (reflect-plugin(7)); fix it and "
			           "rebuild the plugin", path);
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
 * (occlusion-box): modes of two kinds may share a name, box the
 * projection and box the occlusion, in one directory. */
static int
kind_prefixed(const char *stem, const struct rf_plugin *p)
{
	const char *kind = rf_plugin_kind_name(p->kind);
	size_t n = kind ? strlen(kind) : 0;

	return n && !strncmp(stem, kind, n) && stem[n] == '-' && !strcmp(stem + n + 1, p->name);
}

static int
check_descriptor(const struct rf_plugin *p, const char *path, unsigned kind,
                 char *err, size_t errlen)
{
	uint32_t known;
	int rc;
	char stem[256];
	const char *missing = NULL;

	/* Only the first three fields may be read before these checks. */
	if (p->abi_major != RF_PLUGIN_ABI_MAJOR) {
		rf__format(err, errlen, "plugin '%s': built for plugin ABI %u.%u, but "
		           "this reflect (%s) supports ABI %d.%d; rebuild it against "
		           "this reflect's <reflect/plugin.h>, or remove it", path,
		           p->abi_major, p->abi_minor, RF_VERSION_STRING,
		           RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR);
		return RF_EPLUGIN;
	}
	if (p->abi_minor > RF_PLUGIN_ABI_MINOR) {
		rf__format(err, errlen, "plugin '%s': built for plugin ABI %u.%u, newer "
		           "than the ABI %d.%d of this reflect (%s); upgrade reflect, or "
		           "rebuild the plugin against this reflect's <reflect/plugin.h>",
		           path, p->abi_major, p->abi_minor, RF_PLUGIN_ABI_MAJOR,
		           RF_PLUGIN_ABI_MINOR, RF_VERSION_STRING);
		return RF_EPLUGIN;
	}
	if (p->size < descriptor_size[p->abi_minor]) {
		rf__format(err, errlen, "plugin '%s': built for plugin ABI %u.%u, its "
		           "descriptor is %u bytes, less than the %zu bytes of that ABI "
		           "(this reflect (%s) supports ABI %d.%d); it was built with a "
		           "wrong header: set size to sizeof(struct rf_plugin) from "
		           "this reflect's <reflect/plugin.h> and rebuild it, or remove "
		           "it", path, p->abi_major, p->abi_minor, p->size,
		           descriptor_size[p->abi_minor], RF_VERSION_STRING,
		           RF_PLUGIN_ABI_MAJOR, RF_PLUGIN_ABI_MINOR);
		return RF_EPLUGIN;
	}
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
		rf__format(err, errlen, "plugin '%s': its descriptor is named '%.60s', "
		           "but a plugin's name must equal its file name; rename the "
		           "file to '%.60s.so' or set the name to '%.60s'", path,
		           p->name, p->name, stem);
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

int
rf_module_load_file(rf_module **mp, const char *path, unsigned kind, char *err,
                    size_t errlen)
{
	rf_plugin_entry_fn entry;
	rf_module *m;
	struct stat st;
	char why[512];
	void *sym;
	int rc;

	*mp = NULL;
	if (stat(path, &st) < 0) {
		rf__format(err, errlen, "cannot open plugin '%s': %s", path,
		           strerror(errno));
		return RF_ENOTFOUND;
	}
	if (!S_ISREG(st.st_mode)) {
		rf__format(err, errlen, "plugin '%s': not a regular file; give the "
		           "path of a .so file", path);
		return RF_EPLUGIN;
	}
	/* Read as data first: dlopen would fault on a file cut short and
	 * run the constructors of a library that is no plugin. */
	if (rf__elf_check(path, why, sizeof(why)) != 0) {
		rf__format(err, errlen, "plugin '%s': %s", path, why);
		return RF_EPLUGIN;
	}
	if (!(m = calloc(1, sizeof(*m))) || !(m->path = strdup(path))) {
		free(m);
		rf__format(err, errlen, "plugin '%s': %s", path, rf_strerror(RF_ENOMEM));
		return RF_ENOMEM;
	}
	/* its constructors run here, and its entry below: a crash in them is
	 * reported with the file's name */
	rf__call_enter_file(m->path);
	m->handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
	rf__call_leave();
	if (!m->handle) {
		const char *dl = dlerror();

		/* dlopen says "cannot open shared object file" for a library the
		 * plugin needs and cannot find: only then is ldd the way on */
		rf__format(err, errlen, "plugin '%s': cannot load it: %s%s", path,
		           dl ? dl : "unknown error",
		           dl && strstr(dl, "cannot open shared object")
		               ? "; ldd(1) on the plugin shows which library is missing" : "");
		rc = RF_EPLUGIN;
		goto fail;
	}
	dlerror();
	sym = dlsym(m->handle, RF_PLUGIN_ENTRY);
	if (!sym) {
		rf__format(err, errlen, "plugin '%s': not a reflect plugin, it exports "
		           "no %s(); define it with RF_PLUGIN_DEFINE(descriptor) from "
		           "<reflect/plugin.h>, or remove the file from the plugin path",
		           path, RF_PLUGIN_ENTRY);
		rc = RF_EPLUGIN;
		goto fail;
	}
	/* dlsym gives an object pointer; POSIX makes it callable. */
	memcpy(&entry, &sym, sizeof(entry));
	rf__call_enter_file(m->path);
	m->plugin = entry();
	rf__call_leave();
	if (!m->plugin) {
		rf__format(err, errlen, "plugin '%s': %s() returned no descriptor; "
		           "fix the plugin and rebuild it", path, RF_PLUGIN_ENTRY);
		rc = RF_EPLUGIN;
		goto fail;
	}
	if ((rc = check_descriptor(m->plugin, path, kind, err, errlen)) < 0)
		goto fail;
	*mp = m;
	return 0;
fail:
	rf_module_unload(m);
	return rc;
}

void
rf_module_unload(rf_module *m)
{
	if (!m)
		return;
	if (m->handle)
		dlclose(m->handle);
	free(m->path);
	free(m);
}

const struct rf_plugin *
rf_module_plugin(const rf_module *m)
{
	return m->plugin;
}

const char *
rf_module_path(const rf_module *m)
{
	return m->path;
}

/* The installed plugin directory: beside the library itself when the
 * tree was moved (the library's directory + REFLECT_PLUGINDIR_REL, when
 * that is a directory), else the one it was built for. */
static const char *
installed_plugindir(void)
{
	static __thread char dir[4096];
	Dl_info info;
	struct stat st;
	const char *slash;

	if (*REFLECT_PLUGINDIR_REL && dladdr((void *)rf_plugin_search_path, &info) &&
	    info.dli_fname && (slash = strrchr(info.dli_fname, '/'))) {
		rf__format(dir, sizeof(dir), "%.*s/%s", (int)(slash - info.dli_fname),
		           info.dli_fname, REFLECT_PLUGINDIR_REL);
		if (stat(dir, &st) == 0 && S_ISDIR(st.st_mode))
			return dir;
	}
	return REFLECT_PLUGINDIR;
}

const char *
rf_plugin_search_path(void)
{
	static __thread char buf[8192];
	const char *user = getenv("REFLECT_PLUGIN_PATH");
	const char *sys = getenv("REFLECT_PLUGIN_SYSTEM_PATH");

	if (!sys)
		sys = installed_plugindir();
	rf__format(buf, sizeof(buf), "%s%s%s", user && *user ? user : "",
	           user && *user && *sys ? ":" : "", sys);
	return buf;
}

/*
 * Whoever can write to a directory of the search path chooses the code
 * every tool runs: a directory any user may write to (and not sticky,
 * where they could also replace another's file) is refused, as ssh
 * refuses such files.  A relative directory is searched from wherever
 * the tool runs, which is seldom what was meant: a warning.
 */
static int
check_list(const char *list, const char *var, char *err, size_t errlen, char *warning,
           size_t warnlen)
{
	const char *p;
	size_t n;

	for (p = list; p && *p; p += n + (p[n] == ':')) {
		char dir[4096];
		struct stat st;

		n = strcspn(p, ":");
		if (!n)
			continue;
		rf__format(dir, sizeof(dir), "%.*s", (int)n, p);
		if (*dir != '/' && warning && !*warning)
			rf__format(warning, warnlen, "relative directory '%s' in %s is searched "
			           "from the current directory; give an absolute path", dir, var);
		if (stat(dir, &st) < 0 || !S_ISDIR(st.st_mode))
			continue;
		if ((st.st_mode & S_IWOTH) && !(st.st_mode & S_ISVTX)) {
			rf__format(err, errlen, "plugin directory '%s' in %s is writable by "
			           "every user (mode %04o): anyone could put a plugin there; "
			           "chmod o-w '%s', or take it out of %s", dir, var,
			           (unsigned)(st.st_mode & 07777), dir, var);
			return RF_EPLUGIN;
		}
	}
	return 0;
}

int
rf_plugin_path_check(char *err, size_t errlen, char *warning, size_t warnlen)
{
	const char *sys = getenv("REFLECT_PLUGIN_SYSTEM_PATH");
	int rc;

	if (warning && warnlen)
		*warning = '\0';
	if ((rc = check_list(getenv("REFLECT_PLUGIN_PATH"), "REFLECT_PLUGIN_PATH", err, errlen,
	                     warning, warnlen)) < 0)
		return rc;
	return check_list(sys ? sys : installed_plugindir(),
	                  sys ? "REFLECT_PLUGIN_SYSTEM_PATH" : "the installed plugin directory",
	                  err, errlen, warning, warnlen);
}

static int
mode_name_valid(const char *s)
{
	if (!*s || *s == '.' || strlen(s) > 200)
		return 0;
	for (; *s; s++)
		if (!isalnum((unsigned char)*s) && *s != '_' && *s != '-' && *s != '.')
			return 0;
	return 1;
}

int
rf_module_load(rf_module **mp, const char *name, unsigned kind, char *err,
               size_t errlen)
{
	char path[4096], why[512], not_plugin[1024] = "";
	const char *dirs, *p;
	struct stat st;
	size_t n;

	*mp = NULL;
	if (strchr(name, '/'))
		return rf_module_load_file(mp, name, kind, err, errlen);
	if (!mode_name_valid(name)) {
		rf__format(err, errlen, "'%.80s' is not a valid mode name (letters, "
		           "digits, '_', '-' and '.'; a path needs a '/')", name);
		return RF_EINVAL;
	}
	if (rf_plugin_path_check(err, errlen, NULL, 0) < 0)
		return RF_EPLUGIN;
	dirs = rf_plugin_search_path();
	for (p = dirs; *p; p += n + (p[n] == ':')) {
		int k;

		n = strcspn(p, ":");
		if (!n)
			continue;
		/* KIND-NAME.so first: a name another kind has too */
		for (k = kind && rf_plugin_kind_name(kind) ? 0 : 1; k < 2; k++) {
			if (k == 0)
				rf__format(path, sizeof(path), "%.*s/%s-%s.so", (int)n, p,
				           rf_plugin_kind_name(kind), name);
			else
				rf__format(path, sizeof(path), "%.*s/%s.so", (int)n, p, name);
			if (stat(path, &st) < 0 || !S_ISREG(st.st_mode))
				continue;
			/* A library that is no plugin is passed over, as -l passes
			 * it; the first is named should no plugin follow. */
			if (rf__elf_check(path, why, sizeof(why)) == RF__ELF_NOT_PLUGIN) {
				if (!*not_plugin)
					rf__format(not_plugin, sizeof(not_plugin), "plugin '%s': %s",
					           path, why);
				continue;
			}
			return rf_module_load_file(mp, path, kind, err, errlen);
		}
	}
	if (*not_plugin) {
		rf__format(err, errlen, "%s", not_plugin);
		return RF_EPLUGIN;
	}
	n = strlen(name);
	rf__format(err, errlen, "unknown %s mode '%s': no %s.so in %s%s%s%s%s (-l "
	           "lists the modes)", kind ? rf_plugin_kind_name(kind) : "plugin",
	           name, name, *dirs ? "'" : "", *dirs ? dirs : "an empty search path",
	           *dirs ? "'" : "",
	           n > 3 && !strcmp(name + n - 3, ".so")
	           ? "; a path to a file needs a '/', as in ./" : "",
	           n > 3 && !strcmp(name + n - 3, ".so") ? name : "");
	return RF_ENOTFOUND;
}

static int
cmp_str(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

int
rf_plugin_scan(rf_plugin_visit_fn fn, void *arg)
{
	char *dirs, *dir, *save = NULL, **seen = NULL, **files = NULL, why[1024];
	size_t nseen = 0, nfiles = 0, ndirs = 0, i, j;
	struct stat dirst[64];
	int rc = 0;

	if (rf_plugin_path_check(why, sizeof(why), NULL, 0) < 0)
		return RF_EPLUGIN;
	if (!(dirs = strdup(rf_plugin_search_path())))
		return RF_ENOMEM;
	for (dir = strtok_r(dirs, ":", &save); dir; dir = strtok_r(NULL, ":", &save)) {
		struct dirent *e;
		struct stat ds;
		DIR *d;

		/* A directory named twice (or through a link) is scanned once:
		 * its files would otherwise shadow themselves. */
		if (stat(dir, &ds) < 0 || !S_ISDIR(ds.st_mode))
			continue;
		for (i = 0; i < ndirs; i++)
			if (dirst[i].st_dev == ds.st_dev && dirst[i].st_ino == ds.st_ino)
				break;
		if (i < ndirs)
			continue;
		if (ndirs < sizeof(dirst) / sizeof(dirst[0]))
			dirst[ndirs++] = ds;
		if (!(d = opendir(dir)))
			continue;
		nfiles = 0;
		while ((e = readdir(d))) {
			size_t len = strlen(e->d_name);
			char **grown;

			if (len <= 3 || strcmp(e->d_name + len - 3, ".so"))
				continue;
			if (!(grown = realloc(files, (nfiles + 1) * sizeof(*files))) ||
			    !(grown[nfiles] = strdup(e->d_name))) {
				files = grown ? grown : files;
				closedir(d);
				rc = RF_ENOMEM;
				goto out;
			}
			files = grown;
			nfiles++;
		}
		closedir(d);
		qsort(files, nfiles, sizeof(*files), cmp_str);
		for (i = 0; i < nfiles; i++) {
			char path[4096];
			struct stat st;
			int shadowed = 0;
			char **grown;

			rf__format(path, sizeof(path), "%s/%s", dir, files[i]);
			if (stat(path, &st) < 0 || !S_ISREG(st.st_mode))
				continue;
			/* Only plugins are visited: a library beside them is not
			 * loaded (its constructors would run), and hides nothing. */
			if (rf__elf_check(path, why, sizeof(why)) == RF__ELF_NOT_PLUGIN)
				continue;
			for (j = 0; j < nseen; j++)
				if (!strcmp(seen[j], files[i]))
					shadowed = 1;
			if (!shadowed) {
				if (!(grown = realloc(seen, (nseen + 1) * sizeof(*seen))) ||
				    !(grown[nseen] = strdup(files[i]))) {
					seen = grown ? grown : seen;
					rc = RF_ENOMEM;
					goto out;
				}
				seen = grown;
				nseen++;
			}
			fn(arg, path, shadowed);
		}
		for (i = 0; i < nfiles; i++)
			free(files[i]);
		nfiles = 0;
	}
out:
	for (i = 0; i < nfiles; i++)
		free(files[i]);
	for (i = 0; i < nseen; i++)
		free(seen[i]);
	free(seen);
	free(files);
	free(dirs);
	return rc;
}
