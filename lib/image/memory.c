/*
 * Images held in memory, read through a private temporary file: the
 * readers (libpng's, OpenEXR's, and OpenImageIO's in the module) take
 * paths, and the module's table has no memory reader; a file keeps every
 * format and every bound the readers apply (bounds.c) the same for
 * embedded images as for files.  The file is unlinked before returning.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image/image-internal.h"
#include "util/util.h"

/* The file's extension, which the module picks its reader by. */
static const char *
sniff(const unsigned char *b, size_t n, const char *ext)
{
	if (n >= 8 && !memcmp(b, "\x89PNG\r\n\x1a\n", 8))
		return "png";
	if (n >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff)
		return "jpg";
	if (n >= 4 && !memcmp(b, "\x76\x2f\x31\x01", 4))
		return "exr";
	if (n >= 2 && !memcmp(b, "#?", 2))
		return "hdr";
	if (ext && *ext && strlen(ext) <= 8 && !strpbrk(ext, "/."))
		return ext;
	return "img";
}

int
rf__image_read_memory(rf_image **img, const void *data, size_t size, const char *ext,
                      const char *name, char *err, size_t errlen)
{
	const char *dir = getenv("TMPDIR");
	char path[4096], msg[512];
	const char *e = sniff(data, size, ext);
	FILE *fp;
	int fd, rc;

	*img = NULL;
	if (!dir || !*dir)
		dir = "/tmp";
	if ((size_t)snprintf(path, sizeof(path), "%s/reflect-image-XXXXXX.%s", dir, e) >=
	    sizeof(path)) {
		rf__format(err, errlen, "%s: TMPDIR is too long a path", name);
		return RF_EINVAL;
	}
	if ((fd = mkstemps(path, (int)strlen(e) + 1)) < 0) {
		rf__format(err, errlen, "%s: cannot make a temporary file in '%s': %s", name, dir,
		           strerror(errno));
		return RF_EIO;
	}
	if (!(fp = fdopen(fd, "wb"))) {
		close(fd);
		unlink(path);
		return RF_ENOMEM;
	}
	if (fwrite(data, 1, size, fp) != size || fclose(fp) != 0) {
		rf__format(err, errlen, "%s: cannot write a temporary file in '%s': %s", name,
		           dir, strerror(errno));
		unlink(path);
		return RF_EIO;
	}
	rc = rf_image_read(img, path, msg, sizeof(msg));
	unlink(path);
	if (rc < 0) {
		/* the reader names the temporary file: name the image instead */
		char *at = strstr(msg, path);

		if (at)
			rf__format(err, errlen, "%.*s%s%s", (int)(at - msg), msg, name,
			           at + strlen(path));
		else
			rf__format(err, errlen, "%s: %s", name, msg);
	}
	return rc;
}
