/*
 * Includes the header named by RF__LANES_BODY (a string) once for each
 * width the compiler can make: 4 lanes (SSE on every x86-64, generic
 * vectors elsewhere), with functions suffixed _4, and where it can
 * target AVX2, 8 lanes (_8), to be chosen at run time by
 * rf__lanes_wide().  See lanes.h.
 */
#include "maths/lanes.h"

#if defined(RF__LANES_NARROW)
#define LANES 4
#define VF rf__lanes_v4f
#define VI rf__lanes_v4i
#define NAME(x) x##_4
#define LANES_ATTR
#include RF__LANES_BODY
#undef LANES
#undef VF
#undef VI
#undef NAME
#undef LANES_ATTR
#endif
#if defined(RF__LANES_WIDE)
#define LANES 8
#define VF rf__lanes_v8f
#define VI rf__lanes_v8i
#define NAME(x) x##_8
#define LANES_ATTR __attribute__((target("avx2")))
#include RF__LANES_BODY
#undef LANES
#undef VF
#undef VI
#undef NAME
#undef LANES_ATTR
#endif
#undef RF__LANES_BODY
