/* The plugin search path (REFLECT_PLUGIN_PATH, then the system's), the
 * check of its directories, and a mode found by name in it or listed
 * from it. */
#include <ctype.h>
#include <dirent.h>
#include <dlfcn.h>
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

/* The user's own plugin directory, $XDG_DATA_HOME/reflect/plugins, or
 * ~/.local/share/reflect/plugins when XDG_DATA_HOME is unset or not
 * absolute (as the XDG base directory rules have it); "" without HOME,
 * or for a directory whose name holds a ':', which no search path can
 * hold. */
static const char *
user_plugindir(void)
{
	static __thread char dir[4096];
	const char *xdg = getenv("XDG_DATA_HOME"), *home = getenv("HOME");

	if (xdg && *xdg == '/')
		snprintf(dir, sizeof(dir), "%s/reflect/plugins", xdg);
	else if (home && *home == '/')
		snprintf(dir, sizeof(dir), "%s/.local/share/reflect/plugins", home);
	else
		*dir = '\0';
	if (strchr(dir, ':'))
		*dir = '\0';
	return dir;
}

/* The user plugin directory when it is one: a directory not made yet
 * is left out of the search path and its messages. */
static const char *
user_plugindir_present(void)
{
	const char *dir = user_plugindir();
	struct stat st;

	return *dir && stat(dir, &st) == 0 && S_ISDIR(st.st_mode) ? dir : "";
}

/* The lists of the search path in order, each with the name of where it
 * comes from (for messages and listings). */
struct dir_list {
	const char *list;
	const char *origin;
};

static size_t
search_lists(struct dir_list lists[3], int all)
{
	const char *sys = getenv("REFLECT_PLUGIN_SYSTEM_PATH");

	lists[0].list = getenv("REFLECT_PLUGIN_PATH");
	lists[0].origin = "REFLECT_PLUGIN_PATH";
	lists[1].list = sys ? sys : installed_plugindir();
	lists[1].origin = sys ? "REFLECT_PLUGIN_SYSTEM_PATH" : "the installed plugin directory";
	lists[2].list = all ? user_plugindir() : user_plugindir_present();
	lists[2].origin = "the user plugin directory";
	return 3;
}

const char *
rf_plugin_search_path(void)
{
	static __thread char buf[16384];
	struct dir_list lists[3];
	size_t i, n = search_lists(lists, 0), used = 0;

	*buf = '\0';
	for (i = 0; i < n; i++) {
		const char *l = lists[i].list;

		if (!l || !*l)
			continue;
		snprintf(buf + used, sizeof(buf) - used, "%s%s", used ? ":" : "", l);
		used = strlen(buf);
	}
	return buf;
}

int
rf_plugin_search_dir(size_t i, const char **dir, const char **origin)
{
	static __thread char buf[4096];
	struct dir_list lists[3];
	size_t k, n = search_lists(lists, 1), len;
	const char *p;

	for (k = 0; k < n; k++)
		for (p = lists[k].list; p && *p; p += len + (p[len] == ':')) {
			len = strcspn(p, ":");
			if (!len || i--)
				continue;
			snprintf(buf, sizeof(buf), "%.*s", (int)len, p);
			*dir = buf;
			*origin = lists[k].origin;
			return 1;
		}
	return 0;
}

/* Whether a and b name the same directory: the same text (trailing
 * slashes aside), or the same inode. */
