/*
 * The rules a plugin's inputs must keep (reflect.h says which), checked
 * on the row a stage gathers for its plugin, where a clamped value can
 * be written without touching the input (which may be a read-only
 * mapping of the file).  A rule is planned once a frame from the input
 * names, so a pixel costs a few compares per checked channel.
 */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "util/util.h"
#include "util/invalid.h"

void
rf__first_invalid_keep(struct rf__first_invalid *f, size_t at, const char *fmt, ...)
{
	va_list ap;

	if (at >= f->at)
		return;
	f->at = at;
	va_start(ap, fmt);
	vsnprintf(f->why, sizeof(f->why), fmt, ap);
	va_end(ap);
}

int
rf__first_invalid_report(const struct rf__first_invalid *first, size_t n, size_t stride,
                         size_t ncols, char *msg, size_t len)
{
	const struct rf__first_invalid *best = NULL;
	size_t i;

	for (i = 0; i < n; i++) {
		const struct rf__first_invalid *f =
			(const struct rf__first_invalid *)((const char *)first + i * stride);

		if (f->at != SIZE_MAX && (!best || f->at < best->at))
			best = f;
	}
	if (!best)
		return 0;
	rf__format(msg, len, "row %zu, pixel %zu: %s", best->at / ncols + 1,
	           best->at % ncols + 1, best->why);
	return RF_EINVAL;
}

int
rf_invalid_parse(const char *name, enum rf_invalid *policy)
{
	static const char *const names[] = { "error", "clamp", "zero" };
	int i;

	for (i = 0; i < 3; i++)
		if (!strcmp(name, names[i])) {
			*policy = (enum rf_invalid)i;
			return 0;
		}
	return RF_EINVAL;
}

static int
is(const char *name, const char *base, const char *suffix)
{
	size_t n = strlen(base);

	return !strncmp(name, base, n) && !strcmp(name + n, suffix);
}

static int
find(const char *const *names, size_t n, const char *base, const char *suffix)
{
	size_t i;

	for (i = 0; i < n; i++)
		if (is(names[i], base, suffix))
			return (int)i;
	return -1;
}

void
rf__check_plan(struct rf__check *c, const char *const *names, size_t n)
{
	static const char *const finite[] = { "P", "R", "D" };
	static const char *const unit[] = { "roughness", "metallic", "mask" };
	static const char *const dist[] = { "hit.dist", "probe.dist" };
	static const char *const radiance[] = { "emission.R", "emission.G", "emission.B" };

	static const char *const vectors[] = { "N", "Ng", "V" };
	static const char *const axes[] = { ".X", ".Y", ".Z" };
	size_t i, k;
	int j;

	c->n = 0;
	for (i = 0; i < 3; i++) {
		int at[3];

		for (k = 0; k < 3; k++)
			at[k] = find(names, n, vectors[i], axes[k]);
		if (at[0] >= 0 && at[1] >= 0 && at[2] >= 0 && c->n < RF__CHECK_MAX) {
			struct rf__check_item *it = &c->item[c->n++];

			it->kind = RF__CHECK_DIRECTION;
			it->name = vectors[i];
			memcpy(it->at, at, sizeof(at));
		}
	}
	for (i = 0; i < n && c->n < RF__CHECK_MAX; i++) {
		struct rf__check_item *it = &c->item[c->n];
		int kind = -1;

		for (k = 0; k < 3; k++)
			for (j = 0; j < 3; j++)
				if (is(names[i], finite[k], axes[j]))
					kind = RF__CHECK_FINITE;
		for (k = 0; k < 2; k++)
			if (!strcmp(names[i], dist[k]))
				kind = RF__CHECK_DISTANCE;
		for (k = 0; k < 3; k++)
			if (!strcmp(names[i], unit[k]))
				kind = RF__CHECK_UNIT;
		for (k = 0; k < 3; k++)
			if (!strcmp(names[i], radiance[k]))
				kind = RF__CHECK_RADIANCE;
		if (kind < 0)
			continue;
		it->kind = kind;
		it->name = names[i];
		it->at[0] = (int)i;
		c->n++;
	}
}

static int
planned(const struct rf__check *c, int col)
{
	size_t i;
	int k;

	for (i = 0; i < c->n; i++)
		for (k = 0; k < (c->item[i].kind == RF__CHECK_DIRECTION ? 3 : 1); k++)
			if (c->item[i].at[k] == col)
				return 1;
	return 0;
}

void
rf__check_plan_outputs(struct rf__check *c, const char *const *names, size_t n)
{
	size_t i;

	rf__check_plan(c, names, n);
	for (i = 0; i < n && c->n < RF__CHECK_MAX; i++) {
		struct rf__check_item *it = &c->item[c->n];

		if (planned(c, (int)i))
			continue;
		if (!strcmp(names[i], "roughness.eff") || !strcmp(names[i], "occlusion"))
			it->kind = RF__CHECK_UNIT;
		else if (!strncmp(names[i], "spec.", 5))
			it->kind = RF__CHECK_RADIANCE;
		else
			it->kind = RF__CHECK_NUMBER;
		it->name = names[i];
		it->at[0] = (int)i;
		c->n++;
	}
}

/*
 * The common case: every pixel valid, walls' directions included.  One
 * rule at a time down the row, adding up instead of branching: v * 0 is
 * 0 for a finite v and NaN otherwise, v less its clamp to [0, 1] is 0
 * inside the range, and a direction's squared lengths are kept as their
 * least and greatest.  A branch or a flag a pixel and rule made
 * reflect-project half as slow again; this costs it some 15%.
 */
