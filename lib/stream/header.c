/* The stream header as a value: size, channels and the lines it carries. */
#include <ctype.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stream/stream-internal.h"

struct rf_header {
	size_t ncols, nrows;
	enum rf_format format;
	int big_endian;
	size_t nchan;
	char **chan;
	size_t nlines;
	char **lines;
};

static const char *const reserved_keys[] = {
	"NCOLS", "NROWS", "NCOMP", "CHANNELS", "BigEndian", "FORMAT",
	"FAILED", "FAILED_ROWS", /* a failed stream's trailer (rf_writer_fail) */
	NULL
};

int
rf__header_key_reserved(const char *key, size_t len)
{
	const char *const *k;

	for (k = reserved_keys; *k; k++)
		if (strlen(*k) == len && !memcmp(*k, key, len))
			return 1;
	return 0;
}

/* Length of the key of a KEY=value line, 0 for a free line. */
static size_t
key_length(const char *line)
{
	size_t i;

	if (!isalpha((unsigned char)line[0]))
		return 0;
	for (i = 1; line[i] && line[i] != '='; i++)
		if (!isalnum((unsigned char)line[i]) && line[i] != '_' && line[i] != '.')
			return 0;
	return line[i] == '=' ? i : 0;
}

int
rf_header_create(rf_header **h)
{
	return (*h = calloc(1, sizeof(rf_header))) ? 0 : RF_ENOMEM;
}

void
rf_header_destroy(rf_header *h)
{
	size_t i;

	if (!h)
		return;
	for (i = 0; i < h->nchan; i++)
		free(h->chan[i]);
	for (i = 0; i < h->nlines; i++)
		free(h->lines[i]);
	free(h->chan);
	free(h->lines);
	free(h);
}

int
rf_header_dup(rf_header **copy, const rf_header *h)
{
	rf_header *d;
	size_t i;

	*copy = NULL;
	if (rf_header_create(&d) < 0)
		return RF_ENOMEM;
	d->ncols = h->ncols;
	d->nrows = h->nrows;
	d->format = h->format;
	d->big_endian = h->big_endian;
	for (i = 0; i < h->nchan; i++)
		if (rf_header_add_channel(d, h->chan[i]) < 0)
			goto fail;
	for (i = 0; i < h->nlines; i++)
		if (rf__header_push_line(d, h->lines[i]) < 0)
			goto fail;
	*copy = d;
	return 0;
fail:
	rf_header_destroy(d);
	return RF_ENOMEM;
}

size_t
rf_header_ncols(const rf_header *h)
{
	return h->ncols;
}

size_t
rf_header_nrows(const rf_header *h)
{
	return h->nrows;
}

int
rf_header_set_size(rf_header *h, size_t ncols, size_t nrows)
{
	size_t n;

	if (!ncols || !nrows || rf__mul3(ncols, nrows, sizeof(float), &n))
		return RF_ETOOBIG;
	h->ncols = ncols;
	h->nrows = nrows;
	return 0;
}

int
rf_header_big_endian(const rf_header *h)
{
	return h->big_endian;
}

enum rf_format
rf_header_format(const rf_header *h)
{
	return h->format;
}

void
rf__header_set_format(rf_header *h, enum rf_format format, int big_endian)
{
	h->format = format;
	h->big_endian = big_endian;
}

size_t
rf_header_nchannels(const rf_header *h)
{
	return h->nchan;
}

const char *
rf_header_channel(const rf_header *h, size_t i)
{
	return i < h->nchan ? h->chan[i] : NULL;
}

int
rf_header_find_channel(const rf_header *h, const char *name)
{
	size_t i;

	for (i = 0; i < h->nchan; i++)
		if (!strcmp(h->chan[i], name))
			return (int)i;
	return RF_ECHANNEL;
}

int
rf_channel_name_valid(const char *name)
{
	size_t n = strlen(name);
	size_t i;

	if (n == 0 || n > RF_CHANNEL_NAME_MAX)
		return 0;
	for (i = 0; i < n; i++)
		if (!isgraph((unsigned char)name[i]) || name[i] == ',' || name[i] == '=')
			return 0;
	return 1;
}

int
rf_header_add_channel(rf_header *h, const char *name)
{
	char **chan;
	char *copy;

	if (!rf_channel_name_valid(name) || rf_header_find_channel(h, name) >= 0)
		return RF_ECHANNEL;
	if (h->nchan >= RF_CHANNELS_MAX)
		return RF_ETOOBIG;
	if (!(chan = realloc(h->chan, (h->nchan + 1) * sizeof(*chan))))
		return RF_ENOMEM;
	h->chan = chan;
	if (!(copy = strdup(name)))
		return RF_ENOMEM;
	h->chan[h->nchan] = copy;
	return (int)h->nchan++;
}

