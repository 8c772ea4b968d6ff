/*
 * What a surface sends back toward the eye: its emission, and on a
 * surface that does not reflect the probe (mask 0), Lambert's share of
 * the direct light of the scene's lights (the mesh files'
 * KHR_lights_punctual):
 *
 *	Lo = Le + (1 - mask) (1 - metallic) albedo / pi  sum E_l(P) V_l(P)
 *
 * E_l the light's irradiance on the surface (I cos / r^2 for a point,
 * times the cone's falloff for a spot, E cos for a directional light,
 * each times glTF's range window), V_l 1 where a shadow ray reaches the
 * light and 0 where anything (the room, an object, a triangle) stands in
 * between.  reflect-capture bakes it, reflect-trace reflects it and
 * reflect-gbuffer writes it as the emission of the pixels that do not
 * reflect, so that the three agree on what every surface sends out.
 */
#include <math.h>

#include "scene/accel.h"
#include "scene/vector.h"

/* glTF's recommended window on a light's range (KHR_lights_punctual):
 * the irradiance falls smoothly to 0 at the range; 1 without one. */
static double
range_window(double r, double range)
{
	double x, w;

	if (!(range > 0.0))
		return 1.0;
	x = r / range;
	w = 1.0 - x * x * x * x;
	w = w > 0.0 ? (w < 1.0 ? w : 1.0) : 0.0;
	return w * w;
}

/* glTF's spot falloff: 0 outside the outer cone, 1 inside the inner
 * one, and between them the square of a ramp linear in the cosine. */
static double
spot_falloff(const struct rf__light *l, const double to_light[3])
{
	const double cos_outer = cos(l->outer_cone), cos_inner = cos(l->inner_cone);
	const double scale = 1.0 / fmax(1e-3, cos_inner - cos_outer);
	const double cd = -rf__dot(l->direction, to_light);
	double a = (cd - cos_outer) * scale;

	a = a > 0.0 ? (a < 1.0 ? a : 1.0) : 0.0;
	return a * a;
}

/* The irradiance factor of light l at p (facing n, geometric normal ng,
 * both toward the viewer): E / I with the light's visibility, 0 in
 * shadow or behind the surface. */
static double
light_at(const rf_scene *s, const struct rf__light *l, const double p[3],
         const double n[3], const double ng[3])
{
	double to_light[3], dist, cosn, w, o[3], eps;
	int k;

	if (l->kind == RF__LIGHT_DIRECTIONAL) {
		for (k = 0; k < 3; k++)
			to_light[k] = -l->direction[k];
		dist = INFINITY;
		w = 1.0;
	} else {
		for (k = 0; k < 3; k++)
			to_light[k] = l->position[k] - p[k];
		dist = sqrt(rf__dot(to_light, to_light));
		if (!(dist > 0.0))
			return 0.0;
		for (k = 0; k < 3; k++)
			to_light[k] /= dist;
		w = range_window(dist, l->range) / (dist * dist);
		if (l->kind == RF__LIGHT_SPOT)
			w *= spot_falloff(l, to_light);
	}
	cosn = rf__dot(n, to_light);
	/* the light on the side the surface is seen from, by both normals:
	 * a normal map does not let light in from behind the face */
	if (!(w > 0.0) || !(cosn > 0.0) || !(rf__dot(ng, to_light) > 0.0))
		return 0.0;
	/* off the surface, so that the shadow ray does not meet its own
	 * face: a relative step, as the ray caster's own margin */
	eps = 1e-5 * (1.0 + fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2]))));
	for (k = 0; k < 3; k++)
		o[k] = p[k] + eps * ng[k];
	if (rf__occluded(s, o, to_light, dist - 2.0 * eps))
		return 0.0;
	return w * cosn;
}

void
rf__direct_light(const rf_scene *s, const struct rf_hit *hit, float rgb[3])
{
	const double lambert = (1.0 - hit->mask) * (1.0 - hit->metallic) / M_PI;
	double acc[3] = { 0.0, 0.0, 0.0 };
	size_t i;
	int c;

	rgb[0] = rgb[1] = rgb[2] = 0.0f;
	if (!s->nlights || hit->objid == RF_OBJID_NONE || !(lambert > 0.0))
		return;
	for (i = 0; i < s->nlights; i++) {
		const struct rf__light *l = &s->lights[i];
		const double e = light_at(s, l, hit->P, hit->N, hit->Ng);

		for (c = 0; c < 3; c++)
			acc[c] += e * l->colour[c];
	}
	for (c = 0; c < 3; c++)
		rgb[c] = (float)(lambert * hit->albedo[c] * acc[c]);
}

void
rf__radiance(const rf_scene *s, const struct rf_hit *hit, float rgb[3])
{
	float more[3];
	int c;

	if (hit->objid == RF_OBJID_NONE) {
		/* a miss: N is the ray's way back */
		const double d[3] = { -hit->N[0], -hit->N[1], -hit->N[2] };

		rf__sky_radiance(s, d, rgb);
		return;
	}
	rf__emission(s, hit, rgb);
	if (s->nlights) {
		rf__direct_light(s, hit, more);
		for (c = 0; c < 3; c++)
			rgb[c] += more[c];
	}
	if (s->sky) {
		rf__sky_diffuse(s, hit, more);
		for (c = 0; c < 3; c++)
			rgb[c] += more[c];
	}
}
