/* -l and -m: listing and selecting the modes (plugins) of a tool. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

struct listing {
	unsigned kind;
	int count;
	char **first; /* the files no earlier one shadows, in search order */
	size_t nfirst;
};

static const char *
base_name(const char *path)
{
	const char *slash = strrchr(path, '/');

	return slash ? slash + 1 : path;
}

/* The stream once plugin code may run: its own descriptor. */
static FILE *stream_out;

FILE *
cli_stdout(void)
{
	return stream_out ? stream_out : stdout;
}

/*
 * A plugin that prints (a printf left in while debugging, a library that
 * logs) would write into the stream, and the next tool would read its
 * text as pixels, or refuse the stream, after this one exited 0.  So the
 * stream keeps standard output's descriptor under another number, and
 * fd 1 leads to standard error for whatever else writes to it, plugin
 * code and its constructors alike.  A closed fd 1 is left closed.
 */
void
cli_keep_stdout(void)
{
	int fd;

	if (stream_out)
		return;
	fflush(stdout);
	if ((fd = fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3)) < 0) {
		if (errno == EBADF)
			return;
		die_sys("cannot keep standard output from the plugins:");
	}
	if (!(stream_out = fdopen(fd, "wb")))
		die_sys("cannot keep standard output from the plugins:");
	if (dup2(STDERR_FILENO, STDOUT_FILENO) < 0) {
		/* no standard error: what plugins print goes nowhere */
		int null = open("/dev/null", O_WRONLY | O_CLOEXEC);

		if (null < 0 || dup2(null, STDOUT_FILENO) < 0)
			die_sys("cannot keep standard output from the plugins:");
		close(null);
	}
}

static void
remember(struct listing *l, const char *path)
{
	l->first = realloc(l->first, (l->nfirst + 1) * sizeof(*l->first));
	if (!l->first)
		die_sys("out of memory");
	l->first[l->nfirst++] = estrdup(path);
}

/* Whether a file name is one -m tries for the mode: KIND-NAME.so or
 * NAME.so. */
static int
names_mode(const char *file, const struct rf_plugin *p)
{
	const char *kind = rf_plugin_kind_name(p->kind);
	size_t n = strlen(kind);

	if (!strncmp(file, kind, n) && file[n] == '-')
		file += n + 1;
	n = strlen(p->name);
	return !strncmp(file, p->name, n) && !strcmp(file + n, ".so");
}

/* The earlier file that -m finds for the mode before this one. */
static const char *
winner(const struct listing *l, const struct rf_plugin *p)
{
	size_t i;

	for (i = 0; i < l->nfirst; i++)
		if (names_mode(base_name(l->first[i]), p))
			return l->first[i];
	return NULL;
}

/* The name of choice number `value` of a RF_PARAM_CHOICE parameter. */
static void
print_choice(FILE *fp, const struct rf_param *q, double value)
{
	const char *c = q->choices;
	int i;

	for (i = 0; i < (int)value && strchr(c, '|'); i++)
		c = strchr(c, '|') + 1;
	fprintf(fp, "%.*s", (int)strcspn(c, "|"), c);
}

static void
print_param(const struct rf_param *q)
{
	char range[96];

	if (q->flags & RF_PARAM_STRING) {
		fprintf(cli_stdout(), "    %s=%s\t%s (a string)\n", q->name, q->choices ? q->choices : "",
		        q->help);
		return;
	}
	if (q->flags & RF_PARAM_CHOICE) {
		fprintf(cli_stdout(), "    %s=", q->name);
		print_choice(cli_stdout(), q, q->def);
		fprintf(cli_stdout(), "\t%s (%s)\n", q->help, q->choices);
		return;
	}
	if (q->flags & RF_PARAM_BOOL)
		snprintf(range, sizeof(range), "0 or 1");
	else
		snprintf(range, sizeof(range), "%s%s%g, %g%s",
		         q->flags & RF_PARAM_INTEGER ? "integer " : "",
		         isinf(q->min) ? "(" : "[", q->min, q->max,
		         isinf(q->max) ? ")" : "]");
	fprintf(cli_stdout(), "    %s=%g\t%s (%s)\n", q->name, q->def, q->help, range);
}

static void
print_channels(const char *what, const char *const *list)
{
	size_t i;

	fprintf(cli_stdout(), "  %s:", what);
	for (i = 0; list[i]; i++)
		fprintf(cli_stdout(), " %s", list[i]);
	fprintf(cli_stdout(), "%s\n", list[0] ? "" : " (none)");
}

