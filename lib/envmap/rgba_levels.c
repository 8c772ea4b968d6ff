/* Building a cube's levels as RGBA vectors, which the prefilter and the
 * shading pass sample. */
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "envmap/rgba_levels.h"

int
rf__rgba_levels_from_cube(struct rf__rgba_levels *p, const rf_cubemap *c)
{
	size_t l, total = 0, i;
	int f;

	memset(p, 0, sizeof(*p));
	p->nlevels = rf_cubemap_levels(c);
	for (l = 0; l < p->nlevels; l++) {
		p->size[l] = rf_cubemap_level_size(c, l);
		p->face_stride[l] = (p->size[l] + 2) * (p->size[l] + 2);
		total += 6 * p->face_stride[l];
	}
	if (!(p->data = rf__alloc_big(total * sizeof(rf__v4), 0)))
		return RF_ENOMEM;
	total = 0;
	for (l = 0; l < p->nlevels; l++) {
		p->level[l] = p->data + total;
		p->lvl_scale[l] = (float)p->size[l];
		p->lvl_base[l] = (int32_t)total; /* within range where the kernels run */
		p->lvl_face[l] = (int32_t)p->face_stride[l];
		p->lvl_row[l] = (int32_t)(p->size[l] + 2);
		for (f = 0; f < 6; f++) {
			const float *src = rf__cubemap_padded_face(c, l, f);
			rf__v4 *dst = p->level[l] + (size_t)f * p->face_stride[l];

			for (i = 0; i < p->face_stride[l]; i++) {
				rf__v4 t = { src[3 * i], src[3 * i + 1], src[3 * i + 2], 0.0f };

				dst[i] = t;
			}
		}
		total += 6 * p->face_stride[l];
	}
	return 0;
}

void
rf__rgba_levels_turn(struct rf__rgba_levels *p, const float rotation[9])
{
	p->turned = rotation != NULL;
	if (rotation)
		memcpy(p->turn, rotation, sizeof(p->turn));
}

void
rf__rgba_levels_destroy(struct rf__rgba_levels *p)
{
	free(p->data);
	p->data = NULL;
}
