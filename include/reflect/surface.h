/*
 * libreflect: the surface's BRDF under an environment.
 *
 * The split-sum environment BRDF of GGX (the DFG table) that the shading
 * pass (reflect/shading.h, which includes this header) and a scene's
 * capture (reflect/scene.h) both weigh a surface's reflection with.
 */
#ifndef REFLECT_SURFACE_H
#define REFLECT_SURFACE_H

#include "reflect/reflect.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * For GGX with Smith height-correlated masking-shadowing and Schlick's
 * Fresnel F = F0 + (1 - F0) (1 - v.h)^5, the directional albedo is
 * F0 A + B with
 *   A = integral of f1 (1 - (1 - v.h)^5) n.l dl,
 *   B = integral of f1 (1 - v.h)^5 n.l dl,
 * f1 the BRDF with F = 1, over the hemisphere of n.  A + B is the albedo
 * of a white (F = 1) GGX surface.  Perceptual roughness r, alpha = r^2.
 *
 * The table has RF_DFG_SIZE x RF_DFG_SIZE entries (A, B): row j holds
 * roughness j / (size - 1), column i holds n.v = (i / (size - 1))^2 (the
 * square root spacing puts more columns toward grazing, where the
 * integrals change fastest).  It is integrated when reflect is built.
 */
#define RF_DFG_SIZE 64

/* Bilinear lookup; n_dot_v and roughness are clamped to [0, 1] (NaN
 * counts as 0).  Thread-safe. */
RF_EXTERN void rf_dfg_lookup(float n_dot_v, float roughness, float *a, float *b);
/* The table: *size x *size pairs (A, B), rows by roughness. */
RF_EXTERN const float *rf_dfg_table(size_t *size);
/* One entry, integrated with `samples` quasi-random samples of the GGX
 * distribution of visible normals (what the table is made of). */
RF_EXTERN void rf_dfg_integrate(double n_dot_v, double roughness, unsigned samples,
                                double *a, double *b);

#ifdef __cplusplus
}
#endif

#endif
