/* Fast number-to-text for large text outputs (the curvature CSV): the same characters as
 * snprintf's "%.Pg" and "%d", without printf's parsing and multi-precision arithmetic. */
#ifndef LUCENT_SRC_BASE_FORMAT_G_H
#define LUCENT_SRC_BASE_FORMAT_G_H

#include <stdint.h>

enum { LUCENT_FORMAT_G_MAX = 32 }; /* room for any %.Pg text of P <= 17, with its NUL */

/* Writes x as snprintf(dest, LUCENT_FORMAT_G_MAX, "%.*g", precision, x) would (C locale) and
 * returns the length; precision 1..17. Byte-identical by construction: finite values whose
 * scaled decimal fits 128 bits are rounded exactly in integers (ties to even, as glibc does in
 * round-to-nearest), everything else (inf, nan, subnormal, very small or >= 10^precision) goes
 * to snprintf itself. */
int lucent_format_g(char *dest, double x, int precision);

/* Writes v in decimal (as "%llu" would) and returns the length (at most 20, no NUL). */
int lucent_format_u64(char *dest, uint64_t v);

#endif
