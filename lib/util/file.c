/*
 * Only regular files reach a decoder.  Decoders take a path and may seek,
 * probe one format after another or read to the end: OpenImageIO's IFF
 * probe reads /dev/zero for ever, and opening a FIFO blocks until some
 * writer comes, which may be never.  A stream is another matter: it is
 * read once, front to back, so the tools take those from pipes.
 */
#include <sys/stat.h>

#include "util/util.h"

const char *
rf__file_kind(unsigned mode)
{
	if (S_ISDIR(mode))
		return "a directory";
	if (S_ISFIFO(mode))
		return "a FIFO";
	if (S_ISCHR(mode))
		return "a character device";
	if (S_ISBLK(mode))
		return "a block device";
	if (S_ISSOCK(mode))
		return "a socket";
	return "not a file";
}

int
rf__regular_file(const char *path, char *err, size_t errlen)
{
	struct stat st;

	if (stat(path, &st) < 0 || S_ISREG(st.st_mode))
		return 0; /* a missing file: the reader says so in its words */
	rf__format(err, errlen, "cannot open '%s': not a regular file (%s)", path,
	           rf__file_kind(st.st_mode));
	return RF_EINVAL;
}