int
rf_header_set_channels(rf_header *h, const char *names)
{
	char name[RF_CHANNEL_NAME_MAX + 1];
	const char *p = names;
	rf_header *t;
	size_t i, n;
	int rc = 0;

	/* Built aside, so that a bad list leaves the header as it was. */
	if (rf_header_create(&t) < 0)
		return RF_ENOMEM;
	while (*p) {
		while (*p == ' ' || *p == ',' || *p == '\t')
			p++;
		if (!*p)
			break;
		n = strcspn(p, " ,\t");
		if (n > RF_CHANNEL_NAME_MAX) {
			rc = RF_ECHANNEL;
			break;
		}
		memcpy(name, p, n);
		name[n] = '\0';
		if ((rc = rf_header_add_channel(t, name)) < 0)
			break;
		rc = 0;
		p += n;
	}
	if (!rc && !t->nchan)
		rc = RF_ECHANNEL;
	if (!rc) {
		for (i = 0; i < h->nchan; i++)
			free(h->chan[i]);
		free(h->chan);
		h->chan = t->chan;
		h->nchan = t->nchan;
		t->chan = NULL;
		t->nchan = 0;
	}
	rf_header_destroy(t);
	return rc;
}

static int
find_key(const rf_header *h, const char *key)
{
	size_t n = strlen(key);
	size_t i;

	for (i = h->nlines; i-- > 0;)
		if (!strncmp(h->lines[i], key, n) && h->lines[i][n] == '=')
			return (int)i;
	return -1;
}

const char *
rf_header_get(const rf_header *h, const char *key)
{
	int i = find_key(h, key);

	return i < 0 ? NULL : h->lines[i] + strlen(key) + 1;
}

int
rf_header_supersample(const rf_header *h, size_t *factor)
{
	const char *v = rf_header_get(h, RF_KEY_SUPERSAMPLE);
	unsigned long n = 1;
	char *end;

	*factor = 1;
	if (v) {
		errno = 0;
		n = strtoul(v, &end, 10);
		if (end == v || *end || errno || n < 1 || n > RF_SUPERSAMPLE_MAX ||
		    h->ncols % n || h->nrows % n)
			return RF_EFORMAT;
	}
	*factor = n;
	return 0;
}

int
rf_header_samples(const rf_header *h, uint64_t *samples)
{
	const char *v = rf_header_get(h, RF_KEY_SAMPLES);
	unsigned long long n = 1;
	char *end;

	*samples = 1;
	if (v) {
		/* digits only: strtoull would take a sign or leading spaces */
		if (*v < '0' || *v > '9')
			return RF_EFORMAT;
		errno = 0;
		n = strtoull(v, &end, 10);
		if (*end || errno || n < 1 || n > RF_SAMPLES_MAX)
			return RF_EFORMAT;
	}
	*samples = n;
	return 0;
}

int
rf_header_region(const rf_header *h, struct rf_region *r)
{
	const char *v = rf_header_get(h, RF_KEY_REGION);
	unsigned long long n[4];
	char *end;
	int i;

	r->x0 = r->y0 = 0;
	r->width = h->ncols;
	r->height = h->nrows;
	if (!v)
		return 0;
	for (i = 0; i < 4; i++) {
		/* digits only, one space between: strtoull takes signs too */
		if (*v < '0' || *v > '9')
			return RF_EFORMAT;
		errno = 0;
		n[i] = strtoull(v, &end, 10);
		if (errno || n[i] > RF_FRAME_SIDE_MAX || (*end != (i < 3 ? ' ' : '\0')))
			return RF_EFORMAT;
		v = end + (i < 3);
	}
	if (n[2] < 1 || n[3] < 1 || n[0] + h->ncols > n[2] || n[1] + h->nrows > n[3])
		return RF_EFORMAT;
	r->x0 = (size_t)n[0];
	r->y0 = (size_t)n[1];
	r->width = (size_t)n[2];
	r->height = (size_t)n[3];
	return 0;
}

int
rf_header_set_region(rf_header *h, const struct rf_region *r)
{
	char buf[96];

	if (r->width > RF_FRAME_SIDE_MAX || r->height > RF_FRAME_SIDE_MAX ||
	    r->x0 > r->width || r->y0 > r->height || h->ncols > r->width - r->x0 ||
	    h->nrows > r->height - r->y0)
		return RF_EINVAL;
	if (!r->x0 && !r->y0 && r->width == h->ncols && r->height == h->nrows)
		return rf_header_unset(h, RF_KEY_REGION);
	snprintf(buf, sizeof(buf), "%zu %zu %zu %zu", r->x0, r->y0, r->width, r->height);
	return rf_header_set(h, RF_KEY_REGION, buf);
}

