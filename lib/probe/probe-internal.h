/* What the probe's files share inside the library (lib/probe/). */
#ifndef REFLECT_PROBE_INTERNAL_H
#define REFLECT_PROBE_INTERNAL_H

#include <stddef.h>

#include "reflect/probe.h"

/* The key of a numbered probe: PROBE_BOX of probe index 1 is PROBE2_BOX. */
void rf__header_probe_key(char *buf, size_t size, size_t index, const char *key);
/* A PROBE_BLEND value: one distance for every face, or six, +X -X +Y -Y
 * +Z -Z (HDRP's per face), each at least 0. */
int rf__probe_blend_parse(const char *v, float face[6]);
/* The three geometry keys of probe `index`. */
int rf__header_set_probe_keys(rf_header *h, size_t index, const double box_min[3],
                              const double box_max[3], const double center[3],
                              int box_projection);

#endif
