/*
 * The shading pass's probe blending, a row at a time: each pixel's
 * weights (rf_blend_weights), then for every probe after the first the
 * pixel's reflection box-projected with that probe's own box and read
 * from that probe's chain, all of a probe's reads of the row in one
 * batch, and the remainder read from the fallback.  The first probe's
 * reads are the pass's own, along the D that reflect-project found with
 * it (whatever its projection mode), so a frame whose pixels all lie in
 * the first probe alone costs only the weights.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/rgba_levels.h"
#include "envmap/rgba_levels_simd.h"
#include "probe/shape.h"
#include "shade/blend-pass.h"
#include "util/util.h"

/* One probe's reads of a row. */
struct batch {
	float *x, *y, *z, *lod;
	rf__v4 *rgb;
	uint32_t *pixel;
	size_t n;
};

struct rf__blend_pass {
	struct rf_blend blend;
	enum rf_blend_fallback fallback;
	/* the probes', [0] unused (the pass's own, first), and the sky's */
	struct rf__rgba_levels levels[RF_PROBES_MAX + 1];
	const struct rf__rgba_levels *first;
	int vector[RF_PROBES_MAX + 1], first_vector;
	enum rf_mapping mapping[RF_PROBES_MAX + 1];
	float steps[RF_PROBES_MAX + 1];
	struct rf__proxy proxy[RF_PROBES_MAX]; /* the shapes each probe's lookups leave by */
	size_t ncols;
	int nthreads;
	/* per thread: a batch per probe and one for the fallback, weights */
	struct batch *batches;
	float *weights;
};

static int
alloc_batch(struct batch *b, size_t n)
{
	b->x = malloc(n * sizeof(float));
	b->y = malloc(n * sizeof(float));
	b->z = malloc(n * sizeof(float));
	b->lod = malloc(n * sizeof(float));
	b->rgb = aligned_alloc(16, n * sizeof(rf__v4));
	b->pixel = malloc(n * sizeof(uint32_t));
	return b->x && b->y && b->z && b->lod && b->rgb && b->pixel ? 0 : RF_ENOMEM;
}

static void
free_batch(struct batch *b)
{
	free(b->x);
	free(b->y);
	free(b->z);
	free(b->lod);
	free(b->rgb);
	free(b->pixel);
}

void
rf__blend_pass_destroy(struct rf__blend_pass *bp)
{
	size_t i;

	if (!bp)
		return;
	for (i = 1; i <= bp->blend.nprobes && i < RF_PROBES_MAX + 1; i++)
		rf__rgba_levels_destroy(&bp->levels[i]);
	if (bp->batches)
		for (i = 0; i < (size_t)bp->nthreads * (RF_PROBES_MAX + 1); i++)
			free_batch(&bp->batches[i]);
	free(bp->batches);
	free(bp->weights);
	free(bp);
}

int
rf__blend_pass_create(struct rf__blend_pass **out, const struct rf_blend *b,
                      const rf_cubemap *const *envs, const enum rf_mapping *mappings,
                      const float *steps, enum rf_blend_fallback fallback,
                      const struct rf__rgba_levels *first, int first_vector,
                      int nthreads, size_t ncols)
{
	struct rf__blend_pass *bp;
	size_t i;
	int rc;

	*out = NULL;
	if (!(bp = calloc(1, sizeof(*bp))))
		return RF_ENOMEM;
	bp->blend = *b;
	bp->fallback = fallback;
	bp->first = first;
	bp->first_vector = first_vector;
	bp->ncols = ncols;
	bp->nthreads = nthreads;
	for (i = 0; i <= b->nprobes; i++) {
		if (i < b->nprobes)
			bp->proxy[i] = rf__proxy_of_probe(&b->probes[i]);
		if (i == b->nprobes && fallback != RF_BLEND_SKY)
			break;
		bp->mapping[i] = mappings[i];
		bp->steps[i] = steps[i];
		if (i == 0)
			continue;
		if ((rc = rf__rgba_levels_from_cube(&bp->levels[i], envs[i])) < 0) {
			bp->blend.nprobes = (uint32_t)i - 1;
			rf__blend_pass_destroy(bp);
			return rc;
		}
		bp->vector[i] = rf__rgba_levels_simd_usable(&bp->levels[i]);
		if (i < b->nprobes && b->probes[i].rotated)
			rf__rgba_levels_turn(&bp->levels[i], b->probes[i].rotation);
	}
	bp->batches = calloc((size_t)nthreads * (RF_PROBES_MAX + 1), sizeof(*bp->batches));
	bp->weights = malloc((size_t)nthreads * (RF_PROBES_MAX + 1) * ncols * sizeof(float));
	if (!bp->batches || !bp->weights) {
		rf__blend_pass_destroy(bp);
		return RF_ENOMEM;
	}
	for (i = 0; i < (size_t)nthreads * (RF_PROBES_MAX + 1); i++)
		if ((rc = alloc_batch(&bp->batches[i], ncols)) < 0) {
			rf__blend_pass_destroy(bp);
			return rc;
		}
	*out = bp;
	return 0;
}

