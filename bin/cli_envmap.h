/* Loading environments: the options reflect-prefilter and reflect-shade
 * share (--env, --layout, --prefiltered, --rgbm, ...). */
#ifndef REFLECT_CLI_ENVMAP_H
#define REFLECT_CLI_ENVMAP_H

#include "cli.h"
#include "reflect/envmap.h"

struct envmap_opts {
	const char *path;       /* NULL or "default": the embedded room */
	enum rf_layout layout;  /* --layout */
	int prefiltered;        /* --prefiltered: take the levels as convolved */
	int srgb;               /* --srgb=on|off; -1: from the file */
	struct rf_decode decode;
	int strict;             /* -S: refuse NaN and Inf texels */
	size_t size;            /* --size: face size of level 0 (0: the file's) */
	int nthreads;           /* for rendering the embedded room */
	int from_header;        /* path named by a stream (PROBE_ENV): a file */
};

void envmap_opts_init(struct envmap_opts *o);
/* A cube, or death with a message (over the memory limit, levels the
 * size cannot halve to). */
rf_cubemap *envmap_cube_new(size_t size, size_t levels);
/* Handles one long option by name; 1 when taken, dies on a bad value. */
int envmap_opts_parse(struct envmap_opts *o, const char *name, const char *arg);

/* Loads the environment: a raw one as level 0 of a one-level cube
 * (info->prefiltered 0), a chain as all its levels. */
rf_cubemap *envmap_load(const struct envmap_opts *o, struct rf_chain_info *info);

/* Levels of a prefiltered chain of a cube of `size` texels: `levels`
 * when not 0 (dies when the size cannot halve that often), else at most
 * RF_STEPS_DEFAULT + 1 (Unity's 7), never below min_size texels, never
 * halving an odd size. */
size_t envmap_chain_levels(size_t size, size_t levels, size_t min_size);

#endif
