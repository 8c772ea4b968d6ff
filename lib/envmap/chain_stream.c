/* Cube chains as streams: one ENVMAP=CUBE frame per level. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "envmap/envmap-internal.h"
#include "stream/stream-internal.h"
#include "reflect/envmap.h"

static void
set_number(rf_header *h, const char *key, double v)
{
	char buf[64];

	rf__format(buf, sizeof(buf), "%.9g", v);
	rf_header_set(h, key, buf);
}

int
rf_chain_write_stream(const rf_cubemap *c, const struct rf_chain_info *info,
                      rf_writer *w, const rf_header *base, char *err, size_t errlen)
{
	size_t levels = rf_cubemap_levels(c), k, n, f, j;
	rf_header *h;
	float *row;
	int rc = 0;

	if (!(row = malloc(rf_cubemap_size(c) * 3 * sizeof(float))))
		return RF_ENOMEM;
	for (k = 0; k < levels && rc == 0; k++) {
		n = rf_cubemap_level_size(c, k);
		if ((base ? rf_header_dup(&h, base) : rf_header_create(&h)) < 0) {
			rc = RF_ENOMEM;
			break;
		}
		rf_header_set_size(h, n, 6 * n);
		rf_header_set_channels(h, "R G B");
		rf_header_set(h, "ENVMAP", "CUBE");
		set_number(h, "LEVEL", (double)k);
		set_number(h, "LEVELS", (double)levels);
		rf_header_set(h, "PREFILTER", info->prefiltered ? "ggx" : "box");
		rf_header_set(h, "MAPPING", rf_mapping_name(info->mapping));
		set_number(h, "STEPS", info->steps);
		if (info->prefiltered)
			set_number(h, "SAMPLES", info->samples);
		rf_header_set(h, "BASE", info->base_copied ? "copied" : "filtered");
		if (k == 0) {
			/* the diffuse light's coefficients, so a shade tool need
			 * not project the level itself */
			float sh[27];
			double v[27];
			int i;

			rf_cubemap_sh9(c, 0, sh);
			for (i = 0; i < 27; i++)
				v[i] = sh[i];
			rf__header_set_numbers(h, "IRRADIANCE_SH9", v, 27);
		}
		if ((rc = rf_writer_begin_frame(w, h)) < 0) {
			rf__format(err, errlen, "%s", rf_writer_error(w));
			rf_header_destroy(h);
			break;
		}
		for (f = 0; f < 6 && rc == 0; f++)
			for (j = 0; j < n && rc == 0; j++) {
				size_t i;

				for (i = 0; i < n; i++)
					memcpy(row + 3 * i,
					       rf_cubemap_texel_const(c, k, (enum rf_face)f, i, j),
					       3 * sizeof(float));
				if ((rc = rf_writer_write_rows(w, row, 1)) < 0)
					rf__format(err, errlen, "%s", rf_writer_error(w));
			}
		if (rc == 0 && (rc = rf_writer_end_frame(w)) < 0)
			rf__format(err, errlen, "%s", rf_writer_error(w));
		rf_header_destroy(h);
	}
	free(row);
	return rc;
}

static int
key_number(const rf_header *h, const char *key, double lo, double hi, double *out,
           char *err, size_t errlen)
{
	const char *v = rf_header_get(h, key);
	char *end;

	if (!v)
		return 1;
	errno = 0;
	*out = strtod(v, &end);
	if (end == v || *end || errno || !(*out >= lo && *out <= hi)) {
		rf__format(err, errlen, "header key %s: '%s' is not a number in [%g, %g]",
		           key, v, lo, hi);
		return RF_EFORMAT;
	}
	return 0;
}

/* Reads one ENVMAP=CUBE frame's texels into level k of c; a NaN or
 * infinite one is refused, or without nf made 0 and noted in nf. */
static int
read_level(rf_reader *r, rf_cubemap *c, size_t k, const rf_header *h,
           struct rf__nonfinite *nf, char *err, size_t errlen)
{
	size_t n = rf_cubemap_level_size(c, k), f, j, i, nch = rf_header_nchannels(h);
	int ch[3], rc, q;
	const float *mapped = NULL;
	float *row = NULL;