/* A mode as -l and -m MODE --help show it: what it is, where it was
 * found, what it reads and writes, its parameters and its man page. */
static void
print_mode(const char *path, const struct rf_plugin *p)
{
	const char *const *optional = rf_plugin_optional_inputs(p);
	const char *origin = rf_plugin_dir_origin(path);
	char page[4096];
	uint32_t i;

	fprintf(cli_stdout(), "%s\t%s\n", p->name, p->summary);
	fprintf(cli_stdout(), "  file: %s (version %s, plugin ABI %u.%u, %s, %s)\n", path,
	        p->version, p->abi_major, p->abi_minor, p->author, p->license);
	fprintf(cli_stdout(), "  found in: %s\n", origin ? origin : "a path given to -m");
	if (p->kind == RF_KIND_FILTER) {
		/* it filters values of any channel, guided by its inputs */
		print_channels("guided by", p->inputs);
	} else if (p->kind == RF_KIND_ACCUMULATE) {
		/* it combines values of any channel; its outputs are its state */
		print_channels("state of each value", p->outputs);
	} else {
		print_channels("reads", p->inputs);
	}
	if (optional && optional[0])
		print_channels("reads when present", optional);
	if (p->kind != RF_KIND_FILTER && p->kind != RF_KIND_ACCUMULATE)
		print_channels("writes", p->outputs);
	if (p->nparams) {
		fprintf(cli_stdout(), "  parameters:\n");
		for (i = 0; i < p->nparams; i++)
			print_param(&p->params[i]);
	}
	if (rf_plugin_man_page(path, p, page, sizeof(page)) == 0)
		fprintf(cli_stdout(), "  man page: %s\n", page);
	else
		fprintf(cli_stdout(), "  man page: none beside the file (reflect-plugin(7) says where "
		        "one goes)\n");
}

/* A file the scan found, loaded: NULL, with a warning, when it cannot
 * be.  The first file of each name is remembered, to name what shadows
 * the later ones. */
static const struct rf_plugin *
load_listed(struct listing *l, const char *path, int shadowed, rf_module **m)
{
	char err[1024];

	if (!shadowed)
		remember(l, path);
	if (rf_module_load_file(m, path, 0, err, sizeof(err)) < 0) {
		warn("ignoring %s", err);
		return NULL;
	}
	return rf_module_plugin(*m);
}

static void
say_shadowed(const struct listing *l, const struct rf_plugin *p, const char *path)
{
	const char *first = winner(l, p);

	fprintf(cli_stdout(), "# %s: shadowed by %s, earlier in the search path\n", path,
	        first ? first : "an earlier file");
}

static void
list_one(void *arg, const char *path, int shadowed)
{
	struct listing *l = arg;
	const struct rf_plugin *p;
	rf_module *m;

	if (!(p = load_listed(l, path, shadowed, &m)))
		return;
	if (p->kind == l->kind && shadowed) {
		say_shadowed(l, p, path);
	} else if (p->kind == l->kind) {
		l->count++;
		print_mode(path, p);
	}
	rf_module_unload(m);
}

/* The search path's directories checked: death for one anyone may write
 * to, a warning for a relative one. */
static void
check_search_path(void)
{
	char err[1024], warning[1024];

	if (rf_plugin_path_check(err, sizeof(err), warning, sizeof(warning)) < 0)
		die("%s", err);
	if (*warning)
		warn("%s", warning);
}

void
mode_list(unsigned kind)
{
	struct listing l = { kind, 0, NULL, 0 };
	const char *dirs;
	size_t i;
	int rc;

	/* what a plugin's code prints while it is listed stays out */
	cli_keep_stdout();
	check_search_path();
	rc = rf_plugin_scan(list_one, &l);

	if (rc < 0)
		die_status(rc, NULL);
	for (i = 0; i < l.nfirst; i++)
		free(l.first[i]);
	free(l.first);
	dirs = rf_plugin_search_path();
	if (!l.count)
		warn("no %s modes in %s%s%s", rf_plugin_kind_name(kind),
		     *dirs ? "'" : "", *dirs ? dirs : "an empty search path",
		     *dirs ? "'" : "");
	fshut(cli_stdout(), "<stdout>");
	exit(l.count ? 0 : EXIT_BAD_INPUT);
}

