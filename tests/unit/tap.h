/* A small TAP harness for the C unit tests (libuv's ASSERT style). */
#ifndef REFLECT_TESTS_TAP_H
#define REFLECT_TESTS_TAP_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int tap_count, tap_failed, tap_current_failed;

#define TAP_FAIL(...)                                                      \
	do {                                                               \
		printf("# %s:%d: ", __FILE__, __LINE__);                   \
		printf(__VA_ARGS__);                                       \
		printf("\n");                                              \
		tap_current_failed = 1;                                    \
		return;                                                    \
	} while (0)

#define ASSERT(cond)                                                       \
	do {                                                               \
		if (!(cond))                                               \
			TAP_FAIL("assertion failed: %s", #cond);           \
	} while (0)

#define ASSERT_EQ(a, b)                                                    \
	do {                                                               \
		long long a_ = (long long)(a), b_ = (long long)(b);        \
		if (a_ != b_)                                              \
			TAP_FAIL("%s == %s: %lld != %lld", #a, #b, a_, b_); \
	} while (0)

#define ASSERT_STR_EQ(a, b)                                                \
	do {                                                               \
		const char *a_ = (a), *b_ = (b);                           \
		if (!a_ || !b_ || strcmp(a_, b_))                          \
			TAP_FAIL("%s == %s: '%s' != '%s'", #a, #b,         \
			         a_ ? a_ : "(null)", b_ ? b_ : "(null)");   \
	} while (0)

#define ASSERT_NEAR(a, b, tol)                                             \
	do {                                                               \
		double a_ = (a), b_ = (b);                                 \
		if (!(fabs(a_ - b_) <= (tol)))                             \
			TAP_FAIL("%s ~ %s: %.9g vs %.9g (tol %g)", #a, #b,  \
			         a_, b_, (double)(tol));                    \
	} while (0)

#define TEST(name) static void name(void)

#define RUN(name)                                                          \
	do {                                                               \
		tap_current_failed = 0;                                    \
		name();                                                    \
		tap_count++;                                               \
		if (tap_current_failed)                                    \
			tap_failed++;                                      \
		printf("%s %d - %s\n", tap_current_failed ? "not ok" : "ok", \
		       tap_count, #name);                                  \
	} while (0)

#define TAP_DONE()                                                         \
	do {                                                               \
		printf("1..%d\n", tap_count);                              \
		return tap_failed ? 1 : 0;                                 \
	} while (0)

#endif
