/* Internal: the rules of valid input (reflect.h), planned for a row
 * layout and checked a pixel at a time. */
#ifndef REFLECT_INVALID_H
#define REFLECT_INVALID_H

#include <stddef.h>
#include <stdint.h>

#include "util/util.h"

enum {
	RF__CHECK_FINITE,
	RF__CHECK_DISTANCE,
	RF__CHECK_UNIT,
	RF__CHECK_DIRECTION,
	RF__CHECK_RADIANCE, /* an output: finite, not negative */
	RF__CHECK_NUMBER    /* an output of no rule of its own: not NaN */
};
#define RF__CHECK_MAX 64

struct rf__check_item {
	int kind;
	const char *name; /* the channel, or the vector's base name */
	int at[3];        /* its place in the pixel (three for a vector) */
};

struct rf__check {
	size_t n;
	struct rf__check_item item[RF__CHECK_MAX];
};

/* The rules that apply to a pixel laid out as names[0..n-1]; names must
 * outlive the plan. */
void rf__check_plan(struct rf__check *c, const char *const *names, size_t n);
/* The rules a plugin's outputs laid out as names[0..n-1] must keep: those
 * of the same channels as inputs (a projection's R, D and distances are
 * the next tool's inputs), roughness.eff and occlusion in [0, 1], spec.*
 * a radiance, and any other channel not NaN. */
void rf__check_plan_outputs(struct rf__check *c, const char *const *names, size_t n);
/* 1 when every one of n pixels (stride floats apart) keeps every rule,
 * directions included: the fast test of a row, before rf__check_pixel. */
int rf__check_row(const struct rf__check *c, const float *px, size_t stride, size_t n);
/* 0: valid; 1: clamped in place (CLAMP); 2: to be written as 0; -1: the
 * first broken rule in why (ERROR).  A wall (mask 0: nothing reflects
 * there) needs no directions. */
int rf__check_pixel(const struct rf__check *c, float *px, int wall, enum rf_invalid policy,
                    char *why, size_t whylen);

/* The first invalid pixel a thread met in a block, in row order (at is
 * y * ncols + x; SIZE_MAX for none), with why. */
struct rf__first_invalid {
	size_t at;
	char why[200];
};

static inline void
rf__first_invalid_clear(struct rf__first_invalid *f)
{
	f->at = SIZE_MAX;
}

/* Keeps pixel `at` when it comes before the one kept. */
void rf__first_invalid_keep(struct rf__first_invalid *f, size_t at, const char *fmt, ...)
	RF__PRINTF(3, 4);
/* The first of n threads' records (stride bytes apart, as members of an
 * array of per-thread structs) as "row R, pixel X: why" in msg (counted
 * from 1): RF_EINVAL, or 0 when none has one. */
int rf__first_invalid_report(const struct rf__first_invalid *first, size_t n, size_t stride,
                             size_t ncols, char *msg, size_t len);

#endif
