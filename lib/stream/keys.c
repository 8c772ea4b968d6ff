/*
 * The header keys the tools share.  A key's name and the form of its
 * value live here, so that reflect-gbuffer's PROBE_BOX and the one
 * reflect-shade reads are one word: numbers as %.9g (a float's value
 * exactly, and back to the same float), separated by spaces.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stream/stream-internal.h"

int
rf__header_set_numbers(rf_header *h, const char *key, const double *v, size_t n)
{
	char buf[512];
	size_t i, k = 0;

	for (i = 0; i < n && k < sizeof(buf); i++)
		k += (size_t)snprintf(buf + k, sizeof(buf) - k, "%s%.9g", i ? " " : "", v[i]);
	if (k >= sizeof(buf))
		return RF_EINVAL;
	return rf_header_set(h, key, buf);
}
