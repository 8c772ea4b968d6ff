/* Internal to libreflect: a stage as the shading pass drives it. */
#ifndef REFLECT_PLUGIN_INTERNAL_H
#define REFLECT_PLUGIN_INTERNAL_H

#include "util/util.h"

/* A stage's parts for a pass that runs it row by row on its own threads
 * (the shading pass): the frame's row layout once rf_stage_run could run
 * rows y..y+nrows, its thread count, and one row on thread `thread`. */
int rf__stage_ready(const rf_stage *s, size_t y, size_t nrows, size_t *in_ncomp,
                    size_t *out_ncomp);
int rf__stage_threads(const rf_stage *s);
void rf__stage_row(rf_stage *s, const float *in, float *out, size_t y, int thread);
/* For a pass that overwrites the channels names (NULL-terminated) at
 * walls (mask 0) without reading them: when every output of the plugin
 * is one of them, rf__stage_row runs it only on the pixels between
 * walls and writes 0 at walls; else on every pixel. */
void rf__stage_skip_walls(rf_stage *s, const char *const *names);
/* Around a block of rf__stage_row calls: the invalid input they met
 * counted, and RF_EINVAL (rf_stage_error) for the first under ERROR. */
void rf__stage_block_begin(rf_stage *s);
int rf__stage_block_end(rf_stage *s);

/* One instance of a mode for one thread; err says "mode 'name': " and
 * the plugin's message, on one line. */
struct rf_host;
struct rf_plugin;
struct rf__call_site;
int rf__plugin_instance(const struct rf_plugin *p, const struct rf__call_site *site,
                        const struct rf_host *host, const double *values, void **state,
                        char *err, size_t errlen);
/* An instance's destroy(), as a crash report names it. */
void rf__plugin_destroy(const struct rf_plugin *p, const struct rf__call_site *site,
                        void *state);

/* The stream columns a channel-agnostic mode works on: those of list
 * ("a,b"), or by default every spec.* channel and R G B; err says what
 * is missing (verb: what the mode does, for the message). */
int rf__choose_values(const rf_header *in, const char *list, const char *verb, int *cols,
                      size_t *n, char *err, size_t errlen);

/* After a block's threads are joined: 1 and err ("mode 'name': ...")
 * when a run() of the block called the host's fail() (tables of
 * rf_plugin_host only), which it then forgets; else 0. */
int rf__host_take_failure(const struct rf_host *table, const char *mode, char *err,
                          size_t errlen);

/* The passes and band radii a filter mode's create() declared through
 * the host's filter_passes (tables of rf_plugin_host only): their count,
 * 1 with radius 0 when it declared none; and forgetting them. */
struct rf_host;
/* The table plugin p is to get: table itself, or for a plugin built for
 * ABI 1.1 or before a view of it with the probes at that ABI's stride;
 * NULL, with err saying why, when such a plugin reads probes and the
 * frame has one of a shape it cannot see. */
const struct rf_host *rf__host_for_plugin(const struct rf_host *table,
                                          const struct rf_plugin *p, char *err,
                                          size_t errlen);
/* Whether table is one of rf_plugin_host's (rf_plugin_host_table), not
 * a caller's own: only those keep what a mode declares to them. */
int rf__host_is_own(const struct rf_host *table);
uint32_t rf__host_filter_passes(const struct rf_host *table, uint32_t *radius);
void rf__host_filter_reset(const struct rf_host *table);
/* A projection mode that does not read P has no parallax: box projection
 * off in the host's probe (tables of rf_plugin_host only), so that the
 * probe it writes to the stream says so, and the modes after it that
 * trace their own rays (project_rays) keep their directions too. */
void rf__host_take_distant(const struct rf_host *table);

/* A mode as a crash report names it, made when an instance is: its name
 * and its file (found from the descriptor's address; NULL when unknown). */
struct rf__call_site {
	const char *mode;
	char *file;
};
void rf__call_site_init(struct rf__call_site *site, const struct rf_plugin *p);
void rf__call_site_fini(struct rf__call_site *site);
/* Around every call into plugin code on a thread (rf_plugin_current_call):
 * what ("create", "run", "destroy"), and for run() the frame (from 1)
 * and rows; a file's loading (its constructors, its entry) by path. */
void rf__call_enter(const struct rf__call_site *site, const char *what, size_t frame,
                    size_t y, size_t nrows);
void rf__call_enter_file(const char *file);
void rf__call_leave(void);

/* Whether the file at path may be dlopen'ed as a plugin: 0 for a whole
 * ELF shared object of this machine whose dynamic symbols export
 * RF_PLUGIN_ENTRY; RF__ELF_NOT_PLUGIN for a file that is no plugin (not
 * ELF, no entry: a library beside the plugins), RF__ELF_BROKEN for one
 * that cannot be loaded (cut short, another machine's); why says what,
 * without the path.  It never maps or loads the file. */
enum { RF__ELF_NOT_PLUGIN = 1, RF__ELF_BROKEN = 2 };
int rf__elf_check(const char *path, char *why, size_t len);

/* A loaded descriptor whose ABI fields load.c found good, checked
 * (descriptor.c): its other fields, its name against its file's (path),
 * its kind against the one the tool wants (0: any) and that kind's
 * output contract, its parameters.  0, or RF_EPLUGIN with err saying
 * "plugin 'PATH': " what is wrong and the fix. */
struct rf_plugin;
int rf__descriptor_check(const struct rf_plugin *p, const char *path, unsigned kind,
                         char *err, size_t errlen);

#endif
