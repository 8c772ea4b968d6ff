/*
 * Prefiltered environments kept between runs: a raw environment that a
 * shading pass prefilters on the fly (0.3 s for the embedded room on 2
 * threads, more for a large image) is written to a cache directory under
 * a hash of its level 0 texels and the prefilter's parameters, and read
 * from there the next time, so that the second run of a script costs
 * what a prefiltered file costs.
 *
 * Writers write a temporary file and rename it into place, so a reader
 * sees a whole file or none, however many processes run at once; a file
 * that does not read back whole (cut short by a full disk, say) is a
 * miss, and written again.  The directory is kept under a size: the
 * oldest entries go first.
 */
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include "shade/cache.h"
#include "util/util.h"

/* Bumped whenever the prefilter would make other texels from the same
 * input, so that old entries are never read for new ones; the library's
 * version is in the key too. */
#define CACHE_FORMAT "reflect-prefilter 1"

uint64_t
rf__env_cache_key(const rf_cubemap *src, enum rf_mapping mapping, float steps,
                  unsigned samples, size_t levels)
{
	const size_t n = rf_cubemap_size(src);
	uint64_t h = 0xcbf29ce484222325u; /* FNV-1a */
	char params[128];
	size_t i, j, k;
	int f;

	snprintf(params, sizeof(params), CACHE_FORMAT " %s %zu %zu %d %.9g %u",
	         rf_version_string(), n, levels, (int)mapping, (double)steps, samples);
	for (k = 0; params[k]; k++)
		h = (h ^ (unsigned char)params[k]) * 0x100000001b3u;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			for (i = 0; i < n; i++) {
				const unsigned char *b =
					(const void *)rf_cubemap_texel_const(src, 0, (enum rf_face)f, i, j);

				for (k = 0; k < 3 * sizeof(float); k++)
					h = (h ^ b[k]) * 0x100000001b3u;
			}
	return h;
}

static void
entry_path(char *buf, size_t size, const char *dir, uint64_t key)
{
	snprintf(buf, size, "%s/%016llx.rfl", dir, (unsigned long long)key);
}

int
rf__env_cache_get(const char *dir, uint64_t key, rf_cubemap **env,
                  struct rf_chain_info *info)
{
	char path[4096], err[256];
	rf_reader *r;
	FILE *fp;
	int rc;

	*env = NULL;
	entry_path(path, sizeof(path), dir, key);
	if (!(fp = fopen(path, "rb")))
		return RF_ENOTFOUND;
	if ((rc = rf_reader_open(&r, fp, path, NULL)) == 0) {
		rc = rf_chain_read_stream(env, info, r, err, sizeof(err));
		rf_reader_close(r);
	}
	fclose(fp);
	if (rc < 0 || !info->prefiltered) {
		rf_cubemap_destroy(*env);
		*env = NULL;
		return RF_ENOTFOUND;
	}
	/* the entry was used: the last to go when the cache is trimmed */
	utimes(path, NULL);
	return 0;
}

/* mkdir -p */
static int
make_dirs(const char *dir)
{
	char path[4096], *p;

	snprintf(path, sizeof(path), "%s", dir);
	for (p = path + 1; *p; p++)
		if (*p == '/') {
			*p = '\0';
			if (mkdir(path, 0755) < 0 && errno != EEXIST)
				return -1;
			*p = '/';
		}
	return mkdir(path, 0755) < 0 && errno != EEXIST ? -1 : 0;
}

/* Removes the oldest entries while the cache holds more than cap bytes. */
static void
trim(const char *dir, size_t cap)
{
	for (;;) {
		char path[4096], oldest[4096] = "";
		time_t when = 0;
		size_t total = 0;
		struct dirent *e;
		DIR *d = opendir(dir);

		if (!d)
			return;
		while ((e = readdir(d))) {
			struct stat st;
			size_t len = strlen(e->d_name);

			if (len < 5 || strcmp(e->d_name + len - 4, ".rfl"))
				continue;
			snprintf(path, sizeof(path), "%s/%s", dir, e->d_name);
			if (stat(path, &st) < 0)
				continue;
			total += (size_t)st.st_size;
			if (!oldest[0] || st.st_mtime < when) {
				when = st.st_mtime;
				snprintf(oldest, sizeof(oldest), "%s", path);
			}
		}
		closedir(d);
		if (total <= cap || !oldest[0] || unlink(oldest) < 0)
			return;
	}
}

int
rf__env_cache_put(const char *dir, uint64_t key, const rf_cubemap *env,
                  const struct rf_chain_info *info, size_t cap)
{
	char tmp[4096], path[4096], err[256];
	struct rf_writer_options wo = { RF_FORMAT_FLOAT, 0 };
	rf_header *base;
	rf_writer *w;
	FILE *fp;
	int fd, rc;

	if (make_dirs(dir) < 0)
		return RF_EIO;
	snprintf(tmp, sizeof(tmp), "%s/.entry.XXXXXX", dir);
	if ((fd = mkstemp(tmp)) < 0)
		return RF_EIO;
	if (!(fp = fdopen(fd, "wb"))) {
		close(fd);
		unlink(tmp);
		return RF_EIO;
	}
	rc = rf_header_create(&base);
	if (rc == 0 && (rc = rf_writer_open(&w, fp, tmp, &wo)) == 0) {
		rc = rf_chain_write_stream(env, info, w, base, err, sizeof(err));
		rf_writer_close(w);
	}
	rf_header_destroy(base);
	if (fclose(fp) != 0 && rc == 0)
		rc = RF_EIO;
	entry_path(path, sizeof(path), dir, key);
	if (rc < 0 || rename(tmp, path) < 0) {
		unlink(tmp);
		return rc < 0 ? rc : RF_EIO;
	}
	trim(dir, cap);
	return 0;
}
