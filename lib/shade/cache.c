/*
 * Prefiltered environments kept between runs: a raw environment that a
 * shading pass prefilters on the fly (0.3 s for the embedded room on 2
 * threads, more for a large image) is written to a cache directory under
 * a hash of its level 0 texels and the prefilter's parameters, and read
 * from there the next time, so that the second run of a script costs
 * what a prefiltered file costs.
 *
 * Writers write a temporary file and rename it into place, so a reader
 * sees a whole file or none, however many processes run at once.  The
 * directory is kept under a size: the oldest entries go first.
 *
 * An entry is used only when it is the chain asked for, whole: it reads
 * back to its last level and no further, every texel finite, with the
 * levels, size, mapping, steps and samples asked for, its own key (a
 * file copied under another name is not), its level 0 equal to the
 * source's bit for bit, and the hash of all its texels (CACHE_SUM,
 * written with it) the same again.  The key is a hash of the source's
 * texels as decoded, not of the file (its size and times say nothing of
 * an edit in place, and change with a mere copy); and since the
 * prefilter reads nothing of the source but its level 0, the comparison
 * of that level means that no other source, whatever its hash, can be
 * given another's chain.  An entry that fails is made again, and the
 * caller says so.
 */
#include <dirent.h>
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include "envmap/envmap-internal.h"
#include "shade/cache.h"
#include "util/util.h"

/* Bumped whenever the prefilter would make other texels from the same
 * input, or entries change form, so that old entries are never read for
 * new ones; the library's version is in the key too. */
#define CACHE_FORMAT "reflect-prefilter 2"

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

/* FNV-1a over every texel of every level, a 32-bit word at a time: a
 * changed word anywhere changes it (each step is one-to-one). */
static uint64_t
texels_sum(const rf_cubemap *c)
{
	uint64_t h = 0xcbf29ce484222325u;
	size_t k, j, i;
	uint32_t u;
	int f;

	for (k = 0; k < rf_cubemap_levels(c); k++) {
		size_t n = rf_cubemap_level_size(c, k);

		for (f = 0; f < 6; f++)
			for (j = 0; j < n; j++) {
				const float *t = rf_cubemap_texel_const(c, k, (enum rf_face)f, 0, j);

				for (i = 0; i < 3 * n; i++) {
					memcpy(&u, t + i, sizeof(u));
					h = (h ^ u) * 0x100000001b3u;
				}
			}
	}
	return h;
}

/* Level 0 of a and b, bit for bit (a face's row is contiguous). */
static int
same_level0(const rf_cubemap *a, const rf_cubemap *b)
{
	size_t n = rf_cubemap_size(a), j;
	int f;

	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++)
			if (memcmp(rf_cubemap_texel_const(a, 0, (enum rf_face)f, 0, j),
			           rf_cubemap_texel_const(b, 0, (enum rf_face)f, 0, j),
			           3 * n * sizeof(float)))
				return 0;
	return 1;
}

/* The entry read from r, checked (see the top of the file): 0, or
 * RF_EINVAL with what is wrong in why. */
static int
read_entry(rf_reader *r, uint64_t key, const rf_cubemap *src, size_t levels,
           const struct rf_chain_info *want, rf_cubemap **env, char *why, size_t whylen)
{
	struct rf_chain_info got;
	const rf_header *h;
	const char *v;
	unsigned long long their_key, sum;
	char err[256], *end;
	int rc;

	if ((rc = rf_reader_next_frame(r, &h)) <= 0) {
		rf__format(why, whylen, "%s", rc < 0 ? rf_reader_error(r) : "it is empty");
		return RF_EINVAL;
	}
	if (!(v = rf_header_get(h, "CACHE_KEY")) ||
	    (their_key = strtoull(v, &end, 16), *end) || !*v) {
		rf__format(why, whylen, "it has no CACHE_KEY");
		return RF_EINVAL;
	}
	if (their_key != key) {
		rf__format(why, whylen, "its CACHE_KEY is %016llx, not its name's", their_key);
		return RF_EINVAL;
	}
	if (!(v = rf_header_get(h, "CACHE_SUM")) || (sum = strtoull(v, &end, 16), *end) ||
	    !*v) {
		rf__format(why, whylen, "it has no CACHE_SUM");
		return RF_EINVAL;
	}
	/* NaN and Inf refused as they are read */
	if (rf__chain_read_stream(env, &got, r, h, NULL, err, sizeof(err)) < 0) {
		rf__format(why, whylen, "%s", err);
		return RF_EINVAL;
	}
	if ((rc = rf_reader_next_frame(r, &h)) != 0) {
		rf__format(why, whylen, "%s", rc < 0 ? rf_reader_error(r)
		           : "it goes on past its last level");
		return RF_EINVAL;
	}
	if (!got.prefiltered || rf_cubemap_levels(*env) != levels ||
	    rf_cubemap_size(*env) != rf_cubemap_size(src) || got.mapping != want->mapping ||
	    got.steps != want->steps || got.samples != want->samples) {
		rf__format(why, whylen, "it is %s%zu levels of %zu texels, mapping %s, steps %g, "
		           "samples %u, where %zu of %zu, %s, %g, %u were asked for",
		           got.prefiltered ? "" : "not prefiltered, ", rf_cubemap_levels(*env),
		           rf_cubemap_size(*env), rf_mapping_name(got.mapping), (double)got.steps,
		           got.samples, levels, rf_cubemap_size(src),
		           rf_mapping_name(want->mapping), (double)want->steps, want->samples);
		return RF_EINVAL;
	}
	if (!same_level0(*env, src)) {
		rf__format(why, whylen, "its level 0 is not the environment's");
		return RF_EINVAL;
	}
	if (texels_sum(*env) != sum) {
		rf__format(why, whylen, "its texels do not add up to its CACHE_SUM");
		return RF_EINVAL;
	}
	return 0;
}

int
rf__env_cache_get(const char *dir, uint64_t key, const rf_cubemap *src, size_t levels,
                  const struct rf_chain_info *want, rf_cubemap **env, char *why,
                  size_t whylen)
{
	char path[4096], bad[512];
	rf_reader *r;
	FILE *fp;
	int rc;

	*env = NULL;
	entry_path(path, sizeof(path), dir, key);
	if (!(fp = fopen(path, "rb")))
		return RF_ENOTFOUND;
	if ((rc = rf_reader_open(&r, fp, path, NULL)) == 0) {
		rc = read_entry(r, key, src, levels, want, env, bad, sizeof(bad));
		rf_reader_close(r);
	} else {
		rf__format(bad, sizeof(bad), "it is not a stream");
		rc = RF_EINVAL;
	}
	fclose(fp);
	if (rc < 0) {
		rf_cubemap_destroy(*env);
		*env = NULL;
		rf__format(why, whylen, "'%s': %s", path, bad);
		return RF_EINVAL;
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
	char tmp[4096], path[4096], err[256], hex[20];
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
	if (rc == 0) {
		snprintf(hex, sizeof(hex), "%016" PRIx64, key);
		rc = rf_header_set(base, "CACHE_KEY", hex);
	}
	if (rc == 0) {
		snprintf(hex, sizeof(hex), "%016" PRIx64, texels_sum(env));
		rc = rf_header_set(base, "CACHE_SUM", hex);
	}
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
