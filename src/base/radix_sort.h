/* Sorting of 64-bit keys for the large passes (mesh edge statistics). */
#ifndef LUCENT_SRC_BASE_RADIX_SORT_H
#define LUCENT_SRC_BASE_RADIX_SORT_H

#include <stddef.h>
#include <stdint.h>

/* Sorts keys[0..n) ascending, as qsort with a < comparison would. scratch holds n keys (its
 * contents on return are unspecified). Least-significant-digit radix sort, 11-bit digits: one
 * pass to count all six digits, then one stable scatter per digit, skipping digits that are the
 * same in every key; O(n) time, no recursion, no key distribution makes it slower. */
void lucent_radix_sort_u64(uint64_t *keys, uint64_t *scratch, size_t n);

#endif
