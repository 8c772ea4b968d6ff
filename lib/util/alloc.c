/* Sizes: buffers of megabytes on huge pages where the kernel offers them,
 * and products that must not overflow. */
#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>

#include "util/util.h"

#define HUGE_PAGE ((uintptr_t)2 << 20)

void *
rf__alloc_big(size_t bytes, int zero)
{
	void *p = zero ? calloc(1, bytes ? bytes : 1) : malloc(bytes ? bytes : 1);
#ifdef MADV_HUGEPAGE
	/* The whole 2 MB pages inside the buffer: transparent huge pages in
	 * madvise mode back them with huge pages when asked.  calloc's big
	 * blocks are fresh from the kernel, so zeroing costs nothing more. */
	uintptr_t lo = ((uintptr_t)p + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
	uintptr_t hi = ((uintptr_t)p + bytes) & ~(HUGE_PAGE - 1);

	if (p && hi > lo)
		(void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
#endif
	return p;
}

int
rf__mul3(size_t x, size_t y, size_t z, size_t *out)
{
	size_t xy;

	if (__builtin_mul_overflow(x, y, &xy) || __builtin_mul_overflow(xy, z, out))
		return -1;
	return 0;
}
