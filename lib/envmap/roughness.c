/* The one roughness-to-lod mapping, used by the prefilter and samplers. */
#include <math.h>
#include <string.h>

#include "reflect/envmap.h"

int
rf_mapping_parse(const char *name, enum rf_mapping *out)
{
	if (!strcmp(name, "unity"))
		*out = RF_MAPPING_UNITY;
	else if (!strcmp(name, "linear"))
		*out = RF_MAPPING_LINEAR;
	else if (!strcmp(name, "exact"))
		*out = RF_MAPPING_EXACT;
	else
		return RF_EINVAL;
	return 0;
}

const char *
rf_mapping_name(enum rf_mapping m)
{
	switch (m) {
	case RF_MAPPING_UNITY: return "unity";
	case RF_MAPPING_LINEAR: return "linear";
	case RF_MAPPING_EXACT: return "exact";
	}
	return "?";
}

static double
clamp01(double x)
{
	return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0;
}

/*
 * exact: alpha = r^2 becomes a Blinn-Phong power n = 2 / alpha^2 - 2,
 * quartered to move from the N.H lobe to the N.R lobe a cubemap level
 * holds, and mapped back to perceptual roughness (2 / (n + 2))^(1/4).
 * In closed form: r' = (4 a^2 / (1 + 3 a^2))^(1/4) with a = alpha.
 */
static double
exact_remap(double r)
{
	double a2 = r * r * r * r;

	return pow(4.0 * a2 / (1.0 + 3.0 * a2), 0.25);
}

static double
exact_unmap(double rp)
{
	double q = rp * rp * rp * rp; /* = 4 a2 / (1 + 3 a2) */
	double a2;

	if (q >= 1.0)
		return 1.0;
	a2 = q / (4.0 - 3.0 * q);
	return sqrt(sqrt(a2));
}

float
rf_roughness_to_lod(enum rf_mapping m, float steps, float roughness)
{
	double r = clamp01(roughness);

	switch (m) {
	case RF_MAPPING_LINEAR:
		return (float)(r * steps);
	case RF_MAPPING_EXACT:
		return (float)(exact_remap(r) * steps);
	case RF_MAPPING_UNITY:
	default:
		return (float)(r * (1.7 - 0.7 * r) * steps);
	}
}

float
rf_lod_to_roughness(enum rf_mapping m, float steps, float lod)
{
	double t = steps > 0.0f ? clamp01(lod / steps) : 0.0;

	switch (m) {
	case RF_MAPPING_LINEAR:
		return (float)t;
	case RF_MAPPING_EXACT:
		return (float)exact_unmap(t);
	case RF_MAPPING_UNITY:
	default:
		/* The root of 0.7 r^2 - 1.7 r + t = 0 in [0, 1]. */
		return (float)clamp01((1.7 - sqrt(2.89 - 2.8 * t)) / 1.4);
	}
}
