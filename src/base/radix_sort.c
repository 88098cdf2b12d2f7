/* LSD radix sort of 64-bit keys (Knuth, TAOCP vol. 3, 5.2.5): stable counting scatters from the
 * least significant 11-bit digit up, so after the last one the keys are in full order. */
#include "base/radix_sort.h"

#include <string.h>

enum { BITS = 11, BUCKETS = 1 << BITS, DIGITS = (64 + BITS - 1) / BITS };

void lucent_radix_sort_u64(uint64_t *keys, uint64_t *scratch, size_t n)
{
    size_t count[DIGITS][BUCKETS] = {{0}}; /* 96 KiB of stack */
    if (n < 2) return;
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < DIGITS; d++) count[d][keys[i] >> (BITS * d) & (BUCKETS - 1)]++;
    uint64_t *src = keys, *dst = scratch;
    for (int d = 0; d < DIGITS; d++) {
        size_t *c = count[d];
        int shift = BITS * d;
        if (c[src[0] >> shift & (BUCKETS - 1)] == n) continue; /* one value of this digit: order kept */
        size_t sum = 0;
        for (int b = 0; b < BUCKETS; b++) {
            size_t k = c[b];
            c[b] = sum, sum += k;
        }
        for (size_t i = 0; i < n; i++) dst[c[src[i] >> shift & (BUCKETS - 1)]++] = src[i];
        uint64_t *t = src;
        src = dst, dst = t;
    }
    if (src != keys) memcpy(keys, src, n * sizeof *keys);
}
