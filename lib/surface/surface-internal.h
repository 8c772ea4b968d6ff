/*
 * Internal to the library: the surface's BRDF under an environment, the
 * one the shading pass (shade/pass.c) and a scene's capture
 * (scene/capture.c) both shade with, so that an object in a capture and
 * the same material in a shaded frame cannot drift apart.  Inline, as
 * the shading pass runs it for every pixel.
 *
 * The material is metallic-roughness: perceptual roughness, metallic and
 * albedo in [0, 1] (the callers clamp or check them).  The specular
 * weights multiply the prefiltered environment's radiance (what
 * reflect-shade writes as spec); the diffuse term is added to that.
 */
#ifndef REFLECT_SURFACE_INTERNAL_H
#define REFLECT_SURFACE_INTERNAL_H

#include "envmap/envmap-internal.h"
#include "reflect/surface.h"

static inline float
rf__surface_sat(float x)
{
	return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; /* NaN -> 0 */
}

/* Schlick's reflectance at normal incidence, per channel: 0.04 for a
 * dielectric, the albedo for a metal, linear in metallic between. */
static inline void
rf__surface_f0(const float albedo[3], float metallic, float f0[3])
{
	int k;

	for (k = 0; k < 3; k++)
		f0[k] = 0.04f + (albedo[k] - 0.04f) * metallic;
}

/* The split sum's specular weight F0 A + B, (A, B) the DFG table's at
 * (n.v, roughness) (rf_dfg_lookup clamps both); with hdrp, HDRP's FGD:
 * the energy lost to single scattering, 1 - E with E = A + B, given back
 * in proportion to F0. */
static inline void
rf__surface_split_sum(const float f0[3], float n_dot_v, float roughness, int hdrp,
                      float w[3])
{
	float a, b;
	int k;

	rf_dfg_lookup(n_dot_v, roughness, &a, &b);
	for (k = 0; k < 3; k++) {
		float fgd = f0[k] * a + b;

		if (hdrp && a + b > 0.0f)
			fgd *= 1.0f + f0[k] * (1.0f / (a + b) - 1.0f);
		w[k] = fgd;
	}
}

/* Unity Standard's specular weight (BRDF1, linear colour space): its
 * surface reduction times lerp(F0, grazing, (1 - n.v)^5). */
static inline void
rf__surface_unity(const float f0[3], float n_dot_v, float roughness, float metallic,
                  float w[3])
{
	const float alpha = roughness * roughness, reduction = 1.0f / (alpha * alpha + 1.0f);
	const float one_minus_refl = 0.96f * (1.0f - metallic);
	const float grazing = rf__surface_sat((1.0f - roughness) + (1.0f - one_minus_refl));
	const float c = 1.0f - rf__surface_sat(n_dot_v), c5 = c * c * c * c * c;
	int k;

	for (k = 0; k < 3; k++)
		w[k] = reduction * (f0[k] + (grazing - f0[k]) * c5);
}

/* Lambert's diffuse light albedo (1 - metallic) E(n) / pi, E the
 * irradiance of the 9 coefficients q (rf__sh9_quadratic) at the unit
 * direction n. */
static inline void
rf__surface_diffuse(const float q[3][9], const float n[3], const float albedo[3],
                    float metallic, float rgb[3])
{
	int k;

	rf__sh9_quadratic_eval(q, n, rgb);
	for (k = 0; k < 3; k++)
		rgb[k] *= albedo[k] * (1.0f - metallic) * (float)(1.0 / 3.14159265358979);
}

#endif
