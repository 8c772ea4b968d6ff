/*
 * libFuzzer harness for the probe keys of a stream's header: the first
 * probe (rf_probe_resolve), the list of every probe (rf_probe_list_read)
 * and the blend of several (rf_blend_read, rf_blend_order,
 * rf_blend_weights), as reflect-shade reads them from every frame.
 *
 * The input is a stream; the header of each frame that parses is read
 * for its probes.  A refusal must come with a message of printable text;
 * what is taken must be usable: boxes that are not empty, finite centres,
 * and, at points in and around every box, weights in [0, 1] that, with
 * the fallback's share, sum to 1.
 *
 * make fuzz builds and runs it; make check replays its corpus (see
 * tests/fuzz/README).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reflect/plugin.h"
#include "reflect/reflect.h"
#include "reflect/shading.h"

#define HARNESS "fuzz-probes"
#include "harness.h"

/* Rows orthonormal to the key's tolerance, and no reflection. */
static int
rotation(const float *m)
{
	int i, j;

	for (i = 0; i < 3; i++)
		for (j = 0; j < 3; j++) {
			double d = (double)m[3 * i] * m[3 * j] + (double)m[3 * i + 1] * m[3 * j + 1] +
			           (double)m[3 * i + 2] * m[3 * j + 2];

			if (!(fabs(d - (i == j)) <= 1e-3))
				return 0;
		}
	return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
	           m[2] * (m[3] * m[7] - m[4] * m[6]) > 0.0f;
}

static void
check_probe(const struct rf_probe *p)
{
	int i;

	for (i = 0; i < 3; i++) {
		check(isfinite(p->box_min[i]) && isfinite(p->box_max[i]), "a box not finite");
		check(p->box_min[i] < p->box_max[i], "an empty box taken");
		check(isfinite(p->center[i]), "a centre not finite");
	}
	check(p->shape == RF_SHAPE_BOX || p->shape == RF_SHAPE_SPHERE, "an unknown shape taken");
	check(p->proxy_shape <= RF_SHAPE_INFINITE, "an unknown proxy taken");
	check(!p->rotated || rotation(p->rotation), "a rotation that is none taken");
	check(!p->proxy_rotated || rotation(p->proxy_rotation),
	      "a proxy rotation that is none taken");
}

/* Points at the corners, the centre and just outside every box. */
static void
check_weights(struct rf_blend *b, int normal_fade)
{
	static const float t[] = { -0.25f, 0.0f, 0.01f, 0.5f, 0.99f, 1.0f, 1.25f };
	const float n[3] = { 0.0f, 1.0f, 0.0f };
	float w[RF_PROBES_MAX];
	uint32_t k, j, i, a;

	b->normal_fade = normal_fade;
	for (k = 0; k < b->nprobes; k++)
		for (i = 0; i < sizeof(t) / sizeof(t[0]); i++)
			for (j = 0; j < 3; j++) {
				const struct rf_probe *p = &b->probes[k];
				float pt[3], sum, fallback;

				for (a = 0; a < 3; a++) {
					float s = a == j ? t[i] : 0.5f;

					pt[a] = p->box_min[a] + s * (p->box_max[a] - p->box_min[a]);
				}
				fallback = rf_blend_weights(b, pt, normal_fade ? n : NULL, w);
				check(isfinite(fallback) && fallback >= 0.0f && fallback <= 1.0f,
				      "the fallback's share outside [0, 1]");
				sum = fallback;
				for (a = 0; a < b->nprobes; a++) {
					check(isfinite(w[a]) && w[a] >= 0.0f && w[a] <= 1.0f,
					      "a weight outside [0, 1]");
					sum += w[a];
				}
				check(fabsf(sum - 1.0f) < 1e-4f, "the weights do not sum to 1");
			}
}

static void
probes_of(const rf_header *h)
{
	struct rf_probe first, list[RF_PROBES_MAX];
	float blend[RF_PROBES_MAX];
	struct rf_blend *b;
	char err[1024];
	int rc, n, i;

	err[0] = '\0';
	rc = rf_probe_resolve(&first, h, NULL, NULL, NULL, err, sizeof(err));
	if (rc < 0)
		check_message(err);
	else
		check_probe(&first);
	n = rf_probe_list_read(list, blend, RF_PROBES_MAX, h);
	check(n <= RF_PROBES_MAX, "more probes than asked for");
	for (i = 0; i < n; i++) {
		check_probe(&list[i]);
		check(isfinite(blend[i]) && blend[i] >= 0.0f, "a blend distance below 0");
	}
	if (!(b = calloc(1, sizeof(*b))))
		return;
	err[0] = '\0';
	n = rf_blend_read(b, h, err, sizeof(err));
	if (n < 0) {
		check_message(err);
	} else {
		check((uint32_t)n == b->nprobes && n <= RF_PROBES_MAX, "a count not the list's");
		for (i = 0; i < n; i++) {
			int f;

			check_probe(&b->probes[i]);
			for (f = 0; f < 6; f++)
				check(isfinite(b->face_blend[i][f]) && b->face_blend[i][f] >= 0.0f,
				      "a face's blend distance below 0");
			check(isfinite(b->importance[i]), "an importance not finite");
		}
		b->max_probes = 0;
		rf_blend_order(b);
		check_weights(b, 0);
		check_weights(b, 1);
		b->max_probes = 1;
		check_weights(b, 0);
	}
	free(b);
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	const rf_header *h;
	rf_reader *r;
	FILE *fp;
	int frames = 0;

	if (!size || !(fp = fmemopen((void *)data, size, "rb")))
		return 0;
	if (rf_reader_open(&r, fp, "fuzz", NULL) < 0) {
		fclose(fp);
		return 0;
	}
	/* headers only (the reader skips the rows): rows are fuzz-header's */
	while (frames++ < 4 && rf_reader_next_frame(r, &h) == 1)
		probes_of(h);
	rf_reader_close(r);
	fclose(fp);
	return 0;
}
