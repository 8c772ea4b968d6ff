/*
 * Blending several probes, as HDRP weighs them: inside each influence
 * box the weight falls off over the blend distance toward the nearest
 * face, smoothstepped; probes are taken most important first (then the
 * smallest box, the most local one), each clipped to what those before
 * left, so that weights never sum past 1 and a small probe inside a
 * large one takes over instead of adding to it; what is left goes to a
 * fallback (the sky, or the first probe without parallax).  Unity's
 * two-probe lerp is the case of two probes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "probe/probe-internal.h"
#include "probe/shape.h"
#include "util/util.h"

static float
volume(const struct rf_probe *p)
{
	float v = (p->box_max[0] - p->box_min[0]) * (p->box_max[1] - p->box_min[1]) *
	          (p->box_max[2] - p->box_min[2]);

	/* the sphere inscribed in its cube: pi / 6 of it */
	return p->shape == RF_SHAPE_SPHERE ? v * (float)(3.14159265358979323846 / 6.0) : v;
}

void
rf_blend_order(struct rf_blend *b)
{
	uint32_t i, j;

	for (i = 0; i < b->nprobes; i++)
		b->order[i] = i;
	/* insertion sort: a handful of probes, and stable for ties */
	for (i = 1; i < b->nprobes; i++) {
		uint32_t k = b->order[i];

		for (j = i; j > 0; j--) {
			uint32_t q = b->order[j - 1];

			if (b->importance[q] > b->importance[k] ||
			    (b->importance[q] == b->importance[k] &&
			     volume(&b->probes[q]) <= volume(&b->probes[k])))
				break;
			b->order[j] = q;
		}
		b->order[j] = k;
	}
}

int
rf_blend_read(struct rf_blend *b, const rf_header *h, char *err, size_t errlen)
{
	char key[64];
	const char *v;
	uint32_t i;
	int n;

	memset(b->importance, 0, sizeof(b->importance));
	memset(b->face_blend, 0, sizeof(b->face_blend));
	n = rf_probe_list_read(b->probes, b->blend, RF_PROBES_MAX, h);
	if (n < 0) {
		if (err && errlen && rf__probe_why_not(h, 0, err, errlen) < 0 && *err)
			return n;
		rf__format(err, errlen, "the frame's first probe keys (PROBE_BOX ...) do "
		           "not parse");
		return n;
	}
	b->nprobes = (uint32_t)n;
	/* the list ends at a probe without a box, never at a bad key */
	rf__header_probe_key(key, sizeof(key), b->nprobes, RF_KEY_PROBE_BOX);
	if (b->nprobes < RF_PROBES_MAX && rf_header_get(h, key)) {
		char blend[64];

		rf__header_probe_key(blend, sizeof(blend), b->nprobes, RF_KEY_PROBE_BLEND);
		if (err && errlen && rf__probe_why_not(h, b->nprobes, err, errlen) < 0 && *err) {
			char why[200];

			snprintf(why, sizeof(why), "%s", err);
			rf__format(err, errlen, "probe %u: %s", (unsigned)b->nprobes + 1, why);
			return RF_EFORMAT;
		}
		rf__format(err, errlen, "probe %u: its keys (%s, %s...) do not parse: a box "
		           "of 6 numbers with min < max, a centre of 3, one or six blend "
		           "distances of 0 or more", (unsigned)b->nprobes + 1, key, blend);
		return RF_EFORMAT;
	}
	for (i = 0; i < b->nprobes; i++) {
		rf__header_probe_key(key, sizeof(key), i, RF_KEY_PROBE_BLEND);
		if ((v = rf_header_get(h, key)) && rf__probe_blend_parse(v, b->face_blend[i]) < 0) {
			rf__format(err, errlen, "header key %s: '%.60s' is not one or six "
			           "distances of 0 or more", key, v);
			return RF_EFORMAT;
		}
		rf__header_probe_key(key, sizeof(key), i, RF_KEY_PROBE_IMPORTANCE);
		if ((v = rf_header_get(h, key)) &&
		    (rf__scan_floats(v, &b->importance[i], 1) < 0)) {
			rf__format(err, errlen, "header key %s: '%.60s' is not a number", key, v);
			return RF_EFORMAT;
		}
	}
	rf_blend_order(b);
	return n;
}