static int
same_dir(const char *a, size_t alen, const char *b)
{
	size_t blen = strlen(b);
	struct stat sa, sb;
	char pa[4096];

	while (alen > 1 && a[alen - 1] == '/')
		alen--;
	while (blen > 1 && b[blen - 1] == '/')
		blen--;
	if (alen == blen && !strncmp(a, b, alen))
		return 1;
	snprintf(pa, sizeof(pa), "%.*s", (int)alen, a);
	return stat(pa, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
	       sa.st_ino == sb.st_ino;
}

const char *
rf_plugin_dir_origin(const char *path)
{
	const char *slash = strrchr(path, '/'), *dir, *origin;
	size_t i;

	if (!slash)
		return NULL;
	for (i = 0; rf_plugin_search_dir(i, &dir, &origin); i++)
		if (same_dir(path, slash == path ? 1 : (size_t)(slash - path), dir))
			return origin;
	return NULL;
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
	if ((rc = check_list(sys ? sys : installed_plugindir(),
	                     sys ? "REFLECT_PLUGIN_SYSTEM_PATH"
	                         : "the installed plugin directory",
	                     err, errlen, warning, warnlen)) < 0)
		return rc;
	return check_list(user_plugindir(), "the user plugin directory", err, errlen, NULL, 0);
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

/*
 * The mode of that name of another kind (reflect-filter -m none finds
 * shade-none.so): loaded for its refusal, which names the tool that
 * takes it, as a NAME.so of another kind found first is.  1 when there
 * is none; when a file so named turns out to be of the kind wanted (a
 * plain plugin named KIND-NAME), it is not what -m asked for either.
 */
static int
other_kind(rf_module **mp, const char *dirs, const char *name, unsigned kind, char *err,
           size_t errlen)
{
	char path[4096], why[512];
	const char *p, *kn;
	struct stat st;
	unsigned k;
	size_t n;
	int rc;

	for (p = dirs; *p; p += n + (p[n] == ':')) {
		n = strcspn(p, ":");
		for (k = 1; n && (kn = rf_plugin_kind_name(k)); k++) {
			if (k == kind)
				continue;
			rf__format(path, sizeof(path), "%.*s/%s-%s.so", (int)n, p, kn, name);
			if (stat(path, &st) < 0 || !S_ISREG(st.st_mode) ||
			    rf__elf_check(path, why, sizeof(why)) == RF__ELF_NOT_PLUGIN)
				continue;
			if ((rc = rf_module_load_file(mp, path, kind, err, errlen)) < 0)
				return rc;
			rf_module_unload(*mp);
			*mp = NULL;
		}
	}
	return 1;
}

static unsigned file_mode(const char *file, const char **rest);

/*
 * A mode of the kind (any kind for 0) in the search path whose name is
 * closest to a misspelt one, into near (empty when none is close): the
 * names are read from the files' names, nothing is loaded.
 */
static void
closest_mode(const char *dirs, const char *name, unsigned kind, char *near, size_t len)
{
	const char *names[512], *p, *rest;
	char *store[512];
	size_t n, count = 0, i;
	int best;

	*near = '\0';
	for (p = dirs; *p && count < 512; p += n + (p[n] == ':')) {
		char dir[4096];
		struct dirent *e;
		DIR *d;

		n = strcspn(p, ":");
		if (!n)
			continue;
		snprintf(dir, sizeof(dir), "%.*s", (int)n, p);
		if (!(d = opendir(dir)))
			continue;
		while ((e = readdir(d)) && count < 512) {
			size_t l = strlen(e->d_name);
			unsigned k;

			if (l <= 3 || strcmp(e->d_name + l - 3, ".so"))
				continue;
			k = file_mode(e->d_name, &rest);
			if (k && kind && k != kind)
				continue;
			if (!(store[count] = strndup(rest, strlen(rest) - 3)))
				break;
			names[count] = store[count];
			count++;
		}
		closedir(d);
	}
	if ((best = rf__closest(name, names, count)) >= 0)
		snprintf(near, len, "%s", names[best]);
	for (i = 0; i < count; i++)
		free(store[i]);
}

int
rf_module_load(rf_module **mp, const char *name, unsigned kind, char *err,
               size_t errlen)
{
	char near[256];
	char path[4096], why[512], not_plugin[1024] = "";
	const char *dirs, *p, *kn;
	struct stat st;
	size_t n;
	int rc;

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
		/* KIND-NAME.so first, as the modes reflect installs are named
		 * (two kinds have a mode named box); then NAME.so, a name a
		 * plugin may have too */
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
	if (kind && (rc = other_kind(mp, dirs, name, kind, err, errlen)) < 0)
		return rc;
	if (*not_plugin) {
		rf__format(err, errlen, "%s", not_plugin);
		return RF_EPLUGIN;
	}
	n = strlen(name);
	kn = kind ? rf_plugin_kind_name(kind) : NULL;
	closest_mode(dirs, name, kind, near, sizeof(near));
	rf__format(err, errlen, "unknown %s mode '%s': no %s%s%s%s%s.so in %s%s%s%s%s%s%s%s "
	           "(-l lists the modes)", kn ? kn : "plugin", name, kn ? kn : "",
	           kn ? "-" : "", kn ? name : "", kn ? ".so or " : "", name,
	           *dirs ? "'" : "", *dirs ? dirs : "an empty search path", *dirs ? "'" : "",
	           n > 3 && !strcmp(name + n - 3, ".so")
	           ? "; a path to a file needs a '/', as in ./" : "",
	           n > 3 && !strcmp(name + n - 3, ".so") ? name : "",
	           *near ? "; did you mean '" : "", near, *near ? "'?" : "");
	return RF_ENOTFOUND;
}

/*
 * A file name as the search answers to it: KIND-NAME.so holds the mode
 * NAME of that kind (a kind as rf_plugin_kind_name spells it), a plain
 * NAME.so a mode of any kind.  Returns the kind, 0 for a plain name, and
 * in *rest the name from the mode's on, ".so" included.
 */
static unsigned
file_mode(const char *file, const char **rest)
{
	const char *kn;
	unsigned k;
	size_t n;

	for (k = 1; (kn = rf_plugin_kind_name(k)); k++) {
		n = strlen(kn);
		if (!strncmp(file, kn, n) && file[n] == '-' && strcmp(file + n + 1, ".so")) {
			*rest = file + n + 1;
			return k;
		}
	}
	*rest = file;
	return 0;
}

/* The order rf_module_load tries a directory's files in: a mode's
 * KIND-NAME.so before its NAME.so, the modes by name. */
static int
cmp_file(const void *a, const void *b)
{
	const char *fa = *(char *const *)a, *fb = *(char *const *)b, *ra, *rb;
	unsigned ka = file_mode(fa, &ra), kb = file_mode(fb, &rb);
	int c = strcmp(ra, rb);

	if (c)
		return c;
	if (!ka != !kb)
		return ka ? -1 : 1;
	return strcmp(fa, fb);
}

/*
 * Whether rf_module_load would stop at an earlier file (seen) before it
 * reaches this one: a plain NAME.so stops the search for NAME of every
 * kind, KIND-NAME.so that of its kind, which for a plain file is known
 * only once it is loaded: that is done only for such a file that a
 * KIND-NAME.so came before.
 */
static int
is_shadowed(char *const *seen, size_t nseen, const char *file, const char *path)
{
	const char *rest, *seen_rest;
	unsigned kind = file_mode(file, &rest), plain_kind = 0, k;
	int loaded = 0;
	size_t i;

	for (i = 0; i < nseen; i++) {
		k = file_mode(seen[i], &seen_rest);
		if (strcmp(rest, seen_rest))
			continue;
		if (!k || k == kind)
			return 1;
		if (!kind && !loaded) {
			char why[1024];
			rf_module *m;

			loaded = 1;
			if (rf_module_load_file(&m, path, 0, why, sizeof(why)) == 0) {
				plain_kind = rf_module_plugin(m)->kind;
				rf_module_unload(m);
			}
		}
		if (!kind && k == plain_kind)
			return 1;
	}
	return 0;
}

int
rf_plugin_scan(rf_plugin_visit_fn fn, void *arg)
{
	char *dirs, *dir, *save = NULL, **seen = NULL, **files = NULL, why[1024];
	size_t nseen = 0, nfiles = 0, ndirs = 0, i;
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
		qsort(files, nfiles, sizeof(*files), cmp_file);
		for (i = 0; i < nfiles; i++) {
			char path[4096];
			struct stat st;
			int shadowed;
			char **grown;

			rf__format(path, sizeof(path), "%s/%s", dir, files[i]);
			if (stat(path, &st) < 0 || !S_ISREG(st.st_mode))
				continue;
			/* Only plugins are visited: a library beside them is not
			 * loaded (its constructors would run), and hides nothing. */
			if (rf__elf_check(path, why, sizeof(why)) == RF__ELF_NOT_PLUGIN)
				continue;
			shadowed = is_shadowed(seen, nseen, files[i], path);
			/* a shadowed file is remembered too: a plain NAME.so that
			 * its kind's KIND-NAME.so hides still ends the search of
			 * every other kind for NAME */
			if (!(grown = realloc(seen, (nseen + 1) * sizeof(*seen))) ||
			    !(grown[nseen] = strdup(files[i]))) {
				seen = grown ? grown : seen;
				rc = RF_ENOMEM;
				goto out;
			}
			seen = grown;
			nseen++;
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

#ifndef REFLECT_MANDIR
#define REFLECT_MANDIR "/usr/local/share/man"
#endif

/* page, when it is a regular file, into buf: 0, else RF_ENOTFOUND. */
static int
page_at(char *buf, size_t len, const char *dir, size_t dirlen, const char *sub,
        const char *kn, const char *name)
{
	struct stat st;
	char *real;

	if (kn) {
		snprintf(buf, len, "%.*s%s/reflect-mode-%s-%s.7", (int)dirlen, dir, sub, kn,
		         name);
		if (stat(buf, &st) == 0 && S_ISREG(st.st_mode))
			goto found;
	}
	snprintf(buf, len, "%.*s%s/reflect-mode-%s.7", (int)dirlen, dir, sub, name);
	if (stat(buf, &st) < 0 || !S_ISREG(st.st_mode))
		return RF_ENOTFOUND;
found:
	/* lib/../share/man, as a moved tree finds it, said plainly */
	if (strstr(buf, "/../") && (real = realpath(buf, NULL))) {
		snprintf(buf, len, "%s", real);
		free(real);
	}
	return 0;
}

int
rf_plugin_man_page(const char *path, const struct rf_plugin *p, char *buf, size_t len)
{
	const char *slash = strrchr(path, '/'), *kn = rf_plugin_kind_name(p->kind);
	size_t dirlen = slash ? (size_t)(slash - path) : 1;
	Dl_info info;

	if (!slash)
		path = ".";
	/* beside the plugin, as a third party installs it */
	if (page_at(buf, len, path, dirlen, "", kn, p->name) == 0)
		return 0;
	/* the modes of the installed plugin directory: the installation's
	 * manual, beside the library when the tree was moved, else where
	 * it was built for */
	if (!same_dir(path, dirlen, installed_plugindir()))
		return RF_ENOTFOUND;
	if (*REFLECT_PLUGINDIR_REL && dladdr((void *)rf_plugin_search_path, &info) &&
	    info.dli_fname && (slash = strrchr(info.dli_fname, '/')) &&
	    page_at(buf, len, info.dli_fname, (size_t)(slash - info.dli_fname),
	            "/../share/man/man7", kn, p->name) == 0)
		return 0;
	return page_at(buf, len, REFLECT_MANDIR, strlen(REFLECT_MANDIR), "/man7", kn,
	               p->name);
}
