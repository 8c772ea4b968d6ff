/*
 * A report of modes against the truth (reflect/report.h): each picture
 * read once, measured against the truth as reflect-compare measures it
 * (relative RMSE and PSNR of the colour, FLIP of the kind the pictures
 * call for), and kept as the PNG files the page embeds.
 *
 * The page shows linear pictures at whole-stop exposures, each an 8-bit
 * PNG, rather than embedding floats and tone-mapping them in a canvas:
 * PNG is compressed where base64 floats are 16 bytes a pixel (a 1080p
 * frame 33 MB a picture, a fresh tone map on every flip), an <img>
 * zooms with nearest-neighbour pixels through CSS alone, and a picture
 * decoded once flips without a delay.  The cost is the exposure's
 * steps, a stop apart, and the page's size (a PNG a picture and a
 * stop, which rf_report_stops lets the caller trade against the range).
 */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image/image-internal.h"
#include "report/report-internal.h"
#include "util/util.h"
#include "reflect/compare.h"
#include "reflect/image.h"

static char *
dup(const char *s)
{
	size_t n = strlen(s) + 1;
	char *d = malloc(n);

	return d ? memcpy(d, s, n) : NULL;
}

static void
free_picture(struct rf__report_picture *p)
{
	size_t i;

	free(p->name);
	free(p->path);
	free(p->caption);
	for (i = 0; i < RF__REPORT_NSTOPS; i++)
		free(p->shots[i]);
	free(p->heat);
}

void
rf_report_destroy(rf_report *r)
{
	size_t i;

	if (!r)
		return;
	for (i = 0; i < r->npics; i++)
		free_picture(&r->pics[i]);
	free(r->pics);
	rf_picture_destroy(r->truth);
	free(r);
}

/* Base64 of len bytes (RFC 4648), NUL-terminated; NULL: no memory. */
static char *
base64(const unsigned char *s, size_t len)
{
	static const char set[] =
		"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
	size_t i, o = 0;
	char *d;

	if (len > ((size_t)-1 - 1) / 4 * 3 - 3 || !(d = malloc((len + 2) / 3 * 4 + 1)))
		return NULL;
	for (i = 0; i + 2 < len; i += 3) {
		const unsigned long v = (unsigned long)s[i] << 16 | (unsigned long)s[i + 1] << 8 |
		                        s[i + 2];

		d[o++] = set[v >> 18 & 63];
		d[o++] = set[v >> 12 & 63];
		d[o++] = set[v >> 6 & 63];
		d[o++] = set[v & 63];
	}
	if (i < len) {
		const unsigned long v = (unsigned long)s[i] << 16 |
		                        (i + 1 < len ? (unsigned long)s[i + 1] << 8 : 0);

		d[o++] = set[v >> 18 & 63];
		d[o++] = set[v >> 12 & 63];
		d[o++] = i + 1 < len ? set[v >> 6 & 63] : '=';
		d[o++] = '=';
	}
	d[o] = '\0';
	return d;
}

/* rgb (width x height x 3 display values) as a PNG in base64. */
static int
encode(char **out, const float *rgb, size_t width, size_t height)
{
	unsigned char *png;
	size_t len;
	int rc;

	if ((rc = rf__png_encode(&png, &len, rgb, width, height, 3)) < 0)
		return rc;
	*out = base64(png, len);
	free(png);
	return *out ? 0 : RF_ENOMEM;
}

/* The colour a picture shares with the truth: R G B where both have it,
 * else spec.R spec.G spec.B, as reflect-compare chooses; 0 or -1. */
static int
colour(const rf_picture *a, const rf_picture *b, int *acol, int *bcol)
{
	static const char *const sets[2][3] = { { "R", "G", "B" },
	                                        { "spec.R", "spec.G", "spec.B" } };
	int s, k;

	for (s = 0; s < 2; s++) {
		for (k = 0; k < 3; k++) {
			acol[k] = rf_picture_find_channel(a, sets[s][k]);
			bcol[k] = rf_picture_find_channel(b, sets[s][k]);
			if (acol[k] < 0 || bcol[k] < 0)
				break;
		}
		if (k == 3)
			return 0;
	}
	return -1;
}

/* RF_EINVAL with a message when a colour value is not finite: the count
 * and the first. */
