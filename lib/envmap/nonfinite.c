/*
 * The NaN and infinite values an environment reader meets (and those past
 * RF__TEXEL_MAX): each is made 0 so that a cube is always finite,
 * counted, and the first is kept with its place, for the loader that
 * refuses the file (or, asked to repair it, says how many it replaced).
 */
#include <float.h>
#include <stdio.h>

#include "envmap/envmap-internal.h"

void
rf__nonfinite_note(struct rf__nonfinite *nf, size_t level, int face, size_t x, size_t y,
                   int channel, float value)
{
	if (!nf)
		return;
	if (!nf->count++) {
		nf->level = level;
		nf->face = face;
		nf->x = x;
		nf->y = y;
		nf->channel = channel;
		nf->value = value;
	}
}

void
rf__nonfinite_where(const struct rf__nonfinite *nf, char *buf, size_t len)
{
	static const char *const faces[6] = { "+X", "-X", "+Y", "-Y", "+Z", "-Z" };
	static const char *const channels[4] = { "R", "G", "B", "A" };
	const char *ch = nf->channel >= 0 && nf->channel < 4 ? channels[nf->channel] : "?";
	char v[64], where[64];

	if (nf->value != nf->value || nf->value > FLT_MAX || nf->value < -FLT_MAX)
		snprintf(v, sizeof(v), "%s", nf->value != nf->value ? "nan"
		                             : nf->value > 0.0f ? "inf" : "-inf");
	else
		snprintf(v, sizeof(v), "%g, past a quarter of the float range",
		         (double)nf->value);
	if (nf->face < 0)
		snprintf(where, sizeof(where), "pixel (%zu, %zu)", nf->x, nf->y);
	else
		snprintf(where, sizeof(where), "level %zu, face %s, texel (%zu, %zu)", nf->level,
		         faces[nf->face % 6], nf->x, nf->y);
	rf__format(buf, len, "%s: %s is %s", where, ch, v);
}
