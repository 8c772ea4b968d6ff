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
/* Every probe of h with box projection off (its BOX_PROJECTION key 0):
 * the frame of a projection without parallax. */
int rf__header_probes_distant(rf_header *h);
/* The shape keys of probe `index` (PROBE_SHAPE, PROBE_ROTATION,
 * PROBE_PROXY...) into *probe, whose box and bevel are read already;
 * RF_EINVAL with err naming the key and the fix. */
int rf__probe_shape_read(const rf_header *h, size_t index, struct rf_probe *probe,
                         char *err, size_t errlen);
/* Probe index's keys read again for their message: RF_EINVAL with err
 * saying what is wrong with the shape keys ("" when it is the box or the
 * centre), 1 when they parse, 0 when the probe has no box. */
int rf__probe_why_not(const rf_header *h, size_t index, char *err, size_t errlen);
/* Writes them, each absent where the probe has today's default. */
int rf__probe_shape_write(rf_header *h, size_t index, const struct rf_probe *probe);
/* A rotation from 3 angles in degrees, Unity's order (z, then x, then y,
 * about the world axes): row-major, local to world. */
void rf__rotation_from_euler(const double deg[3], double m[9]);
/* 0 for a rotation (orthonormal to 2e-4), -1 for a matrix that is not
 * orthonormal, -2 for a reflection. */
int rf__rotation_check(const double m[9]);
/* A PROBE_ROTATION value (9 numbers or 3 angles) into m, and whether it
 * differs from the identity; -3 when it is neither, else as above. */
int rf__rotation_parse(const char *v, float m[9], int *rotated);

#endif