/* reflect-info --plugins: every mode of every kind, by kind, and where
 * each was found. */
static void
all_one(void *arg, const char *path, int shadowed)
{
	struct listing *l = arg;
	const struct rf_plugin *p;
	const char *origin;
	rf_module *m;

	if (!(p = load_listed(l, path, shadowed, &m)))
		return;
	if (shadowed) {
		say_shadowed(l, p, path);
	} else {
		origin = rf_plugin_dir_origin(path);
		l->count++;
		fprintf(cli_stdout(), "%s\t%s\t%s\t%s\n", rf_plugin_kind_name(p->kind), p->name,
		        path, origin ? origin : "");
	}
	rf_module_unload(m);
}

void
mode_list_all(void)
{
	struct listing l = { 0, 0, NULL, 0 };
	const char *dir, *origin;
	struct stat st;
	size_t i;
	int rc;

	cli_keep_stdout();
	check_search_path();
	fprintf(cli_stdout(), "search path, in order (a mode's first file wins):\n");
	for (i = 0; rf_plugin_search_dir(i, &dir, &origin); i++)
		fprintf(cli_stdout(), "  %s\t%s%s\n", dir, origin,
		        stat(dir, &st) == 0 && S_ISDIR(st.st_mode) ? "" : " (not there)");
	if (!i)
		fprintf(cli_stdout(), "  (empty)\n");
	fprintf(cli_stdout(), "modes (kind, name, file, where it was found):\n");
	if ((rc = rf_plugin_scan(all_one, &l)) < 0)
		die_status(rc, NULL);
	for (i = 0; i < l.nfirst; i++)
		free(l.first[i]);
	free(l.first);
	fshut(cli_stdout(), "<stdout>");
	exit(0);
}

/* The names of the modes of a kind that -m reaches, for the help. */
struct names {
	unsigned kind;
	char **name;
	size_t n;
};

static void
name_one(void *arg, const char *path, int shadowed)
{
	struct names *l = arg;
	char err[1024];
	rf_module *m;

	if (shadowed || rf_module_load_file(&m, path, 0, err, sizeof(err)) < 0)
		return;
	if (rf_module_plugin(m)->kind == l->kind) {
		l->name = realloc(l->name, (l->n + 1) * sizeof(*l->name));
		if (!l->name)
			die_sys("out of memory");
		l->name[l->n++] = estrdup(rf_module_plugin(m)->name);
	}
	rf_module_unload(m);
}

static int
cmp_name(const void *a, const void *b)
{
	return strcmp(*(char *const *)a, *(char *const *)b);
}

void
mode_help_line(unsigned kind, const char *def)
{
	struct names l = { kind, NULL, 0 };
	size_t i, col;

	cli_keep_stdout();
	/* what is installed, not a list written once: a plugin added is
	 * named, one taken away is not */
	rf_plugin_scan(name_one, &l);
	if (l.n)
		qsort(l.name, l.n, sizeof(*l.name), cmp_name);
	fprintf(cli_stdout(), "  -m MODE[:K=V...]  the %s mode, default %s; -m MODE --help tells\n"
	        "      one, -l lists them all. Modes:", rf_plugin_kind_name(kind), def);
	col = 36;
	for (i = 0; i < l.n; i++) {
		size_t w = strlen(l.name[i]) + (i + 1 < l.n ? 1 : 0);

		if (col + 1 + w > 78) {
			fprintf(cli_stdout(), "\n     ");
			col = 5;
		}
		fprintf(cli_stdout(), " %s%s", l.name[i], i + 1 < l.n ? "," : "");
		col += 1 + w;
		free(l.name[i]);
	}
	fprintf(cli_stdout(), "%s\n", l.n ? "" : " none found (-l says where they are looked for)");
	free(l.name);
}

void
mode_help(unsigned kind, const char *spec)
{
	char err[1024], *name = estrdup(spec), *colon;
	rf_module *m;
	int rc;

	/* the parameters given do not matter to the help (a path may hold
	 * ':' only before its last '/') */
	colon = strchr(strrchr(name, '/') ? strrchr(name, '/') : name, ':');
	if (colon)
		*colon = '\0';
	cli_keep_stdout();
	if (!strchr(name, '/'))
		check_search_path();
	if ((rc = rf_module_load(&m, name, kind, err, sizeof(err))) < 0) {
		free(name);
		die_status(rc == RF_ENOMEM ? rc : RF_EPLUGIN, err);
	}
	fprintf(cli_stdout(), "usage: %s -m %s[:KEY=VALUE...] [options] [file]\n", argv0,
	       rf_module_plugin(m)->name);
	print_mode(rf_module_path(m), rf_module_plugin(m));
	fprintf(cli_stdout(), "(%s --help: the tool's options)\n", argv0);
	rf_module_unload(m);
	free(name);
	fshut(cli_stdout(), "<stdout>");
	exit(0);
}

