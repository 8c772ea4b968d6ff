/* Loading a plugin file: read as data first (elf.c), then opened, its
 * entry called, and its descriptor's ABI checked before any other
 * field is read (the others in descriptor.c). */
#include <dlfcn.h>
#include <errno.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "plugin/plugin-internal.h"
#include "util/util.h"
#include "reflect/plugin.h"

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
	END_OF(struct rf_plugin, optional_inputs), /* 1.2: the descriptor is 1.1's */
};

/* The three fields every ABI begins a descriptor with: no other field
 * may be read before they are checked, as the size a plugin's ABI gives
 * its descriptor says how much of it there is. */
static int
check_abi(const struct rf_plugin *p, const char *path, char *err, size_t errlen)
{
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
	return 0;
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
	if ((rc = check_abi(m->plugin, path, err, errlen)) < 0 ||
	    (rc = rf__descriptor_check(m->plugin, path, kind, err, errlen)) < 0)
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
