/* Numbers in text: header values and option arguments. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "util/util.h"

int
rf__scan_doubles(const char *s, double *out, int n)
{
	char *end;
	int i;

	for (i = 0; i < n; i++) {
		while (*s == ' ' || (i && *s == ','))
			s++;
		errno = 0;
		out[i] = strtod(s, &end);
		if (end == s || errno == ERANGE || !isfinite(out[i]))
			return -1;
		s = end;
	}
	while (*s == ' ')
		s++;
	return *s ? -1 : 0;
}

int
rf__scan_floats(const char *s, float *out, int n)
{
	double v[32];
	int i;

	if (n > 32 || rf__scan_doubles(s, v, n) < 0)
		return -1;
	/* finite as a double, infinite as a float (1e39) is no number here */
	for (i = 0; i < n; i++)
		if (fabs(v[i]) > FLT_MAX)
			return -1;
	for (i = 0; i < n; i++)
		out[i] = (float)v[i];
	return 0;
}