static int
check_finite(const rf_picture *p, const int *col, const char *path, const char *what,
             char *err, size_t errlen)
{
	const size_t w = rf_picture_width(p), n = w * rf_picture_height(p),
	             nch = rf_picture_nchannels(p);
	const float *px = rf_picture_pixels(p);
	size_t i, bad = 0, first = 0;
	int k, fk = 0;

	for (i = 0; i < n; i++)
		for (k = 0; k < 3; k++)
			if (!isfinite(px[i * nch + (size_t)col[k]]) && !bad++) {
				first = i;
				fk = k;
			}
	if (!bad)
		return 0;
	rf__format(err, errlen, "%s'%s' has %zu colour value%s that %s not finite (NaN or "
	           "infinite), the first at pixel %zu, %zu in %s: a report measures finite "
	           "colours; render it again without them", what, path, bad, bad == 1 ? "" : "s",
	           bad == 1 ? "is" : "are", first % w, first / w,
	           rf_picture_channel(p, (size_t)col[fk]));
	return RF_EINVAL;
}

/* The picture's colour at every exposure the page shows it at. */
static int
shots(struct rf__report_picture *pic, const rf_report *r, const rf_picture *p, const int *col)
{
	const size_t n = r->width * r->height, nch = rf_picture_nchannels(p);
	const float *px = rf_picture_pixels(p);
	float *rgb = rf__alloc_big(n * 3 * sizeof(float), 0);
	size_t i, e;
	int rc = 0;

	if (!rgb)
		return RF_ENOMEM;
	for (e = 0; e < (size_t)(r->srgb ? 1 : r->nstops) && !rc; e++) {
		for (i = 0; i < n; i++) {
			rgb[3 * i] = px[i * nch + (size_t)col[0]];
			rgb[3 * i + 1] = px[i * nch + (size_t)col[1]];
			rgb[3 * i + 2] = px[i * nch + (size_t)col[2]];
		}
		if (!r->srgb)
			rf_display_encode(rgb, n, 3, 3,
			                  (float)ldexp(1.0, r->stop_lo + (int)e),
			                  RF_TONE_NONE, 1);
		rc = encode(&pic->shots[e], rgb, r->width, r->height);
	}
	free(rgb);
	return rc;
}

/* Room for one more picture, zeroed. */
static struct rf__report_picture *
grow(rf_report *r)
{
	if (r->npics == r->cap) {
		size_t cap = r->cap ? 2 * r->cap : 8;
		struct rf__report_picture *p = realloc(r->pics, cap * sizeof(*p));

		if (!p)
			return NULL;
		r->pics = p;
		r->cap = cap;
	}
	memset(&r->pics[r->npics], 0, sizeof(r->pics[0]));
	return &r->pics[r->npics];
}

int
rf_report_create(rf_report **rp, const char *path, char *err, size_t errlen)
{
	static const int none[3] = { -1, -1, -1 };
	struct rf__report_picture *pic;
	rf_report *r;
	int rc;

	if (!(*rp = r = calloc(1, sizeof(*r)))) {
		rf__format(err, errlen, "out of memory");
		return RF_ENOMEM;
	}
	if ((rc = rf_picture_read(&r->truth, path, err, errlen)) < 0)
		goto fail;
	memcpy(r->col, none, sizeof(none));
	if (colour(r->truth, r->truth, r->col, r->col) < 0) {
		rf__format(err, errlen, "the truth '%s' has no colour: neither R G B nor spec.R "
		           "spec.G spec.B is among its channels", path);
		rc = RF_ECHANNEL;
		goto fail;
	}
	if ((rc = check_finite(r->truth, r->col, path, "the truth ", err, errlen)) < 0)
		goto fail;
	r->width = rf_picture_width(r->truth);
	r->height = rf_picture_height(r->truth);
	r->srgb = rf_picture_srgb(r->truth);
	r->stop_lo = RF__REPORT_STOP_MIN;
	r->nstops = RF__REPORT_STOP_MAX - RF__REPORT_STOP_MIN + 1;
	r->ppd = RF_FLIP_PPD_DEFAULT;
	r->start = r->stop = NAN;
	if (!(pic = grow(r))) {
		rc = RF_ENOMEM;
		goto nomem;
	}
	r->npics = 1;
	if (!(pic->name = dup("truth")) || !(pic->path = dup(path)))
		rc = RF_ENOMEM;
	else
		rc = shots(pic, r, r->truth, r->col);
	if (rc < 0)
		goto nomem;
	return 0;
nomem:
	rf__format(err, errlen, "'%s': %s for the page's pictures", path, rf_strerror(rc));
fail:
	rf_report_destroy(r);
	*rp = NULL;
	return rc;
}

