/*
 * The sky (reflect-scene(5)'s `sky FILE`): an environment that rays
 * leaving the scene see, and whose irradiance, through its 9 spherical
 * harmonic coefficients, lights what does not reflect, as reflect-shade
 * lights a pixel's diffuse part.  Unoccluded, as there: it suits scenes
 * open to the sky (a courtyard, an object on a plane); a closed room
 * sees its sky through its windows' emission instead.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "surface/surface-internal.h"
#include "scene/parser.h"

#define SKY_WORDS "strength"

int
rf__parse_sky(struct parser *p, const struct rf__token *kw)
{
	struct rf_envmap_options eo;
	struct rf_chain_info info;
	const struct rf__token *file, *key;
	rf_cubemap *cube = NULL;
	double strength = 1.0;
	char *path = NULL, msg[1024];
	float sh[27];
	int rc, k;

	if (p->s->sky)
		return FAIL_TOK(p, kw, "a second 'sky' (the first is on line %zu): a scene "
		                "has one sky", p->s->sky_line);
	if ((rc = rf__parse_word(p, "an environment file after 'sky'", &file)) < 0)
		return rc;
	while ((rc = rf__parse_attribute(p, &key)) > 0) {
		if (rf__tok_is(key, "strength")) {
			if ((rc = rf__parse_number(p, "strength", &strength)) < 0)
				return rc;
			if (!(strength >= 0.0) || strength > 1e30)
				return FAIL_TOK(p, key, "expected a strength of 0 or more, found %g",
				                strength);
		} else {
			return rf__parse_unknown_attribute(p, key, "sky", SKY_WORDS);
		}
	}
	if (rc < 0)
		return rc;
	if ((rc = rf__parse_path(p, file, &path)) < 0)
		return rc;
	rf_envmap_options_init(&eo);
	/* the scene may come on standard input: the sky is a file */
	eo.from_header = 1;
	rc = rf_envmap_load(&cube, &info, path, &eo, NULL, msg, sizeof(msg));
	free(path);
	if (rc == RF_ENOMEM)
		return rc;
	if (rc < 0)
		return FAIL_TOK(p, file, "%s", msg);
	rf_cubemap_sh9(cube, 0, sh);
	for (k = 0; k < 27; k++)
		sh[k] *= (float)strength;
	rf__sh9_quadratic(sh, p->s->sky_q);
	p->s->sky = cube;
	p->s->sky_strength = (float)strength;
	p->s->sky_line = kw->line;
	p->s->has_emission = 1;
	return 0;
}

void
rf__sky_radiance(const rf_scene *s, const double d[3], float rgb[3])
{
	const float dir[3] = { (float)d[0], (float)d[1], (float)d[2] };
	int k;

	if (!s->sky) {
		rgb[0] = rgb[1] = rgb[2] = 0.0f;
		return;
	}
	rf_cubemap_sample_level(s->sky, 0, dir, rgb);
	for (k = 0; k < 3; k++)
		rgb[k] *= s->sky_strength;
}

void
rf__sky_diffuse(const rf_scene *s, const struct rf_hit *hit, float rgb[3])
{
	const float n[3] = { (float)hit->N[0], (float)hit->N[1], (float)hit->N[2] };
	const float keep = 1.0f - hit->mask;
	int k;

	rf__surface_diffuse(s->sky_q, n, hit->albedo, hit->metallic, rgb);
	for (k = 0; k < 3; k++)
		rgb[k] *= keep;
}
