/* "%.Pg" without printf. A finite double is x = m 2^q exactly (m < 2^53). With E the decimal
 * exponent of x, its P significant digits are round(x 10^s), s = P - 1 - E, and for 0 <= s <= 22
 * the product m 10^s is an integer below 2^127, so the integer part and the remainder of
 * m 10^s 2^q are exact: rounding needs no approximation and no error bound. C11 7.21.6.1 gives
 * the layout: E is the exponent %e would print after rounding; %f style with P - 1 - E decimals
 * when -4 <= E < P, else %e; trailing zeros and a bare decimal point dropped (no '#' flag). */
#include "base/format_g.h"

#include <stdio.h>
#include <string.h>

typedef unsigned __int128 u128;

static const uint64_t k_pow10[20] = {1ull,
                                     10ull,
                                     100ull,
                                     1000ull,
                                     10000ull,
                                     100000ull,
                                     1000000ull,
                                     10000000ull,
                                     100000000ull,
                                     1000000000ull,
                                     10000000000ull,
                                     100000000000ull,
                                     1000000000000ull,
                                     10000000000000ull,
                                     100000000000000ull,
                                     1000000000000000ull,
                                     10000000000000000ull,
                                     100000000000000000ull,
                                     1000000000000000000ull,
                                     10000000000000000000ull};

/* m 10^s exactly, m < 2^53, 0 <= s <= 22 (m 10^3 < 2^63, 10^22 < 2^74). */
static u128 scale_up(uint64_t m, int s)
{
    if (s <= 19) return (u128)m * k_pow10[s];
    return (u128)(m * k_pow10[s - 19]) * k_pow10[19];
}

static int fallback(char *dest, double x, int p) { return snprintf(dest, LUCENT_FORMAT_G_MAX, "%.*g", p, x); }

/* The P digits of d (10^(P-1) <= d < 10^P) at exponent e, laid out as %g does. */
static int layout(char *dest, int neg, uint64_t d, int e, int p)
{
    char dig[17], *o = dest;
    for (int i = p - 1; i >= 0; i--) dig[i] = (char)('0' + d % 10), d /= 10;
    int nd = p; /* significant digits left once trailing zeros go */
    while (nd > 1 && dig[nd - 1] == '0') nd--;
    if (neg) *o++ = '-';
    if (e >= 0 && e < p) { /* %f, integer part of e + 1 digits */
        memcpy(o, dig, (size_t)e + 1), o += e + 1;
        if (nd > e + 1) *o++ = '.', memcpy(o, dig + e + 1, (size_t)(nd - e - 1)), o += nd - e - 1;
    } else if (e < 0 && e >= -4) { /* %f, 0.000ddd */
        *o++ = '0', *o++ = '.';
        for (int i = 0; i < -e - 1; i++) *o++ = '0';
        memcpy(o, dig, (size_t)nd), o += nd;
    } else { /* %e, at least two exponent digits */
        *o++ = dig[0];
        if (nd > 1) *o++ = '.', memcpy(o, dig + 1, (size_t)nd - 1), o += nd - 1;
        int a = e < 0 ? -e : e;
        *o++ = 'e', *o++ = e < 0 ? '-' : '+';
        if (a >= 100) *o++ = (char)('0' + a / 100), a %= 100;
        *o++ = (char)('0' + a / 10), *o++ = (char)('0' + a % 10);
    }
    *o = 0;
    return (int)(o - dest);
}

int lucent_format_g(char *dest, double x, int precision)
{
    int p = precision < 1 ? 1 : precision > 17 ? 17 : precision;
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int neg = (int)(bits >> 63), biased = (int)(bits >> 52 & 0x7ff);
    uint64_t frac = bits & ((1ull << 52) - 1);
    if (biased == 0 && frac == 0) return neg ? (memcpy(dest, "-0", 3), 2) : (memcpy(dest, "0", 2), 1);
    if (biased == 0 || biased == 0x7ff) return fallback(dest, x, p); /* subnormal, inf, nan */
    uint64_t m = frac | 1ull << 52;
    int q = biased - 1075, b = biased - 1023;                   /* x = m 2^q, 2^b <= |x| < 2^(b+1) */
    int e = (int)((b * 78913 - (b < 0 ? 262143 : 0)) / 262144); /* floor(b log10 2), +-1 fixed below */
    for (int tries = 0; tries < 3; tries++) {
        int s = p - 1 - e;
        if (s < 0 || s > 22 || q > 8 || q < -127) break;
        u128 n = scale_up(m, s), i, rem = 0, half = 1;
        if (q >= 0) {
            i = n << q;
        } else {
            i = n >> -q, rem = n & (((u128)1 << -q) - 1), half = (u128)1 << (-q - 1);
        }
        if (i >= k_pow10[p]) {
            e++;
            continue;
        }
        if (i < k_pow10[p - 1]) {
            e--;
            continue;
        }
        uint64_t d = (uint64_t)i;
        if (q < 0 && (rem > half || (rem == half && (d & 1)))) d++; /* to nearest, ties to even */
        if (d == k_pow10[p]) d = k_pow10[p - 1], e++;
        return layout(dest, neg, d, e, p);
    }
    return fallback(dest, x, p);
}

int lucent_format_u64(char *dest, uint64_t v)
{
    char tmp[20];
    int n = 0;
    do tmp[n++] = (char)('0' + v % 10), v /= 10;
    while (v);
    for (int i = 0; i < n; i++) dest[i] = tmp[n - 1 - i];
    return n;
}
