/*
 * The first bytes of an input, looked at without taking them from it: a
 * stream tool given a path learns from them whether it holds a stream or
 * an image.  Reading them through stdio and rewinding lost them on a
 * pipe (a FIFO, <(...), /dev/stdin): rewind cannot go back on a pipe,
 * and stdio's buffer of 4 KB went with the failed seek, so the stream
 * lost its header.  A regular file is read with pread at its offset,
 * which moves nothing.  Anything else is read once, and handed on as a
 * stream that gives back what was read, then the rest.
 *
 * Nothing here prints or exits, so that a fuzz harness can link it
 * (tests/fuzz/fuzz-sniff.c).
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

struct replay {
	int fd;
	unsigned char head[CLI_SNIFF_BYTES];
	size_t len, pos;
	struct replay *next;
};

/* The replays open, in a list of our own: a tool that dies with its
 * input open leaves them to the exit, and LeakSanitizer, which does not
 * look into stdio's streams, would call them leaked.  Inputs are opened
 * and closed by the main thread. */
static struct replay *replays;

static ssize_t
replay_read(void *cookie, char *buf, size_t size)
{
	struct replay *r = cookie;
	ssize_t n;

	if (r->pos < r->len) {
		size_t k = r->len - r->pos < size ? r->len - r->pos : size;

		memcpy(buf, r->head + r->pos, k);
		r->pos += k;
		return (ssize_t)k;
	}
	do
		n = read(r->fd, buf, size);
	while (n < 0 && errno == EINTR);
	return n;
}

static int
replay_close(void *cookie)
{
	struct replay *r = cookie, **p;
	int rc = close(r->fd);

	for (p = &replays; *p && *p != r; p = &(*p)->next)
		;
	if (*p)
		*p = r->next;
	free(r);
	return rc;
}

/* Up to n bytes from fd, fewer only at its end. */
static ssize_t
read_full(int fd, unsigned char *buf, size_t n)
{
	size_t got = 0;
	ssize_t k;

	while (got < n) {
		k = read(fd, buf + got, n - got);
		if (k < 0 && errno == EINTR)
			continue;
		if (k < 0)
			return -1;
		if (k == 0)
			break;
		got += (size_t)k;
	}
	return (ssize_t)got;
}

int
cli_sniff_open(int fd, struct cli_sniff *s, FILE **fp)
{
	cookie_io_functions_t io = { replay_read, NULL, NULL, replay_close };
	struct replay *r;
	struct stat st;
	ssize_t n;
	off_t at;

	memset(s, 0, sizeof(*s));
	*fp = NULL;
	if (fstat(fd, &st) < 0)
		return -1;
	s->regular = S_ISREG(st.st_mode);
	if (s->regular && (at = lseek(fd, 0, SEEK_CUR)) >= 0) {
		do
			n = pread(fd, s->head, sizeof(s->head), at);
		while (n < 0 && errno == EINTR);
		if (n < 0 || !(*fp = fdopen(fd, "rb")))
			return -1;
		s->len = (size_t)n;
		return 0;
	}
	if (!(r = calloc(1, sizeof(*r))))
		return -1;
	if ((n = read_full(fd, r->head, sizeof(r->head))) < 0) {
		free(r);
		return -1;
	}
	r->fd = fd;
	r->len = (size_t)n;
	memcpy(s->head, r->head, r->len);
	s->len = r->len;
	if (!(*fp = fopencookie(r, "rb", io))) {
		free(r);
		return -1;
	}
	r->next = replays;
	replays = r;
	return 0;
}

enum cli_kind
cli_sniff_kind(const struct cli_sniff *s)
{
	static const char exr[] = "\x76\x2f\x31\x01", png[] = "\x89PNG\r\n\x1a\n";

	if (rf_stream_sniff(s->head, s->len))
		return CLI_KIND_STREAM;
	if (s->len >= sizeof(exr) - 1 && !memcmp(s->head, exr, sizeof(exr) - 1))
		return CLI_KIND_EXR;
	if (s->len >= sizeof(png) - 1 && !memcmp(s->head, png, sizeof(png) - 1))
		return CLI_KIND_PNG;
	return CLI_KIND_OTHER;
}