/* The probe's influence at p before the smoothstep: the least over its
 * faces of sat(d / blend), a face without a blend distance 1 where p is
 * inside; -1 outside the box (or for a p that is not finite).  *near is
 * set when p lies within some face's blend distance.  An oriented box
 * measures in its own frame; a sphere by the distance to its surface,
 * with the widest face's blend distance, as HDRP's sphere has one. */
static float
influence(const struct rf_probe *b, const float *blend, const float p[3], int *near)
{
	float w = 1.0f, q[3];
	int a;

	*near = 0;
	if (b->shape == RF_SHAPE_SPHERE) {
		float o[3], r = 0.5f * (b->box_max[0] - b->box_min[0]), d, bf = 0.0f;

		for (a = 0; a < 3; a++)
			o[a] = p[a] - (0.5f * b->box_min[a] + 0.5f * b->box_max[a]);
		for (a = 0; a < 6; a++)
			bf = blend[a] > bf ? blend[a] : bf;
		d = r - sqrtf(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
		if (!(d >= 0.0f))
			return -1.0f;
		if (bf > 0.0f && d < bf) {
			*near = 1;
			w = d / bf;
		}
		return w;
	}
	if (b->rotated) {
		struct rf__frame f;

		rf__frame_of(&f, b->box_min, b->box_max, b->rotation);
		rf__frame_point_in(&f, p, q);
		p = q;
	}
	for (a = 0; a < 3; a++) {
		const float d[2] = { b->box_max[a] - p[a], p[a] - b->box_min[a] };
		int s;

		for (s = 0; s < 2; s++) {
			const float bf = blend[2 * a + s];

			if (!(d[s] >= 0.0f))
				return -1.0f;
			if (bf > 0.0f && d[s] < bf) {
				*near = 1;
				w = d[s] / bf < w ? d[s] / bf : w;
			}
		}
	}
	return w;
}

float
rf_blend_weights(const struct rf_blend *b, const float p[3], const float n[3],
                 float *weights)
{
	uint32_t i, k, used = 0;
	float sum = 0.0f;

	for (i = 0; i < b->nprobes; i++)
		weights[i] = 0.0f;
	for (k = 0; k < b->nprobes && sum < 1.0f; k++) {
		const uint32_t i0 = b->order[k];
		const struct rf_probe *pr = &b->probes[i0];
		int near;
		float w = influence(pr, b->face_blend[i0], p, &near);

		if (!(w >= 0.0f))
			continue; /* outside its box */
		if (b->max_probes && used == b->max_probes)
			break;
		w = w < 1.0f ? w * w * (3.0f - 2.0f * w) : 1.0f;
		/* HDRP's normal fade: within the blend distance of the faces, a
		 * surface turned away from the capture point (which the probe
		 * saw from behind, if at all) fades out, fully from n.l = 0.6,
		 * not at all below 0.2 */
		if (n && b->normal_fade && near) {
			float l[3] = { p[0] - pr->center[0], p[1] - pr->center[1],
				       p[2] - pr->center[2] };
			float len = sqrtf(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]), c, f;

			if (len > 0.0f) {
				c = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len;
				f = (0.6f - c) / 0.4f;
				w *= f < 0.0f ? 0.0f : f > 1.0f ? 1.0f : f;
			}
		}
		if (w > 1.0f - sum)
			w = 1.0f - sum;
		if (w > 0.0f) {
			weights[i0] = w;
			sum += w;
			used++;
		}
	}
	return 1.0f - sum;
}
