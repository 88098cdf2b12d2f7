/* Random number streams: xoshiro256** (Blackman & Vigna, "Scrambled linear pseudorandom
 * number generators", 2018), seeded through SplitMix64 (Steele, Lea & Flood 2014). */
#include "lucent/base.h"

/* The SplitMix64 finaliser: a bijective 64-bit mixer with full avalanche. */
static uint64_t splitmix64_mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

void lucent_rng_init(uint64_t seed, uint64_t stream, lucent_rng *dest)
{
    /* Hash (seed, stream) to one 64-bit key, then expand it with the SplitMix64
     * sequence (Weyl increment + mixer), as the xoshiro authors recommend for seeding. */
    const uint64_t golden = 0x9e3779b97f4a7c15u;
    uint64_t x = splitmix64_mix(splitmix64_mix(seed + golden) ^ splitmix64_mix(~stream));
    uint64_t any = 0;
    for (int i = 0; i < 4; i++) {
        x += golden;
        dest->s[i] = splitmix64_mix(x);
        any |= dest->s[i];
    }
    if (!any) dest->s[0] = 1; /* the all-zero state is the generator's only fixed point */
}

void lucent_rng_jump(lucent_rng *r)
{
    /* The jump polynomial for 2^128 steps, as published with xoshiro256. */
    static const uint64_t jump[4] = {0x180ec6d33cfd0abau, 0xd5a61266f0c9392cu, 0xa9582618e03fc9aau,
                                     0x39abdc4529b1661cu};
    uint64_t t[4] = {0, 0, 0, 0};
    for (int i = 0; i < 4; i++) {
        for (int b = 0; b < 64; b++) {
            if (jump[i] & ((uint64_t)1 << b))
                for (int k = 0; k < 4; k++) t[k] ^= r->s[k];
            lucent_rng_next(r);
        }
    }
    for (int k = 0; k < 4; k++) r->s[k] = t[k];
}
