/* Internal: point sources of the diffusion models (dipole, better dipole, multipole).
 * A source of charge q at signed depth h below the surface it is seen from contributes the
 * normal flux q E(h, r) with E = (1/4pi) h (1 + s D) e^{-s D} / D^3, D = sqrt(r^2 + h^2),
 * s = sigma_tr (Jensen et al. 2001, eq. 4; Donner & Jensen 2005, multipole). */
#ifndef LUCENT_PROFILE_POLE_H
#define LUCENT_PROFILE_POLE_H

#include <math.h>

/* E(h, r), mm^-2. */
static inline double pole_flux(double h, double s, double r)
{
    if (h == 0.0) return 0.0;
    double d = hypot(r, h);
    return h * (1.0 + s * d) * exp(-s * d) / (4.0 * M_PI * d * d * d);
}

/* 2 pi integral_{r0}^{r1} E(h, r) r dr = (h/2) (e^{-s D0}/D0 - e^{-s D1}/D1), exactly
 * (d/dD (e^{-sD}/D) = -(1 + sD) e^{-sD} / D^2 and D dD = r dr). */
static inline double pole_flux_bin(double h, double s, double r0, double r1)
{
    if (h == 0.0) return 0.0;
    double d0 = hypot(r0, h), d1 = hypot(r1, h);
    return 0.5 * h * (exp(-s * d0) / d0 - exp(-s * d1) / d1);
}

/* The plane integral of E(h, .): sign(h) e^{-s |h|} / 2. */
static inline double pole_flux_total(double h, double s)
{
    if (h == 0.0) return 0.0;
    return (h > 0.0 ? 0.5 : -0.5) * exp(-s * fabs(h));
}

/* (e^{-s a} - e^{-s b}) / s, its limit b - a at s = 0, without cancellation for small s. */
static inline double exp_diff_over_s(double s, double a, double b)
{
    if (s == 0.0) return b - a;
    double x = s * (b - a);
    if (fabs(x) > 50.0) return (exp(-s * a) - exp(-s * b)) / s;
    return exp(-s * b) * expm1(x) / s;
}

/* Bin average from a bin's plane integral: divide by the annulus area pi (r1^2 - r0^2). */
static inline double bin_average(double integral, double r0, double r1)
{
    return integral / (M_PI * (r1 - r0) * (r1 + r0));
}

#endif