	if (rf_header_ncols(h) != n || rf_header_nrows(h) != 6 * n) {
		rf__format(err, errlen, "level %zu is %zux%zu, expected %zux%zu", k,
		           rf_header_ncols(h), rf_header_nrows(h), n, 6 * n);
		return RF_EFORMAT;
	}
	for (q = 0; q < 3; q++) {
		static const char *const names[] = { "R", "G", "B" };

		if ((ch[q] = rf_header_find_channel(h, names[q])) < 0) {
			rf__format(err, errlen, "cube frame has no channel '%s'", names[q]);
			return RF_ECHANNEL;
		}
	}
	/* A file's level is mapped in one go; otherwise it is read a row at
	 * a time. */
	if ((rc = rf_reader_map_rows(r, 6 * n, &mapped)) < 0) {
		rf__format(err, errlen, "%s", rf_reader_error(r));
		return rc;
	}
	if (!mapped && !(row = malloc(n * nch * sizeof(float))))
		return RF_ENOMEM;
	for (f = 0; f < 6; f++)
		for (j = 0; j < n; j++) {
			/* A face's row is contiguous, borders aside. */
			float *t = rf_cubemap_texel(c, k, (enum rf_face)f, 0, j);
			const float *p = mapped ? mapped + (f * n + j) * n * nch : row;

			if (!mapped && (rc = rf_reader_read_rows(r, row, 1)) < 0) {
				rf__format(err, errlen, "%s", rf_reader_error(r));
				free(row);
				return rc;
			}
			for (i = 0; i < n; i++, t += 3, p += nch)
				for (q = 0; q < 3; q++) {
					t[q] = p[ch[q]];
					if (rf__texel_ok(t[q]))
						continue;
					if (!nf) {
						struct rf__nonfinite one = { 0 };

						rf__nonfinite_note(&one, k, (int)f, i, j, q, t[q]);
						rf__nonfinite_where(&one, err, errlen);
						free(row);
						return RF_EINVAL;
					}
					rf__nonfinite_note(nf, k, (int)f, i, j, q, t[q]);
					t[q] = 0.0f;
				}
		}
	free(row);
	rf_cubemap_seal_level(c, k);
	return 0;
}

int
rf_chain_read_stream(rf_cubemap **cp, struct rf_chain_info *info, rf_reader *r,
                     char *err, size_t errlen)
{
	return rf__chain_read_stream(cp, info, r, NULL, NULL, err, errlen);
}

int
rf__chain_read_stream(rf_cubemap **cp, struct rf_chain_info *info, rf_reader *r,
                      const rf_header *first, struct rf__nonfinite *nf, char *err,
                      size_t errlen)
{
	const rf_header *h = first;
	double levels = 1, level = 0, steps = 0, samples = 0;
	const char *v;
	size_t n, k;
	int rc;

	*cp = NULL;
	memset(info, 0, sizeof(*info));
	if (!h && (rc = rf_reader_next_frame(r, &h)) <= 0) {
		rf__format(err, errlen, "%s", rc < 0 ? rf_reader_error(r)
		           : "no environment in the stream");
		return rc < 0 ? rc : RF_EFORMAT;
	}
	if (!(v = rf_header_get(h, "ENVMAP")) || strcmp(v, "CUBE")) {
		rf__format(err, errlen, "the stream's frame is not a cube (no "
		           "ENVMAP=CUBE key)");
		return RF_EFORMAT;
	}
	n = rf_header_ncols(h);
	if ((rc = key_number(h, "LEVELS", 1, 16, &levels, err, errlen)) < 0 ||
	    (rc = key_number(h, "LEVEL", 0, 0, &level, err, errlen)) < 0 ||
	    (rc = key_number(h, "STEPS", 0, 64, &steps, err, errlen)) < 0 ||
	    (rc = key_number(h, "SAMPLES", 0, 1 << 20, &samples, err, errlen)) < 0)
		return rc;
	if ((v = rf_header_get(h, "MAPPING")) && rf_mapping_parse(v, &info->mapping) < 0) {
		rf__format(err, errlen, "header key MAPPING: unknown mapping '%s'", v);
		return RF_EFORMAT;
	}
	info->prefiltered = (v = rf_header_get(h, "PREFILTER")) && !strcmp(v, "ggx");
	info->base_copied = !(v = rf_header_get(h, "BASE")) || strcmp(v, "filtered");
	info->steps = (float)steps;
	info->samples = (unsigned)samples;
	if ((v = rf_header_get(h, "IRRADIANCE_SH9"))) {
		if (rf__scan_floats(v, info->sh9, 27) < 0) {
			rf__format(err, errlen, "header key IRRADIANCE_SH9: '%.60s' needs 27 "
			           "finite float numbers", v);
			return RF_EFORMAT;
		}
		info->has_sh9 = 1;
	}
	if ((rc = rf_cubemap_check_size(n, (size_t)levels, err, errlen)) < 0)
		return rc;
	if ((rc = rf_cubemap_create(cp, n, (size_t)levels)) < 0) {
		rf__format(err, errlen, "a cube of %zu texels cannot have %g levels", n,
		           levels);
		return rc;
	}
	for (k = 0;; k++) {
		if ((rc = read_level(r, *cp, k, h, nf, err, errlen)) < 0)
			goto fail;
		if (k + 1 == (size_t)levels)
			break;
		if ((rc = rf_reader_next_frame(r, &h)) <= 0) {
			rf__format(err, errlen, "%s", rc < 0 ? rf_reader_error(r)
			           : "the chain ends before its last level");
			rc = rc < 0 ? rc : RF_ETRUNCATED;
			goto fail;
		}
		if ((rc = key_number(h, "LEVEL", (double)(k + 1), (double)(k + 1), &level,
		                     err, errlen)) != 0) {
			if (rc > 0)
				rf__format(err, errlen, "frame of level %zu has no LEVEL key", k + 1);
			rc = RF_EFORMAT;
			goto fail;
		}
	}
	return 0;
fail:
	rf_cubemap_destroy(*cp);
	*cp = NULL;
	return rc;
}
