/*
 * Which channels a channel-agnostic mode (accumulate, filter) works on:
 * those named, or by default what a shade pass writes, every spec.*
 * channel and R G B (not the .se channels of an earlier accumulation).
 */
#include <stdlib.h>
#include <string.h>

#include "plugin/plugin-internal.h"

static int
by_default(const char *name)
{
	size_t len = strlen(name);

	if (len > 3 && !strcmp(name + len - 3, ".se"))
		return 0;
	return !strncmp(name, "spec.", 5) || !strcmp(name, "R") || !strcmp(name, "G") ||
	       !strcmp(name, "B");
}

int
rf__choose_values(const rf_header *in, const char *list, const char *verb, int *cols,
                  size_t *n, char *err, size_t errlen)
{
	char *copy, *name, *save = NULL;
	size_t i;

	*n = 0;
	if (!list) {
		for (i = 0; i < rf_header_nchannels(in) && *n < RF_CHANNELS_MAX; i++)
			if (by_default(rf_header_channel(in, i)))
				cols[(*n)++] = (int)i;
		if (!*n) {
			rf__format(err, errlen, "the stream has no spec.* or R G B channel to "
			           "%s; name the channels with --channels", verb);
			return RF_ECHANNEL;
		}
		return 0;
	}
	if (!(copy = strdup(list)))
		return RF_ENOMEM;
	for (name = strtok_r(copy, ", ", &save); name; name = strtok_r(NULL, ", ", &save)) {
		int c = rf_header_find_channel(in, name);

		if (c < 0) {
			rf__format(err, errlen, "the stream has no channel '%.63s' to %s "
			           "(reflect-info lists its channels)", name, verb);
			free(copy);
			return RF_ECHANNEL;
		}
		for (i = 0; i < *n; i++)
			if (cols[i] == c)
				break;
		if (i == *n && *n < RF_CHANNELS_MAX)
			cols[(*n)++] = c; /* a channel named twice counts once */
	}
	free(copy);
	if (!*n) {
		rf__format(err, errlen, "--channels names no channel");
		return RF_EINVAL;
	}
	return 0;
}