void
mode_load(struct cli_mode *m, unsigned kind, const char *spec, int verbose)
{
	char err[1024], *name = estrdup(spec);
	const char *params = "";
	char *colon;
	int rc;

	cli_keep_stdout();
	cli_guard_plugins();
	if (!strchr(spec, '/'))
		check_search_path();

	/* A path may hold ':' only before its last '/'. */
	colon = strchr(strrchr(name, '/') ? strrchr(name, '/') : name, ':');
	if (colon) {
		*colon = '\0';
		params = colon + 1;
		if (!*params) {
			cli_message_start();
			fputs("mode ", stderr);
			cli_put_quoted(stderr, name);
			fputs(": a ':' with no parameter after it; write -m MODE or "
			      "-m MODE:KEY=VALUE\n", stderr);
			free(name);
			exit(EXIT_BAD_INPUT);
		}
	}
	/* The messages are made before name (params lies in it) is freed. */
	if ((rc = rf_module_load(&m->module, name, kind, err, sizeof(err))) < 0) {
		free(name);
		die_status(rc == RF_ENOMEM ? rc : RF_EPLUGIN, err);
	}
	m->plugin = rf_module_plugin(m->module);
	m->verbose = verbose;
	m->told = NULL;
	m->values = ecalloc(m->plugin->nparams + 1, sizeof(double));
	if (rf_plugin_parse_params(m->plugin, params, m->values, err, sizeof(err)) < 0) {
		free(name);
		mode_unload(m);
		die("%s", err);
	}
	if (verbose) {
		const struct rf_plugin *p = m->plugin;
		uint32_t i;

		cli_message_start();
		fprintf(stderr, "mode '%s' from ", p->name);
		cli_put_quoted(stderr, rf_module_path(m->module));
		for (i = 0; i < p->nparams; i++) {
			const struct rf_param *q = &p->params[i];

			fprintf(stderr, "%s%s=", i ? " " : " (", q->name);
			if (q->flags & RF_PARAM_STRING)
				cli_put_quoted(stderr, rf_plugin_param_string(q, m->values[i]));
			else if (q->flags & RF_PARAM_CHOICE)
				print_choice(stderr, q, m->values[i]);
			else
				fprintf(stderr, "%.9g", m->values[i]);
		}
		fprintf(stderr, "%s\n", p->nparams ? ")" : "");
	}
	free(name);
}

void
mode_note_absent(struct cli_mode *m, struct cli_io *io, const rf_header *in)
{
	const char *const *opt = rf_plugin_optional_inputs(m->plugin);
	size_t i, n = 0;

	if (!m->verbose || !opt)
		return;
	for (i = 0; opt[i]; i++)
		;
	if (!m->told)
		m->told = ecalloc(i + 1, 1);
	for (i = 0; opt[i]; i++) {
		if (m->told[i] || rf_header_find_channel(in, opt[i]) >= 0)
			continue;
		m->told[i] = 1;
		if (!n++) {
			cli_message_start();
			fprintf(stderr, "'%s': frame %zu: mode '%s' reads as NaN its optional "
			        "input", io->input_name, io->frames, m->plugin->name);
		}
		fprintf(stderr, " '%s'", opt[i]);
	}
	if (n)
		fprintf(stderr, ", which the stream lacks\n");
}

void
mode_unload(struct cli_mode *m)
{
	free(m->told);
	m->told = NULL;
	free(m->values);
	rf_module_unload(m->module);
	m->module = NULL;
}

void
mode_invalid_note(struct cli_io *io, size_t count)
{
	if (count)
		warn("'%s': frame %zu: %zu pixel%s where the mode broke its output contract %s",
		     io->input_name, io->frames, count, count == 1 ? "" : "s",
		     io->invalid == RF_INVALID_CLAMP ? "clamped (or zeroed)" : "zeroed");
}
