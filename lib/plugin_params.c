/* "-m mode:key=value:key=value": parameters checked against the table. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "internal.h"
#include "reflect/plugin.h"

static void
format_range(char *buf, size_t size, const struct rf_param *q)
{
	if (q->flags & RF_PARAM_CHOICE)
		rf__format(buf, size, "one of %s", q->choices);
	else if (q->flags & RF_PARAM_BOOL)
		rf__format(buf, size, "0 or 1");
	else if (isinf(q->min) && isinf(q->max))
		rf__format(buf, size, "any %s", q->flags & RF_PARAM_INTEGER
		           ? "integer" : "number");
	else if (isinf(q->max))
		rf__format(buf, size, "%s%s%g", q->flags & RF_PARAM_INTEGER
		           ? "an integer " : "", ">= ", q->min);
	else if (isinf(q->min))
		rf__format(buf, size, "%s%s%g", q->flags & RF_PARAM_INTEGER
		           ? "an integer " : "", "<= ", q->max);
	else
		rf__format(buf, size, "%sin [%g, %g]", q->flags & RF_PARAM_INTEGER
		           ? "an integer " : "", q->min, q->max);
}

static int
parse_choice(const struct rf_param *q, const char *v, double *out)
{
	const char *c = q->choices;
	size_t n = strlen(v);
	int i = 0;

	while (c) {
		size_t len = strcspn(c, "|");

		if (len == n && !strncmp(c, v, n)) {
			*out = i;
			return 0;
		}
		c = c[len] ? c + len + 1 : NULL;
		i++;
	}
	return -1;
}

static int
parse_bool(const char *v, double *out)
{
	static const char *const yes[] = { "1", "on", "yes", "true", NULL };
	static const char *const no[] = { "0", "off", "no", "false", NULL };
	size_t i;

	for (i = 0; yes[i]; i++)
		if (!strcasecmp(v, yes[i]))
			return *out = 1, 0;
	for (i = 0; no[i]; i++)
		if (!strcasecmp(v, no[i]))
			return *out = 0, 0;
	return -1;
}

int
rf_plugin_parse_params(const struct rf_plugin *p, const char *spec,
                       double *values, char *err, size_t errlen)
{
	char item[512];
	unsigned char given[256] = { 0 };
	const char *s = spec ? spec : "";
	uint32_t i;

	for (i = 0; i < p->nparams; i++)
		values[i] = p->params[i].def;
	while (*s) {
		size_t len = strcspn(s, ":");
		const struct rf_param *q = NULL;
		char *eq, *end, range[128];
		double v;

		if (len == 0) {
			s++;
			continue;
		}
		if (len >= sizeof(item)) {
			rf__format(err, errlen, "mode '%s': parameter '%.40s...' is too "
			           "long", p->name, s);
			return RF_EINVAL;
		}
		memcpy(item, s, len);
		item[len] = '\0';
		s += len + (s[len] == ':');
		if (!(eq = strchr(item, '='))) {
			rf__format(err, errlen, "mode '%s': parameter '%s' has no value "
			           "(write %s=VALUE)", p->name, item, item);
			return RF_EINVAL;
		}
		*eq = '\0';
		for (i = 0; i < p->nparams; i++)
			if (!strcmp(p->params[i].name, item))
				q = &p->params[i];
		if (!q) {
			char known[256] = "";
			size_t k = 0;

			for (i = 0; i < p->nparams && k + 2 < sizeof(known); i++)
				k += (size_t)snprintf(known + k, sizeof(known) - k, "%s%s",
				                      i ? ", " : "", p->params[i].name);
			if (p->nparams)
				rf__format(err, errlen, "mode '%s' has no parameter '%s' "
				           "(it has: %s)", p->name, item, known);
			else
				rf__format(err, errlen, "mode '%s' has no parameter '%s' "
				           "(it takes none)", p->name, item);
			return RF_EINVAL;
		}
		i = (uint32_t)(q - p->params);
		if (i < sizeof(given) && given[i]++) {
			rf__format(err, errlen, "mode '%s': parameter '%s' is given twice",
			           p->name, q->name);
			return RF_EINVAL;
		}
		format_range(range, sizeof(range), q);
		if (q->flags & RF_PARAM_CHOICE) {
			if (parse_choice(q, eq + 1, &v) < 0) {
				rf__format(err, errlen, "mode '%s': parameter '%s' must be "
				           "%s, not '%s'", p->name, q->name, range, eq + 1);
				return RF_EINVAL;
			}
			values[i] = v;
			continue;
		}
		if (q->flags & RF_PARAM_BOOL) {
			if (parse_bool(eq + 1, &v) < 0) {
				rf__format(err, errlen, "mode '%s': parameter '%s' must be "
				           "0 or 1, not '%s'", p->name, q->name, eq + 1);
				return RF_EINVAL;
			}
			values[i] = v;
			continue;
		}
		errno = 0;
		v = strtod(eq + 1, &end);
		if (end == eq + 1 || *end || errno == ERANGE || !isfinite(v)) {
			rf__format(err, errlen, "mode '%s': parameter '%s' needs a "
			           "number (%s), not '%s'", p->name, q->name, range, eq + 1);
			return RF_EINVAL;
		}
		if ((q->flags & RF_PARAM_INTEGER) && v != floor(v)) {
			rf__format(err, errlen, "mode '%s': parameter '%s' must be %s, "
			           "not %s", p->name, q->name, range, eq + 1);
			return RF_EINVAL;
		}
		if (v < q->min || v > q->max) {
			rf__format(err, errlen, "mode '%s': parameter '%s' is %s, out of "
			           "its range (%s)", p->name, q->name, eq + 1, range);
			return RF_EINVAL;
		}
		values[i] = v;
	}
	return 0;
}
