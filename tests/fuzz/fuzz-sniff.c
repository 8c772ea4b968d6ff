/*
 * libFuzzer harness for the tools' look at an input's first bytes
 * (bin/cli_sniff.c): the input comes through a pipe, written in pieces
 * of sizes the input chooses, and from a memory file at an offset.
 * Whatever it is, the bytes looked at are the input's first, and reading
 * on gives back every byte of the input, those first ones included: a
 * pipe cannot go back, and the first 4 KB were lost that way.
 */
#ifndef _GNU_SOURCE
#define _GNU_SOURCE
#endif
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

#include "cli.h"

#define HARNESS "fuzz-sniff"
#include "harness.h"

struct feed {
	int fd;
	const uint8_t *data;
	size_t size;
};

/* Writes the input in pieces of 1 to 64 bytes, as the bytes say. */
static void *
feed(void *arg)
{
	struct feed *f = arg;
	size_t done = 0, n;
	ssize_t k;

	while (done < f->size) {
		n = 1 + f->data[done] % 64;
		if (n > f->size - done)
			n = f->size - done;
		if ((k = write(f->fd, f->data + done, n)) <= 0)
			break;
		done += (size_t)k;
	}
	close(f->fd);
	return NULL;
}

/* Everything fp gives, which must be data[0..size). */
static void
read_back(FILE *fp, const uint8_t *data, size_t size)
{
	unsigned char buf[4096];
	size_t got = 0, n;

	while ((n = fread(buf, 1, sizeof(buf), fp)) > 0) {
		check(got + n <= size, "more bytes than were written");
		check(!memcmp(buf, data + got, n), "bytes changed or lost");
		got += n;
	}
	check(!ferror(fp), "a read error");
	check(got == size, "bytes lost");
}

static void
check_head(const struct cli_sniff *s, const uint8_t *data, size_t size)
{
	enum cli_kind k = cli_sniff_kind(s);

	check(s->len == (size < CLI_SNIFF_BYTES ? size : CLI_SNIFF_BYTES),
	      "fewer bytes looked at than there were");
	check(!memcmp(s->head, data, s->len), "the bytes looked at are not the first");
	if (size >= 9 && !memcmp(data, "#?REFLECT", 9))
		check(k == CLI_KIND_STREAM, "a stream not told");
	else
		check(k != CLI_KIND_STREAM, "a stream told where there is none");
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	struct cli_sniff s;
	struct feed f;
	pthread_t t;
	size_t at;
	FILE *fp;
	int p[2], fd;

	/* a pipe */
	if (pipe(p) == 0) {
		f.fd = p[1];
		f.data = data;
		f.size = size;
		if (pthread_create(&t, NULL, feed, &f) != 0) {
			close(p[0]);
			close(p[1]);
		} else {
			check(cli_sniff_open(p[0], &s, &fp) == 0, "a pipe not opened");
			check(!s.regular, "a pipe taken for a file");
			check_head(&s, data, size);
			read_back(fp, data, size);
			fclose(fp);
			pthread_join(t, NULL);
		}
	}
	/* a file, read from an offset as a shell's redirection may leave it */
	if ((fd = memfd_create("fuzz-sniff", 0)) >= 0) {
		at = size ? data[0] % (size + 1) : 0;
		if (write(fd, data, size) != (ssize_t)size || lseek(fd, (off_t)at, SEEK_SET) < 0) {
			close(fd);
			return 0;
		}
		check(cli_sniff_open(fd, &s, &fp) == 0, "a file not opened");
		check(s.regular, "a file taken for a pipe");
		check_head(&s, data + at, size - at);
		read_back(fp, data + at, size - at);
		fclose(fp);
	}
	return 0;
}
