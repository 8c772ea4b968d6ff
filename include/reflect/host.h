/*
 * The services a tool gives its plugins (struct rf_host of plugin.h),
 * made once in the library for every tool: the frame's header keys, the
 * probe, and when there is an environment its sampling and its
 * roughness-to-lod mapping.
 */
#ifndef REFLECT_HOST_H
#define REFLECT_HOST_H

#include "reflect/envmap.h"
#include "reflect/plugin.h"
#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rf_plugin_host rf_plugin_host;

/* A host with no frame, probe or environment: header_get answers NULL,
 * probe and the sampling services are NULL. */
RF_EXTERN int rf_plugin_host_create(rf_plugin_host **h);
RF_EXTERN void rf_plugin_host_destroy(rf_plugin_host *h);
/* The frame header_get reads, kept by pointer (NULL: none). */
RF_EXTERN void rf_plugin_host_set_frame(rf_plugin_host *h, const rf_header *frame);
/* The probe, copied (NULL: none). */
RF_EXTERN void rf_plugin_host_set_probe(rf_plugin_host *h, const struct rf_probe *probe);
/* The probe as the modes have it, with the bevel a projection mode
 * declared (declare_bevel); NULL when there is none. */
RF_EXTERN const struct rf_probe *rf_plugin_host_probe(const rf_plugin_host *h);
/* The environment sample() and sample_many() read (through the shading
 * pass's kernels), kept by pointer, and its mapping; NULL takes
 * the sampling services away, as does running out of memory (returned). */
RF_EXTERN int rf_plugin_host_set_environment(rf_plugin_host *h, const rf_cubemap *env,
                                             enum rf_mapping mapping, float steps);
/* For modes that write radiance themselves: sample_radiance reads
 * env's level 0 and plain box-filtered levels made from it here (the
 * host's copy: env may go); NULL takes the service away. */
RF_EXTERN int rf_plugin_host_set_radiance(rf_plugin_host *h, const rf_cubemap *env);
RF_EXTERN void rf_plugin_host_set_seed(rf_plugin_host *h, uint32_t seed);
/* The table for rf_stage_create, as the settings are when a plugin
 * reads it; valid until rf_plugin_host_destroy.  Change the settings
 * only while no stage made with it runs. */
RF_EXTERN const struct rf_host *rf_plugin_host_table(const rf_plugin_host *h);

#ifdef __cplusplus
}
#endif

#endif
