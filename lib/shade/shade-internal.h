/* Internal to shade: the settings of the pass that only the shader
 * (shader.c) makes, for a frame's probes and the mode's stages, in the
 * one order that lines their rows up. */
#ifndef REFLECT_SHADE_INTERNAL_H
#define REFLECT_SHADE_INTERNAL_H

#include "reflect/shading.h"

/* Blends the frame's probes (b, as rf_blend_read made it) into each
 * reflective pixel: probe 0 along D through the pass's own environment,
 * probe k >= 1 along R box-projected with its own box from P through
 * envs[k] (mappings and steps per probe; [0] is the pass's), the rest
 * from the fallback (RF_BLEND_SKY: envs[nprobes], with its mapping and
 * steps); every pixel also gets weight.probe1 ...
 * weight.probeN and weight.fallback.  Before the frame's channels are
 * listed; NULL or one probe turns it off.  A mode that writes its own
 * radiance needs no envs (NULL) but rf__shade_set_blend_stages.
 * RF_EINVAL for a probe without an environment. */
int rf__shade_set_blend(rf_shade *s, const struct rf_blend *b,
                        const rf_cubemap *const *envs, const enum rf_mapping *mappings,
                        const float *steps, enum rf_blend_fallback fallback);
/* For a mode that traces its own rays (mode_radiance), the frame's other
 * probes as stages of the same mode (stages[k], k = 1 .. nprobes - 1,
 * each created with a host whose probe and environment are probe k's,
 * begun on the same frame with the pass's channels reserved, so that
 * their rows have the first stage's layout): where probe k has weight
 * its stage traces the row, and spec becomes the weighted sum (the
 * fallback's share goes to the first probe).  After rf__shade_set_blend
 * and rf_shade_begin_frame; the stages must outlive the frame. */
int rf__shade_set_blend_stages(rf_shade *s, rf_stage *const *stages);
/* For the frames that follow: 1 looks up along the reflection vector R
 * (box projection off: the classic lookup), not along D; 0 (the
 * default) along D. */
void rf__shade_set_unprojected(rf_shade *s, int unprojected);
/* The environment's frame: a turned probe's rotation (row-major, world =
 * rotation local), or NULL for the world's. */
void rf__shade_set_env_frame(rf_shade *s, const float rotation[9]);
/* The shade mode's stage and the pass in one: rows y..y+nrows of the
 * stage's input to out, each row through the stage and then shaded in
 * place while it is in cache.  The stage's output header must be the
 * pass's input header and hold its channels (rf_stage_reserve_channel),
 * and the stage must have at least the pass's threads. */
int rf__shade_run_stage(rf_shade *s, rf_stage *stage, const float *in, float *out,
                        size_t y, size_t nrows);

#endif
