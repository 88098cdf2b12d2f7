/* Large arrays for the curvature passes. On the development machines (virtual, 4 KiB pages) a
 * page fault costs about 15 us, so the fresh pages of one res1 dragon run (about 120 MB) cost
 * more than the arithmetic; with transparent huge pages the same memory faults in 2 MiB at a
 * time, about 50 times cheaper. Large blocks are therefore 2 MiB-aligned, rounded up to whole
 * huge pages and advised MADV_HUGEPAGE where the system has it (advice only: without it they
 * are ordinary pages). Freed with free(). */
#include <stdlib.h>
#include <sys/mman.h>

#include "mesh/internal.h"

enum { HUGE_PAGE = 2u << 20, LARGE = 256u << 10 };

void *mesh_alloc_large(size_t bytes)
{
    if (bytes < LARGE) return malloc(bytes ? bytes : 1);
    if (bytes > SIZE_MAX - HUGE_PAGE) return NULL;
    size_t size = (bytes + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
    void *p = aligned_alloc(HUGE_PAGE, size);
#ifdef MADV_HUGEPAGE
    if (p) (void)madvise(p, size, MADV_HUGEPAGE);
#endif
    return p;
}

void mesh_advise_large(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    uintptr_t begin = ((uintptr_t)p + HUGE_PAGE - 1) / HUGE_PAGE * HUGE_PAGE;
    uintptr_t end = ((uintptr_t)p + bytes) / HUGE_PAGE * HUGE_PAGE;
    if (p && bytes >= LARGE && end > begin) (void)madvise((void *)begin, end - begin, MADV_HUGEPAGE);
#else
    (void)p, (void)bytes;
#endif
}