int
rf_report_stops(rf_report *r, int lo, int hi)
{
	struct rf__report_picture *t = &r->pics[0];
	int e;

	if (lo > hi || lo < -RF_REPORT_STOP_LIMIT || hi > RF_REPORT_STOP_LIMIT ||
	    hi - lo + 1 > RF__REPORT_NSTOPS || r->npics > 1)
		return RF_EINVAL;
	for (e = 0; e < RF__REPORT_NSTOPS; e++) {
		free(t->shots[e]);
		t->shots[e] = NULL;
	}
	r->stop_lo = lo;
	r->nstops = hi - lo + 1;
	return shots(t, r, r->truth, r->col);
}

int
rf_report_find(const rf_report *r, const char *name)
{
	size_t i;

	for (i = 1; i < r->npics; i++)
		if (!strcmp(r->pics[i].name, name))
			return (int)i - 1;
	return -1;
}

size_t
rf_report_nmodes(const rf_report *r)
{
	return r->npics - 1;
}

void
rf_report_errors(const rf_report *r, size_t mode, struct rf_report_errors *e)
{
	*e = r->pics[mode + 1].e;
}

int
rf_report_caption(rf_report *r, const char *name, const char *text)
{
	int i = rf_report_find(r, name);
	char *c = NULL;

	if (i < 0)
		return RF_EINVAL;
	if (text && !(c = dup(text)))
		return RF_ENOMEM;
	free(r->pics[i + 1].caption);
	r->pics[i + 1].caption = c;
	return 0;
}

int
rf_report_time(rf_report *r, const char *name, double ns)
{
	int i = rf_report_find(r, name);

	if (i < 0)
		return RF_EINVAL;
	r->pics[i + 1].e.ns = ns;
	return 0;
}

/* FLIP of the mode against the truth: its mean and map. */
static int
flip(rf_report *r, struct rf__report_picture *pic, const struct rf_compare_input *in,
     int nthreads, const char *path, char *err, size_t errlen)
{
	const size_t n = r->width * r->height;
	struct rf_flip_options o = { 0 };
	struct rf_flip_stats st;
	float *error, *rgb;
	int rc;

	if (!r->srgb && isnan(r->start) &&
	    rf_flip_exposures(in, &r->start, &r->stop, &r->nexposures) < 0) {
		r->start = NAN;
		rf__format(err, errlen, "the truth '%s': more than half its pixels are black, so "
		           "HDR-FLIP's exposures cannot come from its luminance: give the truth as "
		           "a display picture (reflect-export to PNG) for LDR-FLIP",
		           r->pics[0].path);
		return RF_EINVAL;
	}
	o.hdr = !r->srgb;
	o.a_srgb = o.b_srgb = r->srgb;
	o.ppd = r->ppd;
	o.start = r->start;
	o.stop = r->stop;
	o.nexposures = r->nexposures;
	o.nthreads = nthreads > 0 ? nthreads : 1;
	if (!(error = rf__alloc_big(n * sizeof(float), 0)))
		goto nomem;
	if ((rc = rf_compare_flip(error, &o, in)) < 0) {
		free(error);
		if (rc == RF_ENOMEM)
			goto nomem;
		rf__format(err, errlen, "'%s': FLIP failed: %s", path, rf_strerror(rc));
		return rc;
	}
	rf_flip_stats(&st, error, r->width, r->height, NULL, 1.0, 1.0);
	pic->e.flip = st.mean;
	if (!(rgb = rf__alloc_big(n * 3 * sizeof(float), 0))) {
		free(error);
		goto nomem;
	}
	rf_flip_heatmap(rgb, error, r->width, r->height, NULL);
	free(error);
	rc = encode(&pic->heat, rgb, r->width, r->height);
	free(rgb);
	if (rc == RF_ENOMEM)
		goto nomem;
	if (rc < 0)
		rf__format(err, errlen, "'%s': its FLIP map cannot be encoded: %s", path,
		           rf_strerror(rc));
	return rc;
nomem:
	rf__format(err, errlen, "'%s': out of memory for FLIP", path);
	return RF_ENOMEM;
}

