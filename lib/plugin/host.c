/*
 * The host services of plugin.h, once for every tool: reflect-project
 * and reflect-shade, and every tool that runs plugins after them, give
 * their modes the same table with the same meanings.
 */
#include <stdlib.h>
#include <string.h>

#include "util/util.h"
#include "reflect/host.h"

struct rf_plugin_host {
	struct rf_host table; /* its ctx is this host */
	const rf_header *frame;
	struct rf_probe probe;
	const rf_cubemap *env;
	enum rf_mapping mapping;
	float steps;
};

static const char *
header_get(void *ctx, const char *key)
{
	const rf_plugin_host *h = ctx;

	return h->frame ? rf_header_get(h->frame, key) : NULL;
}

static void
sample(void *ctx, const float dir[3], float lod, float rgb[3])
{
	rf_cubemap_sample(((const rf_plugin_host *)ctx)->env, dir, lod, rgb);
}

static float
roughness_to_lod(void *ctx, float roughness)
{
	const rf_plugin_host *h = ctx;

	return rf_roughness_to_lod(h->mapping, h->steps, roughness);
}

static float
lod_to_roughness(void *ctx, float lod)
{
	const rf_plugin_host *h = ctx;

	return rf_lod_to_roughness(h->mapping, h->steps, lod);
}

int
rf_plugin_host_create(rf_plugin_host **hp)
{
	rf_plugin_host *h;

	if (!(*hp = h = calloc(1, sizeof(*h))))
		return RF_ENOMEM;
	h->table.size = sizeof(h->table);
	h->table.abi_major = RF_PLUGIN_ABI_MAJOR;
	h->table.abi_minor = RF_PLUGIN_ABI_MINOR;
	h->table.ctx = h;
	h->table.header_get = header_get;
	h->mapping = RF_MAPPING_DEFAULT;
	return 0;
}

void
rf_plugin_host_destroy(rf_plugin_host *h)
{
	free(h);
}

void
rf_plugin_host_set_frame(rf_plugin_host *h, const rf_header *frame)
{
	h->frame = frame;
}

void
rf_plugin_host_set_probe(rf_plugin_host *h, const struct rf_probe *probe)
{
	if (probe)
		h->probe = *probe;
	h->table.probe = probe ? &h->probe : NULL;
}

void
rf_plugin_host_set_environment(rf_plugin_host *h, const rf_cubemap *env,
                               enum rf_mapping mapping, float steps)
{
	h->env = env;
	h->mapping = mapping;
	h->steps = steps;
	h->table.sample = env ? sample : NULL;
	h->table.roughness_to_lod = env ? roughness_to_lod : NULL;
	h->table.lod_to_roughness = env ? lod_to_roughness : NULL;
	h->table.lod_steps = env ? steps : 0.0f;
}

void
rf_plugin_host_set_seed(rf_plugin_host *h, uint32_t seed)
{
	h->table.seed = seed;
}

const struct rf_host *
rf_plugin_host_table(const rf_plugin_host *h)
{
	return &h->table;
}
