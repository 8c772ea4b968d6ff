/*
 * Which plugin code a thread is running, for a tool's crash handler: a
 * mode that faults takes the process with it, and all the handler can
 * still do is say which mode, from which file, on which frame and row.
 * The record is the thread's own (run() runs on every pool thread at
 * once), set in plain stores before the call and cleared after, so a
 * handler on the faulting thread reads what that thread was running.
 */
#include <dlfcn.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "plugin/plugin-internal.h"
#include "reflect/plugin.h"

static __thread struct rf_plugin_call current;
static __thread volatile sig_atomic_t running;

void
rf__call_site_init(struct rf__call_site *site, const struct rf_plugin *p)
{
	Dl_info info;

	site->mode = p->name;
	site->file = NULL;
	if (dladdr((const void *)p, &info) && info.dli_fname && *info.dli_fname)
		site->file = strdup(info.dli_fname);
}

void
rf__call_site_fini(struct rf__call_site *site)
{
	free(site->file);
	site->file = NULL;
}

void
rf__call_enter(const struct rf__call_site *site, const char *what, size_t frame,
               size_t y, size_t nrows)
{
	running = 0;
	atomic_signal_fence(memory_order_seq_cst);
	current.mode = site ? site->mode : NULL;
	current.file = site ? site->file : NULL;
	current.what = what;
	current.frame = frame;
	current.row_first = y;
	current.nrows = nrows;
	/* a handler on this thread sees the record whole once running is 1 */
	atomic_signal_fence(memory_order_seq_cst);
	running = 1;
}

void
rf__call_enter_file(const char *file)
{
	running = 0;
	atomic_signal_fence(memory_order_seq_cst);
	memset(&current, 0, sizeof(current));
	current.file = file;
	current.what = "load";
	atomic_signal_fence(memory_order_seq_cst);
	running = 1;
}

void
rf__call_leave(void)
{
	running = 0;
}

const struct rf_plugin_call *
rf_plugin_current_call(void)
{
	return running ? &current : NULL;
}
