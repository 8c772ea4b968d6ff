/*
 * What the vector code written once for LANES lanes shares (the
 * a-trous taps, the raytraced mode's rays, the host's projection):
 * included by each such header, itself included once per width with
 * LANES, VF and VI (vector types of LANES floats and int32s), NAME(x)
 * (x with the width's suffix) and LANES_ATTR (the target attribute, or
 * nothing) defined.  Header-only, for the library and for plugins,
 * which link nothing.
 *
 * Once, whatever the width: rf__lanes_wide(), whether to take the
 * eight-lane code (AVX2 without FMA, so the bits of either width are
 * the same); REFLECT_SIMD=off, the library's switch for its own
 * kernels, takes the four-lane code, to compare.
 */
#ifndef REFLECT_MATHS_LANES_H
#define REFLECT_MATHS_LANES_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "maths/soa.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define RF__LANES_WIDE 1
typedef float rf__lanes_v8f __attribute__((vector_size(32)));
typedef int rf__lanes_v8i __attribute__((vector_size(32)));
#endif
/* Four lanes: SSE on every x86-64, and the compiler's generic vectors
 * (the same operations, the same bits) wherever else it has them. */
#if defined(__SSE2__) || defined(__GNUC__) || defined(__clang__)
#define RF__LANES_NARROW 1
typedef float rf__lanes_v4f __attribute__((vector_size(16)));
typedef int rf__lanes_v4i __attribute__((vector_size(16)));
#endif

static inline int
rf__lanes_wide(void)
{
#if defined(RF__LANES_WIDE)
	const char *simd = getenv("REFLECT_SIMD");

	__builtin_cpu_init();
	return __builtin_cpu_supports("avx2") &&
	       !(simd && (!strcmp(simd, "off") || !strcmp(simd, "0")));
#else
	return 0;
#endif
}
#endif

#if defined(LANES)
LANES_ATTR static inline VF
NAME(v_splat)(float x)
{
	VF v;
	int k;

	for (k = 0; k < LANES; k++)
		v[k] = x;
	return v;
}

/* Lane by lane: a where mask is set (all ones), else b. */
LANES_ATTR static inline VF
NAME(v_select)(VI m, VF a, VF b)
{
	return (VF)(((VI)a & m) | ((VI)b & ~m));
}

/* as max0: NaN and -0 give 0 */
LANES_ATTR static inline VF
NAME(v_max0)(VF x)
{
	return (VF)((VI)x & (x > NAME(v_splat)(0.0f)));
}

LANES_ATTR static inline VF
NAME(v_sqrt)(VF x)
{
	VF r;
	int k;

	for (k = 0; k < LANES; k++)
		r[k] = sqrtf(x[k]);
	return r;
}

LANES_ATTR static inline VF
NAME(v_load)(const float *p)
{
	VF v;

	memcpy(&v, p, sizeof(v));
	return v;
}

LANES_ATTR static inline void
NAME(v_store)(float *p, VF v)
{
	memcpy(p, &v, sizeof(v));
}

#if defined(__SSE2__)
/* LANES xyz triples to three vectors and back, four at a time by
 * soa.h's shuffles, joined and split in registers: lanes written one by
 * one would go through memory, and a wide load after narrow stores
 * waits on store forwarding (15 % of the raytraced mode's lod loop). */
LANES_ATTR static inline void
NAME(v_aos_to_soa)(const float *in, VF v[3])
{
#if LANES == 4
	rf__aos_to_soa(in, v);
#else
	rf__soa_v4 a[3], b[3];
	int j;

	rf__aos_to_soa(in, a);
	rf__aos_to_soa(in + 12, b);
	for (j = 0; j < 3; j++)
		v[j] = __builtin_shufflevector(a[j], b[j], 0, 1, 2, 3, 4, 5, 6, 7);
#endif
}

LANES_ATTR static inline void
NAME(v_soa_to_aos)(const VF v[3], float *out)
{
#if LANES == 4
	rf__soa_to_aos(v, out);
#else
	rf__soa_v4 a[3], b[3];
	int j;

	for (j = 0; j < 3; j++) {
		a[j] = __builtin_shufflevector(v[j], v[j], 0, 1, 2, 3);
		b[j] = __builtin_shufflevector(v[j], v[j], 4, 5, 6, 7);
	}
	rf__soa_to_aos(a, out);
	rf__soa_to_aos(b, out + 12);
#endif
}
#endif
#endif
