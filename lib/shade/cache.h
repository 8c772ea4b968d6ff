/* Internal to shading: prefiltered environments cached between runs. */
#ifndef REFLECT_SHADE_CACHE_H
#define REFLECT_SHADE_CACHE_H

#include <stdint.h>

#include "reflect/envmap.h"

/* The hash of a raw environment's level 0 and how it is prefiltered. */
uint64_t rf__env_cache_key(const rf_cubemap *src, enum rf_mapping mapping, float steps,
                           unsigned samples, size_t levels);
/* The chain of key in dir, made from src's level 0 into `levels` levels
 * as want says (mapping, steps, samples): RF_ENOTFOUND for none;
 * RF_EINVAL for an entry that is not that chain, whole and finite (why
 * says what is wrong with it), which the caller makes again. */
int rf__env_cache_get(const char *dir, uint64_t key, const rf_cubemap *src,
                      size_t levels, const struct rf_chain_info *want, rf_cubemap **env,
                      char *why, size_t whylen);
/* Writes the chain for key, whole or not at all, then trims dir to cap
 * bytes, the oldest entries first. */
int rf__env_cache_put(const char *dir, uint64_t key, const rf_cubemap *env,
                      const struct rf_chain_info *info, size_t cap);

#endif