uint32_t
rf__blend_pass_nprobes(const struct rf__blend_pass *bp)
{
	return bp->blend.nprobes;
}

static void
add(struct batch *b, uint32_t pixel, const float d[3], float lod)
{
	if (!isfinite(d[0]) || !isfinite(d[1]) || !isfinite(d[2]))
		return; /* reads black, as the pass's own reads do */
	b->x[b->n] = d[0];
	b->y[b->n] = d[1];
	b->z[b->n] = d[2];
	b->lod[b->n] = lod;
	b->pixel[b->n++] = pixel;
}

float
rf__blend_pixel_weights(const struct rf_blend *b, enum rf_blend_fallback fallback,
                        const float *p, const int *ch, float *w)
{
	const uint32_t np = b->nprobes;
	const float pos[3] = { p[ch[RF__BLEND_PX]], p[ch[RF__BLEND_PX + 1]],
		               p[ch[RF__BLEND_PX + 2]] };
	float n[3], rest, sum = 0.0f;
	const float *np3 = NULL;
	uint32_t k;

	if (ch[RF__BLEND_NX] >= 0) {
		n[0] = p[ch[RF__BLEND_NX]];
		n[1] = p[ch[RF__BLEND_NX + 1]];
		n[2] = p[ch[RF__BLEND_NX + 2]];
		np3 = n;
	}
	rest = rf_blend_weights(b, pos, np3, w);
	if (fallback == RF_BLEND_NONE) {
		for (k = 0; k < np; k++)
			sum += w[k];
		for (k = 0; k < np && sum > 0.0f; k++)
			w[k] /= sum;
		rest = 0.0f;
	}
	w[np] = rest;
	return rest;
}

const float *
rf__blend_pass_row(const struct rf__blend_pass *bp, int thread, const float *in,
                   size_t in_ncomp, const int *ch, const float *mask, rf__v4 *mirror)
{
	const uint32_t np = bp->blend.nprobes, stride = np + 1;
	struct batch *batches = bp->batches + (size_t)thread * (RF_PROBES_MAX + 1);
	float *weights = bp->weights + (size_t)thread * (RF_PROBES_MAX + 1) * bp->ncols;
	size_t x, i;
	uint32_t k;

	for (k = 0; k <= np; k++)
		batches[k].n = 0;
	for (x = 0; x < bp->ncols; x++) {
		const float *p = in + x * in_ncomp;
		const float pos[3] = { p[ch[RF__BLEND_PX]], p[ch[RF__BLEND_PX + 1]],
			               p[ch[RF__BLEND_PX + 2]] };
		const float r[3] = { p[ch[RF__BLEND_RX]], p[ch[RF__BLEND_RX + 1]],
			             p[ch[RF__BLEND_RX + 2]] };
		float *w = weights + x * stride, reff;
		const float rest = rf__blend_pixel_weights(&bp->blend, bp->fallback, p, ch, w);

		if (!(mask[x] > 0.0f))
			continue;
		reff = p[ch[RF__BLEND_REFF]];
		for (k = 1; k < np; k++) {
			float d[3] = { r[0], r[1], r[2] }, t, reach;

			if (!(w[k] > 0.0f))
				continue;
			if (bp->blend.probes[k].box_projection &&
			    rf__proxy_exit(&bp->proxy[k], pos, r, &t) == 0)
				rf__lookup_from_hit(&bp->proxy[k].box, pos, r, t, d, &reach);
			add(&batches[k], (uint32_t)x, d,
			    rf_roughness_to_lod(bp->mapping[k], bp->steps[k], reff));
		}
		/* the fallback: the sky, or probe 0 with no parallax */
		if (rest > 0.0f) {
			const uint32_t f = bp->fallback == RF_BLEND_SKY ? np : 0;

			add(&batches[np], (uint32_t)x, r,
			    rf_roughness_to_lod(bp->mapping[f], bp->steps[f], reff));
		}
	}
	for (k = 1; k <= np; k++) {
		struct batch *b = &batches[k];

		if (!b->n)
			continue;
		if (k < np || bp->fallback == RF_BLEND_SKY)
			rf__rgba_levels_fetch_many(&bp->levels[k], bp->vector[k], b->n, b->x, b->y,
			                           b->z, b->lod, b->rgb);
		else
			rf__rgba_levels_fetch_many(bp->first, bp->first_vector, b->n, b->x, b->y,
			                           b->z, b->lod, b->rgb);
	}
	/* probe 0's share of the pass's own read, then the others' */
	for (x = 0; x < bp->ncols; x++)
		if (mask[x] > 0.0f)
			mirror[x] *= weights[x * stride];
	for (k = 1; k <= np; k++) {
		const struct batch *b = &batches[k];

		for (i = 0; i < b->n; i++) {
			const uint32_t px = b->pixel[i];

			mirror[px] += weights[px * stride + k] * b->rgb[i];
		}
	}
	return weights;
}
