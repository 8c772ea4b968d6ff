/*
 * libreflect: the probe.
 *
 * A capture point, the box its environment is projected through and
 * blends by, and its shape: read from and written to a stream's header
 * keys, and weighed against the frame's other probes at a point.  The
 * struct is part of the plugin ABI, so it is defined in plugin.h, which
 * stands alone; the functions are the library's.
 */
#ifndef REFLECT_PROBE_H
#define REFLECT_PROBE_H

#include <stddef.h>
#include <stdint.h>

#include "reflect/reflect.h"
/* struct rf_probe and RF_PROBES_MAX: they are the plugin ABI's, and a
 * plugin is built against that one header alone. */
#include "reflect/plugin.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The probe of a frame, from the strings a tool was given for its
 * --box, --center and --box-projection (NULL: not given), else from the
 * frame's PROBE_BOX, PROBE_CENTER and PROBE_BOX_PROJECTION, and the bevel
 * from PROBE_BEVEL; the centre defaults to the box's, box projection to
 * on.  RF_ENOTFOUND when
 * neither gives a box, RF_EINVAL for a value that does not parse or an
 * empty box; err says which. */
RF_EXTERN int rf_probe_resolve(struct rf_probe *probe, const rf_header *h,
                               const char *box, const char *center,
                               const char *projection, char *err, size_t errlen);
/* Every probe of a frame, from its keys (PROBE_*, then PROBE2_*, ...
 * while they have a box) into probes and their blend distances
 * (PROBE_BLEND..., 0 when absent), at most max: how many (a probe whose
 * keys do not parse ends the list), or RF_EINVAL when the first's do
 * not. */
RF_EXTERN int rf_probe_list_read(struct rf_probe *probes, float *blend, size_t max,
                                 const rf_header *h);
/* Writes the probe as PROBE_BOX, PROBE_CENTER, PROBE_BOX_PROJECTION and
 * PROBE_BEVEL (removed for the box). */
RF_EXTERN int rf_probe_to_header(const struct rf_probe *probe, rf_header *h);

/*
 * A frame's probes (PROBE_*, PROBE2_*, ... with PROBEk_BLEND and
 * PROBEk_IMPORTANCE) and how they are blended at a point, as HDRP does:
 * each probe's weight is smoothstep(min over its box's faces of
 * sat(d_f / blend_f)), d_f the distance from the point to face f and
 * blend_f that face's blend distance (a face without one does not fade;
 * 0 outside the box), times with normal_fade HDRP's fade of
 * surfaces turned away from the capture point within the blend distance;
 * probes are taken most important first, then smallest box first, each
 * clipped to what the ones before left (w' = min(w, 1 - sum)), at most
 * max_probes of them (0: all).  What is left, 1 - sum, is the fallback's.
 */
struct rf_blend {
	uint32_t nprobes;
	struct rf_probe probes[RF_PROBES_MAX];
	float blend[RF_PROBES_MAX];   /* the widest face's, as plugins see it */
	float face_blend[RF_PROBES_MAX][6]; /* +X -X +Y -Y +Z -Z; 0: none */
	float importance[RF_PROBES_MAX];
	uint32_t order[RF_PROBES_MAX]; /* the order they are taken in */
	uint32_t max_probes;
	int normal_fade;
};

/* The frame's probes into b (max_probes and normal_fade untouched), and
 * their order: how many, or < 0 with err saying why. */
RF_EXTERN int rf_blend_read(struct rf_blend *b, const rf_header *h, char *err,
                            size_t errlen);
/* b->order from the probes' importance and boxes. */
RF_EXTERN void rf_blend_order(struct rf_blend *b);
/* Each probe's weight at p (b->nprobes floats, in the probes' order),
 * the unit normal n for the normal fade (NULL: none); returns the
 * fallback's share. */
RF_EXTERN float rf_blend_weights(const struct rf_blend *b, const float p[3],
                                 const float n[3], float *weights);

#ifdef __cplusplus
}
#endif

#endif
