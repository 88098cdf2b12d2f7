/* The library's one set of 3-vector helpers (internal): double precision, by value, never
 * allocating. Degenerate input has a defined result, as in cglm: normalising a zero (or
 * non-finite) vector gives the zero vector, everywhere in Lucent. Data kept as double[3] arrays
 * (mesh positions, scene fields) passes through v3_load and v3_store. */
#ifndef LUCENT_BASE_VEC3_H
#define LUCENT_BASE_VEC3_H

#include <math.h>

typedef struct v3 {
    double x, y, z;
} v3;

/* fmax(a, x) and fmin(a, x) for a bound a that is a number: the same values (x NaN gives a), but
 * inlined; GCC calls libm's fmax and fmin for their rules on NaN (1% of the tracer's time). */
static inline double lucent_at_least(double a, double x) { return x > a ? x : a; }
static inline double lucent_at_most(double a, double x) { return x < a ? x : a; }

static inline v3 v3_make(double x, double y, double z) { return (v3){x, y, z}; }
static inline v3 v3_load(const double a[3]) { return (v3){a[0], a[1], a[2]}; }
static inline void v3_store(v3 a, double dest[3]) { dest[0] = a.x, dest[1] = a.y, dest[2] = a.z; }
static inline v3 v3_add(v3 a, v3 b) { return (v3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline v3 v3_sub(v3 a, v3 b) { return (v3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline v3 v3_scale(v3 a, double s) { return (v3){a.x * s, a.y * s, a.z * s}; }
static inline v3 v3_neg(v3 a) { return (v3){-a.x, -a.y, -a.z}; }
/* a + b s */
static inline v3 v3_madd(v3 a, v3 b, double s) { return (v3){a.x + b.x * s, a.y + b.y * s, a.z + b.z * s}; }
static inline double v3_dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline double v3_length(v3 a) { return sqrt(v3_dot(a, a)); }
static inline v3 v3_cross(v3 a, v3 b)
{
    return (v3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/* a / |a| (one division, then three products); zero when |a| is 0 or not finite. */
static inline v3 v3_normalize(v3 a)
{
    double l = v3_length(a);
    return l > 0 && isfinite(l) ? v3_scale(a, 1.0 / l) : (v3){0, 0, 0};
}

#endif
