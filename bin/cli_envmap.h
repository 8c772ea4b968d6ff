/* Loading environments: the options reflect-prefilter and reflect-shade
 * share (--env, --layout, --prefiltered, --rgbm, --nonfinite, ...). */
#ifndef REFLECT_CLI_ENVMAP_H
#define REFLECT_CLI_ENVMAP_H

#include "cli.h"
#include "reflect/envmap.h"

struct envmap_opts {
	const char *path;              /* --env; NULL or "default": the embedded room */
	struct rf_envmap_options load; /* the rest, as the library takes them */
};

void envmap_opts_init(struct envmap_opts *o);
/* A cube, or death with a message (over the memory limit, levels the
 * size cannot halve to). */
rf_cubemap *envmap_cube_new(size_t size, size_t levels);
/* Handles one long option by name; 1 when taken, dies on a bad value. */
int envmap_opts_parse(struct envmap_opts *o, const char *name, const char *arg);

/* rf_envmap_load, or death with its message; warns of replaced texels. */
rf_cubemap *envmap_load(const struct envmap_opts *o, struct rf_chain_info *info);

/* rf_chain_levels, or death with its message. */
size_t envmap_chain_levels(size_t size, size_t levels, size_t min_size);

#endif
