/* "-m mode:key=value:key=value": parameters checked against the table. */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "util/util.h"
#include "reflect/plugin.h"

static void
format_range(char *buf, size_t size, const struct rf_param *q)
{
	if (q->flags & RF_PARAM_STRING)
		rf__format(buf, size, "a string");
	else if (q->flags & RF_PARAM_CHOICE)
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

/* A decimal number as strtod reads it, without its hexadecimal, inf and
 * nan forms or surrounding blanks. */
static int
parse_number(const char *v, double *out)
{
	char *end;

	if (!((*v >= '0' && *v <= '9') || *v == '-' || *v == '+' || *v == '.') ||
	    strpbrk(v, "xX"))
		return -1;
	errno = 0;
	*out = strtod(v, &end);
	if (end == v || *end || errno == ERANGE || !isfinite(*out))
		return -1;
	return 0;
}

static const struct rf_param *
find_param(const struct rf_plugin *p, const char *name)
{
	uint32_t i;

	for (i = 0; i < p->nparams; i++)
		if (!strcmp(p->params[i].name, name))
			return &p->params[i];
	return NULL;
}

static void
unknown_param(const struct rf_plugin *p, const char *name, char *err, size_t errlen)
{
	char known[512] = "";
	size_t k = 0;
	uint32_t i;

	const char *names[256];
	int close;

	for (i = 0; i < p->nparams && k + 2 < sizeof(known); i++)
		k += (size_t)snprintf(known + k, sizeof(known) - k, "%s%s",
		                      i ? ", " : "", p->params[i].name);
	for (i = 0; i < p->nparams && i < 256; i++)
		names[i] = p->params[i].name;
	close = rf__closest(name, names, i);
	if (close >= 0)
		rf__format(err, errlen, "mode '%s' has no parameter '%s'; did you mean "
		           "'%s'? (it has: %s)", p->name, name, names[close], known);
	else if (p->nparams)
		rf__format(err, errlen, "mode '%s' has no parameter '%s' (it has: %s)",
		           p->name, name, known);
	else
		rf__format(err, errlen, "mode '%s' has no parameter '%s' (it takes none)",
		           p->name, name);
}

/* The strings of RF_PARAM_STRING parameters, value k at strings[k - 1]:
 * a value is a double, and so a string given on a command line (or a
 * default) is kept here, for the process's life (a tool parses its -m
 * once). */
static char **strings;
static size_t nstrings;
static pthread_mutex_t strings_mu = PTHREAD_MUTEX_INITIALIZER;

static int
keep_string(const char *v, double *out)
{
	char **grown, *copy = strdup(v);
	int rc = 0;

	if (!copy)
		return RF_ENOMEM;
	pthread_mutex_lock(&strings_mu);
	if (!(grown = realloc(strings, (nstrings + 1) * sizeof(*strings)))) {
		free(copy);
		rc = RF_ENOMEM;
	} else {
		strings = grown;
		strings[nstrings++] = copy;
		*out = (double)nstrings;
	}
	pthread_mutex_unlock(&strings_mu);
	return rc;
}

const char *
rf_plugin_param_string(const struct rf_param *q, double value)
{
	const char *s = NULL;

	pthread_mutex_lock(&strings_mu);
	if (value >= 1 && value <= (double)nstrings && value == floor(value))
		s = strings[(size_t)value - 1];
	pthread_mutex_unlock(&strings_mu);
	return s ? s : q && q->choices ? q->choices : "";
}

/* One "key=value" item; q is its parameter. */
static int
parse_value(const struct rf_plugin *p, const struct rf_param *q, const char *v,
            double *out, char *err, size_t errlen)
{
	char range[160];

	if (q->flags & RF_PARAM_STRING) {
		if (keep_string(v, out) < 0) {
			rf__format(err, errlen, "%s", rf_strerror(RF_ENOMEM));
			return RF_ENOMEM;
		}
		return 0;
	}
	format_range(range, sizeof(range), q);
	if (q->flags & RF_PARAM_CHOICE) {
		if (parse_choice(q, v, out) < 0) {
			rf__format(err, errlen, "mode '%s': parameter '%s' must be %s, "
			           "not '%s'", p->name, q->name, range, v);
			return RF_EINVAL;
		}
		return 0;
	}
	if (q->flags & RF_PARAM_BOOL) {
		if (parse_bool(v, out) < 0) {
			rf__format(err, errlen, "mode '%s': parameter '%s' must be 0 or 1 "
			           "(or off/on, no/yes, false/true), not '%s'", p->name,
			           q->name, v);
			return RF_EINVAL;
		}
		return 0;
	}
	if (parse_number(v, out) < 0) {
		rf__format(err, errlen, "mode '%s': parameter '%s' needs a number (%s), "
		           "not '%s'", p->name, q->name, range, v);
		return RF_EINVAL;
	}
	if ((q->flags & RF_PARAM_INTEGER) && *out != floor(*out)) {
		rf__format(err, errlen, "mode '%s': parameter '%s' must be %s, not %s",
		           p->name, q->name, range, v);
		return RF_EINVAL;
	}
	if (*out < q->min || *out > q->max) {
		rf__format(err, errlen, "mode '%s': parameter '%s' is %s, out of its "
		           "range (%s)", p->name, q->name, v, range);
		return RF_EINVAL;
	}
	return 0;
}

int
rf_plugin_parse_params(const struct rf_plugin *p, const char *spec,
                       double *values, char *err, size_t errlen)
{
	char item[512];
	unsigned char *given;
	const char *s = spec ? spec : "";
	uint32_t i;
	int rc = 0;

	for (i = 0; i < p->nparams && !rc; i++) {
		const struct rf_param *q = &p->params[i];

		values[i] = q->def;
		/* a string's default is kept too, so that its value names it */
		if (q->flags & RF_PARAM_STRING)
			rc = keep_string(q->choices ? q->choices : "", &values[i]);
	}
	if (rc < 0) {
		rf__format(err, errlen, "%s", rf_strerror(rc));
		return rc;
	}
	if (!(given = calloc(p->nparams + 1, 1))) {
		rf__format(err, errlen, "%s", rf_strerror(RF_ENOMEM));
		return RF_ENOMEM;
	}
	while (*s && !rc) {
		size_t len = strcspn(s, ":");
		const struct rf_param *q;
		char *eq;
		double v;

		if (len == 0 || (s[len] == ':' && !s[len + 1])) {
			/* "a::b", ":a", "a:": a slip, not "no parameter" */
			rf__format(err, errlen, "mode '%s': an empty parameter in '%.200s' (a "
			           "':' with nothing %s it); remove the ':'", p->name, spec,
			           len == 0 ? "before" : "after");
			rc = RF_EINVAL;
			break;
		}
		if (len >= sizeof(item)) {
			rf__format(err, errlen, "mode '%s': parameter '%.40s...' is too "
			           "long", p->name, s);
			rc = RF_EINVAL;
			break;
		}
		memcpy(item, s, len);
		item[len] = '\0';
		s += len + (s[len] == ':');
		if ((eq = strchr(item, '=')))
			*eq = '\0';
		if (!(q = find_param(p, item))) {
			unknown_param(p, item, err, errlen);
			rc = RF_EINVAL;
			break;
		}
		if (!eq) {
			rf__format(err, errlen, "mode '%s': parameter '%s' has no value "
			           "(write %s=VALUE)", p->name, item, item);
			rc = RF_EINVAL;
			break;
		}
		i = (uint32_t)(q - p->params);
		if (given[i]++) {
			rf__format(err, errlen, "mode '%s': parameter '%s' is given twice",
			           p->name, q->name);
			rc = RF_EINVAL;
			break;
		}
		if ((rc = parse_value(p, q, eq + 1, &v, err, errlen)) == 0)
			values[i] = v;
	}
	free(given);
	return rc;
}