int
rf__check_row(const struct rf__check *c, const float *px, size_t stride, size_t n)
{
	float finite = 0.0f, outside = 0.0f, shortest = FLT_MAX, longest = 0.0f;
	int nan = 0;
	size_t i, x;

	for (i = 0; i < c->n; i++) {
		const struct rf__check_item *it = &c->item[i];
		const float *v = px + it->at[0];

		switch (it->kind) {
		case RF__CHECK_FINITE:
			for (x = 0; x < n; x++)
				finite += v[x * stride] * 0.0f;
			break;
		case RF__CHECK_DISTANCE:
		case RF__CHECK_NUMBER:
			for (x = 0; x < n; x++)
				nan |= v[x * stride] != v[x * stride];
			break;
		case RF__CHECK_RADIANCE:
			/* t - a is -a below 0, NaN for NaN; a * 0 NaN for +-inf */
			for (x = 0; x < n; x++) {
				float a = v[x * stride], t = a > 0.0f ? a : 0.0f;

				outside += t - a;
				finite += a * 0.0f;
			}
			break;
		case RF__CHECK_UNIT:
			for (x = 0; x < n; x++) {
				float a = v[x * stride], t = a > 0.0f ? a : 0.0f;

				t = t < 1.0f ? t : 1.0f;
				outside += fabsf(a - t);
			}
			break;
		default: {
			const float *vy = px + it->at[1], *vz = px + it->at[2];

			for (x = 0; x < n; x++) {
				float a = v[x * stride], b = vy[x * stride], d = vz[x * stride];
				float l2 = a * a + b * b + d * d;

				shortest = l2 < shortest ? l2 : shortest;
				longest = l2 > longest ? l2 : longest;
				finite += l2 * 0.0f;
			}
		}
		}
	}
	return finite == 0.0f && outside == 0.0f && !nan && shortest >= FLT_MIN &&
	       longest <= FLT_MAX;
}

/* What a broken rule does under the policy: -1 with why (ERROR), 2 (the
 * pixel to be written as 0), or 0: the caller clamps. */
static int RF__PRINTF(4, 5)
broken(enum rf_invalid policy, char *why, size_t len, const char *fmt, ...)
{
	va_list ap;

	if (policy == RF_INVALID_ZERO)
		return 2;
	if (policy == RF_INVALID_CLAMP)
		return 0;
	if (why) {
		va_start(ap, fmt);
		vsnprintf(why, len, fmt, ap);
		va_end(ap);
	}
	return -1;
}

int
rf__check_pixel(const struct rf__check *c, float *px, int wall, enum rf_invalid policy,
                char *why, size_t whylen)
{
	int result = 0, r;
	size_t i;

	for (i = 0; i < c->n; i++) {
		const struct rf__check_item *it = &c->item[i];
		float *v = px + it->at[0];

		if (it->kind == RF__CHECK_DIRECTION && wall)
			continue;
		if (it->kind == RF__CHECK_DISTANCE) {
			/* Any sign (behind the point), +-inf (nothing hit). */
			if (!isnan(*v))
				continue;
			if ((r = broken(policy, why, whylen, "channel '%s' is %g, not a distance",
			                it->name, (double)*v)))
				return r;
			*v = INFINITY;
		} else if (it->kind == RF__CHECK_UNIT) {
			if (*v >= 0.0f && *v <= 1.0f)
				continue;
			if ((r = broken(policy, why, whylen, "channel '%s' is %g, outside [0, 1]",
			                it->name, (double)*v)))
				return r;
			*v = *v > 0.0f ? (*v < 1.0f ? *v : 1.0f) : 0.0f;
		} else if (it->kind == RF__CHECK_NUMBER) {
			if (!isnan(*v))
				continue;
			if ((r = broken(policy, why, whylen, "channel '%s' is nan", it->name)))
				return r;
			*v = 0.0f;
		} else if (it->kind == RF__CHECK_RADIANCE) {
			if (isfinite(*v) && *v >= 0.0f)
				continue;
			if ((r = broken(policy, why, whylen, "channel '%s' is %g, not a radiance "
			                "(finite, not negative)", it->name, (double)*v)))
				return r;
			*v = *v > 0.0f ? FLT_MAX : 0.0f; /* NaN and below 0: 0 */
		} else if (it->kind == RF__CHECK_FINITE) {
			if (isfinite(*v))
				continue;
			if ((r = broken(policy, why, whylen, "channel '%s' is %g", it->name,
			                (double)*v)))
				return r;
			*v = isnan(*v) ? 0.0f : *v > 0.0f ? FLT_MAX : -FLT_MAX;
		} else {
			float *x = px + it->at[0], *y = px + it->at[1], *z = px + it->at[2];
			float l2 = *x * *x + *y * *y + *z * *z;
			double dl;

			if (isfinite(l2) && l2 >= FLT_MIN)
				continue;
			if ((r = broken(policy, why, whylen, "%s is (%g, %g, %g), %s", it->name,
			                (double)*x, (double)*y, (double)*z,
			                !isfinite(*x) || !isfinite(*y) || !isfinite(*z) ? "not finite"
			                : *x == 0.0f && *y == 0.0f && *z == 0.0f ? "not a direction"
			                : l2 < FLT_MIN ? "too short to normalise in float"
			                               : "too long to normalise in float")))
				return r;
			dl = isfinite(*x) && isfinite(*y) && isfinite(*z)
			             ? sqrt((double)*x * *x + (double)*y * *y + (double)*z * *z)
			             : 0.0;
			if (!(dl > 0.0))
				return 2; /* no direction to keep */
			*x = (float)(*x / dl);
			*y = (float)(*y / dl);
			*z = (float)(*z / dl);
		}
		result = 1;
	}
	return result;
}
