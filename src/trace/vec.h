/* Small double-precision vector helpers for the path tracer (never allocate; degenerate input has a
 * defined result: normalising a zero vector gives zero). */
#ifndef LUCENT_TRACE_VEC_H
#define LUCENT_TRACE_VEC_H

#include <math.h>

#define TR_PI 3.14159265358979323846
#define TR_INV_PI 0.31830988618379067154
#define TR_INV_4PI 0.07957747154594766788

typedef struct v3 {
    double x, y, z;
} v3;

static inline v3 v3_make(double x, double y, double z) { return (v3){x, y, z}; }
static inline v3 v3_from(const double a[3]) { return (v3){a[0], a[1], a[2]}; }
static inline v3 v3_add(v3 a, v3 b) { return (v3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline v3 v3_sub(v3 a, v3 b) { return (v3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline v3 v3_scale(v3 a, double s) { return (v3){a.x * s, a.y * s, a.z * s}; }
static inline v3 v3_neg(v3 a) { return (v3){-a.x, -a.y, -a.z}; }
/* a + b * s */
static inline v3 v3_madd(v3 a, v3 b, double s) { return (v3){a.x + b.x * s, a.y + b.y * s, a.z + b.z * s}; }
static inline double v3_dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline double v3_len(v3 a) { return sqrt(v3_dot(a, a)); }
static inline v3 v3_cross(v3 a, v3 b)
{
    return (v3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
static inline v3 v3_norm(v3 a)
{
    double l = v3_len(a);
    return l > 0 && isfinite(l) ? v3_scale(a, 1.0 / l) : (v3){0, 0, 0};
}

/* An orthonormal basis (t, b, n) around unit n (Duff et al. 2017, "Building an orthonormal basis,
 * revisited", JCGT 6(1)): branch-free but for the sign of n.z. */
static inline void v3_basis(v3 n, v3 *t, v3 *b)
{
    double s = n.z >= 0 ? 1.0 : -1.0, a = -1.0 / (s + n.z), c = n.x * n.y * a;
    *t = (v3){1.0 + s * n.x * n.x * a, s * c, -s * n.x};
    *b = (v3){c, s + n.y * n.y * a, -n.y};
}

/* Local coordinates (x, y, z) of direction w in the frame (t, b, n), and back. */
static inline v3 v3_to_local(v3 w, v3 t, v3 b, v3 n) { return (v3){v3_dot(w, t), v3_dot(w, b), v3_dot(w, n)}; }
static inline v3 v3_from_local(v3 l, v3 t, v3 b, v3 n)
{
    return v3_add(v3_add(v3_scale(t, l.x), v3_scale(b, l.y)), v3_scale(n, l.z));
}

/* A direction at cosine mu from axis n with azimuth phi. */
static inline v3 v3_around(v3 n, double mu, double phi)
{
    v3 t, b;
    v3_basis(n, &t, &b);
    double s = sqrt(fmax(0.0, 1.0 - mu * mu));
    return v3_norm(v3_from_local((v3){s * cos(phi), s * sin(phi), mu}, t, b, n));
}

static inline double tr_max3(const double a[3]) { return fmax(a[0], fmax(a[1], a[2])); }
static inline double tr_mean3(const double a[3]) { return (a[0] + a[1] + a[2]) * (1.0 / 3.0); }

#endif
