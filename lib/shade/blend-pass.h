/* Internal to the shading pass: blending probes a row at a time. */
#ifndef REFLECT_SHADE_BLEND_PASS_H
#define REFLECT_SHADE_BLEND_PASS_H

#include "envmap/rgba_levels.h"
#include "reflect/shading.h"

struct rf__blend_pass;

/* The channels a row is read by: P, N (all -1: no normal fade), R, and
 * the effective roughness. */
enum { RF__BLEND_PX, RF__BLEND_NX = 3, RF__BLEND_RX = 6, RF__BLEND_REFF = 9,
       RF__BLEND_CHANNELS };

/* One pixel's weights into w, nprobes + 1 (the last the fallback's),
 * read at the P and N channels ch gives; with RF_BLEND_NONE the probes'
 * own, scaled to 1 where any covers, and the fallback's 0.  Returns the
 * fallback's. */
float rf__blend_pixel_weights(const struct rf_blend *b, enum rf_blend_fallback fallback,
                              const float *pixel, const int *ch, float *w);

/* The probes of b; envs, mappings and steps per probe (envs[0] unused:
 * probe 0 is the pass's own environment, `first`); rows of ncols pixels
 * on up to nthreads threads. */
int rf__blend_pass_create(struct rf__blend_pass **bp, const struct rf_blend *b,
                          const rf_cubemap *const *envs, const enum rf_mapping *mappings,
                          const float *steps, enum rf_blend_fallback fallback,
                          const struct rf__rgba_levels *first, int first_vector,
                          int nthreads, size_t ncols);
void rf__blend_pass_destroy(struct rf__blend_pass *bp);
uint32_t rf__blend_pass_nprobes(const struct rf__blend_pass *bp);
/* One row on thread `thread`: mirror[x] holds probe 0's read of each
 * pixel whose mask > 0 and becomes the blend.  Returns every pixel's
 * weights, nprobes + 1 a pixel (the last the fallback's), until the
 * thread's next row. */
const float *rf__blend_pass_row(const struct rf__blend_pass *bp, int thread,
                                const float *in, size_t in_ncomp, const int *ch,
                                const float *mask, rf__v4 *mirror);

#endif