int
rf__header_push_line(rf_header *h, const char *line)
{
	char **lines;
	char *copy;

	if (h->nlines >= RF_HEADER_LINES_MAX)
		return RF_ETOOBIG;
	if (!(copy = strdup(line)))
		return RF_ENOMEM;
	if (!(lines = realloc(h->lines, (h->nlines + 1) * sizeof(*lines)))) {
		free(copy);
		return RF_ENOMEM;
	}
	h->lines = lines;
	h->lines[h->nlines++] = copy;
	return 0;
}

static int
line_valid(const char *line)
{
	size_t n = strlen(line);
	size_t i;

	if (n == 0 || n > RF_HEADER_LINE_MAX)
		return 0;
	for (i = 0; i < n; i++)
		if ((unsigned char)line[i] < 0x20 && line[i] != '\t')
			return 0;
	return 1;
}

int
rf_header_set(rf_header *h, const char *key, const char *value)
{
	size_t klen = strlen(key), vlen = strlen(value);
	char *line;
	int i, rc;

	if (!klen || rf__header_key_reserved(key, klen))
		return RF_EINVAL;
	if (!(line = malloc(klen + vlen + 2)))
		return RF_ENOMEM;
	memcpy(line, key, klen);
	line[klen] = '=';
	memcpy(line + klen + 1, value, vlen + 1);
	if (key_length(line) != klen || !line_valid(line)) {
		free(line);
		return RF_EINVAL;
	}
	if ((i = find_key(h, key)) >= 0) {
		free(h->lines[i]);
		h->lines[i] = line;
		return 0;
	}
	rc = rf__header_push_line(h, line);
	free(line);
	return rc;
}

int
rf_header_unset(rf_header *h, const char *key)
{
	int i;

	while ((i = find_key(h, key)) >= 0) {
		free(h->lines[i]);
		memmove(h->lines + i, h->lines + i + 1,
		        (h->nlines - (size_t)i - 1) * sizeof(*h->lines));
		h->nlines--;
	}
	return 0;
}

int
rf_header_add_line(rf_header *h, const char *line)
{
	size_t k = key_length(line);

	if (!line_valid(line) || (k && rf__header_key_reserved(line, k)))
		return RF_EINVAL;
	return rf__header_push_line(h, line);
}

/* Appends s to buf (of size RF_HEADER_LINE_MAX + 1), quoted for a shell
 * when it needs to be; control characters become '?'. */
static int
append_word(char *buf, size_t *len, const char *s)
{
	char tmp[RF_HEADER_LINE_MAX + 1];
	size_t n = 0, i;
	int quote = !*s || s[strcspn(s, " \t'\"\\$`*?[]{}()<>|&;#~!")] != '\0';

	if (quote)
		tmp[n++] = '\'';
	for (i = 0; s[i] && n + 5 < sizeof(tmp); i++) {
		unsigned char c = (unsigned char)s[i];

		if (c == '\'') {
			memcpy(tmp + n, "'\\''", 4);
			n += 4;
		} else {
			tmp[n++] = c < 0x20 || c == 0x7f ? '?' : (char)c;
		}
	}
	if (s[i])
		return -1; /* the word alone is too long: never cut it */
	if (quote)
		tmp[n++] = '\'';
	if (*len + (*len ? 1 : 0) + n > RF_HEADER_LINE_MAX)
		return -1;
	if (*len)
		buf[(*len)++] = ' ';
	memcpy(buf + *len, tmp, n);
	*len += n;
	buf[*len] = '\0';
	return 0;
}

int
rf_header_add_command(rf_header *h, int argc, char *const *argv)
{
	char line[RF_HEADER_LINE_MAX + 1];
	size_t len = 0, ends[3] = { 0, 0, 0 }; /* ends of the last words */
	int i, k;

	line[0] = '\0';
	for (i = 0; i < argc; i++) {
		const char *arg = argv[i];

		if (i == 0 && strrchr(arg, '/'))
			arg = strrchr(arg, '/') + 1;
		if (i == 0 && !strncmp(arg, "lt-", 3))
			arg += 3; /* libtool's uninstalled wrapper */
		if (append_word(line, &len, arg) < 0) {
			/* Too long for one header line: say so rather than cut a
			 * word, dropping the last words to make room for " ...".
			 * At most two go (a word and its space are 2 bytes or more),
			 * and never the tool's name. */
			for (k = 0; len + 4 > RF_HEADER_LINE_MAX && k < 2 && i - k > 1; k++)
				len = ends[(i - 2 - k) % 3];
			if (len && len + 4 <= RF_HEADER_LINE_MAX) {
				memcpy(line + len, " ...", 5);
				len += 4;
			}
			break;
		}
		ends[i % 3] = len;
	}
	if (!len)
		return RF_EINVAL;
	return rf__header_push_line(h, line);
}

const char *
rf_header_line(const rf_header *h, size_t i)
{
	return i < h->nlines ? h->lines[i] : NULL;
}