/* Whether the mode's picture can stand beside the truth; RF_EINVAL with
 * a message when not. */
static int
check_mode(const rf_report *r, const rf_picture *p, const char *path, int *acol, int *bcol,
           char *err, size_t errlen)
{
	const char *tp = r->pics[0].path;

	if (rf_picture_width(p) != r->width || rf_picture_height(p) != r->height) {
		rf__format(err, errlen, "'%s' is %zux%zu and the truth '%s' %zux%zu: render every "
		           "mode at the truth's size", path, rf_picture_width(p),
		           rf_picture_height(p), tp, r->width, r->height);
		return RF_EINVAL;
	}
	if (colour(p, r->truth, acol, bcol) < 0) {
		rf__format(err, errlen, "'%s' has no colour the truth '%s' has: neither R G B nor "
		           "spec.R spec.G spec.B is in both", path, tp);
		return RF_ECHANNEL;
	}
	if (rf_picture_srgb(p) != r->srgb) {
		rf__format(err, errlen, "'%s' is %s and the truth '%s' %s: give every picture as "
		           "the truth is (reflect-export them all to EXR, or all to PNG)", path,
		           r->srgb ? "linear" : "display sRGB", tp,
		           r->srgb ? "display sRGB" : "linear");
		return RF_EINVAL;
	}
	return check_finite(p, acol, path, "", err, errlen);
}

int
rf_report_add(rf_report *r, const char *name, const char *path, double ns, int nthreads,
              char *err, size_t errlen)
{
	struct rf__report_picture *pic;
	struct rf_compare_input in;
	struct rf_compare_stats st;
	int acol[3], bcol[3], rc;
	rf_picture *p;

	if (!*name) {
		rf__format(err, errlen, "'%s' has no name: give each mode as NAME=FILE", path);
		return RF_EINVAL;
	}
	if (rf_report_find(r, name) >= 0) {
		rf__format(err, errlen, "two modes are named '%s' ('%s' and '%s'): give each a "
		           "name of its own", name, r->pics[rf_report_find(r, name) + 1].path, path);
		return RF_EINVAL;
	}
	if ((rc = rf_picture_read(&p, path, err, errlen)) < 0)
		return rc;
	if ((rc = check_mode(r, p, path, acol, bcol, err, errlen)) < 0) {
		rf_picture_destroy(p);
		return rc;
	}
	if (!(pic = grow(r)) || !(pic->name = dup(name)) || !(pic->path = dup(path))) {
		if (pic)
			free_picture(pic);
		rf_picture_destroy(p);
		rf__format(err, errlen, "'%s': out of memory", path);
		return RF_ENOMEM;
	}
	in.a = rf_picture_pixels(p);
	in.b = rf_picture_pixels(r->truth);
	in.a_stride = rf_picture_nchannels(p);
	in.b_stride = rf_picture_nchannels(r->truth);
	in.a_col = acol;
	in.b_col = bcol;
	in.nch = 3;
	in.width = r->width;
	in.height = r->height;
	in.keep = NULL;
	rf_compare_stats(&st, &in, 1.0, 0.0, 0.0);
	pic->e.rel_rmse = st.rel_rmse;
	pic->e.psnr = st.psnr;
	pic->e.ns = ns;
	if ((rc = flip(r, pic, &in, nthreads, path, err, errlen)) < 0 ||
	    (rc = shots(pic, r, p, acol)) < 0) {
		if (rc == RF_ENOMEM)
			rf__format(err, errlen, "'%s': out of memory for the page's pictures", path);
		free_picture(pic);
		rf_picture_destroy(p);
		return rc;
	}
	rf_picture_destroy(p);
	r->npics++;
	return 0;
}

int
rf_report_write(rf_report *r, FILE *fp, const char *title, char *err, size_t errlen)
{
	errno = 0;
	rf__report_page(r, fp, title);
	if (fflush(fp) != 0 || ferror(fp)) {
		rf__format(err, errlen, "cannot write the page: %s",
		           strerror(errno ? errno : EIO));
		return RF_EIO;
	}
	return 0;
}
