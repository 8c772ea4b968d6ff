/*
 * Files written whole or not at all, as git and sqlite write theirs: to
 * a temporary file beside the path, synced, then renamed over it.  A
 * write that fails (a full disk, input that ends early) leaves an old
 * file as it was, and no reader ever sees half a file.  Every writer of
 * a file goes through here: the image writers, the KTX writer, and the
 * tools' streams (rf_output_open).
 *
 * The temporary files being written are kept in a table that
 * rf_output_remove_all empties with nothing but atomic loads and
 * unlink(2), so that a tool's signal handler may call it: a tool ended
 * by SIGINT or SIGTERM leaves no hidden file behind.  The library itself
 * installs no handler; it removes them at exit(3) (a tool dying on bad
 * input).
 *
 * The temporary file keeps the path's extension, which the image module
 * goes by.  Devices, FIFOs and symbolic links are written in place: a
 * rename would replace them.
 */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/util.h"

/* Files being written at once: a tool writes one or two. */
#define SLOTS 64
#define SLOT_PATH 4096

enum { SLOT_FREE, SLOT_FILLING, SLOT_LIVE };

static char slot_path[SLOTS][SLOT_PATH];
static atomic_int slot_state[SLOTS];

struct rf_output {
	char *path;
	char *temp; /* NULL: written in place */
	int slot;
	FILE *fp;   /* rf_output_open's, else NULL */
};

void
rf_output_remove_all(void)
{
	int i;

	for (i = 0; i < SLOTS; i++)
		if (atomic_load(&slot_state[i]) == SLOT_LIVE)
			(void)unlink(slot_path[i]);
}

static void
register_exit(void)
{
	atexit(rf_output_remove_all);
}

/* A slot holding path, or -1 when all are taken. */
static int
take_slot(const char *path)
{
	static pthread_once_t once = PTHREAD_ONCE_INIT;
	int i, expected;

	pthread_once(&once, register_exit);
	for (i = 0; i < SLOTS; i++) {
		expected = SLOT_FREE;
		if (atomic_compare_exchange_strong(&slot_state[i], &expected, SLOT_FILLING)) {
			memcpy(slot_path[i], path, strlen(path) + 1);
			atomic_store(&slot_state[i], SLOT_LIVE);
			return i;
		}
	}
	return -1;
}

static void
free_slot(int slot)
{
	if (slot >= 0)
		atomic_store(&slot_state[slot], SLOT_FREE);
}

static void
destroy(rf_output *o)
{
	free(o->path);
	free(o->temp);
	free(o);
}

/* The temporary file made for o->path, registered; 0 or RF_EIO/RF_ENOMEM
 * with a message.  None for a path that is there and no regular file. */
static int
make_temp(rf_output *o, const char *dir, const char *base, char *err, size_t errlen)
{
	const char *dot = strrchr(base, '.');
	size_t suffix = dot && dot != base ? strlen(dot) : 0;
	struct stat st;
	mode_t mask;
	int fd, exists = lstat(o->path, &st) == 0;

	if (exists && !S_ISREG(st.st_mode))
		return 0;
	if (!(o->temp = malloc(strlen(dir) + strlen(base) + 16))) {
		rf__format(err, errlen, "cannot write '%s': out of memory", o->path);
		return RF_ENOMEM;
	}
	sprintf(o->temp, "%s.%.*s.XXXXXX%s", dir, (int)(strlen(base) - suffix), base,
	        suffix ? dot : "");
	if (strlen(o->temp) >= SLOT_PATH) {
		rf__format(err, errlen, "cannot write '%s': %s", o->path, strerror(ENAMETOOLONG));
		return RF_EIO;
	}
	if ((fd = mkostemps(o->temp, (int)suffix, O_CLOEXEC)) < 0) {
		rf__format(err, errlen, "cannot write '%s': %s", o->path, strerror(errno));
		return RF_EIO;
	}
	/* In the table before anything is written to it. */
	if ((o->slot = take_slot(o->temp)) < 0) {
		close(fd);
		unlink(o->temp);
		rf__format(err, errlen, "cannot write '%s': more than %d files written at "
		           "once", o->path, SLOTS);
		return RF_EIO;
	}
	/* The mode a new file would get, or the one the old file has. */
	if (exists) {
		(void)fchmod(fd, st.st_mode & 07777);
	} else {
		mask = umask(0);
		umask(mask);
		(void)fchmod(fd, 0666 & ~mask);
	}
	close(fd);
	return 0;
}

int
rf_output_begin(rf_output **op, const char *path, char *err, size_t errlen)
{
	const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path;
	rf_output *o;
	char *dir;
	int rc;

	*op = NULL;
	if (!(o = calloc(1, sizeof(*o))) || !(o->path = strdup(path)) ||
	    !(dir = strndup(path, (size_t)(base - path)))) {
		if (o)
			free(o->path);
		free(o);
		rf__format(err, errlen, "cannot write '%s': out of memory", path);
		return RF_ENOMEM;
	}
	o->slot = -1;
	rc = make_temp(o, dir, base, err, errlen);
	free(dir);
	if (rc < 0) {
		destroy(o);
		return rc;
	}
	*op = o;
	return 0;
}

const char *
rf_output_file(const rf_output *o)
{
	return o->temp ? o->temp : o->path;
}

int
rf_output_open(rf_output **op, const char *path, FILE **fp, char *err, size_t errlen)
{
	rf_output *o;
	int rc;

	*fp = NULL;
	if ((rc = rf_output_begin(&o, path, err, errlen)) < 0)
		return rc;
	if (!(o->fp = fopen(rf_output_file(o), "wb"))) {
		rf__format(err, errlen, "cannot write '%s': %s", path, strerror(errno));
		rf_output_discard(o);
		return RF_EIO;
	}
	*fp = o->fp;
	*op = o;
	return 0;
}

void
rf_output_discard(rf_output *o)
{
	if (!o)
		return;
	if (o->fp)
		fclose(o->fp);
	if (o->temp)
		unlink(o->temp);
	free_slot(o->slot);
	destroy(o);
}

/* The data on disk before the name: else a crash after the rename could
 * leave the new name on an empty file. */
static int
sync_file(rf_output *o)
{
	int fd, rc;

	if (o->fp) {
		int err = fflush(o->fp) != 0 || ferror(o->fp), e = errno;

		if (fsync(fileno(o->fp)) < 0 && errno != EINVAL && !err) {
			err = 1;
			e = errno;
		}
		if (fclose(o->fp) != 0 && !err) {
			err = 1;
			e = errno;
		}
		o->fp = NULL;
		errno = e ? e : EIO;
		return err ? -1 : 0;
	}
	if (!o->temp)
		return 0;
	if ((fd = open(o->temp, O_RDONLY | O_CLOEXEC)) < 0)
		return -1;
	/* EINVAL: a file system that cannot sync (some FUSE ones). */
	rc = fsync(fd) < 0 && errno != EINVAL ? -1 : 0;
	close(fd);
	return rc;
}

int
rf_output_commit(rf_output *o, char *err, size_t errlen)
{
	int rc = 0;

	if (sync_file(o) < 0) {
		rf__format(err, errlen, "cannot write '%s': %s", o->path, strerror(errno));
		rc = RF_EIO;
	} else if (o->temp && rename(o->temp, o->path) < 0) {
		rf__format(err, errlen, "cannot write '%s': %s", o->path, strerror(errno));
		rc = RF_EIO;
	}
	if (rc < 0) {
		rf_output_discard(o);
		return rc;
	}
	free_slot(o->slot);
	destroy(o);
	return 0;
}
