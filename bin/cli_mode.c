/* -l and -m: listing and selecting the modes (plugins) of a tool. */
#include <math.h>
#include <string.h>

#include "cli.h"

struct listing {
	unsigned kind;
	int count;
};

static void
print_param(const struct rf_param *q)
{
	char range[96];

	if (q->flags & RF_PARAM_CHOICE) {
		const char *c = q->choices;
		int i;

		for (i = 0; i < (int)q->def && strchr(c, '|'); i++)
			c = strchr(c, '|') + 1;
		printf("    %s=%.*s\t%s (%s)\n", q->name, (int)strcspn(c, "|"), c,
		       q->help, q->choices);
		return;
	}
	if (q->flags & RF_PARAM_BOOL)
		snprintf(range, sizeof(range), "0 or 1");
	else
		snprintf(range, sizeof(range), "%s%s%g, %g%s",
		         q->flags & RF_PARAM_INTEGER ? "integer " : "",
		         isinf(q->min) ? "(" : "[", q->min, q->max,
		         isinf(q->max) ? ")" : "]");
	printf("    %s=%g\t%s (%s)\n", q->name, q->def, q->help, range);
}

static void
print_channels(const char *what, const char *const *list)
{
	size_t i;

	printf("  %s:", what);
	for (i = 0; list[i]; i++)
		printf(" %s", list[i]);
	printf("%s\n", list[0] ? "" : " (none)");
}

static void
list_one(void *arg, const char *path, int shadowed)
{
	struct listing *l = arg;
	char err[1024];
	rf_module *m;
	const struct rf_plugin *p;
	uint32_t i;

	if (rf_module_load_file(&m, path, 0, err, sizeof(err)) < 0) {
		warn("ignoring %s", err);
		return;
	}
	p = rf_module_plugin(m);
	if (p->kind != l->kind) {
		rf_module_unload(m);
		return;
	}
	if (shadowed) {
		printf("# %s: shadowed by an earlier '%s' in the search path\n", path,
		       p->name);
		rf_module_unload(m);
		return;
	}
	l->count++;
	printf("%s\t%s\n", p->name, p->summary);
	printf("  file: %s (version %s, plugin ABI %u.%u, %s, %s)\n", path,
	       p->version, p->abi_major, p->abi_minor, p->author, p->license);
	print_channels("reads", p->inputs);
	print_channels("writes", p->outputs);
	if (p->nparams) {
		printf("  parameters:\n");
		for (i = 0; i < p->nparams; i++)
			print_param(&p->params[i]);
	}
	rf_module_unload(m);
}

void
mode_list(unsigned kind)
{
	struct listing l = { kind, 0 };
	int rc = rf_plugin_scan(list_one, &l);

	if (rc < 0)
		die_status(rc, NULL);
	if (!l.count)
		warn("no %s modes in '%s'", rf_plugin_kind_name(kind),
		     rf_plugin_search_path());
	fshut(stdout, "<stdout>");
	exit(l.count ? 0 : EXIT_BAD_INPUT);
}

void
mode_load(struct cli_mode *m, unsigned kind, const char *spec, int verbose)
{
	char err[1024], *name = estrdup(spec);
	const char *params = "";
	char *colon;
	int rc;

	/* A path may hold ':' only before its last '/'. */
	colon = strchr(strrchr(name, '/') ? strrchr(name, '/') : name, ':');
	if (colon) {
		*colon = '\0';
		params = colon + 1;
	}
	if ((rc = rf_module_load(&m->module, name, kind, err, sizeof(err))) < 0)
		die_status(rc == RF_ENOMEM ? rc : RF_EPLUGIN, err);
	m->plugin = rf_module_plugin(m->module);
	m->values = ecalloc(m->plugin->nparams + 1, sizeof(double));
	if (rf_plugin_parse_params(m->plugin, params, m->values, err, sizeof(err)) < 0)
		die("%s", err);
	if (verbose)
		fprintf(stderr, "%s: mode '%s' from '%s'\n", argv0, m->plugin->name,
		        rf_module_path(m->module));
	free(name);
}

void
mode_unload(struct cli_mode *m)
{
	free(m->values);
	rf_module_unload(m->module);
	m->module = NULL;
}
