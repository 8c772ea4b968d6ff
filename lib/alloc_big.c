/* Buffers of megabytes on huge pages where the kernel offers them. */
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "internal.h"

#define HUGE_PAGE ((size_t)2 << 20)

void *
rf__alloc_big(size_t bytes, int zero)
{
	void *p;

	if (bytes < HUGE_PAGE) {
		p = zero ? calloc(1, bytes ? bytes : 1) : malloc(bytes ? bytes : 1);
		return p;
	}
	/* Whole huge pages, aligned to one, so the kernel can back them with
	 * huge pages (transparent huge pages in madvise mode ask for the
	 * hint).  Fresh pages from the kernel are zero already. */
	bytes = (bytes + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
	if (posix_memalign(&p, HUGE_PAGE, bytes) != 0)
		return NULL;
#ifdef MADV_HUGEPAGE
	(void)madvise(p, bytes, MADV_HUGEPAGE);
#endif
	if (zero)
		memset(p, 0, bytes);
	return p;
}

void
rf__free_big(void *p)
{
	free(p);
}
